//! The .vtu of `impact field --format vtu` read back with vtkio's own parser: the same mesh
//! and values as `impact::report::field::field`, the displacement vector (0, 0, w), the
//! stresses 6M/h², the near-load flag, its field data; the load's range and the scaling to
//! an impact's P_max; `--out` refusing a file that is not ours; and the shell completions.

mod common;

use common::reference::{contact_over_period_bound, GANGUE_1, PAPER_PLATE};
use common::{impact, tmp};
use coupled::validity::QUASI_STATIC_MIN_RATIO;
use impact::present::vtk::{to_vtu, Metadata, MOMENTS, POINT_SCALARS, STRESSES};
use impact::provenance::Provenance;
use impact::report::field::{field, FieldFile};
use impact::scene::{Scene, SceneSource};
use std::collections::HashMap;
use vtkio::model::{Attribute, CellType, DataSet, IOBuffer, UnstructuredGridPiece, Vtk};

/// The default scene's Con 1 field on a coarse mesh (the check is of the data path).
fn field_at(x_mm: f64, z_mm: f64, n: usize) -> FieldFile {
    let scene = Scene::default_scene();
    let cond = scene.conditions.iter().find(|c| c.name == "Con 1").expect("Con 1");
    field(&scene, cond, x_mm * 1e-3, z_mm * 1e-3, n).expect("field")
}

struct Read {
    piece: UnstructuredGridPiece,
    point: HashMap<String, IOBuffer>,
    cell: HashMap<String, IOBuffer>,
}

fn read(bytes: &[u8]) -> Read {
    let vtk = Vtk::parse_xml(bytes).expect("vtkio parses the .vtu");
    let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else { panic!("not an UnstructuredGrid") };
    assert_eq!(pieces.len(), 1);
    let piece = pieces.into_iter().next().unwrap().into_loaded_piece_data(None).expect("inline piece");
    let map = |attrs: &[Attribute]| {
        attrs
            .iter()
            .map(|a| match a {
                Attribute::DataArray(d) => (d.name.clone(), d.data.clone()),
                Attribute::Field { name, .. } => panic!("unexpected field attribute {name}"),
            })
            .collect::<HashMap<_, _>>()
    };
    let (point, cell) = (map(&piece.data.point), map(&piece.data.cell));
    Read { piece, point, cell }
}

/// The provenance of the default scene and nothing else.
fn meta() -> Metadata {
    Metadata { provenance: Provenance::of(&Scene::default_scene()), lines: vec![], numbers: vec![] }
}

/// The dataset's FieldData, name to value, read from the XML text (vtkio's reader skips it):
/// every array a single ascii Float64.
fn field_data(bytes: &[u8]) -> HashMap<String, f64> {
    let text = std::str::from_utf8(bytes).expect("UTF-8 XML");
    let start = text.find("<FieldData>").expect("a FieldData element");
    let end = text.find("</FieldData>").expect("its end");
    text[start..end]
        .split("<DataArray ")
        .skip(1)
        .map(|a| {
            assert!(
                a.contains("type=\"Float64\"") && a.contains("NumberOfTuples=\"1\"") && a.contains("format=\"ascii\"")
            );
            let name = a.split("Name=\"").nth(1).and_then(|r| r.split('"').next()).expect("a name");
            let value = a.split('>').nth(1).and_then(|r| r.split('<').next()).expect("a value");
            (name.to_string(), value.trim().parse::<f64>().expect("a number"))
        })
        .collect()
}

fn f64s(b: &IOBuffer) -> Vec<f64> {
    b.clone().into_vec::<f64>().expect("f64 array")
}

fn scaled(v: &[f64], s: f64) -> Vec<f64> {
    v.iter().map(|x| x * s).collect()
}

/// Every array against the field: bit-exact, since vtkio writes binary f64 (the scaling by
/// the force is the same multiplication on both sides).
fn check(f: &FieldFile, r: &Read, force: f64) {
    let n = f.points.len();
    assert_eq!(r.piece.num_points(), n);
    let pts = f64s(&r.piece.points);
    let expected: Vec<f64> = f.points.iter().flat_map(|p| [p[0], p[1], 0.0]).collect();
    assert_eq!(pts, expected, "points (x, z, 0)");

    assert_eq!(r.piece.cells.num_cells(), f.quads.len());
    assert!(r.piece.cells.types.iter().all(|t| *t == CellType::Quad));
    let (conn, offsets) = r.piece.cells.cell_verts.clone().into_xml();
    let quads: Vec<u64> = f.quads.iter().flatten().map(|&i| i as u64).collect();
    assert_eq!(conn, quads);
    assert_eq!(offsets, (1..=f.quads.len() as u64).map(|i| 4 * i).collect::<Vec<_>>());

    let pd = &f.point_data;
    for (name, v) in POINT_SCALARS.iter().zip([&pd.w, &pd.w_x, &pd.w_z]) {
        assert_eq!(f64s(&r.point[*name]), scaled(v, force), "point data {name}");
    }
    let d = f64s(&r.point["displacement"]);
    assert_eq!(d.len(), 3 * n);
    let w = scaled(&pd.w, force);
    for (i, c) in d.chunks(3).enumerate() {
        assert_eq!(c, [0.0, 0.0, w[i]], "displacement at node {i} is (0, 0, w)");
    }

    let cd = &f.cell_data;
    let h = f.thickness;
    for ((m_name, s_name), m) in MOMENTS.iter().zip(STRESSES).zip([&cd.m_x, &cd.m_z, &cd.m_xz]) {
        let m_read = f64s(&r.cell[*m_name]);
        assert_eq!(m_read, scaled(m, force), "cell data {m_name}");
        let s_read = f64s(&r.cell[s_name]);
        assert_eq!(s_read.len(), m.len());
        for (s, m) in s_read.iter().zip(&m_read) {
            let want = 6.0 * m / (h * h);
            assert!((s - want).abs() <= 1e-14 * want.abs().max(1e-300), "{s_name} {s} vs 6M/h² {want}");
        }
    }
    let near: Vec<u8> = r.cell["near_load"].clone().into_vec().expect("u8 flag");
    assert_eq!(near, f.near_load().into_iter().map(u8::from).collect::<Vec<_>>());
}

#[test]
fn vtu_reads_back_with_the_field_values() {
    // The plate centre (458.4 x 360 mm) is a node of the 20 x 16 mesh: four elements touch it.
    let f = field_at(229.2, 180.0, 20);
    let r = read(&to_vtu(&f, 1.0, &meta()).unwrap());
    check(&f, &r, 1.0);
    assert_eq!(f.near_load().iter().filter(|&&b| b).count(), 4);
    // The flagged elements carry the largest |M_x|: the singularity they mark.
    let near = f.near_load();
    let peak = (0..near.len()).max_by(|&a, &b| f.cell_data.m_x[a].abs().total_cmp(&f.cell_data.m_x[b].abs())).unwrap();
    assert!(near[peak]);
}

#[test]
fn load_inside_one_element_flags_one() {
    let f = field_at(100.0, 100.0, 10);
    assert_eq!(f.near_load().iter().filter(|&&b| b).count(), 1);
    check(&f, &read(&to_vtu(&f, 1.0, &meta()).unwrap()), 1.0);
}

#[test]
fn cli_writes_a_scaled_vtu() {
    let dir = tmp();
    let path = dir.join("f.vtu");
    impact(["field", "--format", "vtu", "--x-mm", "229.2", "--z-mm", "180", "--elements", "20", "--force-n", "2.5"])
        .arg("--out")
        .arg(&path)
        .success();
    let f = field_at(229.2, 180.0, 20);
    let bytes = std::fs::read(&path).unwrap();
    check(&f, &read(&bytes), 2.5);
    let fd = field_data(&bytes);
    assert_eq!((fd["force_N"], fd["load_x_m"], fd["load_z_m"]), (2.5, 0.2292, 0.18));

    // The JSON stays per unit load: a force with it is refused, not silently ignored.
    let o = impact(["field", "--x-mm", "229.2", "--z-mm", "180", "--force-n", "2", "--out", "-"]).fails();
    assert!(o.stderr.contains("--format vtu"));
}

#[test]
fn completions_for_every_shell() {
    let o = impact(["completions", "bash"]).success();
    assert!(String::from_utf8(o.stdout).unwrap().contains("solve"));
    for shell in ["zsh", "fish", "powershell", "elvish"] {
        let o = impact(["completions", shell]).run();
        assert!(o.status.success() && !o.stdout.is_empty(), "{shell}");
    }
}

#[test]
fn force_outside_its_range_is_refused_naming_flag_value_and_range() {
    let dir = tmp();
    let out = dir.join("f.vtu");
    let out = out.to_str().unwrap();
    for bad in ["1e308", "1.5e12", "0", "-5", "NaN", "inf", "1e-10"] {
        let o = impact(["field", "--format", "vtu", "--x-mm", "100", "--z-mm", "200", "--force-n", bad, "--out", out])
            .fails_with(1);
        let err = o.stderr;
        let range = impact::scene::limits::FORCE_N;
        assert!(err.contains(&format!("--force-n {bad} is outside the allowed range {range} N")), "{bad}: {err}");
        assert!(!std::path::Path::new(out).exists());
    }
}

/// The worst valid scene for overflow: the largest, thinnest, softest plate the scene limits
/// allow (100 m square, 1 µm, 1 kPa), where a unit load deflects it by about 1e18 m and the
/// surface stress 6M/h² is about 1e12 Pa. At the largest load accepted, 1e12 N, every value
/// written must still be finite.
#[test]
fn the_largest_load_on_the_weakest_plate_stays_finite() {
    let dir = tmp();
    let text = impact::scene::DEFAULT_SCENE
        .replace("length_mm = 458.4", "length_mm = 100000.0")
        .replace("width_mm = 360.0", "width_mm = 100000.0")
        .replace("thickness_mm = 8.0", "thickness_mm = 0.001")
        .replace("youngs_modulus_gpa = 210.0", "youngs_modulus_gpa = 1e-6");
    let scene = dir.write("weak.toml", &text);
    let out = dir.join("weak.vtu");
    impact(["field", "--format", "vtu", "--x-mm", "30000", "--z-mm", "40000", "--elements", "8", "--force-n", "1e12"])
        .arg("--scene")
        .arg(&scene)
        .arg("--out")
        .arg(&out)
        .success();
    let bytes = std::fs::read(&out).unwrap();
    let r = read(&bytes);
    let mut largest = 0.0f64;
    for (name, b) in r.point.iter().chain(&r.cell) {
        if name == "near_load" {
            continue;
        }
        let v = f64s(b);
        assert!(v.iter().all(|x| x.is_finite()), "{name} has a value that is not finite");
        largest = largest.max(v.iter().fold(0.0, |a, x| a.max(x.abs())));
    }
    // The scene is what the test says: deflections far beyond any physical plate.
    assert!(largest > 1e25, "largest value {largest:e}");
    assert!(field_data(&bytes).values().all(|v| v.is_finite()));
}

/// The `impact solve --model plate --json` row of the default scene for `body` on `condition`
/// at `v` (m/s) at the plate's centre.
fn solved_centre_row(body: &str, condition: &str, v: f64) -> serde_json::Value {
    let solved = impact(["solve", "--model", "plate", "--json"]).run();
    let doc: serde_json::Value = serde_json::from_slice(&solved.stdout).unwrap();
    doc["results"]["responses"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| {
            r["body"] == body
                && r["condition"] == condition
                && r["velocity_m_per_s"] == v
                && (r["x_m"].as_f64().unwrap() - 0.2292).abs() < 1e-12
                && (r["z_m"].as_f64().unwrap() - 0.18).abs() < 1e-12
        })
        .cloned()
        .expect("the default scene has the body at the centre at that velocity")
}

/// `--force-of-impact` scales by the quasi-static plate model's P_max of the case, the one
/// `impact solve --model plate` gives for it, and says so with the case's validity.
#[test]
fn scaled_to_the_impacts_quasi_static_p_max() {
    let dir = tmp();
    let out = dir.join("p.vtu");
    let o = impact([
        "field",
        "--format",
        "vtu",
        "--x-mm",
        "229.2",
        "--z-mm",
        "180",
        "--elements",
        "20",
        "--force-of-impact",
    ])
    .args(["--body", "gangue 1", "--velocity-m-per-s", "0.008", "--json", "--out"])
    .arg(&out)
    .success();
    let err = o.stderr.clone();
    let bytes = std::fs::read(&out).unwrap();
    let fd = field_data(&bytes);
    // --json: the provenance first, the file, and the load's numbers as in the field data.
    let printed = String::from_utf8(o.stdout.clone()).unwrap();
    assert!(printed.trim_start().trim_start_matches('{').trim_start().starts_with("\"provenance\""), "{printed}");
    let doc: serde_json::Value = serde_json::from_str(&printed).unwrap();
    assert_eq!(doc["files"][0]["bytes"], bytes.len());
    // Within one unit in the last place: serde_json's default float parser (no
    // float_roundtrip feature) may round the last digit differently from Rust's own.
    for (k, v) in doc["quasi_static_p_max"]["numbers"].as_object().unwrap() {
        let (a, b) = (v.as_f64().unwrap(), fd[k]);
        assert!((a - b).abs() <= 2.0 * f64::EPSILON * b.abs(), "{k}: {a} vs {b}");
    }
    assert!(doc["quasi_static_p_max"]["text"].as_str().unwrap().contains("quasi-static plate model"));

    // The same case through `impact solve --model plate`: its P_max and error, bit for bit.
    let v = solved_centre_row("gangue 1", "Con 1", 0.008);
    assert_eq!(v["applicable"], true);
    // The field computes the case alone and `solve` with the scene's other points in one
    // block of solves, so the two differ by the solves' round-off (about 1e-15 here), far
    // below the FE error estimate (about 1e-5 relative).
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
    assert!(
        close(fd["force_N"], v["contact_force_N"].as_f64().unwrap()),
        "{} vs {}",
        fd["force_N"],
        v["contact_force_N"]
    );
    // The error estimate is a difference of mesh levels, so its round-off is that of the
    // force, not of itself.
    let (e_field, e_solved) = (fd["contact_force_error_N"], v["contact_force_error_N"].as_f64().unwrap());
    assert!((e_field - e_solved).abs() <= 1e-12 * fd["force_N"].abs(), "{e_field} vs {e_solved}");
    assert_eq!(fd["velocity_m_per_s"], 0.008);
    // The values are the unit-load field times that force.
    check(&field_at(229.2, 180.0, 20), &read(&bytes), fd["force_N"]);
    // The case is not quasi-static: Hertz's time on a rigid target over the Rayleigh bound
    // of T₁ (both closed forms, `common::reference`) bounds t_c/T₁ from above, and the bound
    // is below the limit, so the file must flag the case and its t_c/T₁ may not exceed the
    // bound. The file and the terminal say which model and that the transient deflection
    // differs.
    let bound = contact_over_period_bound(GANGUE_1, PAPER_PLATE, 0.008);
    assert!(bound < QUASI_STATIC_MIN_RATIO, "bound {bound}");
    assert_eq!(fd["valid"], 0.0);
    assert!((fd["quasi_static_limit"] - QUASI_STATIC_MIN_RATIO).abs() < 1e-12, "{}", fd["quasi_static_limit"]);
    assert!(fd["quasi_static_value"] <= bound, "t_c/T₁ = {} above its bound {bound}", fd["quasi_static_value"]);
    let xml = String::from_utf8_lossy(&bytes);
    for text in [xml.as_ref(), err.as_str()] {
        assert!(text.contains("quasi-static plate model"), "{text}");
        assert!(text.contains("t_c/T₁ = "), "{text}");
        assert!(text.contains("the transient deflection differs"), "{text}");
    }
}

/// `--out` never replaces a file that is not ours: a scene file given as --out is refused with
/// the reason and left byte for byte; our own earlier .vtu and .json are replaced.
#[test]
fn out_refuses_a_file_that_is_not_ours() {
    let dir = tmp();
    let scene = dir.write("mine.toml", impact::scene::DEFAULT_SCENE);
    for format in ["vtu", "json"] {
        let o = impact(["field", "--format", format, "--x-mm", "100", "--z-mm", "200", "--elements", "4", "--scene"])
            .arg(&scene)
            .arg("--out")
            .arg(&scene)
            .fails_with(1);
        let err = o.stderr;
        assert!(err.contains("mine.toml") && err.contains("not written by impact"), "{err}");
        assert_eq!(std::fs::read_to_string(&scene).unwrap(), impact::scene::DEFAULT_SCENE);

        let ours = dir.join(format!("field.{format}"));
        for _ in 0..2 {
            impact(["field", "--format", format, "--x-mm", "100", "--z-mm", "200", "--elements", "4", "--out"])
                .arg(&ours)
                .success();
        }
    }
}
