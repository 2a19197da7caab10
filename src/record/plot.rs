//! Fitness plots (`berry-evolve plot`), drawn with plotters' SVG backend.
//!
//! Two kinds of table are read, each by its header names, so columns added later (or in
//! another order) just work:
//!
//! - a run's `fitness.csv`: the x axis is `generation`; a curve is drawn for each of `best`,
//!   `mean`, `median`, `worst` and `validation_best` that the header has (empty or non-finite
//!   cells are left out of their curve);
//! - a `summary.csv` across seeds: the x axis is `generation`; for every column `Q_median`
//!   (e.g. `best_median`, `mean_median`, `validation_median`) a median line, with a band from
//!   `Q_q1` to `Q_q3` (first and third quartiles across seeds) when both columns exist.
//!
//! Every curve is one `<polyline>` of the SVG (its legend sample is another, of two points).
//! Text is written as SVG `<text>` for the viewer to set, so no font file is needed. PNG is
//! not offered: plotters' bitmap backend needs a font file to draw text (system fonts through
//! font-kit, or a TTF compiled in for ab_glyph) and the `image` crate; convert the SVG
//! instead (`rsvg-convert plot.svg -o plot.png`).

use crate::record::atomic::write_atomic;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Why a plot could not be made.
#[derive(Debug, Error)]
pub enum PlotError {
    /// The table could not be read.
    #[error("cannot read {path}: {error}")]
    Read {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        error: csv::Error,
    },
    /// A needed column is missing.
    #[error("{path}: no column `{column}` in its header ({header}); {hint}")]
    Column {
        /// The file.
        path: PathBuf,
        /// The column.
        column: String,
        /// The header it has.
        header: String,
        /// What to do.
        hint: &'static str,
    },
    /// A cell is not a number.
    #[error("{path}: line {line}, column `{column}`: `{value}` is not a number")]
    Number {
        /// The file.
        path: PathBuf,
        /// Line number (1 = header).
        line: usize,
        /// The column.
        column: String,
        /// The cell.
        value: String,
    },
    /// Nothing to draw.
    #[error("{path}: {reason}")]
    Empty {
        /// The file.
        path: PathBuf,
        /// Why.
        reason: String,
    },
    /// Drawing failed.
    #[error("cannot draw the plot: {0}")]
    Draw(String),
    /// The picture could not be written.
    #[error("cannot write {path}: {error}")]
    Write {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        error: std::io::Error,
    },
}

/// A CSV table of numbers, columns by header name; empty cells are None.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// The file it came from.
    pub path: PathBuf,
    /// Header names.
    pub header: Vec<String>,
    /// Rows of cells.
    pub rows: Vec<Vec<Option<f64>>>,
}

impl Table {
    /// Reads a CSV file whose cells are numbers or empty.
    pub fn load(path: &Path) -> Result<Table, PlotError> {
        let read = |error| PlotError::Read {
            path: path.to_path_buf(),
            error,
        };
        let mut reader = csv::Reader::from_path(path).map_err(read)?;
        let header: Vec<String> = reader
            .headers()
            .map_err(read)?
            .iter()
            .map(str::to_string)
            .collect();
        let mut rows = Vec::new();
        for (n, record) in reader.records().enumerate() {
            let record = record.map_err(read)?;
            let row = record
                .iter()
                .zip(&header)
                .map(|(cell, column)| {
                    let cell = cell.trim();
                    if cell.is_empty() {
                        return Ok(None);
                    }
                    cell.parse::<f64>()
                        .map(|x| x.is_finite().then_some(x))
                        .map_err(|_| PlotError::Number {
                            path: path.to_path_buf(),
                            line: n + 2,
                            column: column.clone(),
                            value: cell.to_string(),
                        })
                })
                .collect::<Result<Vec<_>, _>>()?;
            rows.push(row);
        }
        Ok(Table {
            path: path.to_path_buf(),
            header,
            rows,
        })
    }

    /// The index of column `name`.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }

    /// (x, y) points of column `y` against column `x`, leaving out empty cells.
    fn points(&self, x: usize, y: usize) -> Vec<(f64, f64)> {
        self.rows
            .iter()
            .filter_map(|r| Some((r.get(x).copied()??, r.get(y).copied()??)))
            .collect()
    }
}

/// Size of every plot in pixels.
const SIZE: (u32, u32) = (800, 500);

/// One named curve, optionally with a band.
struct Curve {
    name: String,
    points: Vec<(f64, f64)>,
    band: Option<Vec<(f64, f64, f64)>>,
    colour: RGBColor,
}

/// Colours of the curves, in order (best, mean, median, worst, validation; then more).
const COLOURS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
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
            name: format!("{} (median, quartiles)", quantity.replace('_', " ")),
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
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        let e = |e: &dyn std::fmt::Display| PlotError::Draw(e.to_string());
        root.fill(&WHITE).map_err(|x| e(&x))?;
        let mut chart = ChartBuilder::on(&root)
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
                .map_err(|x| e(&x))?
                .label(c.name.clone())
                .legend(move |(x, y)| {
                    PathElement::new([(x, y), (x + 20, y)], colour.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerRight)
            .label_font(("sans-serif", 14))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(|x| e(&x))?;
        root.present().map_err(|x| e(&x))?;
    }
    Ok(svg)
}

/// Writes `svg` to `path` atomically.
pub fn write_svg(path: &Path, svg: &str) -> Result<(), PlotError> {
    write_atomic(path, svg.as_bytes()).map_err(|error| PlotError::Write {
        path: path.to_path_buf(),
        error,
    })
}
