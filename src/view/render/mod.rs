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

use crate::record::trace::recorder::{ActorKind, EventKind, TrialTrace};
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

/// The SVG picture of `trace`.
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
    // The arena's floor.
    let _ = writeln!(
        s,
        r##"<rect id="arena" class="arena" x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}" fill="#f7f7f2" stroke="#ddd"/>"##,
        frame.x(0.0),
        frame.y(0.0),
        frame.len(aw),
        frame.len(ah)
    );
    for (k, a) in w.areas.iter().enumerate() {
        let (fill, stroke) = if a.kind == "safe" {
            ("#cdebc5", "#5a9e4b")
        } else {
            ("#f3ecc2", "#b8a94a")
        };
        let _ = writeln!(
            s,
            r#"<rect id="area-{k}" class="area {}" x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}" fill="{fill}" fill-opacity="0.7" stroke="{stroke}" stroke-dasharray="4 3"/>"#,
            escape(&a.kind),
            frame.x(a.lo[0]),
            frame.y(a.lo[1]),
            frame.len(a.hi[0] - a.lo[0]),
            frame.len(a.hi[1] - a.lo[1])
        );
    }
    for (k, d) in w.doors.iter().enumerate() {
        let mid = [(d.from[0] + d.to[0]) / 2.0, (d.from[1] + d.to[1]) / 2.0];
        let _ = writeln!(
            s,
            r##"<g id="trigger-{k}" class="trigger"><circle cx="{:.1}" cy="{:.1}" r="{:.1}" fill="#ffb347" fill-opacity="0.25" stroke="#e07b00" stroke-width="1.5" stroke-dasharray="4 3"/><line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="#e07b00" stroke-width="0.8" stroke-dasharray="1 4"/></g>"##,
            frame.x(d.trigger[0]),
            frame.y(d.trigger[1]),
            frame.len(d.trigger_radius).max(3.0),
            frame.x(d.trigger[0]),
            frame.y(d.trigger[1]),
            frame.x(mid[0]),
            frame.y(mid[1])
        );
    }
    // Walls: opaque ones solid in their colour, glass dashed and pale.
    for (k, wall) in w.walls.iter().enumerate() {
        let style = if wall.opaque {
            r#"stroke-width="3.5" stroke-linecap="round""#.to_string()
        } else {
            r#"stroke-width="5" stroke-opacity="0.55" stroke-dasharray="7 4""#.to_string()
        };
        let _ = writeln!(
            s,
            r#"<line id="wall-{k}" class="wall{}" x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="{}" {style}/>"#,
            if wall.opaque { "" } else { " glass" },
            frame.x(wall.from[0]),
            frame.y(wall.from[1]),
            frame.x(wall.to[0]),
            frame.y(wall.to[1]),
            rgb(wall.colour)
        );
    }
    // Doors: their state at the end of the trial.
    for (k, d) in w.doors.iter().enumerate() {
        let open = trace
            .events
            .iter()
            .rev()
            .find(|e| e.target_kind.as_deref() == Some("door") && e.target == Some(k))
            .is_some_and(|e| e.event == EventKind::DoorOpen);
        let opened = trace
            .events
            .iter()
            .filter(|e| e.event == EventKind::DoorOpen && e.target == Some(k))
            .count();
        let style = if open {
            r#"stroke-width="2" stroke-dasharray="2 5" stroke-opacity="0.8""#
        } else {
            r#"stroke-width="6""#
        };
        let _ = writeln!(
            s,
            r#"<line id="door-{k}" class="door {}" data-opened="{opened}" x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="{}" {style}/>"#,
            if open { "open" } else { "closed" },
            frame.x(d.from[0]),
            frame.y(d.from[1]),
            frame.x(d.to[0]),
            frame.y(d.to[1]),
            rgb(d.colour)
        );
    }
    for (k, t) in w.teleporters.iter().enumerate() {
        let _ = writeln!(
            s,
            r##"<g id="teleporter-{k}" class="teleporter"><circle cx="{:.1}" cy="{:.1}" r="{:.1}" fill="#c77dff" fill-opacity="0.35" stroke="#7b2cbf" stroke-width="1.5"/><path d="M{:.1},{:.1} L{:.1},{:.1}" stroke="#7b2cbf" stroke-width="1.5" stroke-dasharray="6 4" fill="none" marker-end="url(#arrow)"/><circle cx="{:.1}" cy="{:.1}" r="3" fill="none" stroke="#7b2cbf" stroke-width="1.5"/></g>"##,
            frame.x(t.entry[0]),
            frame.y(t.entry[1]),
            frame.len(t.radius).max(3.0),
            frame.x(t.entry[0]),
            frame.y(t.entry[1]),
            frame.x(t.exit[0]),
            frame.y(t.exit[1]),
            frame.x(t.exit[0]),
            frame.y(t.exit[1])
        );
    }
    // Food: a ring of the type's colour; the disc inside has area ∝ amount left / capacity.
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
    // Landmarks: a star where it is, or on the border in its direction from the arena's centre.
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
    // Wanderers, predators, air predators: their paths, then where they are at the end.
    let r_body = frame.len(w.creature_radius).max(2.0);
    let kinds = [
        ActorKind::Wanderer,
        ActorKind::Predator,
        ActorKind::AirPredator,
    ];
    for kind in kinds {
        let count = match kind {
            ActorKind::Wanderer => w.actors.iter().filter(|a| a.role == "wanderer").count(),
            ActorKind::Predator => w.actors.iter().filter(|a| a.role == "predator").count(),
            ActorKind::AirPredator => w.air_predators.len(),
        };
        for k in 0..count {
            let start = match kind {
                ActorKind::AirPredator => Some(w.air_predators[k].position),
                _ => w
                    .actors
                    .iter()
                    .filter(|a| a.role == kind.name())
                    .nth(k)
                    .map(|a| a.start.position),
            };
            let mut pts: Vec<[f64; 2]> = start.into_iter().collect();
            pts.extend(
                trace
                    .actors
                    .iter()
                    .filter(|a| a.kind == kind && a.index == k)
                    .map(|a| [a.x, a.y]),
            );
            let Some(&end) = pts.last() else { continue };
            let (class, colour) = match kind {
                ActorKind::Wanderer => ("wanderer", "#8d99ae"),
                ActorKind::Predator => ("predator", "#9b2226"),
                ActorKind::AirPredator => ("air-predator", "#bb3e03"),
            };
            let step = match kind {
                ActorKind::AirPredator => {
                    let v = w.air_predators[k].velocity;
                    2.0 * dist(v, [0.0, 0.0]) + 1e-9
                }
                _ => 30.0,
            };
            let _ = write!(s, r#"<g id="{class}-{k}" class="{class}">"#);
            for part in split_at_jumps(&pts, step) {
                let _ = write!(
                    s,
                    r#"<polyline class="{class}-path" points="{}" fill="none" stroke="{colour}" stroke-width="{}" stroke-opacity="0.7"{}/>"#,
                    points(frame, &part),
                    if kind == ActorKind::Wanderer {
                        1.0
                    } else {
                        1.5
                    },
                    if kind == ActorKind::Wanderer {
                        ""
                    } else {
                        r#" stroke-dasharray="5 3""#
                    }
                );
            }
            match kind {
                // A raider away between flights (`pause`) waits outside the arena: no disc.
                ActorKind::AirPredator
                    if end[0] < 0.0
                        || end[1] < 0.0
                        || end[0] > w.arena[0]
                        || end[1] > w.arena[1] => {}
                ActorKind::AirPredator => {
                    let sr = frame.len(w.air_predators[k].strike_radius);
                    let _ = write!(
                        s,
                        r#"<circle cx="{:.1}" cy="{:.1}" r="{sr:.1}" fill="{colour}" fill-opacity="0.12" stroke="{colour}" stroke-dasharray="3 3"/><path d="M{:.1},{:.1} l-7,-4 l0,8 z" fill="{colour}"/>"#,
                        frame.x(end[0]),
                        frame.y(end[1]),
                        frame.x(end[0]) + 4.0,
                        frame.y(end[1])
                    );
                }
                _ => {
                    let _ = write!(
                        s,
                        r##"<circle cx="{:.1}" cy="{:.1}" r="{r_body:.1}" fill="{colour}" stroke="#222" stroke-width="0.8"/>"##,
                        frame.x(end[0]),
                        frame.y(end[1])
                    );
                }
            }
            if kind == ActorKind::Predator {
                if let Some(a) = w.actors.iter().filter(|a| a.role == "predator").nth(k) {
                    for p in &a.waypoints {
                        let _ = write!(
                            s,
                            r#"<rect class="waypoint" x="{:.1}" y="{:.1}" width="6" height="6" fill="none" stroke="{colour}"/>"#,
                            frame.x(p[0]) - 3.0,
                            frame.y(p[1]) - 3.0
                        );
                    }
                }
            }
            let _ = writeln!(s, "</g>");
        }
    }
    // The creatures: path coloured by time (split at teleports), heading every N ticks.
    let n = w.creatures.len();
    let every = (ticks / 40).max(1);
    let max_step = 4.0 * std::f64::consts::PI * 2.0 + 1.0;
    for i in 0..n {
        let rows: Vec<_> = trace.creatures.iter().filter(|c| c.creature == i).collect();
        let mut pts: Vec<([f64; 2], u64)> = vec![(w.creatures[i].position, 0)];
        pts.extend(rows.iter().map(|c| ([c.x, c.y], c.tick)));
        let _ = write!(s, r#"<g id="creature-{i}-path" class="creature-path">"#);
        let chunk = (pts.len() / 120).max(1);
        let mut k = 0;
        while k + 1 < pts.len() {
            let end = (k + chunk).min(pts.len() - 1);
            let seg: Vec<[f64; 2]> = pts[k..=end].iter().map(|p| p.0).collect();
            for part in split_at_jumps(&seg, max_step) {
                if part.len() > 1 {
                    let _ = write!(
                        s,
                        r#"<polyline points="{}" fill="none" stroke="{}" stroke-width="2.2" stroke-linejoin="round"/>"#,
                        points(frame, &part),
                        time_colour(pts[k].1 as f64 / ticks as f64)
                    );
                }
            }
            k = end;
        }
        let _ = writeln!(s, "</g>");
        let _ = write!(s, r#"<g class="headings">"#);
        let mut last_arrow: Option<[f64; 2]> = None;
        for c in rows.iter().filter(|c| c.tick % every == 0) {
            // Not again where the last arrow stands (a creature turning on the spot).
            if last_arrow.is_some_and(|p| dist(p, [c.x, c.y]) < 2.0 * w.creature_radius) {
                continue;
            }
            last_arrow = Some([c.x, c.y]);
            let (x, y) = (frame.x(c.x), frame.y(c.y));
            let l = r_body + 5.0;
            let _ = write!(
                s,
                r##"<line class="heading" x1="{x:.1}" y1="{y:.1}" x2="{:.1}" y2="{:.1}" stroke="#222" stroke-width="1" marker-end="url(#head)"/>"##,
                x + l * libm::cos(c.heading),
                y + l * libm::sin(c.heading)
            );
        }
        let _ = writeln!(s, "</g>");
        let start = w.creatures[i].position;
        let _ = writeln!(
            s,
            r##"<g id="creature-{i}-start" class="creature-start"><circle cx="{:.1}" cy="{:.1}" r="{:.1}" fill="#fff" stroke="{}" stroke-width="2"/><text x="{:.1}" y="{:.1}" font-size="11" font-weight="bold">S{}</text></g>"##,
            frame.x(start[0]),
            frame.y(start[1]),
            r_body,
            time_colour(0.0),
            frame.x(start[0]) + r_body + 2.0,
            frame.y(start[1]) - r_body - 2.0,
            if n > 1 { i.to_string() } else { String::new() }
        );
        if let Some(last) = rows.last() {
            let (x, y) = (frame.x(last.x), frame.y(last.y));
            let _ = writeln!(
                s,
                r##"<g id="creature-{i}" class="creature"><circle cx="{x:.1}" cy="{y:.1}" r="{r_body:.1}" fill="{}" stroke="#222" stroke-width="1.2"/><line x1="{x:.1}" y1="{y:.1}" x2="{:.1}" y2="{:.1}" stroke="#222" stroke-width="1.5"/></g>"##,
                time_colour(1.0),
                x + r_body * 1.6 * libm::cos(last.heading),
                y + r_body * 1.6 * libm::sin(last.heading)
            );
        }
    }
    // Event marks; of the bites of one visit to a food object, the first.
    let mut last_bite: Vec<Option<u64>> = vec![None; w.food.len()];
    for e in &trace.events {
        if let (EventKind::Eat, Some(k)) = (e.event, e.target) {
            let repeat = last_bite[k].is_some_and(|t| e.tick <= t + 20);
            last_bite[k] = Some(e.tick);
            if repeat {
                continue;
            }
        }
        let (x, y) = (frame.x(e.x), frame.y(e.y));
        let mark = match e.event {
            EventKind::Eat => format!(
                r##"<circle class="mark eat" cx="{x:.1}" cy="{y:.1}" r="{:.1}" fill="none" stroke="#1b9e3a" stroke-width="1.2" stroke-opacity="0.6"/>"##,
                frame.len(w.creature_radius).max(6.0)
            ),
            EventKind::Shock => format!(
                r##"<path class="mark shock" d="M{x:.1},{:.1} l5,9 l-10,0 z" fill="#ffb703" stroke="#9a6700" stroke-width="0.8"/>"##,
                y - 6.0
            ),
            EventKind::Teleport => match e.from {
                Some(f) => format!(
                    r##"<line class="mark teleport" x1="{:.1}" y1="{:.1}" x2="{x:.1}" y2="{y:.1}" stroke="#7b2cbf" stroke-width="1" stroke-dasharray="2 3"/>"##,
                    frame.x(f[0]),
                    frame.y(f[1])
                ),
                None => String::new(),
            },
            EventKind::Death => format!(
                r##"<path class="mark death" d="M{:.1},{:.1} l12,12 M{:.1},{:.1} l-12,12" stroke="#000" stroke-width="3"/>"##,
                x - 6.0,
                y - 6.0,
                x + 6.0,
                y - 6.0
            ),
            EventKind::Attack => format!(
                r##"<circle class="mark attack" cx="{x:.1}" cy="{y:.1}" r="{:.1}" fill="none" stroke="#9b2226" stroke-width="2"/>"##,
                r_body + 4.0
            ),
            EventKind::DoorOpen | EventKind::DoorClose => String::new(),
        };
        if !mark.is_empty() {
            let _ = writeln!(s, "{mark}");
        }
    }
    s.push_str(&legend.svg);
    let _ = writeln!(s, "</svg>");
    s
}

/// `text` cut to at most `n` characters, keeping its end (file names end in what matters).
fn shorten(text: &str, n: usize) -> String {
    let count = text.chars().count();
    if count <= n {
        return text.to_string();
    }
    let tail: String = text.chars().skip(count - (n - 1)).collect();
    format!("…{tail}")
}

/// Writes the legend's lines, one under the other, and keeps track of how far right and
/// down they reach.
struct LegendWriter {
    s: String,
    x0: f64,
    y: f64,
    right: f64,
}

impl LegendWriter {
    /// One line: a symbol (drawn around (0, 0)) and its text at x = 34.
    fn line(&mut self, symbol: &str, text: &str) {
        let text = shorten(text, 72);
        let _ = writeln!(
            self.s,
            r#"<g transform="translate({:.1},{:.1})">{symbol}<text x="34" y="4">{}</text></g>"#,
            self.x0,
            self.y,
            escape(&text)
        );
        self.right = self.right.max(self.x0 + 34.0 + text_width(&text, 13.0));
        self.y += 20.0;
    }
}

/// The legend's SVG, how far right its text may reach and its bottom, in pixels.
struct Legend {
    svg: String,
    right: f64,
    bottom: f64,
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

fn legend(trace: &TrialTrace, caption: &Caption, x0: f64, ticks: u64) -> Legend {
    let w = &trace.world;
    let mut lg = LegendWriter {
        s: String::new(),
        x0,
        y: MARGIN + 44.0,
        right: x0,
    };
    let _ = writeln!(lg.s, r#"<g id="legend" class="legend">"#);
    for l in &caption.lines {
        lg.line("", l);
    }
    for o in trace.outcomes.iter().take(4) {
        lg.line(
            "",
            &format!(
                "score {:.4}, shocked ticks {}{}",
                o.score,
                o.shocked_ticks,
                if o.non_finite { " (NaN brain)" } else { "" }
            ),
        );
        lg.line(
            "",
            &format!(
                "metabolism A–D {:.2} {:.2} {:.2} {:.2}",
                o.metabolism[0], o.metabolism[1], o.metabolism[2], o.metabolism[3]
            ),
        );
    }
    let count = |k: EventKind| trace.events.iter().filter(|e| e.event == k).count();
    let travelled = trace
        .creatures
        .iter()
        .rev()
        .find(|c| c.creature == 0)
        .map_or(0.0, |c| c.travelled);
    lg.line(
        "",
        &format!(
            "{ticks} ticks lived, {travelled:.0} LU travelled{}",
            if count(EventKind::Death) > 0 {
                ", died"
            } else {
                ""
            }
        ),
    );
    lg.line(
        "",
        &format!(
            "{} bites, {} shocks, {} teleports",
            count(EventKind::Eat),
            count(EventKind::Shock),
            count(EventKind::Teleport),
        ),
    );
    lg.y += 6.0;
    let _ = writeln!(
        lg.s,
        r#"<g transform="translate({x0:.1},{:.1})"><rect x="0" y="-6" width="180" height="10" fill="url(#time)"/><text x="0" y="18" font-size="11">tick 0</text><text x="180" y="18" font-size="11" text-anchor="end">tick {ticks}</text><text x="190" y="4">path, by time</text></g>"#,
        lg.y
    );
    lg.right = lg.right.max(x0 + 190.0 + text_width("path, by time", 13.0));
    lg.y += 34.0;
    lg.line(
        r##"<line x1="0" y1="0" x2="14" y2="0" stroke="#222" marker-end="url(#head)"/>"##,
        "heading",
    );
    for (t, colour) in FOOD_COLOURS.iter().enumerate() {
        if w.food.iter().any(|f| f.food_type == t) {
            lg.line(&format!(
                    r##"<circle cx="8" cy="0" r="6" fill="#fff" stroke="{colour}" stroke-width="1.5"/><circle cx="8" cy="0" r="4" fill="{colour}"/>"##
                ),
                &format!("food {} (disc: amount left)", (b'A' + t as u8) as char));
        }
    }
    if !w.aversives.is_empty() {
        lg.line(
            r##"<circle cx="8" cy="0" r="6" fill="#9d4edd" fill-opacity="0.55"/>"##,
            "aversive object",
        );
    }
    lg.line(
        r##"<line x1="0" y1="0" x2="24" y2="0" stroke="#808080" stroke-width="3.5"/>"##,
        "wall",
    );
    if w.walls.iter().any(|x| !x.opaque) {
        lg.line(r##"<line x1="0" y1="0" x2="24" y2="0" stroke="#99ccff" stroke-width="5" stroke-opacity="0.55" stroke-dasharray="7 4"/>"##,
            "glass wall (smell passes)");
    }
    if !w.doors.is_empty() {
        lg.line(
            r##"<line x1="0" y1="0" x2="24" y2="0" stroke="#996633" stroke-width="6"/>"##,
            "door, closed at the end",
        );
        lg.line(r##"<line x1="0" y1="0" x2="24" y2="0" stroke="#996633" stroke-width="2" stroke-dasharray="2 5"/>"##,
            "door, open at the end");
        lg.line(r##"<circle cx="8" cy="0" r="7" fill="#ffb347" fill-opacity="0.25" stroke="#e07b00" stroke-dasharray="4 3"/>"##,
            "door trigger");
    }
    if !w.teleporters.is_empty() {
        lg.line(r##"<circle cx="8" cy="0" r="6" fill="#c77dff" fill-opacity="0.35" stroke="#7b2cbf"/>"##,
            "teleporter entry → exit");
    }
    if w.areas.iter().any(|a| a.kind == "safe") {
        lg.line(
            r##"<rect x="0" y="-6" width="20" height="12" fill="#cdebc5" stroke="#5a9e4b"/>"##,
            "safe area (nest)",
        );
    }
    if w.areas.iter().any(|a| a.kind != "safe") {
        lg.line(
            r##"<rect x="0" y="-6" width="20" height="12" fill="#f3ecc2" stroke="#b8a94a"/>"##,
            "area",
        );
    }
    if !w.landmarks.is_empty() {
        lg.line(
            r##"<polygon points="8.0,-7.0 9.8,-2.4 14.7,-2.2 10.9,0.9 12.1,5.7 8.0,3.0 3.9,5.7 5.1,0.9 1.3,-2.2 6.2,-2.4" fill="#f4d35e" stroke="#a07c00"/>"##,
            "landmark (beacon; bearing from start)",
        );
    }
    if w.actors.iter().any(|a| a.role == "predator") {
        lg.line(
            r##"<circle cx="8" cy="0" r="5" fill="#9b2226"/>"##,
            "ground predator and its path",
        );
    }
    if !w.air_predators.is_empty() {
        lg.line(
            r##"<line x1="0" y1="0" x2="24" y2="0" stroke="#bb3e03" stroke-dasharray="5 3"/>"##,
            "air predator track, strike disc",
        );
    }
    if w.actors.iter().any(|a| a.role == "wanderer") {
        lg.line(
            r##"<circle cx="8" cy="0" r="5" fill="#8d99ae"/>"##,
            "wanderer and its path",
        );
    }
    // The marks of the events this trial had, and only those.
    let had = |k: EventKind| trace.events.iter().any(|e| e.event == k);
    if had(EventKind::Eat) {
        lg.line(
            r##"<circle cx="8" cy="0" r="6" fill="none" stroke="#1b9e3a"/>"##,
            "ate here",
        );
    }
    if had(EventKind::Shock) {
        lg.line(
            r##"<path d="M8,-6 l5,9 l-10,0 z" fill="#ffb703"/>"##,
            "shocked (onset)",
        );
    }
    if had(EventKind::Attack) {
        lg.line(
            r##"<circle cx="8" cy="0" r="6" fill="none" stroke="#9b2226" stroke-width="2"/>"##,
            "attacked",
        );
    }
    if had(EventKind::Death) {
        lg.line(
            r##"<path d="M2,-6 l12,12 M14,-6 l-12,12" stroke="#000" stroke-width="3"/>"##,
            "died",
        );
    }
    let _ = writeln!(lg.s, "</g>");
    Legend {
        svg: lg.s,
        right: lg.right,
        // The last line's text reaches 4 px below its baseline's row, the row 20 px apart.
        bottom: lg.y - 20.0 + 8.0,
    }
}
