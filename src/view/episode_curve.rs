//! The per-episode learning curve (`compare --episode-curve FILE.svg`): for lives of several
//! episodes with a switch, the share of correct first choices of each row (a genome, its
//! ablations, the random genomes pooled) drawn against the episode, and against the episodes
//! since the last switch, with chance (0.5) dashed; and the same numbers as CSV.
//!
//! The upper panel averages each episode index over the lives; as the switch falls on another
//! episode in each life, a strip beneath it shows the share of lives whose switch had come
//! before each episode. The lower panel aligns the lives on their last switch (0 = the first
//! episode after it, counting only episodes after a life's first switch): a creature that
//! adapts starts there near 0 and climbs, one that does not stays flat. Each of its points
//! pools fewer lives the further it is from the switch (the CSV's `lives` column says how
//! many). Rows with equal shares would hide each other, so each row is shifted sideways by a
//! fixed small amount (at most 0.15 of an episode; the CSV has the exact x).
//!
//! Every row is one `<polyline>` of stroke width 2 per panel (the legend uses `<line>`), text
//! is SVG `<text>` for the viewer to set, as in [`crate::view::plot`].

use super::TAB10;
use crate::view::render::text_width;
use plotters::prelude::*;
use thiserror::Error;

/// The picture's width, the heights of its two panels and of the switch strip, in pixels.
const WIDTH: u32 = 800;
const TITLE: u32 = 40;
const PANEL: u32 = 380;
const STRIP: u32 = 90;
/// The legend's font size and row height.
const LEGEND_FONT: f64 = 14.0;
const LEGEND_ROW: f64 = 22.0;

/// Row colours in order (the genome files and their ablations): tab10 without its grey,
/// which is the random genomes'.
const COLOURS: [RGBColor; 9] = [
    TAB10[0], TAB10[1], TAB10[2], TAB10[3], TAB10[4], TAB10[5], TAB10[6], TAB10[8], TAB10[9],
];
const GREY: RGBColor = TAB10[7];

/// Why the curve cannot be made.
#[derive(Debug, Error)]
pub enum EpisodeCurveError {
    /// No rows, or no lives.
    #[error("nothing to draw: {0}")]
    Empty(&'static str),
    /// A life's choices do not cover the life's episodes.
    #[error("row `{row}`, life {life}: {got} first choices for {expected} episodes")]
    Length {
        /// The row.
        row: String,
        /// The life (trial) index within the row.
        life: usize,
        /// Choices given.
        got: usize,
        /// Episodes per life.
        expected: usize,
    },
    /// plotters failed.
    #[error("cannot draw the episode curve: {0}")]
    Draw(String),
}

/// One life's episodes: the episodes (from 1) a switch came before, and per episode whether
/// the first choice was correct.
#[derive(Debug, Clone, Copy)]
pub struct LifeEpisodes<'a> {
    /// Episodes (numbered from 1) a switch came before.
    pub switches: &'a [u64],
    /// Per episode, in order.
    pub correct: &'a [bool],
}

/// One row's curve.
#[derive(Debug, Clone, PartialEq)]
pub struct CurveRow {
    /// What the row is (`best.json`, `best.json (frozen)`, `32 random genomes`).
    pub label: String,
    /// How many lives it pools.
    pub lives: usize,
    /// Per episode (index 0 = episode 1), the share of lives whose first choice was correct.
    pub by_episode: Vec<f64>,
    /// Per number of episodes since the last switch (index 0 = the first episode after it),
    /// the share correct and how many lives had such an episode (only lives with a switch).
    pub since_switch: Vec<(f64, usize)>,
    /// Drawn in grey (the random genomes).
    pub baseline: bool,
}

/// Every row's curve and where the switches fell.
#[derive(Debug, Clone, PartialEq)]
pub struct EpisodeCurve {
    /// The picture's title.
    pub title: String,
    /// Episodes per life.
    pub episodes: usize,
    /// Per episode, the share of lives (of the first row) whose first switch came at or before
    /// it, i.e. that had been switched by then.
    pub switched: Vec<f64>,
    /// The rows, in the order drawn.
    pub rows: Vec<CurveRow>,
}

impl CurveRow {
    /// The shares of `lives` (each of `episodes` episodes); `baseline` draws it grey.
    pub fn new(
        label: String,
        lives: &[LifeEpisodes<'_>],
        episodes: usize,
        baseline: bool,
    ) -> Result<CurveRow, EpisodeCurveError> {
        if lives.is_empty() {
            return Err(EpisodeCurveError::Empty("a row without lives"));
        }
        let mut right = vec![0usize; episodes];
        let mut since: Vec<(usize, usize)> = Vec::new();
        for (k, life) in lives.iter().enumerate() {
            if life.correct.len() != episodes {
                return Err(EpisodeCurveError::Length {
                    row: label,
                    life: k,
                    got: life.correct.len(),
                    expected: episodes,
                });
            }
            for (e, &c) in life.correct.iter().enumerate() {
                right[e] += usize::from(c);
                // The last switch at or before episode e + 1 (switches are in order).
                let last = life.switches.iter().rev().find(|&&s| s <= e as u64 + 1);
                if let Some(&s) = last {
                    let d = (e as u64 + 1 - s) as usize;
                    if since.len() <= d {
                        since.resize(d + 1, (0, 0));
                    }
                    since[d].0 += usize::from(c);
                    since[d].1 += 1;
                }
            }
        }
        let n = lives.len() as f64;
        Ok(CurveRow {
            label,
            lives: lives.len(),
            by_episode: right.iter().map(|&r| r as f64 / n).collect(),
            since_switch: since
                .iter()
                .map(|&(r, t)| (r as f64 / t.max(1) as f64, t))
                .collect(),
            baseline,
        })
    }
}

impl EpisodeCurve {
    /// The curve of `rows`, switches counted over `lives` (those of the first row: every row
    /// meets the same lives).
    pub fn new(
        title: String,
        episodes: usize,
        lives: &[LifeEpisodes<'_>],
        rows: Vec<CurveRow>,
    ) -> Result<EpisodeCurve, EpisodeCurveError> {
        if rows.is_empty() || lives.is_empty() {
            return Err(EpisodeCurveError::Empty("no rows"));
        }
        let switched = (1..=episodes as u64)
            .map(|e| {
                let n = lives
                    .iter()
                    .filter(|l| l.switches.first().is_some_and(|&s| s <= e))
                    .count();
                n as f64 / lives.len() as f64
            })
            .collect();
        Ok(EpisodeCurve {
            title,
            episodes,
            switched,
            rows,
        })
    }

    /// The numbers as CSV: `panel,row,x,share_correct,lives,switched_share`, panel `episode`
    /// (x from 1; `switched_share` the share of lives switched by then) then `since_switch`
    /// (x from 0; `lives` those with such an episode).
    pub fn csv(&self) -> String {
        let mut w = csv::Writer::from_writer(Vec::new());
        let mut rows: Vec<Vec<String>> = vec![[
            "panel",
            "row",
            "x",
            "share_correct",
            "lives",
            "switched_share",
        ]
        .map(String::from)
        .to_vec()];
        for r in &self.rows {
            for (e, share) in r.by_episode.iter().enumerate() {
                rows.push(vec![
                    "episode".into(),
                    r.label.clone(),
                    (e + 1).to_string(),
                    format!("{share:.6}"),
                    r.lives.to_string(),
                    format!("{:.6}", self.switched[e]),
                ]);
            }
        }
        for r in &self.rows {
            for (d, (share, n)) in r.since_switch.iter().enumerate() {
                rows.push(vec![
                    "since_switch".into(),
                    r.label.clone(),
                    d.to_string(),
                    format!("{share:.6}"),
                    n.to_string(),
                    String::new(),
                ]);
            }
        }
        for row in rows {
            // Writing to a Vec cannot fail.
            let _ = w.write_record(&row);
        }
        String::from_utf8(w.into_inner().unwrap_or_default()).unwrap_or_default()
    }

    /// The colour of row `k`: the palette in order, grey for the baseline.
    fn colour(&self, k: usize) -> RGBColor {
        if self.rows[k].baseline {
            GREY
        } else {
            let n = self.rows[..k].iter().filter(|r| !r.baseline).count();
            COLOURS[n % COLOURS.len()]
        }
    }

    /// The SVG: the by-episode panel, the switch strip, the since-switch panel (when some
    /// life had a switch) and the legend below.
    pub fn svg(&self) -> Result<String, EpisodeCurveError> {
        let longest = self.rows.iter().map(|r| r.since_switch.len()).max();
        let since = longest.unwrap_or(0);
        let legend = self.legend_rows();
        let legend_height = (legend.len() as f64 * LEGEND_ROW + 24.0).ceil() as u32;
        let panels = TITLE + PANEL + STRIP + if since > 0 { PANEL } else { 0 };
        let mut svg = String::new();
        {
            let e = |x: &dyn std::fmt::Display| EpisodeCurveError::Draw(x.to_string());
            let root = SVGBackend::with_string(&mut svg, (WIDTH, panels + legend_height))
                .into_drawing_area();
            root.fill(&WHITE).map_err(|x| e(&x))?;
            let (top, _) = root.split_vertically(panels);
            let (title, rest) = top.split_vertically(TITLE);
            title
                .titled(&self.title, ("sans-serif", 20))
                .map_err(|x| e(&x))?;
            let (by_episode, rest) = rest.split_vertically(PANEL);
            let (strip, since_area) = rest.split_vertically(STRIP);
            let k = self.episodes as f64;
            let points: Vec<Vec<(f64, f64)>> = self
                .rows
                .iter()
                .map(|r| {
                    r.by_episode
                        .iter()
                        .enumerate()
                        .map(|(i, &s)| (i as f64 + 1.0, s))
                        .collect()
                })
                .collect();
            self.panel(&by_episode, (0.5, k + 0.5), "episode of the life", &points)?;
            // The switch strip: the share of lives switched by each episode.
            let mut chart = ChartBuilder::on(&strip)
                .margin_left(12)
                .margin_right(12)
                .x_label_area_size(30)
                .y_label_area_size(60)
                .build_cartesian_2d(0.5..k + 0.5, 0.0..1.0)
                .map_err(|x| e(&x))?;
            chart
                .configure_mesh()
                .disable_mesh()
                .x_desc("share of lives whose switch had come by each episode")
                .y_desc("switched")
                .y_labels(2)
                .x_labels(self.episodes.min(20))
                .x_label_formatter(&whole)
                .label_style(("sans-serif", 12))
                .axis_desc_style(("sans-serif", 13))
                .draw()
                .map_err(|x| e(&x))?;
            chart
                .draw_series(self.switched.iter().enumerate().map(|(i, &s)| {
                    let x = i as f64 + 1.0;
                    Rectangle::new([(x - 0.4, 0.0), (x + 0.4, s)], GREY.mix(0.5).filled())
                }))
                .map_err(|x| e(&x))?;
            if since > 0 {
                let points: Vec<Vec<(f64, f64)>> = self
                    .rows
                    .iter()
                    .map(|r| {
                        r.since_switch
                            .iter()
                            .enumerate()
                            .map(|(d, &(s, _))| (d as f64, s))
                            .collect()
                    })
                    .collect();
                self.panel(
                    &since_area,
                    (-0.5, since as f64 - 0.5),
                    "episodes since the last switch (0: the first after it)",
                    &points,
                )?;
            }
            root.present().map_err(|x| e(&x))?;
        }
        let end = svg
            .rfind("</svg>")
            .ok_or_else(|| EpisodeCurveError::Draw("an SVG without its closing tag".into()))?;
        svg.insert_str(end, &self.legend_svg(&legend, f64::from(panels)));
        Ok(svg)
    }

    /// One panel: share correct (0 to 1) against `x_desc` over `x`, chance dashed, one line
    /// with a dot per point for each row.
    fn panel<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, plotters::coord::Shift>,
        x: (f64, f64),
        x_desc: &str,
        points: &[Vec<(f64, f64)>],
    ) -> Result<(), EpisodeCurveError> {
        let e = |x: &dyn std::fmt::Display| EpisodeCurveError::Draw(x.to_string());
        let mut chart = ChartBuilder::on(area)
            .margin_left(12)
            .margin_right(12)
            .margin_top(8)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(x.0..x.1, -0.02..1.02)
            .map_err(|x| e(&x))?;
        chart
            .configure_mesh()
            .x_desc(x_desc)
            .y_desc("correct first choice (share)")
            .bold_line_style(RGBColor(225, 225, 225))
            .light_line_style(WHITE)
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 14))
            .x_labels(((x.1 - x.0) as usize).min(20))
            .x_label_formatter(&whole)
            .y_labels(6)
            .draw()
            .map_err(|x| e(&x))?;
        chart
            .draw_series(DashedLineSeries::new(
                [(x.0, 0.5), (x.1, 0.5)],
                6,
                5,
                BLACK.mix(0.6).stroke_width(1),
            ))
            .map_err(|x| e(&x))?;
        // The baseline first, so that the genomes' lines are drawn over it; each row
        // shifted sideways a little (at most ±0.15 episode) so that equal shares stay visible.
        let n = points.len();
        let order = (0..n).filter(|&k| self.rows[k].baseline);
        for k in order.chain((0..n).filter(|&k| !self.rows[k].baseline)) {
            let colour = self.colour(k);
            let dx = if n > 1 {
                0.3 * (k as f64 / (n - 1) as f64 - 0.5)
            } else {
                0.0
            };
            let p: Vec<(f64, f64)> = points[k].iter().map(|&(x, y)| (x + dx, y)).collect();
            chart
                .draw_series(LineSeries::new(p.iter().copied(), colour.stroke_width(2)))
                .map_err(|x| e(&x))?;
            chart
                .draw_series(p.iter().map(|&q| Circle::new(q, 3, colour.filled())))
                .map_err(|x| e(&x))?;
        }
        Ok(())
    }

    /// Legend entry `k`: a row's label and how many lives it pools, or (after the rows)
    /// the chance line.
    fn legend_name(&self, k: usize) -> String {
        match self.rows.get(k) {
            Some(r) => format!("{} ({} lives)", r.label, r.lives),
            None => "chance (0.5)".into(),
        }
    }

    /// The legend's entries in rows as wide as the picture: (row index, x offset).
    fn legend_rows(&self) -> Vec<Vec<(usize, f64)>> {
        let room = f64::from(WIDTH) - 40.0;
        let mut rows: Vec<Vec<(usize, f64)>> = vec![Vec::new()];
        let mut x = 0.0;
        for k in 0..=self.rows.len() {
            let w = 28.0 + text_width(&self.legend_name(k), LEGEND_FONT) + 18.0;
            if x > 0.0 && x + w > room {
                rows.push(Vec::new());
                x = 0.0;
            }
            if let Some(row) = rows.last_mut() {
                row.push((k, x));
            }
            x += w;
        }
        rows
    }

    /// The legend (`<g id="legend">`) below the panels, from `top`, with the chance line's
    /// entry last.
    fn legend_svg(&self, rows: &[Vec<(usize, f64)>], top: f64) -> String {
        let mut s = String::from("<g id=\"legend\" class=\"legend\">\n");
        for (r, row) in rows.iter().enumerate() {
            let y = top + 12.0 + LEGEND_ROW * (r as f64 + 0.5);
            for &(k, dx) in row {
                // The last entry is the chance line's.
                let (RGBColor(red, green, blue), style) = match k < self.rows.len() {
                    true => (self.colour(k), "stroke-width=\"2\""),
                    false => (
                        RGBColor(102, 102, 102),
                        "stroke-width=\"1\" stroke-dasharray=\"6 5\"",
                    ),
                };
                let x = 20.0 + dx;
                s.push_str(&format!(
                    "<line x1=\"{x:.0}\" y1=\"{y:.0}\" x2=\"{:.0}\" y2=\"{y:.0}\" stroke=\"#{red:02X}{green:02X}{blue:02X}\" {style}/>\n<text x=\"{:.0}\" y=\"{y:.0}\" dy=\"0.35em\" font-family=\"sans-serif\" font-size=\"{LEGEND_FONT}\" fill=\"#000000\">{}</text>\n",
                    x + 20.0,
                    x + 28.0,
                    escape(&self.legend_name(k))
                ));
            }
        }
        s.push_str("</g>\n");
        s
    }
}

/// Whole numbers only (episodes), fractional ticks unlabelled.
fn whole(x: &f64) -> String {
    if (x - x.round()).abs() < 1e-9 {
        format!("{x:.0}")
    } else {
        String::new()
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}
