"""Error against run time, Rust BFS beside scikit-fem Argyris and Morley.

The problem: the paper's plate with four fixed corners (Con 1), compliance at the centre.
Both codes run their mesh ladders on this machine in this run; the reference value is the
mean of the two Richardson extrapolations (BFS and Argyris), which agree to ~1e-7.
Writes reference/data/timing.csv: code, element, mesh, dofs, seconds, compliance, rel_error.

Usage: python timing.py [--impact PATH_TO_BINARY] [--out FILE]
"""

import argparse
import csv
import json
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import plate_reference as pr  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


def richardson(values):
    q1, q2 = values[-2], values[-1]
    return q2 + (q2 - q1) / 3.0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--impact", default=str(ROOT / "target" / "release" / "impact"))
    ap.add_argument("--out", default=str(ROOT / "reference" / "data" / "timing.csv"))
    args = ap.parse_args(argv)

    bench = json.loads(subprocess.run([args.impact, "fem-bench", "--json"], check=True, capture_output=True, text=True).stdout)
    rows = [("rust", "BFS", f"{r['nx']}x{r['nz']}", r["dofs"], r["seconds"], r["compliance"]) for r in bench["ladder"]]

    plate, _ = pr.plate_from_scene(ROOT / "scenes" / "paper-table-1.toml")
    supports = {"corners": ["fixed"] * 4, "edges": {e: "free" for e in ("left", "right", "near", "far")}}
    centre = [(plate["length"] / 2, plate["width"] / 2)]
    ladders = {"argyris": [(5, 4), (10, 8), (20, 16), (40, 32)], "morley": [(10, 8), (20, 16), (40, 32), (80, 64), (160, 128)]}
    for elem, ladder in ladders.items():
        for nx, nz in ladder:
            mesh = pr.rectangle_mesh(plate["length"], plate["width"], nx, nz)
            (c,), info = pr.compliances(mesh, pr.ELEMENTS[elem](), plate, supports, centre)
            rows.append(("scikit-fem", elem, f"{nx}x{nz}", info["dofs"], info["assembly_s"] + info["solve_s"], c))

    bfs = [r[5] for r in rows if r[1] == "BFS"]
    arg = [r[5] for r in rows if r[1] == "argyris"]
    ref = 0.5 * (richardson(bfs) + richardson(arg))
    out = Path(args.out)
    tmp = out.with_suffix(".csv.tmp")
    with tmp.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["code", "element", "mesh", "dofs", "seconds", "compliance", "rel_error"])
        for code, elem, mesh, dofs, sec, c in rows:
            w.writerow([code, elem, mesh, dofs, f"{sec:.6e}", f"{c:.12e}", f"{abs(c - ref) / ref:.6e}"])
    tmp.replace(out)
    print(f"reference C = {ref:.10e} m/N (BFS and Argyris extrapolations differ by {abs(richardson(bfs) - richardson(arg)) / ref:.1e})")
    for r in rows:
        print(f"{r[0]:>10} {r[1]:>8} {r[2]:>8} dofs {r[3]:>6} {r[4]:8.4f} s  error {abs(r[5] - ref) / ref:.2e}")


if __name__ == "__main__":
    main()
