"""Turns an `impact field` JSON file (format impact-plate-field/1) into .vtu and .xdmf
files that ParaView opens, with meshio.

Usage: python export_fields.py field.json [--out DIR]
Writes DIR/<stem>.vtu and DIR/<stem>.xdmf (data inline as XML) and prints their paths.
"""

import argparse
import json
from pathlib import Path

import meshio
import numpy as np

FORMAT = "impact-plate-field/1"


def read_field(path):
    """The JSON document, checked for its format tag."""
    doc = json.loads(Path(path).read_text())
    if doc.get("format") != FORMAT:
        raise ValueError(f"{path}: format is {doc.get('format')!r}, expected {FORMAT!r}")
    return doc


def to_meshio(doc):
    """A meshio.Mesh: points in 3-D (z-coordinate of the plate mapped to y, w to 0), quads,
    nodal w, w_x, w_z, w_xz and cell moments M_x, M_z, M_xz."""
    pts2 = np.asarray(doc["points"], dtype=float)
    points = np.column_stack([pts2, np.zeros(len(pts2))])
    quads = np.asarray(doc["quads"], dtype=np.int64)
    point_data = {k: np.asarray(v, dtype=float) for k, v in doc["point_data"].items()}
    cell_data = {k: [np.asarray(v, dtype=float)] for k, v in doc["cell_data"].items()}
    return meshio.Mesh(points, [("quad", quads)], point_data=point_data, cell_data=cell_data)


def export(path, out=None):
    doc = read_field(path)
    mesh = to_meshio(doc)
    out = Path(out) if out else Path(path).parent
    out.mkdir(parents=True, exist_ok=True)
    stem = Path(path).stem
    vtu, xdmf = out / f"{stem}.vtu", out / f"{stem}.xdmf"
    meshio.write(vtu, mesh)
    # Data inline as XML: no HDF5 (h5py) needed, and ParaView reads it the same.
    meshio.write(xdmf, mesh, data_format="XML")
    return vtu, xdmf


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("field")
    ap.add_argument("--out")
    args = ap.parse_args(argv)
    for p in export(args.field, args.out):
        print(p)


if __name__ == "__main__":
    main()
