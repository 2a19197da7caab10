//! What the trajectory picture's layers share: the frame from LU to pixels, the colours,
//! text escaping and width, and splitting a path at its jumps. A leaf: the layers and
//! [`super::render_svg`] use it, it uses none of them.

use std::fmt::Write as _;

/// Colours of food types A–D.
pub const FOOD_COLOURS: [&str; 4] = ["#d62728", "#1f77b4", "#2ca02c", "#ff7f0e"];

/// The arena's longer side in pixels.
pub(super) const ARENA_PX: f64 = 720.0;
/// The legend's least width in pixels (wider when its text needs it).
pub(super) const LEGEND_PX: f64 = 300.0;
pub(super) const MARGIN: f64 = 20.0;

pub(super) fn rgb(c: [f64; 3]) -> String {
    let b = |x: f64| (x.clamp(0.0, 1.0) * 255.0).round() as u8;
    format!("#{:02x}{:02x}{:02x}", b(c[0]), b(c[1]), b(c[2]))
}

/// Viridis-like colour at `t` in [0, 1] (dark blue, teal, green, yellow).
pub fn time_colour(t: f64) -> String {
    const STOPS: [[f64; 3]; 5] = [
        [68.0, 1.0, 84.0],
        [59.0, 82.0, 139.0],
        [33.0, 145.0, 140.0],
        [94.0, 201.0, 98.0],
        [253.0, 231.0, 37.0],
    ];
    let t = t.clamp(0.0, 1.0) * (STOPS.len() - 1) as f64;
    let i = (t.floor() as usize).min(STOPS.len() - 2);
    let f = t - i as f64;
    let c: [f64; 3] = std::array::from_fn(|k| STOPS[i][k] + f * (STOPS[i + 1][k] - STOPS[i][k]));
    format!("#{:02x}{:02x}{:02x}", c[0] as u8, c[1] as u8, c[2] as u8)
}

pub(super) fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Maps LU to pixels.
#[derive(Debug, Clone, Copy)]
pub(super) struct Frame {
    pub(super) scale: f64,
}

impl Frame {
    pub(super) fn x(&self, x: f64) -> f64 {
        MARGIN + x * self.scale
    }
    pub(super) fn y(&self, y: f64) -> f64 {
        MARGIN + 30.0 + y * self.scale
    }
    pub(super) fn len(&self, l: f64) -> f64 {
        l * self.scale
    }
}

/// A polyline's `points` attribute.
pub(super) fn points(frame: Frame, pts: &[[f64; 2]]) -> String {
    let mut s = String::with_capacity(pts.len() * 14);
    for p in pts {
        let _ = write!(s, "{:.1},{:.1} ", frame.x(p[0]), frame.y(p[1]));
    }
    s.trim_end().to_string()
}

/// Distance between two points.
pub(super) fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    ((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1])).sqrt()
}

/// Splits a path where it jumps (teleports, an air predator's new flight).
pub(super) fn split_at_jumps(pts: &[[f64; 2]], max_step: f64) -> Vec<Vec<[f64; 2]>> {
    let mut parts: Vec<Vec<[f64; 2]>> = vec![Vec::new()];
    for (k, p) in pts.iter().enumerate() {
        if k > 0 {
            let q = pts[k - 1];
            if dist(*p, q) > max_step {
                parts.push(Vec::new());
            }
        }
        if let Some(v) = parts.last_mut() {
            v.push(*p);
        }
    }
    parts.retain(|p| !p.is_empty());
    parts
}

/// What the legend says about the trial beside the symbols (title, outcome, measures).
#[derive(Debug, Clone, Default)]
pub struct Caption {
    /// The title line.
    pub title: String,
    /// Further lines (genome file, generation, …).
    pub lines: Vec<String>,
}

/// An upper bound of the width of `text` set in a sans-serif font of `size` pixels: per
/// character a little more than DejaVu Sans needs (the widest of the usual sans-serif fonts;
/// the picture is set by whoever views it), so that a legend sized by it is never cut.
pub fn text_width(text: &str, size: f64) -> f64 {
    text.chars()
        .map(|c| match c {
            ' ' | '.' | ',' | ':' | ';' | '\'' | '|' | '!' | '(' | ')' | '[' | ']' | '-' | 'i'
            | 'j' | 'l' | 'I' | 'f' | 't' | 'r' => 0.42,
            'm' | 'w' | 'M' | 'W' | '…' | '—' | '%' | '@' => 1.0,
            c if c.is_uppercase() => 0.78,
            _ => 0.66,
        })
        .sum::<f64>()
        * size
}
