//! The trajectory picture's objects: food (with the amount left at the end), aversive
//! objects and landmarks.

use super::frame::{Frame, FOOD_COLOURS};
use crate::evo::trace::TrialTrace;
use std::fmt::Write as _;

/// Food: a ring of the type's colour; the disc inside has area ∝ amount left / capacity.
pub(super) fn food(s: &mut String, trace: &TrialTrace, frame: Frame) {
    let w = &trace.world;
    let mut left = vec![None; w.food.len()];
    for o in &trace.objects {
        left[o.object] = Some(o.amount);
    }
    for (k, f) in w.food.iter().enumerate() {
        let amount = left[k].unwrap_or(f.amount);
        let cap: f64 = f.capacity.iter().sum();
        let frac = if cap > 0.0 {
            (amount.iter().sum::<f64>() / cap).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let r = frame.len(f.radius).max(4.0);
        let colour = FOOD_COLOURS[f.food_type.min(3)];
        let _ = writeln!(
            s,
            r##"<g id="food-{k}" class="food type-{}" data-left="{frac:.3}"><circle cx="{:.1}" cy="{:.1}" r="{r:.1}" fill="#ffffff" stroke="{colour}" stroke-width="1.5"/><circle cx="{:.1}" cy="{:.1}" r="{:.2}" fill="{colour}"/></g>"##,
            (b'a' + f.food_type.min(3) as u8) as char,
            frame.x(f.position[0]),
            frame.y(f.position[1]),
            frame.x(f.position[0]),
            frame.y(f.position[1]),
            r * frac.sqrt()
        );
    }
}

/// Aversive objects: crossed purple discs.
pub(super) fn aversives(s: &mut String, trace: &TrialTrace, frame: Frame) {
    let w = &trace.world;
    for (k, a) in w.aversives.iter().enumerate() {
        let (x, y, r) = (
            frame.x(a.position[0]),
            frame.y(a.position[1]),
            frame.len(a.radius).max(4.0),
        );
        let d = r * 0.6;
        let _ = writeln!(
            s,
            r##"<g id="aversive-{k}" class="aversive"><circle cx="{x:.1}" cy="{y:.1}" r="{r:.1}" fill="#9d4edd" fill-opacity="0.55" stroke="#5a189a"/><path d="M{:.1},{:.1} L{:.1},{:.1} M{:.1},{:.1} L{:.1},{:.1}" stroke="#fff" stroke-width="1.5"/></g>"##,
            x - d,
            y - d,
            x + d,
            y + d,
            x - d,
            y + d,
            x + d,
            y - d
        );
    }
}

/// Landmarks: a star where it is, or on the border in its direction from the arena's
/// centre, labelled with its bearing from the first creature's start.
pub(super) fn landmarks(s: &mut String, trace: &TrialTrace, frame: Frame) {
    let w = &trace.world;
    let [aw, ah] = w.arena;
    let centre = [aw / 2.0, ah / 2.0];
    for (k, l) in w.landmarks.iter().enumerate() {
        let inside = (0.0..=aw).contains(&l[0]) && (0.0..=ah).contains(&l[1]);
        let at = if inside {
            *l
        } else {
            let (dx, dy) = (l[0] - centre[0], l[1] - centre[1]);
            let t = [
                if dx != 0.0 {
                    (aw / 2.0) / dx.abs()
                } else {
                    f64::INFINITY
                },
                if dy != 0.0 {
                    (ah / 2.0) / dy.abs()
                } else {
                    f64::INFINITY
                },
            ];
            let t = t[0].min(t[1]);
            [centre[0] + dx * t, centre[1] + dy * t]
        };
        let bearing = w.creatures.first().map(|c| {
            let d = libm::atan2(l[1] - c.position[1], l[0] - c.position[0]) - c.heading;
            libm::atan2(libm::sin(d), libm::cos(d)).to_degrees()
        });
        let (x, y) = (frame.x(at[0]), frame.y(at[1]));
        let star: String = (0..10)
            .map(|i| {
                let a = std::f64::consts::PI / 5.0 * i as f64 - std::f64::consts::FRAC_PI_2;
                let r = if i % 2 == 0 { 9.0 } else { 4.0 };
                format!("{:.1},{:.1} ", x + r * libm::cos(a), y + r * libm::sin(a))
            })
            .collect();
        let _ = writeln!(
            s,
            r##"<g id="landmark-{k}" class="landmark"><polygon points="{}" fill="#f4d35e" stroke="#a07c00"/><text x="{:.1}" y="{:.1}" font-size="11" fill="#7a5c00"{}>L{}{}</text></g>"##,
            star.trim_end(),
            // Right of the star in the arena's left half, left of it in the right half, so
            // that the label stays over the arena and off the legend.
            if at[0] > centre[0] {
                x - 10.0
            } else {
                x + 10.0
            },
            y - 6.0,
            if at[0] > centre[0] {
                r#" text-anchor="end""#
            } else {
                ""
            },
            k + 1,
            bearing.map_or(String::new(), |b| format!(" ({b:+.0}° from start)"))
        );
    }
}
