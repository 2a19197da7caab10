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
mod frame;
mod legend;
mod objects;
mod paths;

pub use frame::{text_width, time_colour, Caption, FOOD_COLOURS};

use crate::evo::trace::TrialTrace;
use frame::{escape, Frame, ARENA_PX, LEGEND_PX, MARGIN};
use legend::legend;
use std::fmt::Write as _;

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
