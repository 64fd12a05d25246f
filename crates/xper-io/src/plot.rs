//! PNG line plots: vertically stacked panels, each with axes, labels, a
//! legend and distinct curve colours. Text uses a bundled DejaVu Sans font,
//! so no system font is needed.

use std::io;
use std::ops::Range;
use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::ranged1d::{AsRangedCoord, Ranged, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::atomic::{with_path, write_atomic};

/// The bundled font, registered as the "sans-serif" family.
static FONT: &[u8] = include_bytes!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../assets/fonts/DejaVuSans.ttf"
));

/// Distinct colours (Tableau 10) used for curves, in order.
const COLORS: [RGBColor; 10] = [
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

/// Height in pixels of the figure title band.
const TITLE_HEIGHT: u32 = 40;

/// One line of a panel.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// Legend text; an empty label leaves the curve out of the legend.
    pub label: String,
    /// (x, y) samples; non-finite values are skipped (the line is broken there).
    pub points: Vec<(f64, f64)>,
}

/// One plot area with its own axes.
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    /// Caption above the panel.
    pub title: String,
    /// X axis description.
    pub x_label: String,
    /// Y axis description.
    pub y_label: String,
    /// Curves drawn in this panel.
    pub curves: Vec<Curve>,
    /// Logarithmic y axis; points with y <= 0 are then skipped.
    pub log_y: bool,
}

/// Registers the bundled font once; returns the registration outcome.
pub(crate) fn ensure_font() -> Result<(), String> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            plotters::style::register_font("sans-serif", FontStyle::Normal, FONT)
                .map_err(|_| "bundled DejaVuSans.ttf is not a valid font".to_string())
        })
        .clone()
}

/// Whether a point can be drawn in a panel.
fn usable(p: (f64, f64), log_y: bool) -> bool {
    p.0.is_finite() && p.1.is_finite() && (!log_y || p.1 > 0.0)
}

/// Axis ranges of a panel, in data values.
struct Bounds {
    x: Range<f64>,
    y: Range<f64>,
    log_y: bool,
}

impl Bounds {
    /// Ranges covering the usable points of `panel`.
    /// A log axis with no positive value (a residual of exactly zero, say) falls back to a
    /// linear one, so that the panel shows its curves instead of nothing.
    fn of(panel: &Panel) -> Self {
        let all = || panel.curves.iter().flat_map(|c| c.points.iter().copied());
        let log_y = panel.log_y && all().any(|p| usable(p, true));
        let pts = || all().filter(move |&p| usable(p, log_y));
        let y_values = pts().map(|p| p.1);
        Bounds {
            x: linear_range(pts().map(|p| p.0)),
            y: if log_y {
                log_range(y_values)
            } else {
                linear_range(y_values)
            },
            log_y,
        }
    }

    /// Whether `p` is usable and inside the ranges (points outside, only
    /// possible for values clamped away, would overflow pixel coordinates).
    fn contains(&self, p: (f64, f64)) -> bool {
        usable(p, self.log_y) && self.x.contains(&p.0) && self.y.contains(&p.1)
    }
}

/// Splits a curve into runs of points that can be drawn within `bounds`.
fn segments(points: &[(f64, f64)], bounds: &Bounds) -> Vec<Vec<(f64, f64)>> {
    let mut out = Vec::new();
    let mut current = Vec::new();
    for &p in points {
        if bounds.contains(p) {
            current.push(p);
        } else if !current.is_empty() {
            out.push(std::mem::take(&mut current));
        }
    }
    if !current.is_empty() {
        out.push(current);
    }
    out
}

/// Range of finite `values` with a 5% margin; constant data is widened and
/// no data gives 0..1. Values are clamped to ±1e300 so the span stays finite.
fn linear_range(values: impl Iterator<Item = f64>) -> Range<f64> {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if lo > hi {
        return 0.0..1.0;
    }
    let (lo, hi) = (lo.clamp(-1e300, 1e300), hi.clamp(-1e300, 1e300));
    let span = hi - lo;
    if span <= f64::EPSILON * lo.abs().max(hi.abs()) || span == 0.0 {
        let pad = if lo.abs() > 0.0 { lo.abs() * 0.1 } else { 1.0 };
        return lo - pad..hi + pad;
    }
    lo - 0.05 * span..hi + 0.05 * span
}

/// Range of positive `values` for a log axis, with the margin taken in
/// decades; no data gives 1..10. The range always contains a power of ten
/// (so the axis has labels) and is limited to 300 decades within 1e±307,
/// which plotters' log axis needs to stay finite.
fn log_range(values: impl Iterator<Item = f64>) -> Range<f64> {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v.log10()), hi.max(v.log10()))
    });
    if lo > hi {
        return 1.0..10.0;
    }
    let (lo, hi) = (lo.clamp(-300.0, 300.0), hi.clamp(-300.0, 300.0));
    let pad = if hi - lo < 1e-9 {
        0.5
    } else {
        0.05 * (hi - lo)
    };
    let (mut a, mut b) = (lo - pad, hi + pad);
    if b - a < 1.0 {
        a = a.min(lo.floor());
        b = b.max(hi.ceil());
    }
    let b = b.min(307.0);
    let a = a.max(-307.0).max(b - 300.0);
    10f64.powf(a)..10f64.powf(b)
}

/// Removes trailing zeros (and a trailing point) from a decimal number.
fn trim_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

/// Compact tick label for `v` on an axis spanning `span` (0 for a log axis).
/// Rounding noise much smaller than the span prints as 0.
fn tick(v: f64, span: f64) -> String {
    let a = v.abs();
    if a == 0.0 || (span > 0.0 && a < span * 1e-9) {
        return "0".to_string();
    }
    if !(1e-3..1e5).contains(&a) {
        let digits = if span > 0.0 {
            ((a / span).log10().ceil().max(0.0) as usize + 1).min(12)
        } else {
            1
        };
        let s = format!("{v:.digits$e}");
        let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
        return format!("{}e{exp}", trim_zeros(mantissa));
    }
    let decimals = if span > 0.0 {
        (1.0 - span.log10().floor()).clamp(0.0, 12.0) as usize
    } else {
        4
    };
    trim_zeros(&format!("{v:.decimals$}")).to_string()
}

/// Draws one panel into `area` with y coordinates given by `y_spec`.
fn draw_panel<Y>(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    panel: &Panel,
    bounds: &Bounds,
    y_spec: Y,
) -> Result<(), String>
where
    Y: AsRangedCoord<Value = f64>,
    Y::CoordDescType: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let x_span = bounds.x.end - bounds.x.start;
    let y_span = if bounds.log_y {
        0.0
    } else {
        bounds.y.end - bounds.y.start
    };
    let (w, h) = area.dim_in_pixel();
    let x_labels = (w / 90).clamp(2, 10) as usize;
    let y_labels = (h / 35).clamp(2, 10) as usize;
    let x_tick = |v: &f64| tick(*v, x_span);
    let y_tick = |v: &f64| tick(*v, y_span);
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d::<Range<f64>, Y>(bounds.x.clone(), y_spec)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc(&panel.x_label)
        .y_desc(&panel.y_label)
        .x_labels(x_labels)
        .y_labels(y_labels)
        .x_label_formatter(&x_tick)
        .y_label_formatter(&y_tick)
        .light_line_style(RGBColor(235, 235, 235))
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 15))
        .draw()
        .map_err(|e| e.to_string())?;
    let mut any_label = false;
    for (i, curve) in panel.curves.iter().enumerate() {
        let color = COLORS[i % COLORS.len()];
        for (k, seg) in segments(&curve.points, bounds).into_iter().enumerate() {
            let series = chart
                .draw_series(LineSeries::new(seg, color.stroke_width(2)))
                .map_err(|e| e.to_string())?;
            if k == 0 && !curve.label.is_empty() {
                any_label = true;
                series.label(&curve.label).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
            }
        }
    }
    if any_label {
        chart
            .configure_series_labels()
            .label_font(("sans-serif", 13))
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// Renders the whole figure into an RGB buffer of `width` x `height`.
fn render(
    buf: &mut [u8],
    width: u32,
    height: u32,
    title: &str,
    panels: &[Panel],
) -> Result<(), String> {
    let root = BitMapBackend::with_buffer(buf, (width, height)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let (top, body) = root.split_vertically(TITLE_HEIGHT);
    top.titled(title, ("sans-serif", 24))
        .map_err(|e| e.to_string())?;
    if !panels.is_empty() {
        for (area, panel) in body.split_evenly((panels.len(), 1)).iter().zip(panels) {
            let bounds = Bounds::of(panel);
            if bounds.log_y {
                draw_panel(area, panel, &bounds, bounds.y.clone().log_scale())?;
            } else {
                draw_panel(area, panel, &bounds, bounds.y.clone())?;
            }
        }
    }
    root.present().map_err(|e| e.to_string())
}

/// Encodes an 8-bit RGB buffer as PNG.
pub(crate) fn encode_png(buf: &[u8], width: u32, height: u32) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().map_err(|e| e.to_string())?;
    writer.write_image_data(buf).map_err(|e| e.to_string())?;
    writer.finish().map_err(|e| e.to_string())?;
    Ok(out)
}

/// Draws `panels` stacked vertically under a figure `title` and writes the
/// image to `path` as a PNG, atomically. The image is `width` pixels wide and
/// `height_per_panel` pixels high per panel plus a title band.
///
/// Non-finite points (and non-positive ones on log axes) are skipped; empty
/// or constant data still produce valid axes.
pub fn plot_panels(
    path: &Path,
    title: &str,
    panels: &[Panel],
    width: u32,
    height_per_panel: u32,
) -> io::Result<()> {
    if width < 200 || height_per_panel < 120 {
        return Err(with_path(
            path,
            format!("plot too small: {width} x {height_per_panel} per panel (min 200 x 120)"),
            io::ErrorKind::InvalidInput,
        ));
    }
    let height = TITLE_HEIGHT + height_per_panel * panels.len().max(1) as u32;
    let fail = |e: String| with_path(path, format!("plotting failed: {e}"), io::ErrorKind::Other);
    ensure_font().map_err(fail)?;
    let mut buf = vec![255u8; width as usize * height as usize * 3];
    render(&mut buf, width, height, title, panels).map_err(fail)?;
    let png = encode_png(&buf, width, height).map_err(fail)?;
    write_atomic(path, &png)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_handle_degenerate_data() {
        assert_eq!(linear_range(std::iter::empty()), 0.0..1.0);
        let r = linear_range([2.0, 2.0].into_iter());
        assert!(r.start < 2.0 && r.end > 2.0);
        let r = linear_range([0.0].into_iter());
        assert_eq!(r, -1.0..1.0);
        let r = linear_range([0.0, 10.0].into_iter());
        assert!((r.start + 0.5).abs() < 1e-12 && (r.end - 10.5).abs() < 1e-12);
        let r = log_range([1e-3, 1e3].into_iter());
        assert!(r.start < 1e-3 && r.start > 1e-4 && r.end > 1e3 && r.end < 1e4);
        let r = log_range([5.0].into_iter());
        assert!(r.start < 5.0 && r.end > 5.0);
    }

    #[test]
    fn tick_labels() {
        assert_eq!(tick(-2.2e-16, 2.0), "0");
        assert_eq!(tick(0.4, 2.0), "0.4");
        assert_eq!(tick(-0.6000000000000001, 2.0), "-0.6");
        assert_eq!(tick(2.0, 10.5), "2");
        assert_eq!(tick(1.00012, 0.001), "1.0001");
        assert_eq!(tick(150000.0, 100000.0), "1.5e5");
        assert_eq!(tick(1e-4, 0.0), "1e-4");
        assert_eq!(tick(1e-20, 0.0), "1e-20");
        assert_eq!(tick(0.01, 0.0), "0.01");
    }

    #[test]
    fn segments_break_at_bad_points() {
        let pts = [
            (0.0, 1.0),
            (1.0, f64::NAN),
            (2.0, 2.0),
            (3.0, -1.0),
            (4.0, 2.0),
        ];
        let bounds = |log_y| Bounds {
            x: -1.0..10.0,
            y: -2.0..2.5,
            log_y,
        };
        assert_eq!(segments(&pts, &bounds(false)).len(), 2);
        assert_eq!(segments(&pts, &bounds(true)).len(), 3);
        assert!(segments(&[(f64::INFINITY, 1.0)], &bounds(false)).is_empty());
        assert_eq!(segments(&[(1.0, 9.0)], &bounds(false)).len(), 0);
    }

    #[test]
    fn a_log_panel_without_a_positive_value_is_drawn_on_a_linear_axis() {
        let panel = |ys: &[f64]| Panel {
            title: "residual".into(),
            x_label: "t".into(),
            y_label: "r".into(),
            curves: vec![Curve {
                label: String::new(),
                points: ys.iter().enumerate().map(|(i, &y)| (i as f64, y)).collect(),
            }],
            log_y: true,
        };
        let zeros = Bounds::of(&panel(&[0.0, 0.0, 0.0]));
        assert!(!zeros.log_y);
        assert!(zeros.contains((1.0, 0.0)));
        let some = Bounds::of(&panel(&[0.0, 1e-3, 1e-6]));
        assert!(some.log_y);
        assert!(!some.contains((0.0, 0.0)) && some.contains((1.0, 1e-3)));
    }
}
