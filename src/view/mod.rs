//! View: the pictures, drawn from what a trial or a run left behind (a trace, a CSV's rows)
//! and returned as text: the trajectory picture (`render`), the replay page
//! (`replay_html`), the fitness plots (`plot`), the per-episode learning curve
//! (`episode_curve`) and a MAP-Elites archive's heat map
//! (`heat_map`). Above `record` (whose traces and tables it draws, and whose atomic writes
//! put the replay page on disk), below `run` and `cli`, which say what to draw and where.

use plotters::style::RGBColor;

/// The line colours of the plots (matplotlib's "tab10", so that curves look as users expect
/// from their own plots): blue, orange, green, red, purple, brown, pink, grey, olive, cyan.
pub(crate) const TAB10: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

pub mod episode_curve;
pub mod heat_map;
pub mod plot;
pub mod render;
pub mod replay_html;
