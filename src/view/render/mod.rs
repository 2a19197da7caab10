//! Trajectory pictures (`berry-evolve render`): one trial drawn from its [`TrialTrace`] alone,
//! the arena to scale in the report's frame (x to the right, y downwards, origin top left).
//!
//! The SVG is written element by element here rather than with plotters: every wall and
//! object is one element with an `id` and a `class` (`wall`, `wall glass`, `door open`,
//! `door closed`, `trigger`, `teleporter`, `area safe`, `landmark`, `food type-a`,
//! `aversive`, `predator`, `air-predator`, `wanderer`, `creature-path`, `mark eat`, …), so
//! that a test (or a stylesheet) can find each one; glass is dashed and pale, teleporters have
//! arrow markers to their exits; plotters' SVG backend writes anonymous shapes without ids,
//! classes, dash patterns or markers.
//!
//! What is drawn: areas (safe ones green), door triggers (dashed orange circles, a dotted line
//! to their door), walls in their colours, doors (solid when closed at the end of the trial,
//! dotted when open), teleporter entries with an arrow to the exit, landmarks (inside the
//! arena a star; outside, a star on the border in their direction, with the bearing from the
//! creature's start), food by type A–D (red, blue, green, orange) as a ring whose filled disc
//! shows the amount left at the end (area ∝ amount / capacity), aversive objects (crossed
//! purple discs), ground predators with their paths and waypoints, air-predator tracks (one
//! segment per flight) with the strike disc at the end, wanderers with their paths; each
//! creature's path coloured by time (dark blue at tick 0 to yellow at the end, broken at
//! teleports), its heading every N ticks, and marks where it ate (green ring), was shocked
//! (orange triangle), teleported (purple dashed jump) or died (black cross); then a legend
//! and the trial's outcome. The legend names only the kinds of object the world has and the
//! marks of the events the trial had; the picture is as wide as the legend's longest line
//! needs, measured by [`text_width`] (an upper bound, since the viewer's font sets the text),
//! so that no line is cut at the right edge.

mod arena;
mod legend;
mod objects;
mod paths;

use crate::record::trace::recorder::TrialTrace;
use legend::legend;
use std::fmt::Write as _;

/// Colours of food types A–D.
pub const FOOD_COLOURS: [&str; 4] = ["#d62728", "#1f77b4", "#2ca02c", "#ff7f0e"];

/// The arena's longer side in pixels.
const ARENA_PX: f64 = 720.0;
/// The legend's least width in pixels (wider when its text needs it).
const LEGEND_PX: f64 = 300.0;
const MARGIN: f64 = 20.0;

fn rgb(c: [f64; 3]) -> String {
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

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Maps LU to pixels.
#[derive(Debug, Clone, Copy)]
struct Frame {
    scale: f64,
}

impl Frame {
    fn x(&self, x: f64) -> f64 {
        MARGIN + x * self.scale
    }
    fn y(&self, y: f64) -> f64 {
        MARGIN + 30.0 + y * self.scale
    }
    fn len(&self, l: f64) -> f64 {
        l * self.scale
    }
}

/// A polyline's `points` attribute.
fn points(frame: Frame, pts: &[[f64; 2]]) -> String {
    let mut s = String::with_capacity(pts.len() * 14);
    for p in pts {
        let _ = write!(s, "{:.1},{:.1} ", frame.x(p[0]), frame.y(p[1]));
    }
    s.trim_end().to_string()
}

/// Distance between two points.
fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    ((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1])).sqrt()
}

/// Splits a path where it jumps (teleports, an air predator's new flight).
fn split_at_jumps(pts: &[[f64; 2]], max_step: f64) -> Vec<Vec<[f64; 2]>> {
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

/// The SVG picture of `trace`, drawn layer by layer, bottom first.
pub fn render_svg(trace: &TrialTrace, caption: &Caption) -> String {
    let w = &trace.world;
    let [aw, ah] = w.arena;
    let frame = Frame {
        scale: ARENA_PX / aw.max(ah).max(1e-9),
    };
    let ticks = trace.ticks().max(1);
    // The legend first: the picture is as wide and as tall as it needs.
    let legend = legend(trace, caption, MARGIN * 2.0 + frame.len(aw), ticks);
    let width = (MARGIN * 2.0 + frame.len(aw) + LEGEND_PX).max(legend.right + MARGIN);
    let height = (MARGIN * 2.0 + 30.0 + frame.len(ah))
        .max(legend.bottom + MARGIN)
        .max(560.0);
    let mut s = String::new();
    open_svg(&mut s, width, height, caption);
    arena::floor_and_areas(&mut s, trace, frame);
    arena::triggers(&mut s, trace, frame);
    arena::walls(&mut s, trace, frame);
    arena::doors(&mut s, trace, frame);
    arena::teleporters(&mut s, trace, frame);
    objects::food(&mut s, trace, frame);
    objects::aversives(&mut s, trace, frame);
    objects::landmarks(&mut s, trace, frame);
    paths::actors(&mut s, trace, frame);
    paths::creatures(&mut s, trace, frame, ticks);
    paths::event_marks(&mut s, trace, frame);
    s.push_str(&legend.svg);
    let _ = writeln!(s, "</svg>");
    s
}

/// The `<svg>` element's opening, its shared markers and time gradient, the white page and
/// the title.
fn open_svg(s: &mut String, width: f64, height: f64, caption: &Caption) {
    let _ = writeln!(
        s,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif" font-size="13">
<defs>
<marker id="arrow" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="7" markerHeight="7" orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 z" fill="#7b2cbf"/></marker>
<marker id="head" viewBox="0 0 10 10" refX="5" refY="5" markerWidth="5" markerHeight="5" orient="auto"><path d="M0,1 L9,5 L0,9 z" fill="#222"/></marker>
<linearGradient id="time" x1="0" x2="1" y1="0" y2="0">{}</linearGradient>
</defs>
<rect width="100%" height="100%" fill="#ffffff"/>
<text x="{MARGIN}" y="{:.0}" font-size="17" font-weight="bold">{}</text>"##,
        (0..=10)
            .map(|k| format!(
                r#"<stop offset="{}" stop-color="{}"/>"#,
                k as f64 / 10.0,
                time_colour(k as f64 / 10.0)
            ))
            .collect::<String>(),
        MARGIN + 16.0,
        escape(&caption.title)
    );
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
