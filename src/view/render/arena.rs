//! The trajectory picture's fixed layers under the objects: the arena's floor, areas, door
//! triggers, walls, doors (as they stand at the end) and teleporters.

use super::frame::{escape, rgb, Frame};
use crate::evo::trace::{EventKind, TrialTrace};
use std::fmt::Write as _;

/// The arena's floor and its areas (safe ones green), under everything else.
pub(super) fn floor_and_areas(s: &mut String, trace: &TrialTrace, frame: Frame) {
    let w = &trace.world;
    let [aw, ah] = w.arena;
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
}

/// Door triggers: a dashed orange circle, a dotted line to the middle of their door.
pub(super) fn triggers(s: &mut String, trace: &TrialTrace, frame: Frame) {
    let w = &trace.world;
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
}

/// Walls: opaque ones solid in their colour, glass dashed and pale.
pub(super) fn walls(s: &mut String, trace: &TrialTrace, frame: Frame) {
    let w = &trace.world;
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
}

/// Doors as they stand at the end of the trial: solid when closed, dotted when open.
pub(super) fn doors(s: &mut String, trace: &TrialTrace, frame: Frame) {
    let w = &trace.world;
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
}

/// Teleporter entries, each with a dashed arrow to its exit.
pub(super) fn teleporters(s: &mut String, trace: &TrialTrace, frame: Frame) {
    let w = &trace.world;
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
}
