//! Fitness plots (`berry-evolve plot`), drawn with plotters' SVG backend.
//!
//! The tables are read by [`crate::record::plot::Table`] (which also writes the picture),
//! each by its header names, so columns added later (or in another order) just work:
//!
//! - a run's `fitness.csv`: the x axis is `generation`; a curve is drawn for each of `best`,
//!   `mean`, `median`, `worst` and `validation_best` that the header has (empty or non-finite
//!   cells are left out of their curve);
//! - a MAP-Elites run's `fitness.csv` also gives [`qd_plot`] (QD score and coverage);
//! - a `summary.csv` across seeds: the x axis is `generation`; for every column `Q_median`
//!   (e.g. `best_median`, `mean_median`, `validation_median`) a median line, with a band from
//!   `Q_q1` to `Q_q3` (first and third quartiles across seeds) when both columns exist.
//!
//! Every curve is one `<polyline>` of the SVG (its legend sample is another, of two points);
//! a curve with values on some generations only (validation) also marks each with a circle.
//! The legend (`<g id="legend">`, a framed box) stands below the plot, outside the axes, so
//! that it never covers a curve whatever the curves do; its entries flow left to right in
//! rows as wide as the picture, and the picture grows by the rows it needs.
//! Text is written as SVG `<text>` for the viewer to set, so no font file is needed. PNG is
//! not offered: plotters' bitmap backend needs a font file to draw text (system fonts through
//! font-kit, or a TTF compiled in for ab_glyph) and the `image` crate; convert the SVG
//! instead (`rsvg-convert plot.svg -o plot.png`).

use super::TAB10;
use crate::record::plot::{PlotError, Table};
use crate::view::render::text_width;
use plotters::prelude::*;

/// Size of every plot in pixels, without its legend below.
const SIZE: (u32, u32) = (800, 500);
/// The legend's font size, row height and margin from the picture's sides, in pixels.
const LEGEND_FONT: f64 = 14.0;
const LEGEND_ROW: f64 = 22.0;
const LEGEND_MARGIN: f64 = 12.0;

/// One named curve, optionally with a band.
struct Curve {
    name: String,
    points: Vec<(f64, f64)>,
    band: Option<Vec<(f64, f64, f64)>>,
    colour: RGBColor,
}

/// Colours of the curves, in order (best, mean, median, worst, validation; then more).
const COLOURS: [RGBColor; 8] = [
    TAB10[0], TAB10[1], TAB10[2], TAB10[3], TAB10[4], TAB10[5], TAB10[6], TAB10[7],
];

/// The curves of a run's `fitness.csv`, in the order of [`RUN_COLUMNS`] (the ones present).
pub const RUN_COLUMNS: [&str; 5] = ["best", "mean", "median", "worst", "validation_best"];

fn generation_column(table: &Table, hint: &'static str) -> Result<usize, PlotError> {
    table.column("generation").ok_or_else(|| PlotError::Column {
        path: table.path.clone(),
        column: "generation".into(),
        header: table.header.join(","),
        hint,
    })
}

/// The SVG of a run's fitness curves, titled `title`.
pub fn run_plot(table: &Table, title: &str) -> Result<String, PlotError> {
    let hint = "plot a run folder's fitness.csv or a summary.csv";
    let x = generation_column(table, hint)?;
    let curves: Vec<Curve> = RUN_COLUMNS
        .iter()
        .filter_map(|&name| table.column(name).map(|c| (name, c)))
        .enumerate()
        .map(|(k, (name, c))| Curve {
            name: name.replace('_', " "),
            points: table.points(x, c),
            band: None,
            colour: COLOURS[k % COLOURS.len()],
        })
        .collect();
    if curves.is_empty() {
        return Err(PlotError::Column {
            path: table.path.clone(),
            column: "best".into(),
            header: table.header.join(","),
            hint,
        });
    }
    draw(table, title, "fitness", &curves)
}

/// The SVG of a summary across seeds: per `Q_median` column a median line and, with `Q_q1`
/// and `Q_q3`, a quartile band.
pub fn summary_plot(table: &Table, title: &str) -> Result<String, PlotError> {
    let hint = "a summary.csv has `generation` and `<quantity>_median` columns (e.g. best_median, with best_q1 and best_q3 for the band)";
    let x = generation_column(table, hint)?;
    let mut curves = Vec::new();
    for (c, name) in table.header.iter().enumerate() {
        let Some(quantity) = name.strip_suffix("_median") else {
            continue;
        };
        let band = match (
            table.column(&format!("{quantity}_q1")),
            table.column(&format!("{quantity}_q3")),
        ) {
            (Some(q1), Some(q3)) => Some(
                table
                    .rows
                    .iter()
                    .filter_map(|r| {
                        Some((
                            r.get(x).copied()??,
                            r.get(q1).copied()??,
                            r.get(q3).copied()??,
                        ))
                    })
                    .collect(),
            ),
            _ => None,
        };
        let colour = COLOURS[curves.len() % COLOURS.len()];
        curves.push(Curve {
            name: format!(
                "{} ({})",
                quantity.replace('_', " "),
                if band.is_some() {
                    "median, quartiles"
                } else {
                    "median"
                }
            ),
            points: table.points(x, c),
            band,
            colour,
        });
    }
    if curves.is_empty() {
        return Err(PlotError::Column {
            path: table.path.clone(),
            column: "best_median".into(),
            header: table.header.join(","),
            hint,
        });
    }
    draw(table, title, "fitness across seeds", &curves)
}

fn draw(table: &Table, title: &str, y_label: &str, curves: &[Curve]) -> Result<String, PlotError> {
    let mut xs = Vec::new();
    let mut ys = Vec::new();
    for c in curves {
        for &(x, y) in &c.points {
            xs.push(x);
            ys.push(y);
        }
        for &(x, lo, hi) in c.band.iter().flatten() {
            xs.push(x);
            ys.push(lo);
            ys.push(hi);
        }
    }
    if xs.is_empty() {
        return Err(PlotError::Empty {
            path: table.path.clone(),
            reason: "no rows with numbers to plot (has the run finished a generation?)".into(),
        });
    }
    let range = |v: &[f64]| {
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let pad = if hi > lo { 0.05 * (hi - lo) } else { 1.0 };
        (lo - pad, hi + pad)
    };
    let (x0, x1) = range(&xs);
    let (y0, y1) = range(&ys);
    let x0 = x0.max(xs.iter().copied().fold(f64::INFINITY, f64::min) - 0.5);
    let legend = Legend::lay_out(curves);
    let height = SIZE.1 + legend.height.ceil() as u32;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (SIZE.0, height)).into_drawing_area();
        let e = |e: &dyn std::fmt::Display| PlotError::Draw(e.to_string());
        root.fill(&WHITE).map_err(|x| e(&x))?;
        let (plot_area, _) = root.split_vertically(SIZE.1);
        let mut chart = ChartBuilder::on(&plot_area)
            .caption(title, ("sans-serif", 22))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|x| e(&x))?;
        chart
            .configure_mesh()
            .x_desc("generation")
            .y_desc(y_label)
            .light_line_style(RGBColor(235, 235, 235))
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 15))
            .x_labels(10)
            .x_label_formatter(&|x| {
                // Generations are whole numbers; fractional ticks stay unlabelled.
                if (x - x.round()).abs() < 1e-9 {
                    format!("{x:.0}")
                } else {
                    String::new()
                }
            })
            .draw()
            .map_err(|x| e(&x))?;
        for c in curves {
            if let Some(band) = &c.band {
                let mut outline: Vec<(f64, f64)> = band.iter().map(|&(x, lo, _)| (x, lo)).collect();
                outline.extend(band.iter().rev().map(|&(x, _, hi)| (x, hi)));
                chart
                    .draw_series(std::iter::once(Polygon::new(
                        outline,
                        c.colour.mix(0.2).filled(),
                    )))
                    .map_err(|x| e(&x))?;
            }
        }
        for c in curves {
            let colour = c.colour;
            chart
                .draw_series(LineSeries::new(
                    c.points.iter().copied(),
                    colour.stroke_width(2),
                ))
                .map_err(|x| e(&x))?;
            // A curve with values on some generations only (validation, every N and after
            // the last) gets a mark at each, so that one value is seen too.
            if c.points.len() < table.rows.len() {
                chart
                    .draw_series(c.points.iter().map(|&p| Circle::new(p, 3, colour.filled())))
                    .map_err(|x| e(&x))?;
            }
        }
        root.present().map_err(|x| e(&x))?;
    }
    // plotters' own legend can only stand inside the axes; this one is written below them.
    let end = svg
        .rfind("</svg>")
        .ok_or_else(|| PlotError::Draw("plotters wrote an SVG without its closing tag".into()))?;
    svg.insert_str(end, &legend.svg(curves, f64::from(SIZE.1)));
    Ok(svg)
}

/// The SVG of an archive search's quality-diversity curves over generations, from its
/// fitness.csv's `qd_score` and `coverage` columns: QD score above, coverage (in percent of
/// the cells) below, each on its own axis.
pub fn qd_plot(table: &Table, title: &str) -> Result<String, PlotError> {
    let hint = "a MAP-Elites run's fitness.csv has qd_score and coverage columns";
    let x = generation_column(table, hint)?;
    let column = |name: &str| {
        table.column(name).ok_or_else(|| PlotError::Column {
            path: table.path.clone(),
            column: name.into(),
            header: table.header.join(","),
            hint,
        })
    };
    let qd = table.points(x, column("qd_score")?);
    let coverage: Vec<(f64, f64)> = table
        .points(x, column("coverage")?)
        .into_iter()
        .map(|(g, c)| (g, 100.0 * c))
        .collect();
    if qd.is_empty() {
        return Err(PlotError::Empty {
            path: table.path.clone(),
            reason: "no rows with numbers to plot (has the run finished a generation?)".into(),
        });
    }
    let range = |v: &[(f64, f64)], pick: fn(&(f64, f64)) -> f64| {
        let lo = v.iter().map(pick).fold(f64::INFINITY, f64::min);
        let hi = v.iter().map(pick).fold(f64::NEG_INFINITY, f64::max);
        let pad = if hi > lo { 0.05 * (hi - lo) } else { 1.0 };
        (lo - pad, hi + pad)
    };
    let (x0, x1) = range(&qd, |p| p.0);
    let mut svg = String::new();
    {
        let root =
            SVGBackend::with_string(&mut svg, (SIZE.0, 2 * SIZE.1 - 100)).into_drawing_area();
        let e = |e: &dyn std::fmt::Display| PlotError::Draw(e.to_string());
        root.fill(&WHITE).map_err(|x| e(&x))?;
        let root = root.titled(title, ("sans-serif", 22)).map_err(|x| e(&x))?;
        let panels = root.split_evenly((2, 1));
        for (k, (area, (points, label))) in panels
            .iter()
            .zip([(&qd, "QD score"), (&coverage, "coverage (% of cells)")])
            .enumerate()
        {
            let (y0, y1) = range(points, |p| p.1);
            let mut chart = ChartBuilder::on(area)
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(70)
                .build_cartesian_2d(x0..x1, y0..y1)
                .map_err(|x| e(&x))?;
            chart
                .configure_mesh()
                .x_desc("generation")
                .y_desc(label)
                .light_line_style(RGBColor(235, 235, 235))
                .label_style(("sans-serif", 14))
                .axis_desc_style(("sans-serif", 15))
                .x_labels(10)
                .x_label_formatter(&|x| {
                    if (x - x.round()).abs() < 1e-9 {
                        format!("{x:.0}")
                    } else {
                        String::new()
                    }
                })
                .draw()
                .map_err(|x| e(&x))?;
            chart
                .draw_series(LineSeries::new(
                    points.iter().copied(),
                    COLOURS[k].stroke_width(2),
                ))
                .map_err(|x| e(&x))?;
        }
        root.present().map_err(|x| e(&x))?;
    }
    Ok(svg)
}

/// Where the legend's entries go: rows of (curve index, x offset), and the box's size.
struct Legend {
    rows: Vec<Vec<(usize, f64)>>,
    width: f64,
    height: f64,
}

impl Legend {
    /// The width of one entry: the line sample, a gap, the name, a gap to the next.
    fn entry_width(c: &Curve) -> f64 {
        28.0 + text_width(&c.name, LEGEND_FONT) + 18.0
    }

    /// Entries left to right, a new row when the next would pass the picture's width.
    fn lay_out(curves: &[Curve]) -> Legend {
        let room = f64::from(SIZE.0) - 2.0 * LEGEND_MARGIN - 16.0;
        let mut rows: Vec<Vec<(usize, f64)>> = vec![Vec::new()];
        let mut x = 0.0;
        let mut width: f64 = 0.0;
        for (k, c) in curves.iter().enumerate() {
            let w = Self::entry_width(c);
            if x > 0.0 && x + w > room {
                rows.push(Vec::new());
                x = 0.0;
            }
            if let Some(row) = rows.last_mut() {
                row.push((k, x));
            }
            x += w;
            width = width.max(x);
        }
        Legend {
            height: rows.len() as f64 * LEGEND_ROW + 16.0 + LEGEND_MARGIN,
            width: width.min(room) + 16.0,
            rows,
        }
    }

    /// The legend's SVG: a framed box centred below the plot, whose top is at `top`.
    fn svg(&self, curves: &[Curve], top: f64) -> String {
        let x0 = ((f64::from(SIZE.0) - self.width) / 2.0).round();
        let box_h = self.height - LEGEND_MARGIN;
        let mut s = format!(
            "<g id=\"legend\" class=\"legend\">\n<rect x=\"{x0:.0}\" y=\"{top:.0}\" width=\"{:.0}\" height=\"{box_h:.0}\" fill=\"#FFFFFF\" stroke=\"#000000\" stroke-width=\"1\"/>\n",
            self.width
        );
        for (r, row) in self.rows.iter().enumerate() {
            let y = top + 8.0 + LEGEND_ROW * (r as f64 + 0.5);
            for &(k, dx) in row {
                let c = &curves[k];
                let x = x0 + 8.0 + dx;
                let RGBColor(red, green, blue) = c.colour;
                let colour = format!("#{red:02X}{green:02X}{blue:02X}");
                if c.band.is_some() {
                    s.push_str(&format!(
                        "<rect x=\"{x:.0}\" y=\"{:.0}\" width=\"20\" height=\"12\" fill=\"{colour}\" fill-opacity=\"0.2\" stroke=\"none\"/>\n",
                        y - 6.0
                    ));
                }
                s.push_str(&format!(
                    "<polyline fill=\"none\" stroke=\"{colour}\" stroke-width=\"2\" points=\"{x:.0},{y:.0} {:.0},{y:.0}\"/>\n<text x=\"{:.0}\" y=\"{y:.0}\" dy=\"0.35em\" font-family=\"sans-serif\" font-size=\"{LEGEND_FONT}\" fill=\"#000000\">{}</text>\n",
                    x + 20.0,
                    x + 28.0,
                    escape(&c.name)
                ));
            }
        }
        s.push_str("</g>\n");
        s
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}
