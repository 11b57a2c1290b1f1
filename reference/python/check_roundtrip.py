"""Round trip Rust -> meshio -> scikit-fem on identical geometry.

1. `impact field` writes the Rust mesh and deflection under a unit load (JSON);
2. export_fields.py writes .vtu and .xdmf with meshio;
3. meshio reads both back: points, cells and every field must equal the JSON exactly;
4. scikit-fem reads the same .vtu mesh through meshio, triangulates its quads, and solves
   the same plate (Argyris) on those nodes: its compliance at the load point must agree
   with the Rust deflection there to the discretization error of the mesh.

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

    passed = sum(results)
    failed = len(results) - passed
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
