//! The .vtu of `impact field --format vtu` read back with vtkio's own parser: the same mesh
//! and values as `impact::report::field::field`, the displacement vector (0, 0, w), the
//! stresses 6M/h², the near-load flag; and the shell completions.

use impact::present::vtk::{to_vtu, MOMENTS, POINT_SCALARS, STRESSES};
use impact::report::field::{field, FieldFile};
use impact::scene::{Scene, SceneSource};
use std::collections::HashMap;
use std::process::Command;
use vtkio::model::{Attribute, CellType, DataSet, IOBuffer, UnstructuredGridPiece, Vtk};

const BIN: &str = env!("CARGO_BIN_EXE_impact");

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
    let r = read(&to_vtu(&f, 1.0).unwrap());
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
    check(&f, &read(&to_vtu(&f, 1.0).unwrap()), 1.0);
}

#[test]
fn cli_writes_a_scaled_vtu() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("f.vtu");
    let s = Command::new(BIN)
        .args(["field", "--format", "vtu", "--x-mm", "229.2", "--z-mm", "180", "--elements", "20", "--force-n", "2.5"])
        .arg("--out")
        .arg(&path)
        .status()
        .unwrap();
    assert!(s.success());
    let f = field_at(229.2, 180.0, 20);
    check(&f, &read(&std::fs::read(&path).unwrap()), 2.5);

    // The JSON stays per unit load: a force with it is refused, not silently ignored.
    let o = Command::new(BIN)
        .args(["field", "--x-mm", "229.2", "--z-mm", "180", "--force-n", "2", "--out", "-"])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("--format vtu"));
}

#[test]
fn completions_for_every_shell() {
    let o = Command::new(BIN).args(["completions", "bash"]).output().unwrap();
    assert!(o.status.success());
    assert!(String::from_utf8(o.stdout).unwrap().contains("solve"));
    for shell in ["zsh", "fish", "powershell", "elvish"] {
        let o = Command::new(BIN).args(["completions", shell]).output().unwrap();
        assert!(o.status.success() && !o.stdout.is_empty(), "{shell}");
    }
}
