//! The figures as a reader sees them: each rendered to PNG (resvg, as a browser would draw the
//! SVG) into `target/figures/` to look at, and checked for what a figure for a paper must
//! have: sub-pixel curves, the legend outside the data, one tick format per axis, log-axis
//! zeros and coinciding curves said so, viridis at the plate's true aspect ratio. The
//! deflection map is also checked against the plate model's compliance (reciprocity).

use impact::present::plot::{
    common_format, linear_ticks, log_ticks, viridis, Axis, ColourMap, Mark, Matrix, Plot, Scale, Series, Verdict,
};
use impact::report::plate_field::peak_field;
use impact::scene::{Scene, SceneSource};
use std::path::PathBuf;

/// Renders `svg` to a pixmap (and to target/tmp/figures/NAME.png, beside NAME.svg, for a person
/// to look at).
fn render(name: &str, svg: &str) -> resvg::tiny_skia::Pixmap {
    let mut opt = resvg::usvg::Options::default();
    opt.fontdb_mut().load_system_fonts();
    let tree = resvg::usvg::Tree::from_str(svg, &opt).unwrap_or_else(|e| panic!("{name}: not valid SVG: {e}"));
    let size = tree.size().to_int_size();
    let mut pixmap = resvg::tiny_skia::Pixmap::new(size.width(), size.height()).expect("non-empty figure");
    resvg::render(&tree, resvg::tiny_skia::Transform::default(), &mut pixmap.as_mut());
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("figures");
    std::fs::create_dir_all(&dir).expect("figure directory");
    pixmap.save_png(dir.join(format!("{name}.png"))).expect("png written");
    std::fs::write(dir.join(format!("{name}.svg")), svg).expect("svg written");
    pixmap
}

fn rgb(p: &resvg::tiny_skia::Pixmap, x: f64, y: f64) -> [u8; 3] {
    let c = p.pixel(x.round() as u32, y.round() as u32).expect("inside the image").demultiply();
    [c.red(), c.green(), c.blue()]
}

/// Every number in the `d` attributes of the SVG's paths.
fn path_coordinates(svg: &str) -> Vec<f64> {
    svg.split(" d=\"")
        .skip(1)
        .flat_map(|rest| {
            rest[..rest.find('"').unwrap()]
                .split(|c: char| c.is_ascii_alphabetic() || c == ',')
                .filter(|s| !s.is_empty())
                .map(|s| s.parse::<f64>().unwrap())
                .collect::<Vec<_>>()
        })
        .collect()
}

/// The rectangle (x, y, w, h) of the clip path with `id`.
fn clip_rect(svg: &str, id: &str) -> [f64; 4] {
    let at = svg.find(&format!("<clipPath id=\"{id}\"><rect")).expect("clip path");
    let rect = &svg[at..at + svg[at..].find("/>").unwrap()];
    ["x", "y", "width", "height"].map(|k| {
        let key = format!(" {k}=\"");
        let s = &rect[rect.find(&key).unwrap() + key.len()..];
        s[..s.find('"').unwrap()].parse().unwrap()
    })
}

#[test]
fn line_plot_is_fit_for_a_paper() {
    let xs: Vec<f64> = (0..=100).map(|i| i as f64 * 4.584).collect();
    let curve = |a: f64| xs.iter().map(|&x| (x, a + (x / 73.0).sin().powi(2))).collect::<Vec<_>>();
    let plot = Plot::new("Fig. test", Axis::linear("x (mm)"), Axis::log("P (N)"))
        .with(Series::new("Con 1", curve(1.0)))
        .with(Series::new("Con 2", curve(1.0).into_iter().map(|(x, y)| (x, y * (1.0 + 1e-4))).collect()))
        .with(Series::new("sampled", vec![(0.0, 0.0), (100.0, 1.5), (200.0, 1.7), (300.0, 1.2)]));
    let svg = plot.svg();
    let png = render("line-plot", &svg);

    // No staircase: coordinates to 0.01 px, and most of them not whole pixels.
    let coords = path_coordinates(&svg);
    let fractional = coords.iter().filter(|v| v.fract() != 0.0).count();
    assert!(fractional * 2 > coords.len(), "{fractional} of {} coordinates are sub-pixel", coords.len());

    // The coinciding curve says so and is dashed; the zero on the log axis is counted.
    assert!(svg.contains("Con 2 (dashed: on Con 1)"), "coincidence not named");
    assert!(svg.contains("stroke-dasharray"));
    assert!(svg.contains("sampled (1 ≤ 0 not shown)") && svg.contains("cannot be shown on the log axis"));

    // The legend is right of the plotting area, which holds the data only: the legend's line
    // swatch of the first series is drawn beyond the frame, in the series' colour.
    let [x0, y0, w, _h] = clip_rect(&svg, "area");
    let legend_x = x0 + w + 14.0 + 10.0;
    let swatch = rgb(&png, legend_x, y0 + 6.0 + 8.0);
    assert_eq!(swatch, [0x00, 0x72, 0xB2], "legend swatch of Con 1 outside the axes");

    // Few points get markers (the third series' triangles, one per point shown); the
    // 101-point curves get none.
    assert_eq!(svg.matches("Z\" fill=\"#009E73\"").count(), 3 + 1, "three points and the legend's marker");
}

#[test]
fn tick_labels_share_one_format() {
    let t = linear_ticks(2.1e-4, 2.1e-3);
    assert!(t.factor.as_deref() == Some("×10⁻³"), "{t:?}");
    let decimals = |s: &str| s.split('.').nth(1).map_or(0, str::len);
    let d0 = decimals(&t.major[0].1);
    assert!(t.major.iter().all(|(_, l)| decimals(l) == d0), "{t:?}");
    // A mixed axis, 0.00200 beside 8.00e-4, cannot happen: one factor, one decimal count.
    let (labels, factor) = common_format(&[0.002, 0.0008]);
    assert_eq!((labels, factor.as_deref()), (vec!["2.0".to_string(), "0.8".to_string()], Some("×10⁻³")));
    // Log axes: decades as powers of ten; inside a decade, 1-2-5 values in one format.
    let decades = log_ticks(3e-8, 2e-2);
    assert!(decades.major.iter().all(|(_, l)| l.starts_with("10")), "{decades:?}");
    let inside = log_ticks(1.15, 7.2);
    let labels: Vec<&str> = inside.major.iter().map(|(_, l)| l.as_str()).collect();
    assert!(labels.len() >= 4 && labels.iter().all(|l| decimals(l) == decimals(labels[0])), "{labels:?}");
    assert!(!labels.iter().any(|l| l.starts_with("−0") || *l == "-0"), "{labels:?}");
}

#[test]
fn colour_map_is_viridis_at_true_aspect() {
    // A 400 x 200 field rising along x: the map must be twice as wide as high.
    let xs: Vec<f64> = (0..=40).map(|i| i as f64 * 10.0).collect();
    let ys: Vec<f64> = (0..=20).map(|j| j as f64 * 10.0).collect();
    let map = ColourMap {
        title: "test".into(),
        x: Axis::linear("x (mm)"),
        y: Axis::linear("z (mm)"),
        xs: xs.clone(),
        ys: ys.clone(),
        edges: false,
        values: xs.iter().map(|&x| ys.iter().map(|_| 1.0 + x / 100.0).collect()).collect(),
        bar: Axis { label: "ratio".into(), scale: Scale::Log },
        missing: None,
        marks: vec![Mark { x: 200.0, y: 100.0, label: "impact point".into() }],
        notes: vec![],
    };
    let svg = map.svg();
    let png = render("colour-map", &svg);
    let [x0, y0, w, h] = clip_rect(&svg, "field");
    assert!((w / h - 2.0).abs() < 1e-6, "aspect {}", w / h);
    // The left and right ends of the field are viridis' ends.
    let close = |a: [u8; 3], b: [u8; 3]| a.iter().zip(b).all(|(p, q)| (*p as i32 - q as i32).abs() <= 3);
    assert!(close(rgb(&png, x0 + 2.0, y0 + h / 4.0), viridis(0.0)), "{:?}", rgb(&png, x0 + 2.0, y0 + h / 4.0));
    let right = rgb(&png, x0 + w - 3.0, y0 + h / 4.0);
    assert!(close(right, viridis(1.0)), "{right:?} against {:?}", viridis(1.0));
    // The colour bar is labelled in the ratio itself, not in log10 units.
    assert!(svg.contains(">2<") || svg.contains(">2.0<"), "bar labels in the quantity");
    assert!(!svg.contains("log10"));
}

/// Cells of equal colour are drawn merged (runs down a column widened across columns, one
/// path per colour): every cell's centre still shows the colour of its value's band of the
/// colour bar, on a field with plateaus, steps and missing cells, at cell sizes that are not
/// whole pixels.
#[test]
fn merged_cells_show_every_value() {
    let xs: Vec<f64> = (0..23).map(|i| i as f64 * 7.3).collect();
    let ys: Vec<f64> = (0..17).map(|j| j as f64 * 5.9).collect();
    let value = |i: usize, j: usize| -> f64 {
        match (i, j) {
            (5, 3) => f64::NAN,
            _ if j < 6 => 1.0,
            _ if i % 4 == 0 => (i + j) as f64,
            _ => (j / 3) as f64 * 2.0,
        }
    };
    let values: Vec<Vec<f64>> = (0..xs.len()).map(|i| (0..ys.len()).map(|j| value(i, j)).collect()).collect();
    let (lo, hi) = values
        .iter()
        .flatten()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(*v), b.max(*v)));
    let map = ColourMap {
        title: "merged".into(),
        x: Axis::linear("x (mm)"),
        y: Axis::linear("z (mm)"),
        xs: xs.clone(),
        ys: ys.clone(),
        edges: false,
        values: values.clone(),
        bar: Axis::linear("value"),
        missing: Some("no value".into()),
        marks: vec![],
        notes: vec![],
    };
    let svg = map.svg();
    let cells = xs.len() * ys.len();
    let shapes = svg.matches(" d=\"").count();
    assert!(shapes < 40, "{shapes} paths for {cells} cells");
    let png = render("colour-map-merged", &svg);
    let [x0, y0, w, h] = clip_rect(&svg, "field");
    let (sx, sy) = (w / (xs[xs.len() - 1] - xs[0]), h / (ys[ys.len() - 1] - ys[0]));
    for (i, col) in values.iter().enumerate() {
        for (j, &v) in col.iter().enumerate() {
            // Cells reach halfway to their neighbours; the border cells are half cells.
            let cx = (xs[i]
                + if i == 0 {
                    1.8
                } else if i + 1 == xs.len() {
                    -1.8
                } else {
                    0.0
                })
                * sx
                + x0;
            let cy = y0 + h
                - (ys[j]
                    + if j == 0 {
                        1.4
                    } else if j + 1 == ys.len() {
                        -1.4
                    } else {
                        0.0
                    })
                    * sy;
            // The colour of the colour bar's band (of 100) the value falls in.
            let band = ((v - lo) / (hi - lo) * 100.0).floor().min(99.0);
            let expected = if v.is_finite() { viridis((band + 0.5) / 100.0) } else { [0xc8, 0xc8, 0xc8] };
            let got = rgb(&png, cx, cy);
            assert!(
                got.iter().zip(expected).all(|(p, q)| (*p as i32 - q as i32).abs() <= 2),
                "cell ({i}, {j}) = {v}: {got:?} against {expected:?}"
            );
        }
    }
}

#[test]
fn deflection_map_agrees_with_the_plate_compliance() {
    let scene = Scene::default_scene();
    let cond = &scene.conditions[0];
    let (x, z) = (scene.plate.length() / 2.0, scene.plate.width() / 2.0);
    let p = 1.5;
    let f = peak_field(&scene, cond, x, z, p, &["test".to_string()]).expect("field");
    render("deflection", &f.deflection_svg);
    render("stress", &f.stress_svg);
    // One path per colour, not one element per cell: the 80-element maps were 360-370 kB.
    for svg in [&f.deflection_svg, &f.stress_svg] {
        eprintln!("map: {} bytes", svg.len());
        assert!(svg.len() < 150_000, "{} bytes", svg.len());
    }
    // Reciprocity: the largest deflection is under the load and equals P·C. Reference: the
    // plate model's Richardson-extrapolated compliance (20 x 16 and 40 x 32 meshes); the map's
    // 80-element mesh is within about 1e-5 of it (O(h²) from the 3.6e-5 of 40 x 32), so 2e-4.
    let model = coupled::PlateModel::compute(&scene.plate, std::slice::from_ref(cond), &[(x, z)], 20, 2).unwrap();
    let c = model.get(&cond.name, x, z).unwrap().compliance.total();
    assert!((f.data.w_max / (p * c) - 1.0).abs() < 2e-4, "w_max {} against P·C {}", f.data.w_max, p * c);
    assert!((f.data.w_max_at.0 - x).abs() < 1e-9 && (f.data.w_max_at.1 - z).abs() < 1e-9);
    // The stress map leaves out the load's neighbourhood (within one thickness).
    assert!(f.data.left_out >= 4);
    let h = scene.plate.thickness();
    assert!((f.data.stress_max_at.0 - x).hypot(f.data.stress_max_at.1 - z) >= h);
}

#[test]
fn yes_no_matrix_renders() {
    let m = Matrix {
        title: "t".into(),
        columns: vec!["beam".into(), "plate".into(), "transient".into()],
        rows: vec!["a statement long enough to wrap onto a second line of the figure, which it must do".into()],
        cells: vec![vec![Verdict::Holds, Verdict::Fails, Verdict::NotResolved]],
    };
    let svg = m.svg();
    render("matrix", &svg);
    assert!(svg.contains(">yes<") && svg.contains(">no<") && svg.contains(">not resolved<"));
}
