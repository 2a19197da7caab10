//! View: the pictures, drawn from what a trial or a run left behind (a trace, a CSV's rows)
//! and returned as text: the trajectory picture (`render`), the replay page
//! (`replay_html`), the fitness plots (`plot`), the per-episode learning curve
//! (`episode_curve`) and a MAP-Elites archive's heat map
//! (`heat_map`). Above `record` (whose traces and tables it draws, and whose atomic writes
//! put the replay page on disk), below `run` and `cli`, which say what to draw and where.

pub mod episode_curve;
pub mod heat_map;
pub mod plot;
pub mod render;
pub mod replay_html;
