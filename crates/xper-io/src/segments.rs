//! PNG drawings of line segments in data coordinates with equal scales on both axes (crack
//! patterns, mesh outlines), in the style of [`crate::plot`]: bundled font, legend, atomic
//! write.

use std::io;
use std::ops::Range;
use std::path::Path;

use plotters::prelude::*;

use crate::atomic::{with_path, write_atomic};
use crate::plot::{encode_png, ensure_font};

/// Segments drawn with one colour and width.
#[derive(Debug, Clone, PartialEq)]
pub struct SegmentLayer {
    /// Legend text; an empty label leaves the layer out of the legend.
    pub label: String,
    /// RGB colour.
    pub color: [u8; 3],
    /// Line width in pixels, at least 1.
    pub width: u32,
    /// Segments `[[x0, y0], [x1, y1]]` in data units; non-finite ones are skipped.
    pub segments: Vec<[[f64; 2]; 2]>,
}

/// Pixels of the figure around the plotting area: title band, axis label areas, margins.
const TITLE: u32 = 40;
const X_AREA: u32 = 45;
const Y_AREA: u32 = 80;
const MARGIN: u32 = 15;
/// Height of one legend line below the drawing (px): the legend never covers the drawing.
const LEGEND_LINE: u32 = 20;

fn finite(s: &[[f64; 2]; 2]) -> bool {
    s.iter().flatten().all(|v| v.is_finite())
}

/// The data box of the finite segments with a 3% margin, widened to a square when flat;
/// `0..1` squared when there is nothing to draw.
fn data_box(layers: &[SegmentLayer]) -> (Range<f64>, Range<f64>) {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for p in (layers.iter())
        .flat_map(|l| l.segments.iter().filter(|s| finite(s)))
        .flatten()
    {
        for d in 0..2 {
            lo[d] = lo[d].min(p[d].clamp(-1e300, 1e300));
            hi[d] = hi[d].max(p[d].clamp(-1e300, 1e300));
        }
    }
    if lo[0] > hi[0] {
        return (0.0..1.0, 0.0..1.0);
    }
    let span = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    let span = if span > 0.0 {
        span
    } else {
        lo[0].abs().max(1.0)
    };
    let pad = 0.03 * span;
    // Each axis at least 5% of the other so a thin drawing keeps a usable height.
    let grow = |d: usize| ((0.05 * span - (hi[d] - lo[d])) / 2.0).max(0.0) + pad;
    let (gx, gy) = (grow(0), grow(1));
    (lo[0] - gx..hi[0] + gx, lo[1] - gy..hi[1] + gy)
}

/// Draws `layers` (first layer underneath) with equal x and y scales into a PNG of `width`
/// pixels, its height following the aspect ratio of the data (between 200 and 4000 pixels),
/// under a figure `title`, with axis descriptions `x_label` and `y_label` and a legend of the
/// labelled layers. Written to `path` atomically.
pub fn plot_segments(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    layers: &[SegmentLayer],
    width: u32,
) -> io::Result<()> {
    if width < 300 {
        return Err(with_path(
            path,
            format!("drawing too small: {width} pixels wide (min 300)"),
            io::ErrorKind::InvalidInput,
        ));
    }
    let (xr, yr) = data_box(layers);
    let plot_w = (width - Y_AREA - 2 * MARGIN) as f64;
    let plot_h = plot_w * (yr.end - yr.start) / (xr.end - xr.start);
    let legend = legend_height(layers);
    let height = (plot_h as u32 + TITLE + X_AREA + 2 * MARGIN).clamp(200, 4000) + legend;
    let fail = |e: String| with_path(path, format!("drawing failed: {e}"), io::ErrorKind::Other);
    ensure_font().map_err(fail)?;
    let mut buf = vec![255u8; width as usize * height as usize * 3];
    render(
        &mut buf,
        (width, height),
        title,
        (x_label, y_label),
        layers,
        (xr, yr),
    )
    .map_err(fail)?;
    let png = encode_png(&buf, width, height).map_err(fail)?;
    write_atomic(path, &png)
}

/// Height of the legend below the drawing (px): one line per labelled layer.
fn legend_height(layers: &[SegmentLayer]) -> u32 {
    let n = layers.iter().filter(|l| !l.label.is_empty()).count() as u32;
    if n == 0 {
        0
    } else {
        n * LEGEND_LINE + MARGIN / 2
    }
}

fn render(
    buf: &mut [u8],
    size: (u32, u32),
    title: &str,
    labels: (&str, &str),
    layers: &[SegmentLayer],
    (xr, yr): (Range<f64>, Range<f64>),
) -> Result<(), String> {
    let root = BitMapBackend::with_buffer(buf, size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let (top, body) = root.split_vertically(TITLE);
    top.titled(title, ("sans-serif", 24))
        .map_err(|e| e.to_string())?;
    let body_height = size.1 - TITLE;
    let (body, legend_area) = body.split_vertically(body_height - legend_height(layers));
    let mut chart = ChartBuilder::on(&body)
        .margin(MARGIN)
        .x_label_area_size(X_AREA)
        .y_label_area_size(Y_AREA)
        .build_cartesian_2d(xr, yr)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(labels.0)
        .y_desc(labels.1)
        .x_labels(6)
        .y_labels(6)
        .x_label_formatter(&|v| format!("{v:.3e}"))
        .y_label_formatter(&|v| format!("{v:.3e}"))
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 15))
        .draw()
        .map_err(|e| e.to_string())?;
    for layer in layers {
        let [r, g, b] = layer.color;
        let style = RGBColor(r, g, b).stroke_width(layer.width.max(1));
        let lines = (layer.segments.iter())
            .filter(|s| finite(s))
            .map(|s| PathElement::new(vec![(s[0][0], s[0][1]), (s[1][0], s[1][1])], style));
        chart.draw_series(lines).map_err(|e| e.to_string())?;
    }
    // The legend, one line per labelled layer, below the drawing.
    let labelled = layers.iter().filter(|l| !l.label.is_empty());
    for (k, layer) in labelled.enumerate() {
        let [r, g, b] = layer.color;
        let style = RGBColor(r, g, b).stroke_width(layer.width.max(1) + 1);
        let y = (LEGEND_LINE / 2 + k as u32 * LEGEND_LINE) as i32;
        let x = (Y_AREA + MARGIN) as i32;
        legend_area
            .draw(&PathElement::new(vec![(x, y), (x + 30, y)], style))
            .map_err(|e| e.to_string())?;
        legend_area
            .draw(&Text::new(
                layer.label.clone(),
                (x + 40, y - 7),
                ("sans-serif", 13).into_font().color(&BLACK),
            ))
            .map_err(|e| e.to_string())?;
    }
    root.present().map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn data_box_keeps_the_drawing_and_handles_degenerate_input() {
        let layer = |segments| SegmentLayer {
            label: String::new(),
            color: [0, 0, 0],
            width: 1,
            segments,
        };
        assert_eq!(data_box(&[]), (0.0..1.0, 0.0..1.0));
        let (x, y) = data_box(&[layer(vec![
            [[0.0, 0.0], [2.0, 1.0]],
            [[f64::NAN, 0.0], [9.0, 9.0]],
        ])]);
        assert!(x.start < 0.0 && x.end > 2.0 && x.end < 2.2, "{x:?}");
        assert!(y.start < 0.0 && y.end > 1.0 && y.end < 1.2, "{y:?}");
        let (_, y) = data_box(&[layer(vec![[[0.0, 5.0], [1.0, 5.0]]])]);
        assert!(y.end - y.start >= 0.05, "{y:?}");
    }
}
