//! PNG plot output checks.

mod common;

use std::path::Path;

use xper_io::{plot_panels, plot_segments, Curve, Panel, SegmentLayer};

/// Width and height from the IHDR chunk, after checking the PNG signature.
fn png_size(path: &Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    assert_eq!(&bytes[12..16], b"IHDR");
    let w = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
    let h = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
    (w, h)
}

fn panels() -> Vec<Panel> {
    let t: Vec<f64> = (0..200).map(|i| i as f64 * 0.05).collect();
    vec![
        Panel {
            title: "Kinetic energy".into(),
            x_label: "time [s]".into(),
            y_label: "energy [J]".into(),
            curves: vec![
                Curve {
                    label: "translational".into(),
                    points: t.iter().map(|&x| (x, (-x).exp())).collect(),
                },
                Curve {
                    label: "rotational".into(),
                    points: t.iter().map(|&x| (x, 0.3 * (-0.5 * x).exp())).collect(),
                },
            ],
            log_y: true,
        },
        Panel {
            title: "Solver iterations".into(),
            x_label: "time [s]".into(),
            y_label: "iterations".into(),
            curves: vec![
                Curve {
                    label: "with NaN".into(),
                    points: t
                        .iter()
                        .map(|&x| {
                            (
                                x,
                                if (4.0..5.0).contains(&x) {
                                    f64::NAN
                                } else {
                                    x.sin()
                                },
                            )
                        })
                        .collect(),
                },
                Curve {
                    label: "empty".into(),
                    points: vec![],
                },
                Curve {
                    label: "constant".into(),
                    points: vec![(0.0, 0.5), (10.0, 0.5)],
                },
            ],
            log_y: false,
        },
    ]
}

#[test]
fn two_panel_png_has_expected_size() {
    let dir = common::test_dir("plot");
    let path = dir.join("plots.png");
    plot_panels(&path, "xper test run", &panels(), 900, 350).unwrap();
    assert!(!dir.join("plots.png.tmp").exists());
    let (w, h) = png_size(&path);
    assert_eq!(w, 900);
    assert_eq!(h, 40 + 2 * 350);
    println!("wrote {}", path.display());
}

#[test]
fn degenerate_data_does_not_fail() {
    let dir = common::test_dir("plot_degenerate");
    let path = dir.join("degenerate.png");
    let panel = |log_y: bool, points: Vec<(f64, f64)>| Panel {
        title: String::new(),
        x_label: "x".into(),
        y_label: "y".into(),
        curves: vec![Curve {
            label: String::new(),
            points,
        }],
        log_y,
    };
    let panels = vec![
        panel(false, vec![(f64::NAN, f64::NAN), (f64::INFINITY, 1.0)]),
        panel(true, vec![(0.0, -1.0), (1.0, 0.0), (2.0, f64::NAN)]),
        panel(false, vec![(3.0, 7.0)]),
        panel(true, vec![(1.0, 1e-300), (2.0, 1e300), (3.0, 5e-324)]),
        panel(true, vec![(1.0, 2.0), (2.0, 5.0)]),
        panel(false, vec![(-f64::MAX, -f64::MAX), (f64::MAX, f64::MAX)]),
        panel(false, vec![(0.0, 1e-300), (1.0, 2e-300)]),
    ];
    plot_panels(&path, "", &panels, 400, 150).unwrap();
    assert_eq!(png_size(&path), (400, 40 + 7 * 150));
    plot_panels(&dir.join("none.png"), "no panels", &[], 300, 200).unwrap();
    assert_eq!(png_size(&dir.join("none.png")), (300, 240));
    let err = plot_panels(&dir.join("tiny.png"), "t", &panels, 10, 10).unwrap_err();
    assert!(err.to_string().contains("tiny.png"), "{err}");
}

#[test]
fn segment_drawing_follows_the_aspect_ratio_and_draws_in_colour() {
    let dir = common::test_dir("segments");
    let path = dir.join("cracks.png");
    let square = |x: f64| {
        vec![
            [[x, 0.0], [x + 1.0, 0.0]],
            [[x + 1.0, 0.0], [x + 1.0, 0.5]],
            [[x + 1.0, 0.5], [x, 0.5]],
            [[x, 0.5], [x, 0.0]],
        ]
    };
    let layers = [
        SegmentLayer {
            label: "outline".into(),
            color: [128, 128, 128],
            width: 1,
            segments: square(0.0),
        },
        SegmentLayer {
            label: "broken".into(),
            color: [200, 0, 0],
            width: 3,
            segments: vec![[[0.5, 0.0], [0.5, 0.5]], [[f64::NAN, 0.0], [1.0, 1.0]]],
        },
    ];
    plot_segments(&path, "Crack pattern", "x (m)", "y (m)", &layers, 800).unwrap();
    let (w, h) = png_size(&path);
    assert_eq!(w, 800);
    // Plot area 690 px wide for a 2:1 drawing (with margins): about 370 px high plus bands.
    assert!((450..600).contains(&h), "height {h}");
    let decoder = png::Decoder::new(std::fs::File::open(&path).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    let red = buf[..info.buffer_size()]
        .chunks(3)
        .filter(|p| p[0] > 150 && p[1] < 60 && p[2] < 60)
        .count();
    assert!(red > 300, "only {red} red pixels");
    assert!(plot_segments(&path, "t", "x", "y", &[], 100).is_err());
    plot_segments(&dir.join("empty.png"), "t", "x", "y", &[], 400).unwrap();
}
