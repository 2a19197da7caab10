//! Areas (§4.6) and distal landmarks (§4.5.3) as a running world holds them: rectangles a
//! creature can be inside (safe ones shelter it from predators), and far points whose bearing
//! it senses.

use crate::geometry::Vec2;
use crate::sim::smell::Smell;
use crate::sim::spec::{AreaKind, AreaSpec};
use serde::{Deserialize, Serialize};

/// One area of a running world.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Area {
    /// Smallest corner `(x0, y0)` in LU.
    pub lo: Vec2,
    /// Largest corner `(x1, y1)` in LU.
    pub hi: Vec2,
    /// What it is for.
    pub kind: AreaKind,
    /// What it gives off at its centre.
    pub smell: Smell,
}

impl Area {
    /// The area a `[[world.areas]]` entry describes.
    pub fn from_spec(spec: &AreaSpec) -> Area {
        let [x0, y0, x1, y1] = spec.region;
        Area {
            lo: Vec2::new(x0, y0),
            hi: Vec2::new(x1, y1),
            kind: spec.kind,
            smell: Smell::new(&spec.odour, spec.intensity, spec.range),
        }
    }

    /// Is `p` inside (bounds included)?
    #[inline]
    pub fn contains(&self, p: Vec2) -> bool {
        self.lo.x <= p.x && p.x <= self.hi.x && self.lo.y <= p.y && p.y <= self.hi.y
    }

    /// The centre, where its smell comes from.
    #[inline]
    pub fn centre(&self) -> Vec2 {
        0.5 * (self.lo + self.hi)
    }

    /// Is it a safe area?
    #[inline]
    pub fn is_safe(&self) -> bool {
        self.kind == AreaKind::Safe
    }
}

/// §4.5.3: the bearing of a landmark at `landmark` seen from `position` with unit `heading`,
/// as (sin, cos) of the angle from the heading to the landmark, positive clockwise on screen
/// (y down), i.e. towards the creature's right. Straight ahead is (0, 1), to the right
/// (1, 0), to the left (−1, 0), behind (0, −1). A landmark exactly at `position` has no
/// bearing and reads (0, 0).
#[inline]
pub fn bearing(position: Vec2, heading: Vec2, landmark: Vec2) -> (f64, f64) {
    let d = landmark - position;
    let length = d.length();
    if length == 0.0 || !length.is_finite() {
        return (0.0, 0.0);
    }
    let u = d / length;
    // heading × u is positive when u is clockwise from the heading in the y-down frame.
    (
        heading.perp_dot(u).clamp(-1.0, 1.0),
        heading.dot(u).clamp(-1.0, 1.0),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64) -> Vec2 {
        Vec2::new(x, y)
    }

    #[test]
    fn bearings_at_known_poses() {
        let east = v(1.0, 0.0);
        let at = v(100.0, 100.0);
        // Straight ahead.
        assert_eq!(bearing(at, east, v(200.0, 100.0)), (0.0, 1.0));
        // +y is down the screen: heading east, that is clockwise, the creature's right.
        assert_eq!(bearing(at, east, v(100.0, 250.0)), (1.0, 0.0));
        // Up the screen is to its left.
        assert_eq!(bearing(at, east, v(100.0, 0.0)), (-1.0, 0.0));
        // Behind.
        assert_eq!(bearing(at, east, v(0.0, 100.0)), (0.0, -1.0));
        // Heading south (down the screen), a landmark to the west is on its right.
        let south = v(0.0, 1.0);
        assert_eq!(bearing(at, south, v(10.0, 100.0)), (1.0, 0.0));
        // 45° to the right, ahead: (sin 45°, cos 45°).
        let (s, c) = bearing(at, east, v(110.0, 110.0));
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!((s - h).abs() < 1e-15 && (c - h).abs() < 1e-15);
        // On top of it: no bearing.
        assert_eq!(bearing(at, east, at), (0.0, 0.0));
    }

    #[test]
    fn inside_is_inclusive() {
        let a = Area::from_spec(&AreaSpec {
            name: None,
            region: [10.0, 20.0, 30.0, 40.0],
            kind: AreaKind::Safe,
            odour: [0.0; 8],
            intensity: 0.0,
            range: None,
        });
        assert!(a.contains(v(10.0, 20.0)));
        assert!(a.contains(v(30.0, 40.0)));
        assert!(a.contains(v(20.0, 30.0)));
        assert!(!a.contains(v(9.999, 30.0)));
        assert!(!a.contains(v(20.0, 40.001)));
        assert_eq!(a.centre(), v(20.0, 30.0));
        assert!(a.is_safe());
    }
}
