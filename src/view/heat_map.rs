//! A MAP-Elites archive as a heat map (`berry-evolve plot` on a MAP-Elites run folder): the
//! grid's cells coloured by their elite's fitness, from the rows of the run's `archive.csv`
//! (written and described by [`crate::record::archive`]).

use crate::evo::search::grid::Dimension;
use crate::view::render::text_width;
use std::collections::BTreeMap;

/// The heat map's colours from low to high fitness (viridis at five stops).
const RAMP: [(u8, u8, u8); 5] = [
    (68, 1, 84),
    (59, 82, 139),
    (33, 145, 140),
    (94, 201, 98),
    (253, 231, 37),
];

/// The colour of `t` in [0, 1] on [`RAMP`], as `#RRGGBB`.
fn colour(t: f64) -> String {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let x = t * (RAMP.len() - 1) as f64;
    let k = (x.floor() as usize).min(RAMP.len() - 2);
    let f = x - k as f64;
    let mix = |a: u8, b: u8| (f64::from(a) + f * (f64::from(b) - f64::from(a))).round() as u8;
    let (a, b) = (RAMP[k], RAMP[k + 1]);
    format!(
        "#{:02X}{:02X}{:02X}",
        mix(a.0, b.0),
        mix(a.1, b.1),
        mix(a.2, b.2)
    )
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A number for an axis label: up to 3 decimals, without trailing zeros.
fn short(x: f64) -> String {
    let s = format!("{x:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

/// Where the cells go, in pixels: `nx` × `ny` cells of side `cs` per panel, panels (one per
/// bin of a third descriptor) `cols` to a row `gap` apart, the grid's top left at (`left`,
/// `top`) and its size `grid_w` × `grid_h`.
#[derive(Debug, Clone, Copy)]
struct Grid {
    nx: usize,
    ny: usize,
    cols: usize,
    gap: f64,
    cs: f64,
    left: f64,
    top: f64,
    pw: f64,
    ph: f64,
    grid_w: f64,
    grid_h: f64,
}

/// The archive as a heat map (SVG), titled `title`: each cell coloured by its elite's
/// fitness (viridis, the colour bar at the right gives the scale), empty cells light grey.
/// One dimension: a strip of cells; two: a grid (first descriptor across, second up); three:
/// one such grid per bin of the third descriptor, side by side. Cells are labelled by bin
/// index (as `extract --cell` takes them) and the axes by each range's ends.
pub fn heat_map(dimensions: &[Dimension], elites: &[(Vec<usize>, f64)], title: &str) -> String {
    let nx = dimensions.first().map_or(1, |d| d.bins).max(1);
    let ny = dimensions.get(1).map_or(1, |d| d.bins).max(1);
    let panels = dimensions.get(2).map_or(1, |d| d.bins).max(1);
    let cols = panels.min(4);
    let rows = panels.div_ceil(cols);
    let gap = if panels > 1 { 40.0 } else { 0.0 };
    let room_w = 640.0 - gap * (cols - 1) as f64;
    let room_h = if ny == 1 { 60.0 } else { 440.0 } - gap * (rows - 1) as f64;
    let cs = (room_w / (cols * nx) as f64)
        .min(room_h / (rows * ny) as f64)
        .clamp(2.0, 48.0)
        .floor();
    let (left, top) = (90.0, if panels > 1 { 90.0 } else { 70.0 });
    let pw = cs * nx as f64;
    let ph = cs * ny as f64;
    let grid_w = pw * cols as f64 + gap * (cols - 1) as f64;
    let grid_h = ph * rows as f64 + (gap + 20.0) * (rows - 1) as f64;
    let width = (left + grid_w + 130.0).max(520.0);
    let height = top + grid_h + 80.0;
    let (lo, hi) = elites
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), e| {
            (a.min(e.1), b.max(e.1))
        });
    let scale = |f: f64| if hi > lo { (f - lo) / (hi - lo) } else { 1.0 };
    let cells: usize = dimensions.iter().map(|d| d.bins).product();
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width:.0}\" height=\"{height:.0}\" viewBox=\"0 0 {width:.0} {height:.0}\">\n\
         <rect width=\"100%\" height=\"100%\" fill=\"#FFFFFF\"/>\n\
         <text x=\"{:.0}\" y=\"28\" text-anchor=\"middle\" font-family=\"sans-serif\" font-size=\"20\">{}</text>\n\
         <text x=\"{:.0}\" y=\"50\" text-anchor=\"middle\" font-family=\"sans-serif\" font-size=\"13\" fill=\"#444444\">{} of {cells} cells hold an elite ({:.1}% coverage); grey: empty</text>\n",
        width / 2.0,
        escape(title),
        width / 2.0,
        elites.len(),
        100.0 * elites.len() as f64 / cells.max(1) as f64
    );
    let fitness: BTreeMap<&[usize], f64> = elites.iter().map(|(c, f)| (c.as_slice(), *f)).collect();
    let grid = Grid {
        nx,
        ny,
        cols,
        gap,
        cs,
        left,
        top,
        pw,
        ph,
        grid_w,
        grid_h,
    };
    for p in 0..panels {
        panel(&mut s, dimensions, &grid, p, &fitness, scale);
    }
    axis_names(&mut s, dimensions, &grid);
    colour_bar(&mut s, &grid, elites.is_empty(), lo, hi);
    s
}

/// Panel `p` (the `p`th bin of a third descriptor, or the only one): its cells coloured by
/// `scale`d fitness, empty ones grey, and the bin indices along its axes.
fn panel(
    s: &mut String,
    dimensions: &[Dimension],
    grid: &Grid,
    p: usize,
    fitness: &BTreeMap<&[usize], f64>,
    scale: impl Fn(f64) -> f64,
) {
    let Grid {
        nx,
        ny,
        cols,
        gap,
        cs,
        left,
        top,
        pw,
        ph,
        ..
    } = *grid;
    let label_every = (14.0 / cs).ceil().max(1.0) as usize;
    let px = left + (p % cols) as f64 * (pw + gap);
    let py = top + (p / cols) as f64 * (ph + gap + 20.0);
    s.push_str("<g class=\"panel\">\n");
    if let Some(d) = dimensions.get(2) {
        let w = (d.max - d.min) / d.bins as f64;
        s.push_str(&format!(
            "<text x=\"{:.0}\" y=\"{:.0}\" text-anchor=\"middle\" font-family=\"sans-serif\" font-size=\"12\">{} bin {p}: [{}, {}{}</text>\n",
            px + pw / 2.0,
            py - 8.0,
            escape(&d.measure),
            short(d.min + w * p as f64),
            short(d.min + w * (p + 1) as f64),
            // The last bin holds its top end (and everything clamped above it).
            if p + 1 == d.bins { "]" } else { ")" }
        ));
    }
    for i in 0..nx {
        for j in 0..ny {
            let mut cell = vec![i];
            if dimensions.len() > 1 {
                cell.push(j);
            }
            if dimensions.len() > 2 {
                cell.push(p);
            }
            let x = px + i as f64 * cs;
            let y = py + (ny - 1 - j) as f64 * cs;
            let (fill, tip) = match fitness.get(cell.as_slice()) {
                Some(&f) => (colour(scale(f)), format!("cell {cell:?}: fitness {f}")),
                None => ("#EEEEEE".to_string(), format!("cell {cell:?}: empty")),
            };
            s.push_str(&format!(
                "<rect x=\"{x:.1}\" y=\"{y:.1}\" width=\"{cs:.1}\" height=\"{cs:.1}\" fill=\"{fill}\" stroke=\"#FFFFFF\" stroke-width=\"{:.1}\"><title>{}</title></rect>\n",
                (cs / 16.0).min(1.0),
                tip.replace(['[', ']'], "")
            ));
        }
    }
    // Bin indices along the axes, every few bins when cells are small.
    for i in (0..nx).step_by(label_every) {
        s.push_str(&format!(
            "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\" font-family=\"sans-serif\" font-size=\"10\" fill=\"#444444\">{i}</text>\n",
            px + (i as f64 + 0.5) * cs,
            py + ph + 12.0
        ));
    }
    if dimensions.len() > 1 {
        for j in (0..ny).step_by(label_every) {
            s.push_str(&format!(
                "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\" dy=\"0.35em\" font-family=\"sans-serif\" font-size=\"10\" fill=\"#444444\">{j}</text>\n",
                px - 4.0,
                py + (ny - 1 - j) as f64 * cs + cs / 2.0
            ));
        }
    }
    s.push_str("</g>\n");
}

/// Axis names with their ranges, once for the whole figure.
fn axis_names(s: &mut String, dimensions: &[Dimension], grid: &Grid) {
    let Grid {
        left,
        top,
        grid_w,
        grid_h,
        ..
    } = *grid;
    if let Some(d) = dimensions.first() {
        s.push_str(&format!(
            "<text x=\"{:.0}\" y=\"{:.0}\" text-anchor=\"middle\" font-family=\"sans-serif\" font-size=\"14\">{}: {} to {} in {} bins (bin index under each column)</text>\n",
            left + grid_w / 2.0,
            top + grid_h + 36.0,
            escape(&d.measure),
            short(d.min),
            short(d.max),
            d.bins
        ));
    }
    if let Some(d) = dimensions.get(1) {
        let (x, y) = (left - 40.0, top + grid_h / 2.0);
        let text = format!(
            "{}: {} to {} in {} bins",
            d.measure,
            short(d.min),
            short(d.max),
            d.bins
        );
        // As large as fits along the grid's side (at most 14, at least 9).
        let size = (14.0 * (grid_h + 40.0) / text_width(&text, 14.0)).clamp(9.0, 14.0);
        s.push_str(&format!(
            "<text x=\"{x:.0}\" y=\"{y:.0}\" transform=\"rotate(-90 {x:.0} {y:.0})\" text-anchor=\"middle\" font-family=\"sans-serif\" font-size=\"{size:.1}\">{}</text>\n",
            escape(&text)
        ));
    }
}

/// The colour bar right of the grid, labelled with the highest and lowest fitness (dashes
/// when the archive is `empty`), and the picture's end.
fn colour_bar(s: &mut String, grid: &Grid, empty: bool, lo: f64, hi: f64) {
    let Grid {
        left,
        top,
        grid_w,
        grid_h,
        ..
    } = *grid;
    let bx = left + grid_w + 40.0;
    let bh = grid_h.max(60.0);
    let steps = 50;
    for k in 0..steps {
        let t = k as f64 / (steps - 1) as f64;
        s.push_str(&format!(
            "<rect x=\"{bx:.0}\" y=\"{:.2}\" width=\"16\" height=\"{:.2}\" fill=\"{}\" stroke=\"none\"/>\n",
            top + bh * (1.0 - (k + 1) as f64 / steps as f64),
            bh / steps as f64 + 0.5,
            colour(t)
        ));
    }
    let (top_label, bottom_label) = if empty {
        ("—".to_string(), "—".to_string())
    } else {
        (short(hi), short(lo))
    };
    s.push_str(&format!(
        "<g id=\"colour-bar\"><text x=\"{:.0}\" y=\"{:.0}\" font-family=\"sans-serif\" font-size=\"12\">{top_label}</text>\n\
         <text x=\"{:.0}\" y=\"{:.0}\" font-family=\"sans-serif\" font-size=\"12\">{bottom_label}</text>\n\
         <text x=\"{bx:.0}\" y=\"{:.0}\" font-family=\"sans-serif\" font-size=\"12\">fitness</text></g>\n</svg>\n",
        bx + 22.0,
        top + 10.0,
        bx + 22.0,
        top + bh,
        top - 8.0,
    ));
}
