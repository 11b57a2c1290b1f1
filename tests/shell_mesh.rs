//! `[shell_mesh]`: a structure read from a Gmsh mesh file. Every bad input is refused before
//! the ladder runs, naming its key; the shipped scene's box, read from its file, agrees with
//! the same box built from its dimensions (`[tail_beam]`); `impact mesh` writes a file that
//! reads back.

mod common;

use common::{impact, tmp};
use impact::scene::{parse_in_folder, Scene, SceneSource};
use plate_fem::shell::gmsh::MeshFile;
use std::path::{Path, PathBuf};

fn scenes() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes")
}

fn shipped() -> String {
    std::fs::read_to_string(scenes().join("tail-beam-mesh.toml")).unwrap()
}

/// The shipped scene with `from` replaced by `to` (which must occur), parsed in `scenes/`.
fn edited(from: &str, to: &str) -> Result<Scene, String> {
    let text = shipped();
    assert!(text.contains(from), "the scene has no '{from}'");
    parse_in_folder(&text.replacen(from, to, 1), "edited", &scenes()).map_err(|e| e.to_string())
}

/// Each bad input names its key and what is wrong, before any ladder runs.
#[test]
fn bad_inputs_are_refused_by_key() {
    let cases: [(&str, &str, &[&str]); 11] = [
        ("file = \"meshes/tail-beam.msh\"", "file = \"meshes/none.msh\"", &["shell_mesh.file", "none.msh"]),
        ("struck = \"top\"", "struck = \"roof\"", &["shell_mesh.struck", "roof", "no thickness"]),
        ("group = \"pins\"", "group = \"hinge\"", &["shell_mesh.holds[0].group", "hinge", "\"pins\""]),
        ("top = 30.0,", "top = 30.0, pins = 5.0,", &["shell_mesh.thickness_mm.pins", "not a surface"]),
        ("ribs = 16.0, ", "", &["quadrilateral", "no group given a thickness"]),
        ("dofs = [\"ux\", \"uy\", \"uz\"]", "dofs = [\"ux\", \"wz\"]", &["shell_mesh.holds[0].dofs", "'wz'"]),
        (
            "[800.0, 250.0, 933.3]",
            "[800.0, 250.0, 1500.0]",
            &["shell_mesh.points_mm[1]", "no element of the struck face"],
        ),
        ("[800.0, 250.0, 933.3]", "[800.0, 200.0, 933.3]", &["shell_mesh.points_mm[1]"]),
        ("levels = 4", "levels = 5", &["shell_mesh.levels", "[2, 4]"]),
        ("stiffness_n_per_m = 4.3e7", "stiffness_n_per_m = -1.0", &["shell_mesh.springs[0].stiffness_n_per_m"]),
        (
            "analyses = [\"shell-mesh\"]",
            "analyses = [\"responses\"]\n[points]\nx_mm = [229.2]",
            &["shell_mesh", "read only by"],
        ),
    ];
    for (from, to, needles) in cases {
        let Err(err) = edited(from, to) else { panic!("'{from}' -> '{to}' was taken") };
        assert!(needles.iter().all(|n| err.contains(n)), "'{from}' -> '{to}': {err}");
    }
    // Without the pins and the jacks the box is a mechanism.
    let free = shipped().replace("[[shell_mesh.holds]]\ngroup = \"pins\"\ndofs = [\"ux\", \"uy\", \"uz\"]", "");
    let err = parse_in_folder(&free, "free", &scenes()).unwrap_err().to_string();
    assert!(err.contains("shell_mesh.holds and springs") && err.contains("rigid"), "{err}");
}

/// A group the file names but fills with nothing is refused where the scene uses it.
#[test]
fn an_empty_group_is_refused() {
    let dir = tmp();
    let mesh = std::fs::read_to_string(scenes().join("meshes/tail-beam.msh")).unwrap();
    assert!(mesh.contains("$PhysicalNames\n8\n"));
    dir.write("empty.msh", mesh.replacen("$PhysicalNames\n8\n", "$PhysicalNames\n9\n2 9 \"canopy\"\n", 1));
    let text =
        shipped().replace("meshes/tail-beam.msh", "empty.msh").replace("top = 30.0,", "top = 30.0, canopy = 10.0,");
    let err = parse_in_folder(&text, "empty", dir.path()).unwrap_err().to_string();
    assert!(err.contains("shell_mesh.thickness_mm.canopy") && err.contains("no elements"), "{err}");
}

/// The budget is checked on the file's size before anything is built.
#[test]
fn the_finest_mesh_is_budgeted() {
    let dir = tmp();
    // The shipped mesh refined twice, written as a file: 16 times the nodes, so that four
    // meshes of it exceed the budget.
    let shipped_mesh = std::fs::read_to_string(scenes().join("meshes/tail-beam.msh")).unwrap();
    let mesh = MeshFile::parse(&shipped_mesh, "tail-beam.msh", 1.0).unwrap().refined().refined();
    dir.write("huge.msh", mesh.to_msh41(1.0));
    let text = shipped().replace("meshes/tail-beam.msh", "huge.msh");
    let err = parse_in_folder(&text, "huge", dir.path()).unwrap_err().to_string();
    // Refused on the $Nodes header's count, before a node is read.
    assert!(err.contains("shell_mesh.file") && err.contains("the number of nodes") && err.contains("budget"), "{err}");
}

/// The shipped box read from its file against the same box built from `scenes/tail-beam.toml`
/// on the same meshes (three levels each): at the mid-panel point the two compliances agree
/// within the sum of their error estimates and the contact patch's shape (a disc on the file's
/// structure, a square on the builder's: 0.08 % apart on the 25 mm mesh).
#[test]
fn the_box_from_its_file_is_the_built_box() {
    let from_file = edited("levels = 4", "levels = 3").unwrap();
    let data = studies::shell_mesh::compute(&from_file).unwrap();
    let built = Scene::load(&scenes().join("tail-beam.toml")).unwrap();
    let beam = studies::tail_beam::compute(&built).unwrap();
    let near = |p: [f64; 3], q: [f64; 3]| p.iter().zip(q).all(|(a, b)| (a - b).abs() < 1e-9);
    let a = data.rows.iter().find(|r| near(r.at, [0.8, 0.25, 0.7])).unwrap();
    let b = beam.rows.iter().find(|r| near([r.x, 0.25, r.z], [0.8, 0.25, 0.7])).unwrap();
    let gap = (a.compliance - b.compliance).abs();
    assert!(
        gap <= a.compliance_error + b.compliance_error + 1e-3 * b.compliance,
        "file {:e} ± {:e}, builder {:e} ± {:e}",
        a.compliance,
        a.compliance_error,
        b.compliance,
        b.compliance_error
    );
    assert!((data.mass / beam.mass - 1.0).abs() < 1e-12, "mass {} against {}", data.mass, beam.mass);
    // In time, on each structure's own 200 modes: the same impacts at the same point agree
    // within the sum of their error estimates and the contact's shape (a disc against a
    // square of the same size; measured 4e-5 to 2.2e-4 apart).
    for (ta, ra) in data.in_time.rows.iter().zip(&data.rows) {
        if !near(ra.at, [0.8, 0.25, 0.7]) {
            continue;
        }
        let (tb, _) = beam
            .in_time
            .rows
            .iter()
            .zip(&beam.rows)
            .find(|(t, r)| t.body == ta.body && t.velocity == ta.velocity && near([r.x, 0.25, r.z], ra.at))
            .unwrap();
        let gap = (ta.p_max - tb.p_max).abs();
        assert!(gap <= ta.p_max_error + tb.p_max_error + 5e-3 * tb.p_max, "{ta:?} against {tb:?}");
    }
}

/// `impact mesh` writes the scene's tail beam as a mesh file that the shipped scene's
/// `[shell_mesh]` reads (the committed file is what it writes), and refuses a scene without a
/// `[tail_beam]`.
#[test]
fn impact_mesh_writes_the_shipped_file() {
    let out = tmp();
    let scene = scenes().join("tail-beam.toml");
    impact(["mesh", "--scene"]).arg(&scene).arg("--out").arg(out.join("mesh")).success();
    let written = std::fs::read_to_string(out.join("mesh/tail-beam.msh")).unwrap();
    let committed = std::fs::read_to_string(scenes().join("meshes/tail-beam.msh")).unwrap();
    assert!(
        written == committed,
        "scenes/meshes/tail-beam.msh is not what `impact mesh --scene scenes/tail-beam.toml` writes"
    );
    let refused =
        impact(["mesh", "--scene"]).arg(scenes().join("caving-stream.toml")).arg("--out").arg(out.join("none")).fails();
    assert!(refused.stderr.contains("[tail_beam]") && !out.join("none").exists(), "{}", refused.stderr);
}
