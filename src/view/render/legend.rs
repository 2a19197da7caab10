//! The trajectory picture's legend, right of the arena: the caption and the trial's outcome,
//! then a key to the symbols naming only the kinds of object the world has and the marks of
//! the events the trial had.

use super::frame::{escape, text_width, Caption, FOOD_COLOURS, MARGIN};
use crate::evo::trace::{EventKind, TrialTrace, WorldDescription};
use std::fmt::Write as _;

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
pub(super) struct Legend {
    pub(super) svg: String,
    pub(super) right: f64,
    pub(super) bottom: f64,
}

pub(super) fn legend(trace: &TrialTrace, caption: &Caption, x0: f64, ticks: u64) -> Legend {
    let mut lg = LegendWriter {
        s: String::new(),
        x0,
        y: MARGIN + 44.0,
        right: x0,
    };
    let _ = writeln!(lg.s, r#"<g id="legend" class="legend">"#);
    trial_lines(&mut lg, trace, caption, ticks);
    time_and_heading_keys(&mut lg, x0, ticks);
    world_keys(&mut lg, &trace.world);
    event_keys(&mut lg, trace);
    let _ = writeln!(lg.s, "</g>");
    Legend {
        svg: lg.s,
        right: lg.right,
        // The last line's text reaches 4 px below its baseline's row, the row 20 px apart.
        bottom: lg.y - 20.0 + 8.0,
    }
}

/// The caption's lines, each creature's outcome (up to 4) and what the trial came to.
fn trial_lines(lg: &mut LegendWriter, trace: &TrialTrace, caption: &Caption, ticks: u64) {
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
}

/// The path's colour by time, and the heading arrow.
fn time_and_heading_keys(lg: &mut LegendWriter, x0: f64, ticks: u64) {
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
}

/// The kinds of object this world has, and only those.
fn world_keys(lg: &mut LegendWriter, w: &WorldDescription) {
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
}

/// The marks of the events this trial had, and only those.
fn event_keys(lg: &mut LegendWriter, trace: &TrialTrace) {
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
}
