//! The trajectory picture's moving things: the paths of wanderers, predators and air
//! predators, the creatures' paths coloured by time with their headings, and the marks of the
//! trial's events.

use super::frame::{dist, points, split_at_jumps, time_colour, Frame};
use crate::evo::trace::{ActorKind, EventKind, TrialTrace};
use std::fmt::Write as _;

/// Wanderers, predators, air predators: their paths, then where they are at the end.
pub(super) fn actors(s: &mut String, trace: &TrialTrace, frame: Frame) {
    let w = &trace.world;
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
}

/// The creatures: path coloured by time (split at teleports), heading every N ticks, the
/// start and the body at the end.
pub(super) fn creatures(s: &mut String, trace: &TrialTrace, frame: Frame, ticks: u64) {
    let w = &trace.world;
    let r_body = frame.len(w.creature_radius).max(2.0);
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
}

/// Event marks; of the bites of one visit to a food object, the first.
pub(super) fn event_marks(s: &mut String, trace: &TrialTrace, frame: Frame) {
    let w = &trace.world;
    let r_body = frame.len(w.creature_radius).max(2.0);
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
}
