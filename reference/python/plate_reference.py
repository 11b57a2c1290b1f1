"""Reference compliances of supported Kirchhoff plates from scikit-fem.

The same plates as the Rust crate `plate_fem` (corner points fixed or on springs, edges
simply supported or clamped) with two independent triangular elements:

- Argyris: C1, quintic, conforming (DOFs u, u_x, u_y, u_xx, u_xy, u_yy at vertices, u_n
  at edge midpoints);
- Morley: quadratic, nonconforming (u at vertices, u_n at edge midpoints).

Plate parameters come from the same TOML scenes as the Rust code. For each case and element
the script solves a ladder of meshes and writes, per point, the compliance C = N^T K^-1 N
(by reciprocity: the deflection under a unit point load at that point), with mesh sizes,
DOFs, run times and package versions, to reference/data/<name>.json. Cases that ask for it
(clamped-edge-two-springs) also get each corner spring's reaction and energy share per point.

Before the cases, a self-check of the spring handling: four equal corner springs k and a
load at the centre give C = C(four fixed corners) + 1/(4k) (each spring carries 1/4 by
symmetry, and the plate shifts rigidly by 1/(4k) on top of the fixed-corner deflection).

Usage: python plate_reference.py [--quick] [--scene FILE] [--out DIR] [--case NAME ...]
"""

import argparse
import itertools
import json
import platform
import sys
import time
import tomllib
from pathlib import Path

import meshio
import numpy as np
import scipy
import scipy.sparse.linalg as spla
from scipy.sparse import diags
import skfem
from skfem import Basis, BilinearForm, ElementTriArgyris, ElementTriMorley, FacetBasis, MeshTri, asm
from skfem.element.discrete_field import DiscreteField
from skfem.helpers import dd, ddot, eye, trace

ROOT = Path(__file__).resolve().parents[2]


def plate_from_scene(path):
    """Plate geometry and material (SI) and the scene's spring stiffness."""
    scene = tomllib.loads(Path(path).read_text())
    p = scene["plate"]
    k_t = next((c["spring_stiffness_n_per_m"] for c in scene["conditions"] if "spring_stiffness_n_per_m" in c), None)
    return {
        "length": p["length_mm"] * 1e-3,
        "width": p["width_mm"] * 1e-3,
        "thickness": p["thickness_mm"] * 1e-3,
        "youngs_modulus": p["youngs_modulus_gpa"] * 1e9,
        "poisson_ratio": p["poisson_ratio"],
    }, k_t


def bending_form(plate):
    """a(u, v) = ∫ M(u) : κ(v), M = D[(1-ν)κ + ν tr(κ) I], D = E h³/12(1-ν²)."""
    e, nu, h = plate["youngs_modulus"], plate["poisson_ratio"], plate["thickness"]

    def moments(t):
        return e / (1.0 + nu) * (t + nu / (1.0 - nu) * eye(trace(t), 2))

    @BilinearForm
    def a(u, v, w):
        return h**3 / 12.0 * ddot(moments(dd(u)), dd(v))

    return a


def rectangle_mesh(length, width, nx, nz):
    """A structured triangle mesh over [0, L] x [0, B] (each square split in two)."""
    return MeshTri.init_tensor(np.linspace(0.0, length, nx + 1), np.linspace(0.0, width, nz + 1))


def mesh_from_meshio(path):
    """Reads a quad or triangle mesh written through meshio and triangulates it, so that
    scikit-fem runs on the nodes of the Rust mesh."""
    m = meshio.read(path)
    pts = m.points[:, :2].T
    tris = []
    for block in m.cells:
        if block.type == "quad":
            q = block.data
            tris.append(np.vstack([q[:, [0, 1, 2]], q[:, [0, 2, 3]]]))
        elif block.type == "triangle":
            tris.append(block.data)
    return MeshTri(pts, np.vstack(tris).T)


def constrained_dofs(basis, element, plate, supports):
    """DOFs held at zero: fixed corners (u) and supported edges.

    Argyris (vertex u, u_x, u_y, u_xx, u_xy, u_yy; u_n at edge midpoints; scikit-fem's y is
    the plate's z). Along a straight edge the trace of w is the quintic fixed by u, u_t, u_tt
    at its two ends, and the normal slope w_n is the quartic fixed by u_n, u_nt at its ends
    and u_n at its midpoint. So:
    - simple (w = 0 along the edge): u and its tangential derivatives u_t, u_tt at the
      vertices make the trace of w vanish identically;
    - clamped (w = 0 and w_n = 0 along the edge): in addition u_n (= ±u_x on x = const,
      ±u_y on z = const) at the vertices and edge midpoints, and its tangential derivative
      u_nt (u_xy); the slope then vanishes identically. u_nn (u_xx on x = const) stays free:
      the clamping moment M_n = -D w_nn is not zero.
    Both supports are thus imposed exactly (conforming). Morley (u at vertices, u_n at edge
    midpoints) holds u (simple) and u, u_n (clamped), its usual nonconforming supports."""
    length, width = plate["length"], plate["width"]
    held = []
    corners = [(0.0, 0.0), (length, 0.0), (0.0, width), (length, width)]
    p = basis.mesh.p
    for (cx, cz), kind in zip(corners, supports["corners"]):
        if kind == "fixed":
            node = int(np.argmin((p[0] - cx) ** 2 + (p[1] - cz) ** 2))
            held.extend(basis.get_dofs(nodes=np.array([node])).nodal["u"].tolist())
    edges = {
        "left": lambda x: np.isclose(x[0], 0.0),
        "right": lambda x: np.isclose(x[0], length),
        "near": lambda x: np.isclose(x[1], 0.0),
        "far": lambda x: np.isclose(x[1], width),
    }
    argyris = isinstance(element, ElementTriArgyris)
    for name, kind in supports["edges"].items():
        if kind == "free":
            continue
        dofs = basis.get_dofs(edges[name])
        # Along an x = const edge, u = 0 fixes u_y and u_yy too (tangential derivatives).
        tangential = ["u_y", "u_yy"] if name in ("left", "right") else ["u_x", "u_xx"]
        keys = ["u"] + (tangential if argyris else [])
        if kind == "clamped":
            keys += ["u_n"] + ((["u_x", "u_xy"] if name in ("left", "right") else ["u_y", "u_xy"]) if argyris else [])
        for k in keys:
            if k in dofs.nodal:
                held.extend(dofs.nodal[k].tolist())
            if k in dofs.facet:
                held.extend(dofs.facet[k].tolist())
    return np.unique(np.array(held, dtype=np.int64))


def spring_dofs(basis, plate, supports):
    """(u DOF at the corner, stiffness) of every corner spring."""
    length, width = plate["length"], plate["width"]
    corners = [(0.0, 0.0), (length, 0.0), (0.0, width), (length, width)]
    p = basis.mesh.p
    out = []
    for (cx, cz), kind in zip(corners, supports["corners"]):
        if isinstance(kind, (int, float)):
            node = int(np.argmin((p[0] - cx) ** 2 + (p[1] - cz) ** 2))
            out.append((int(basis.get_dofs(nodes=np.array([node])).nodal["u"][0]), float(kind)))
    return out


def compliances(mesh, element, plate, supports, points, split=None, refine=False):
    """C at each point: solve K w = N(p) and take N(p)·w.

    With `refine`, the solve is on the symmetrically diagonally scaled matrix with one step
    of iterative refinement. The plain LU loses digits on fine Argyris meshes (vertex DOFs
    from u to u_xx, stiffness entries spread over ~h⁻⁴): on the clamped-edge-two-springs
    case at 80 x 64 it is off by 1e-8 relative at (L, B/2), against 1e-10 refined. The
    paper-* cases stop at 40 x 32 and keep the plain solve (their data unchanged).

    With `split` (a dict), also fills in per point each corner spring's reaction
    R = k w(corner) (per unit load, positive when the spring pushes against the load) and its
    energy share R²/k / C, and the bending share a(w, w) / C from the bending matrix alone
    (C = a(w, w) + Σ R²/k: the shares sum to 1)."""
    t0 = time.perf_counter()
    basis = Basis(mesh, element)
    k = asm(bending_form(plate), basis).tocsr()
    springs = spring_dofs(basis, plate, supports)
    if split is not None:
        k_bend = k.copy()
    for dof, stiffness in springs:
        k[dof, dof] += stiffness
    held = constrained_dofs(basis, element, plate, supports)
    free = np.setdiff1d(np.arange(basis.N), held)
    kff = k[free][:, free].tocsc()
    t1 = time.perf_counter()
    if refine:
        scale = 1.0 / np.sqrt(kff.diagonal())
        lu_scaled = spla.splu((diags(scale) @ kff @ diags(scale)).tocsc())

        def solve(f):
            w = scale * lu_scaled.solve(scale * f)
            return w + scale * lu_scaled.solve(scale * (f - kff @ w))

    else:
        lu = spla.splu(kff)
        solve = lu.solve
    out = []
    if split is not None:
        split.update(spring_reaction=[], spring_energy_share=[], bending_energy_share=[])
    for x, z in points:
        f = basis.point_source(np.array([x, z]))[free]
        w = solve(f)
        out.append(float(f @ w))
        if split is not None:
            full = np.zeros(basis.N)
            full[free] = w
            c = out[-1]
            split["spring_reaction"].append([float(s * full[d]) for d, s in springs])
            split["spring_energy_share"].append([float(s * full[d] ** 2 / c) for d, s in springs])
            split["bending_energy_share"].append(float(full @ (k_bend @ full) / c))
    t2 = time.perf_counter()
    return out, {"dofs": int(basis.N), "free_dofs": int(len(free)), "assembly_s": t1 - t0, "solve_s": t2 - t1}


class ElementTriArgyrisLocal(ElementTriArgyris):
    """scikit-fem's Argyris triangle with its power basis centred on each element and an
    equilibrated Vandermonde inverse. The same element in exact arithmetic.

    scikit-fem's ElementGlobal builds each element's basis from monomials in the global
    coordinates, x^i y^j up to degree 5, and inverts their 21 x 21 matrix of DOF values
    (the Vandermonde matrix) per element. For an element of size h at distance ~L from the
    origin that matrix has a condition number ~(L/h)^5 times the spread of u to u_xx scales:
    on this plate the stock element already loses ~1e-8 relative in C at 80 x 64 and ~5e-4
    at 160 x 128 (C then drops below its 80 x 64 value). Here the monomials are in x - c_e
    (c_e the element's centroid; DOFs are derivatives, which a shift leaves unchanged) and
    the matrix is row- and column-scaled before inversion, V⁻¹ = C (R V C)⁻¹ R. Checked to
    agree with the stock element on coarse meshes (see `argyris_local_check`). Used by the
    cases with the option "local_argyris"; the paper-* data (40 x 32 at most) were made with
    the stock element and are kept as they are."""

    def gbasis(self, mapping, X, i, tind=None):
        if tind is None:
            tind = np.arange(mapping.mesh.t.shape[1])
        if self.V is None:
            self._pbasis_init(self.maxdeg, self.dim, self.derivatives, self.tensorial_basis)
            mesh = mapping.mesh
            self._centre = mesh.p[:, mesh.t].mean(axis=1)
            a = self._eval_dofs(mesh)
            r = 1.0 / np.abs(a).max(axis=2)
            a = a * r[:, :, None]
            c = 1.0 / np.abs(a).max(axis=1)
            a = a * c[:, None, :]
            self.V = c[:, :, None] * np.linalg.inv(a) * r[:, None, :]
        V = self.V[tind]
        x = mapping.F(X, tind=tind)
        centre = self._centre[:, tind].reshape((2, len(np.atleast_1d(tind))) + (1,) * (x[0].ndim - 1))
        x, y = x - centre
        # The power basis x^a y^b, a + b <= 5, in scikit-fem's order (a outer, b inner), with
        # its first and second derivatives, from tables of powers (faster than the lambdas).
        px = [np.ones_like(x)] + [x**n for n in range(1, self.maxdeg + 1)]
        py = [np.ones_like(y)] + [y**n for n in range(1, self.maxdeg + 1)]

        def mono(a, b, da, db):
            if a < da or b < db:
                return 0.0
            ca = np.prod(range(a - da + 1, a + 1)) if da else 1
            cb = np.prod(range(b - db + 1, b + 1)) if db else 1
            return (ca * cb) * px[a - da] * py[b - db]

        powers = [(a, b) for a in range(self.maxdeg + 1) for b in range(self.maxdeg + 1) if a + b <= self.maxdeg]
        coef = V[:, :, i][:, :, None] if x.ndim == 2 else V[:, :, i].reshape(V.shape[:2] + (1,) * (x.ndim - 1))
        U = [np.zeros(x.shape), np.zeros((2,) + x.shape), np.zeros((2, 2) + x.shape)]
        for itr, (a, b) in enumerate(powers):
            c = coef[:, itr]
            U[0] += c * mono(a, b, 0, 0)
            U[1][0] += c * mono(a, b, 1, 0)
            U[1][1] += c * mono(a, b, 0, 1)
            U[2][0, 0] += c * mono(a, b, 2, 0)
            xy = c * mono(a, b, 1, 1)
            U[2][0, 1] += xy
            U[2][1, 0] += xy
            U[2][1, 1] += c * mono(a, b, 0, 2)
        return (DiscreteField(value=U[0], grad=U[1], hess=U[2]),)

    def _eval_dofs(self, mesh, tind=None):
        """ElementGlobal._eval_dofs (scikit-fem 12.0.2) with the vertices and edge midpoints
        taken relative to each element's centroid (the normals are unchanged)."""
        if tind is None:
            tind = np.arange(mesh.t.shape[1])
        N = len(self._pbasis[()])
        V = np.zeros((len(tind), N, N))
        centre = mesh.p[:, mesh.t[:, tind]].mean(axis=1)
        w = {"v": np.array([mesh.p[:, mesh.t[itr, tind]] - centre for itr in range(mesh.t.shape[0])])}
        w["e"] = np.array([0.5 * (w["v"][itr] + w["v"][(itr + 1) % mesh.t.shape[0]]) for itr in range(mesh.t.shape[0])])
        w["n"] = np.array([w["v"][itr] - w["v"][(itr + 1) % mesh.t.shape[0]] for itr in range(mesh.t.shape[0])])
        w["n"][2] = -w["n"][2]  # direction swapped due to mesh numbering
        for itr in range(3):
            w["n"][itr] = np.array([w["n"][itr, 1, :], -w["n"][itr, 0, :]])
            w["n"][itr] /= np.linalg.norm(w["n"][itr], axis=0)
        fb = FacetBasis(mesh, mesh.elem(), intorder=0)
        ix = np.isin(mesh.t2f, mesh.boundary_facets())
        sortix = np.argsort(mesh.t2f[ix])
        norms1 = np.vstack((w["n"][:, 0, :][ix][sortix], w["n"][:, 1, :][ix][sortix]))
        norms2 = fb.normals[:, :, 0]
        signs = np.diag(norms1.T @ norms2)
        signs1 = signs.copy()
        signs1[sortix] = signs
        w["n"][:, 0, :][ix] *= signs1
        w["n"][:, 1, :][ix] *= signs1
        for itr in range(N):
            for jtr in range(N):
                F = {k: self._pbasis[k][itr] for k in self._pbasis}
                V[:, jtr, itr] = self.gdof(F, w, jtr)
        return V


ELEMENTS = {"argyris": ElementTriArgyris, "morley": ElementTriMorley}


# Spring stiffness of the general support case: soft enough (against the plate's corner
# stiffness, ~D/L² x O(10)) that the springs carry a visible share of the energy.
K_SOFT = 1.0e6

# Argyris ladder of the general case: down to 160 x 128, so that the two finest meshes give a
# Richardson error estimate below 1e-6 relative at its points (the point-load compliance
# converges at O(h²)).
FINE_ARGYRIS = [(5, 4), (10, 8), (20, 16), (40, 32), (80, 64), (160, 128)]


def cases(plate, k_t):
    """The reference cases: the paper's three conditions and the classical edge checks, then
    a general support set (a clamped edge, two corner springs, free edges).

    Each case is (name, supports, points, options); options may hold "ladders" (per
    element, replacing the default ladder in full runs) and "split" (write the spring
    reactions and energy shares), "refine" (scaled solve with iterative refinement) and
    "local_argyris" (ElementTriArgyrisLocal for Argyris)."""
    length, width = plate["length"], plate["width"]
    free_edges = {"left": "free", "right": "free", "near": "free", "far": "free"}
    pts = [(length / 2, width / 2), (length / 4, width / 4), (length / 2, 0.0), (0.0, width / 2), (0.1 * length, 0.1 * width)]
    out = [
        ("paper-con1", {"corners": ["fixed"] * 4, "edges": free_edges}, pts),
        ("paper-con2", {"corners": [k_t] * 4, "edges": free_edges}, pts),
        ("paper-con3", {"corners": ["fixed", k_t, "fixed", k_t], "edges": free_edges}, pts),
        (
            "paper-simple-all",
            {"corners": ["free"] * 4, "edges": {"left": "simple", "right": "simple", "near": "simple", "far": "simple"}},
            pts[:3],
        ),
        (
            "paper-simple-free",
            {"corners": ["free"] * 4, "edges": {"left": "simple", "right": "simple", "near": "free", "far": "free"}},
            pts[:3],
        ),
    ]
    out = [(name, supports, points, {}) for name, supports, points in out]
    # Left edge (x = 0) clamped; the two right corners (x = L, z = 0 and z = B: corners 1 and 3
    # in the order (0, 0), (L, 0), (0, B), (L, B)) on springs; the other edges free. The left
    # corners are held by the clamp, so "free" as corner supports. Points: centre, (3L/4, B/4),
    # the middle of the free right edge between the springs, a point of the free near edge,
    # then the script's (L/4, B/4) and near edge midpoint. (0, B/2) lies on the clamped edge
    # (C = 0) and is left out.
    out.append(
        (
            "clamped-edge-two-springs",
            {
                "corners": ["free", K_SOFT, "free", K_SOFT],
                "edges": {"left": "clamped", "right": "free", "near": "free", "far": "free"},
            },
            [
                (length / 2, width / 2),
                (0.75 * length, width / 4),
                (length, width / 2),
                (length / 4, 0.0),
                (length / 4, width / 4),
                (length / 2, 0.0),
            ],
            {"ladders": {"argyris": FINE_ARGYRIS}, "split": True, "refine": True, "local_argyris": True},
        )
    )
    return out


def argyris_local_check(plate, k_t, nx=10, nz=8):
    """Largest relative difference between ElementTriArgyrisLocal and scikit-fem's
    ElementTriArgyris over all cases and points on a coarse mesh (where the stock element is
    still well conditioned)."""
    mesh = rectangle_mesh(plate["length"], plate["width"], nx, nz)
    worst = 0.0
    for _, supports, points, _ in cases(plate, k_t):
        a, _ = compliances(mesh, ElementTriArgyris(), plate, supports, points)
        b, _ = compliances(mesh, ElementTriArgyrisLocal(), plate, supports, points)
        scale = max(abs(y) for y in b)  # points on supported edges have C ~ 1e-25: noise
        worst = max([worst] + [abs(x - y) / scale for x, y in zip(a, b)])
    return worst


def spring_self_check(plate, nx, nz, k=K_SOFT):
    """Four equal corner springs k, load at the centre: by symmetry each spring carries 1/4,
    and the deflection is that with fixed corners plus the rigid shift 1/(4k), so
    C = C(four fixed corners) + 1/(4k) exactly. Returns, per element, the deviation relative
    to 1/(4k) and the spring reactions' largest deviation from 1/4."""
    free_edges = {"left": "free", "right": "free", "near": "free", "far": "free"}
    centre = [(plate["length"] / 2, plate["width"] / 2)]
    mesh = rectangle_mesh(plate["length"], plate["width"], nx, nz)
    out = {}
    for elem, cls in ELEMENTS.items():
        (fixed,), _ = compliances(mesh, cls(), plate, {"corners": ["fixed"] * 4, "edges": free_edges}, centre)
        split = {}
        (sprung,), _ = compliances(mesh, cls(), plate, {"corners": [k] * 4, "edges": free_edges}, centre, split)
        out[elem] = {
            "fixed": fixed,
            "springs": sprung,
            "deviation": (sprung - fixed - 0.25 / k) * 4.0 * k,
            "reaction_deviation": max(abs(r - 0.25) for r in split["spring_reaction"][0]),
        }
    return out


def versions():
    return {
        "python": platform.python_version(),
        "scikit-fem": skfem.__version__,
        "meshio": meshio.__version__,
        "numpy": np.__version__,
        "scipy": scipy.__version__,
    }


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default=str(ROOT / "scenes" / "paper-table-1.toml"))
    ap.add_argument("--out", default=str(ROOT / "reference" / "data"))
    ap.add_argument("--quick", action="store_true", help="coarse meshes only (CI smoke run)")
    ap.add_argument("--case", nargs="+", metavar="NAME", help="only these cases (default: all)")
    args = ap.parse_args(argv)
    plate, k_t = plate_from_scene(args.scene)
    # (nx, nz) ladders that halve h exactly and keep the centre on a node: the Rust ladder
    # of the paper's plate is 10 x 8, 20 x 16, ... (B/L = 0.785 ≈ 4/5).
    ladders = {
        "argyris": [(5, 4), (10, 8), (20, 16), (40, 32)],
        "morley": [(10, 8), (20, 16), (40, 32), (80, 64), (160, 128)],
    }
    if args.quick:
        ladders = {"argyris": [(5, 4), (10, 8)], "morley": [(10, 8), (20, 16)]}
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    all_cases = cases(plate, k_t)
    if args.case:
        unknown = set(args.case) - {c[0] for c in all_cases}
        if unknown:
            ap.error(f"unknown case(s): {', '.join(sorted(unknown))}")
    for name, supports, points, options in all_cases:
        if args.case and name not in args.case:
            continue
        record = {
            "case": name,
            "scene": str(Path(args.scene).relative_to(ROOT)) if Path(args.scene).is_relative_to(ROOT) else args.scene,
            "plate": plate,
            "supports": supports,
            "points": points,
            "versions": versions(),
            "results": {},
        }
        if options.get("split"):
            # Which corner each entry of spring_reaction / spring_energy_share belongs to.
            corner_points = [(0.0, 0.0), (plate["length"], 0.0), (0.0, plate["width"]), (plate["length"], plate["width"])]
            record["springs"] = [
                {"corner": i, "point": corner_points[i], "stiffness": float(kind)}
                for i, kind in enumerate(supports["corners"])
                if isinstance(kind, (int, float))
            ]
            record["results"] = record.pop("results")  # keep "results" last
        case_ladders = ladders if args.quick else {**ladders, **options.get("ladders", {})}
        for elem, ladder in case_ladders.items():
            runs = []
            for n, nz in ladder:
                mesh = rectangle_mesh(plate["length"], plate["width"], n, nz)
                split = {} if options.get("split") else None
                cls = ElementTriArgyrisLocal if elem == "argyris" and options.get("local_argyris") else ELEMENTS[elem]
                c, info = compliances(mesh, cls(), plate, supports, points, split, options.get("refine", False))
                runs.append({"nx": n, "nz": nz, "h": plate["length"] / n, **info, "compliance": c, **(split or {})})
                if split is not None:
                    worst = max(abs(b + sum(s) - 1.0) for b, s in zip(split["bending_energy_share"], split["spring_energy_share"]))
                    assert worst < 1e-8, f"{name} {elem} {n}x{nz}: energy shares sum to 1 ± {worst:e}"
                print(f"{name} {elem} {n}x{nz}: dofs {info['dofs']}, C[0] = {c[0]:.10e}, {info['assembly_s'] + info['solve_s']:.2f} s", file=sys.stderr)
            record["results"][elem] = runs
        suffix = "-quick" if args.quick else ""
        path = out / f"{name}{suffix}.json"
        tmp = path.with_suffix(".json.tmp")
        tmp.write_text(json.dumps(record, indent=1))
        tmp.replace(path)
    # Last, so that they are in the tail of CI's log.
    worst = argyris_local_check(plate, k_t)
    print(f"Argyris, local power basis against scikit-fem's, 10x8, all cases and points: {worst:.1e} relative", file=sys.stderr)
    assert worst < 1e-8, f"local Argyris differs from scikit-fem's by {worst:e}"
    nx, nz = (10, 8) if args.quick else (20, 16)
    for elem, r in spring_self_check(plate, nx, nz).items():
        print(
            f"spring self-check {elem} {nx}x{nz}: C(4 springs k={K_SOFT:g}) - C(4 fixed) - 1/(4k) = {r['deviation']:.2e} x 1/(4k); "
            f"reactions 1/4 ± {r['reaction_deviation']:.1e}",
            file=sys.stderr,
        )
        assert abs(r["deviation"]) < 1e-8 and r["reaction_deviation"] < 1e-8, f"spring self-check failed: {elem} {r}"


if __name__ == "__main__":
    main()
