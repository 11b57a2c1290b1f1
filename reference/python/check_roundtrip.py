"""Round trip Rust -> meshio -> scikit-fem on identical geometry.

1. `impact field` writes the Rust mesh and deflection under a unit load (JSON);
2. export_fields.py writes .vtu and .xdmf with meshio;
3. meshio reads both back: points, cells and every field must equal the JSON exactly;
4. scikit-fem reads the same .vtu mesh through meshio, triangulates its quads, and solves
   the same plate (Argyris) on those nodes: its compliance at the load point must agree
   with the Rust deflection there to the discretization error of the mesh;
5. `impact field --format vtu` (the .vtu written by Rust itself, with vtkio) read by meshio:
   the same points, quads and fields as the JSON, displacement = (0, 0, w), the stresses
   6M/h², the near-load flag on the elements touching the load, and --force-n scaling
   every value.
6. `impact field --format pvd` (the transient deflection during contact, a ParaView time
   series): the .pvd parsed as XML, every .vtu it names read by meshio on the same mesh,
   displacement = (0, 0, w), times rising from 0, and the struck node's w at each frame equal
   to the plate displacement of the history.csv row of the same time.

7. `impact mesh` (the tail beam as MSH 4.1) read by meshio, written again as MSH 2.2, and
   read back by `impact compare` through [shell_mesh]: the same compliances from both files.

Prints one line per check and a closing 'N passed, N failed'; exits non-zero on failure.
Usage: python check_roundtrip.py [--impact PATH_TO_BINARY]
"""

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import meshio
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import export_fields  # noqa: E402
import plate_reference as pr  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


def check_rust_vtu(check, path, doc, force, h, load):
    """meshio reads `impact field --format vtu` back with the JSON's values times `force`.
    Rust writes binary f64 and the JSON holds shortest round-trip decimals, so the same
    multiplication gives the same bits: equality is exact except for 6M/h², whose factors
    Rust and numpy may group differently."""
    tag = f".vtu from Rust (F = {force} N)"
    m = meshio.read(path)

    def scalar(a):
        # vtkio writes NumberOfComponents="1" on scalars, which meshio keeps as a column.
        a = np.asarray(a)
        return a[:, 0] if a.ndim == 2 and a.shape[1] == 1 else a

    # The file says what it is: its load and the load point in the dataset's FieldData.
    fd = {k: float(np.asarray(v).ravel()[0]) for k, v in m.field_data.items()}
    check(f"{tag} field_data force_N, load_x_m, load_z_m",
          (fd.get("force_N"), fd.get("load_x_m"), fd.get("load_z_m")) == (float(force), load[0], load[1]), str(fd))
    pts = np.asarray(doc["points"])
    check(f"{tag} points", np.array_equal(m.points, np.column_stack([pts, np.zeros(len(pts))])))
    check(f"{tag} quads", list(m.cells_dict) == ["quad"] and np.array_equal(m.cells_dict["quad"], np.asarray(doc["quads"])))
    for k in ("w", "w_x", "w_z"):
        check(f"{tag} point_data {k}", np.array_equal(scalar(m.point_data[k]), np.asarray(doc["point_data"][k]) * force))
    w = np.asarray(doc["point_data"]["w"]) * force
    disp = m.point_data["displacement"]
    check(f"{tag} displacement = (0, 0, w)", disp.shape == (len(w), 3) and np.array_equal(disp, np.column_stack([0 * w, 0 * w, w])))
    for k, s in (("M_x", "sigma_x"), ("M_z", "sigma_z"), ("M_xz", "sigma_xz")):
        moment = np.asarray(doc["cell_data"][k]) * force
        check(f"{tag} cell_data {k}", np.array_equal(scalar(m.cell_data[k][0]), moment))
        check(f"{tag} cell_data {s} = 6M/h^2", np.allclose(scalar(m.cell_data[s][0]), 6.0 * moment / h**2, rtol=1e-14, atol=0.0))
    # The flag marks exactly the elements whose rectangle holds the load point.
    quads = np.asarray(doc["quads"])
    lo, hi = pts[quads[:, 0]], pts[quads[:, 2]]
    tol = 1e-9 * np.abs(pts).max()
    touching = np.all((lo - tol <= load) & (np.asarray(load) <= hi + tol), axis=1)
    near = scalar(m.cell_data["near_load"][0])
    check(f"{tag} near_load on the elements at the load", np.array_equal(near.astype(bool), touching) and touching.sum() >= 1,
          f"({int(near.sum())} elements)")


def check_rust_pvd(check, series_dir, doc, load, thickness):
    """meshio reads every frame the .pvd names (the contacts and the ringing after); each
    frame's struck-node deflection is the history's plate displacement at the same time, and
    its surface stresses are 6M/h^2 of its moments. The history's value is N^T w with the
    element's shape functions evaluated at the node, which are 1 and 0 up to the round-off of
    the node coordinates: hence a 1e-12 relative tolerance rather than equality."""
    import csv
    import xml.etree.ElementTree as ET

    tag = ".pvd from Rust"
    root = ET.parse(series_dir / "contact.pvd").getroot()
    sets = root.findall("./Collection/DataSet")
    check(f"{tag} is a VTK collection with frames", root.get("type") == "Collection" and len(sets) >= 10, f"({len(sets)} frames)")
    times = [float(d.get("timestep")) for d in sets]
    check(f"{tag} times start at 0 and rise", times[0] == 0.0 and all(b > a for a, b in zip(times, times[1:])))
    with open(series_dir / "history.csv", newline="") as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    by_time = {float(r["t_s"]): float(r["plate_displacement_m"]) for r in rows}
    pts = np.asarray(doc["points"])
    node = int(np.argmin((pts[:, 0] - load[0]) ** 2 + (pts[:, 1] - load[1]) ** 2))
    same_mesh, warp, stresses, matched, worst, peak = True, True, True, 0, 0.0, 0.0
    for d, t in zip(sets, times):
        m = meshio.read(series_dir / d.get("file"))
        same_mesh &= np.array_equal(m.points[:, :2], pts) and np.array_equal(m.cells_dict["quad"], np.asarray(doc["quads"]))
        w = np.asarray(m.point_data["w_m"])
        w = w[:, 0] if w.ndim == 2 else w
        disp = m.point_data["displacement_m"]
        warp &= disp.shape == (len(w), 3) and np.array_equal(disp, np.column_stack([0 * w, 0 * w, w]))
        for k in ("x", "z", "xz"):
            moment = np.asarray(m.cell_data[f"M_{k}_N_m_per_m"][0]).ravel()
            sigma = np.asarray(m.cell_data[f"sigma_{k}_Pa"][0]).ravel()
            stresses &= np.allclose(sigma, 6.0 * moment / thickness**2, rtol=1e-14, atol=0.0)
        peak = max(peak, float(np.abs(w).max()))
        if t in by_time:
            matched += 1
            worst = max(worst, abs(w[node] - by_time[t]))
    check(f"{tag} every frame on the same mesh", same_mesh)
    check(f"{tag} every frame: displacement = (0, 0, w)", warp)
    check(f"{tag} every frame: sigma = 6 M / h^2", stresses)
    check(f"{tag} frames after t = 0 found in history.csv", matched == len(sets) - 1, f"({matched} of {len(sets) - 1})")
    check(f"{tag} struck-node w = history plate displacement", peak > 0 and worst <= 1e-12 * peak, f"(worst {worst:.1e} m of {peak:.2e} m)")


def check_mesh_file(check, impact, tmp):
    """`impact mesh` writes the tail beam as MSH 4.1; meshio reads it (points, quadrilaterals,
    the named groups) and writes it again as MSH 2.2, a format and writer impact shares nothing
    with; `impact compare` on the shipped [shell_mesh] scene (two meshes, for speed) gives the
    same compliances from either file, to the last bit."""
    tmp = Path(tmp)
    subprocess.run([impact, "mesh", "--scene", str(ROOT / "scenes" / "tail-beam.toml"), "--out", str(tmp / "mesh")], check=True, capture_output=True)
    ours = tmp / "mesh" / "tail-beam.msh"
    m = meshio.read(ours)
    quads = sum(len(c.data) for c in m.cells if c.type == "quad")
    lines = sum(len(c.data) for c in m.cells if c.type == "line")
    names = {"top", "bottom", "webs", "ribs", "ends", "pins", "jack 1", "jack 2"}
    check("meshio reads impact mesh: points, quads, lines", (len(m.points), quads, lines) == (864, 902, 4), f"({len(m.points)}, {quads}, {lines})")
    check("meshio reads impact mesh: the named groups", set(m.field_data) == names, str(sorted(m.field_data)))
    theirs = tmp / "meshio.msh"
    meshio.write(theirs, m, file_format="gmsh22", binary=False)
    scene = (ROOT / "scenes" / "tail-beam-mesh.toml").read_text().replace("levels = 4", "levels = 2")
    tables = []
    for name, mesh in (("ours", ours), ("theirs", theirs)):
        text = scene.replace('file = "meshes/tail-beam.msh"', f'file = "{mesh.as_posix()}"')
        path = tmp / f"{name}.toml"
        path.write_text(text)
        subprocess.run([impact, "compare", "--scene", str(path), "--out", str(tmp / name)], check=True, capture_output=True)
        rows = (tmp / name / "shell-mesh" / "structure.csv").read_text().splitlines()
        tables.append([r for r in rows if not r.startswith("#")])
    check("the shell-mesh compliances from impact's MSH 4.1 and meshio's MSH 2.2", tables[0] == tables[1] and len(tables[0]) == 5)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--impact", default=str(ROOT / "target" / "release" / "impact"))
    args = ap.parse_args(argv)
    results = []

    def check(name, ok, detail=""):
        results.append(ok)
        print(f"{'ok  ' if ok else 'FAIL'} {name} {detail}")

    with tempfile.TemporaryDirectory() as tmp:
        field = Path(tmp) / "field.json"
        # A coarse mesh: the check is of the data path, not of accuracy.
        x_mm, z_mm = 229.2, 180.0
        subprocess.run(
            [args.impact, "field", "--condition", "Con 1", "--x-mm", str(x_mm), "--z-mm", str(z_mm), "--elements", "20", "--out", str(field)],
            check=True,
        )
        doc = export_fields.read_field(field)
        vtu, xdmf = export_fields.export(field, tmp)
        for path in (vtu, xdmf):
            m = meshio.read(path)
            check(f"{path.suffix} points", np.array_equal(m.points[:, :2], np.asarray(doc["points"])))
            check(f"{path.suffix} quads", np.array_equal(m.cells_dict["quad"], np.asarray(doc["quads"])))
            for k, v in doc["point_data"].items():
                check(f"{path.suffix} point_data {k}", np.array_equal(m.point_data[k], np.asarray(v)))
            for k, v in doc["cell_data"].items():
                check(f"{path.suffix} cell_data {k}", np.array_equal(m.cell_data[k][0], np.asarray(v)))

        # Same geometry in scikit-fem: the .vtu mesh, triangulated.
        plate, _ = pr.plate_from_scene(ROOT / "scenes" / "paper-table-1.toml")
        mesh = pr.mesh_from_meshio(vtu)
        check("scikit-fem mesh has the Rust nodes", mesh.p.shape[1] == len(doc["points"]))
        supports = {"corners": ["fixed"] * 4, "edges": {e: "free" for e in ("left", "right", "near", "far")}}
        x, z = x_mm * 1e-3, z_mm * 1e-3
        (c_skfem,), _ = pr.compliances(mesh, pr.ElementTriArgyris(), plate, supports, [(x, z)])
        pts = np.asarray(doc["points"])
        node = int(np.argmin((pts[:, 0] - x) ** 2 + (pts[:, 1] - z) ** 2))
        c_rust = doc["point_data"]["w"][node]
        rel = abs(c_skfem - c_rust) / c_rust
        # On 20 x 16 both elements are within ~1.5e-4 (BFS) and ~3e-5 (Argyris) of the limit.
        check("Argyris on the Rust mesh vs Rust BFS compliance", rel < 5e-4, f"(rel. difference {rel:.2e})")

        # The .vtu Rust writes itself, read by meshio, against the JSON.
        for force in (1.0, 2.5):
            rust_vtu = Path(tmp) / f"rust-{force}.vtu"
            subprocess.run(
                [args.impact, "field", "--condition", "Con 1", "--x-mm", str(x_mm), "--z-mm", str(z_mm), "--elements", "20",
                 "--format", "vtu", "--force-n", str(force), "--out", str(rust_vtu)],
                check=True,
            )
            check_rust_vtu(check, rust_vtu, doc, force, plate["thickness"], (x, z))

        # The transient time series, on the same mesh as the JSON.
        series = Path(tmp) / "series"
        subprocess.run(
            [args.impact, "field", "--condition", "Con 1", "--x-mm", str(x_mm), "--z-mm", str(z_mm), "--elements", "20",
             "--format", "pvd", "--out", str(series)],
            check=True,
        )
        check_rust_pvd(check, series, doc, (x, z), plate["thickness"])

        # A shell mesh through meshio and back.
        check_mesh_file(check, args.impact, tmp)

    passed = sum(results)
    failed = len(results) - passed
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
