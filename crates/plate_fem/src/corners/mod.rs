//! Any set of corner supports from one factorization.
//!
//! Factorize once with all four corners on base springs k_b (stiff, so that the base is
//! close to the fixed plate). Every point is solved once on this base; every corner set is
//! then 4 x 4 algebra, by one of two formulations that agree in exact arithmetic.
//!
//! # The rank-4 update
//!
//! A target set differs from the base only at the four corner w DOFs:
//! K = K_b + U_S Δ U_Sᵀ with Δ_i = k_i - k_b (k_i = ∞ for a fixed corner, 0 for a free one)
//! on the corners S that change. With u = Uᵀ K_b⁻¹ N (the base deflection of the corners
//! under the unit load, by reciprocity) and G = Uᵀ K_b⁻¹ U (the 4 x 4 corner flexibility of
//! the base), the Woodbury identity gives
//!
//! ```text
//! (Δ⁻¹ + G_SS) λ = u_S,    C = N ᵀ K_b⁻¹ N - u_Sᵀ λ,    w_corners = u - G_{·S} λ
//! ```
//!
//! where λ are the extra corner forces; a fixed corner has Δ⁻¹ = 0, so rigid supports need
//! no large number. Spring reactions are k_i w_i and spring stores k_i w_i².
//!
//! It loses accuracy at both ends of the stiffness range, in floating point only:
//! - a soft spring, k ≪ k_b: Δ⁻¹ = 1/(k - k_b) differs from the free value -1/k_b by the
//!   relative amount k/k_b, which is all the information about the spring. The matrix
//!   Δ⁻¹ + G_SS tends to the free plate's, singular along the rigid motions, and its
//!   condition grows like (k_b/k)(k_b/4s) (s: the twist stiffness below). Below
//!   k/k_b ~ 1e-16 the spring is lost altogether and the system is singular.
//! - a stiff spring, k ≫ k_b: w_i = u_i - (Gλ)_i is a difference of terms of size |u|
//!   whose round-off, ε|u|, is multiplied by k in the reaction k w_i (error ~ ε k/k_b) and
//!   in the store k w_i² (which can then exceed C and make the plate store negative).
//!
//! # Condensation onto the corners (edges free)
//!
//! Condense the plate onto its four corner w DOFs. The interior, with the corners held, is
//! the plate on four fixed corners (Con 1), so exactly
//!
//! ```text
//! C = C_fix + fᵀ c,    (S + D) c = f,    r = f - S c,
//! ```
//!
//! with C_fix the compliance on fixed corners, f the fixed-corner reactions, S the 4 x 4
//! corner stiffness of the unsupported plate, D = diag(k_i), c the corner deflections and r
//! the reactions. With free edges the rigid motions w = a + bx + cz are exact in the
//! element, so S annihilates their corner values (1, x_i, z_i); their complement in R⁴ is
//! the twist t = (1, -1, -1, 1), and S = s t tᵀ with one scalar s > 0, for any mesh. From
//! the base, G = (S + k_b I)⁻¹, so f = G⁻¹ u (the update to four fixed corners, exactly as
//! the rank-4 path does it), C_fix = Nᵀ K_b⁻¹ N - uᵀ f, and tᵀ G t = 4/(4s + k_b).
//!
//! With flexibilities φ_i = 1/k_i (0 for a fixed corner) and the Sherman-Morrison formula
//! for the rank-1 S, the twist force β = s tᵀc and the spring part of C are
//!
//! ```text
//! β = s Σ t_i φ_i f_i / (1 + s Σ φ_i),
//! fᵀ c = (Σ φ_i f_i² + s Σ_{i<j} φ_i φ_j (f_i t_j - f_j t_i)²) / (1 + s Σ φ_i),
//! r_i = f_i - t_i β,    spring store φ_i r_i²,    plate store C_fix + β²/s,
//! ```
//!
//! (the numerator by Lagrange's identity, Σφf² Σφt² - (Σφtf)²  = Σ_{i<j} φ_iφ_j(f_it_j -
//! f_jt_i)²). Every term is non-negative, so C and the stores carry a few ε of relative
//! error for every k in (0, ∞]: soft springs are a large φ (the statically determinate
//! limit appears as the ratio of the two sums, not as a difference), stiff springs a small
//! one (the limit φ → 0 is the fixed corner, no large number is formed), and reactions
//! come from forces, never from k times a deflection. A free corner (at most one, or the
//! plate would move rigidly) is the limit φ_f → ∞: β = t_f f_f, so its reaction vanishes,
//! and fᵀc = f_f²/s + Σ φ_j r_j². The sums are scaled by the largest φ so that neither
//! 1e-300 nor 1e300 N/m overflows.
//!
//! The fixed-corner reactions f are known exactly in the three rigid directions: statics
//! gives Σ f_i (1, x_i, z_i) = (1, x, z), exact in algebra because the element represents
//! the rigid motions exactly. Condensation takes those components from statics and only
//! the twist component tᵀf/4 from G⁻¹u; this removes the base solve's error (~1e-11) from
//! the soft-spring limits, which depend on the rigid components alone.
//!
//! # Which formulation, and the check
//!
//! Where the rank-4 update is accurate it is kept as it was, so that existing results are
//! reproduced bit for bit. Its error is estimated a priori as
//!
//! ```text
//! e = ε max_i max((k_b/k_i)(1 + k_b/4s), k_i/k_b)    over the springs i,
//! ```
//!
//! (the soft term is the condition growth above, an upper bound the measured error of C
//! stays below by a factor ~20; the stiff term is the round-off of k w in the reactions).
//! The update is used when e ≤ [`UPDATE_ERROR_BOUND`] = 1e-8, condensation otherwise; with
//! supported edges condensation does not apply and the update is always used. For the
//! paper's plate (k_b ≈ 5.97e8 N/m; s = 2(1 - ν)D/(LB), the pure twist being exact in the
//! element, so k_b/4s ≈ 1786 on any mesh) the update covers k from ~2.4e4 to ~2.7e16 N/m.
//!
//! Every result of [`CornerFamily::respond`] passes an a-posteriori check before it is
//! returned: all values finite; spring stores non-negative; C and the plate store not below
//! -1e3 ε times the terms that cancelled in them; the stores adding up to C to the same
//! round-off; with free edges, the reactions in equilibrium with the unit load to 1e-8
//! (the base solve's error, ~1e-11, and the update's bound e); for the update, its 4 x 4
//! system's residual at round-off and its forward-error bound cond₁ ε below 1e-6. If the
//! update fails the check and condensation applies, condensation is used instead; a result
//! that still fails is a [`FemError::CornerUpdate`] naming the corner stiffnesses and what
//! failed.

use crate::model::{Factorization, Model, PointResponse};
use crate::supports::{Corner, CornerSupport, EdgeSupport, Supports};
use crate::FemError;
use faer::Mat;
use nalgebra::{Matrix4, Vector4};

mod check;
mod condensation;
mod update;

/// The base factorization and its corner flexibility.
pub struct CornerFamily<'m> {
    base: Factorization<'m>,
    k_base: f64,
    edges: [EdgeSupport; 4],
    /// G = Uᵀ K_b⁻¹ U.
    g: Matrix4<f64>,
    /// K_b⁻¹ U: the base deflection under a unit load at each corner, n x 4. By reciprocity
    /// its column c read through N(p) is the corner's deflection u_c(p) under a load at p.
    corner_columns: Mat<f64>,
    /// The twist stiffness s of the corner condensation S = s t tᵀ, when the edges are free
    /// and G has the structure that implies (see the module docs).
    twist: Option<f64>,
}

/// The corner twist mode: the one corner motion (orthogonal to the rigid motions) that
/// strains a plate with free edges.
const TWIST: [f64; 4] = [1.0, -1.0, -1.0, 1.0];

/// The a-priori error bound below which the rank-4 update is used (module docs).
pub const UPDATE_ERROR_BOUND: f64 = 1e-8;

/// Allowed error of Σ reactions = 1 (free edges): the fixed-corner reactions f come from
/// the base solve, whose relative residual (≤ ~1e-10 without refinement on the meshes in
/// use) bounds their error; the formulations add only a few ε to it.
const EQUILIBRIUM_TOLERANCE: f64 = 1e-8;

/// Largest gap between a compliance from the selected inverse and from a solve, relative to
/// the largest compliance probed (the selected inverse's own check, [`crate::model::SELECTED_AGREEMENT`]).
pub use crate::model::SELECTED_AGREEMENT;

/// Round-off allowance, in units of ε times the size of the terms that cancel.
const ROUNDOFF_ULPS: f64 = 1e3;

/// Largest accepted forward-error bound cond(M) ε for the update's 4 x 4 solve.
const UPDATE_SOLVE_BOUND: f64 = 1e-6;

/// Which of the two formulations (module docs) produces a response.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Formulation {
    /// The rank-4 Woodbury update of the base.
    Update,
    /// Condensation onto the corners with the twist stiffness (free edges only).
    Condensed,
}

/// What the check needs to know of how a response was computed.
struct Audit {
    /// Size of the terms whose difference gives C (round-off of C is relative to it).
    scale: f64,
    /// For the update: cond₁ of its 4 x 4 matrix and the relative residual of its solve.
    system: Option<(f64, f64)>,
}

/// A point solved on the base: what every corner set needs of it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BasePoint {
    /// Impact point x (m).
    pub x: f64,
    /// Impact point z (m).
    pub z: f64,
    /// N ᵀ K_b⁻¹ N.
    pub compliance: f64,
    /// Base deflections of the four corners under the unit load (m/N), in
    /// [`Corner::ALL`] order: u = Uᵀ K_b⁻¹ N.
    pub u: Vector4<f64>,
    /// Relative residual of the base solve; for points from the selected inverse, of the
    /// solve at the first point that checked it.
    pub residual: f64,
}

impl<'m> CornerFamily<'m> {
    /// A base stiffness stiff against the plate's own corner stiffness, ~1e4 D/(L B): the
    /// update from base to fixed corners then changes C by ~1e-3 of itself, so little is
    /// lost to cancellation.
    pub fn default_base_stiffness(model: &Model) -> f64 {
        let p = model.props();
        1e4 * p.rigidity() / (p.length * p.width)
    }

    /// Factorizes the base (edges as given, corners on springs `k_base`). Elastic edges are
    /// refused: the 4 x 4 algebra follows the corners, not the energy the edge springs
    /// take from the plate's store; factorize such a support set with [`Model::factorize`].
    pub fn new(model: &'m Model, edges: [EdgeSupport; 4], k_base: f64) -> Result<Self, FemError> {
        if edges.iter().any(|e| matches!(e, EdgeSupport::Elastic(_))) {
            return Err(FemError::Support(format!(
                "corner families take free, simply supported or clamped edges, not {edges:?}; factorize elastic edges one support set at a time (Model::factorize)"
            )));
        }
        // The base is well conditioned (stiff springs at all corners); its residuals are
        // reported with every probe, and refinement is left to the caller.
        let base =
            model.factorize(&Supports { corners: [CornerSupport::Spring(k_base); 4], edges })?.with_refinement(0);
        let n = model.dofs();
        let mut rhs = Mat::<f64>::zeros(n, 4);
        let dofs: Vec<usize> = (0..4).map(|c| model.mesh().corner_w_dof(c)).collect();
        for (j, &d) in dofs.iter().enumerate() {
            rhs[(d, j)] = 1.0;
        }
        base.solve_in_place(&mut rhs);
        let g = Matrix4::from_fn(|i, j| 0.5 * (rhs[(dofs[i], j)] + rhs[(dofs[j], i)]));
        let twist = if edges == [EdgeSupport::Free; 4] { Self::twist_stiffness(&g, k_base) } else { None };
        Ok(Self { base, k_base, edges, g, twist, corner_columns: rhs })
    }

    /// s from tᵀ G t = 4/(4s + k_b), after checking that G maps the corner values of the
    /// rigid motions to themselves over k_b (S annihilates them) to 1e-6: the structure
    /// the condensation relies on. The subtraction loses log10(k_b/4s) digits (about 3
    /// for the default base), which leaves s good to ~1e-13.
    fn twist_stiffness(g: &Matrix4<f64>, k_base: f64) -> Option<f64> {
        let rigid = [Vector4::repeat(1.0), Vector4::new(0.0, 1.0, 0.0, 1.0), Vector4::new(0.0, 0.0, 1.0, 1.0)];
        for a in rigid {
            if (g * a * k_base - a).norm() > 1e-6 * a.norm() {
                return None;
            }
        }
        let t = Vector4::from(TWIST);
        let tgt = t.dot(&(g * t));
        let s = 1.0 / tgt - 0.25 * k_base;
        (s.is_finite() && s > 0.0).then_some(s)
    }

    /// The base factorization (all corners on springs k_b).
    pub fn base(&self) -> &Factorization<'m> {
        &self.base
    }
    /// The base spring stiffness k_b (N/m).
    pub fn k_base(&self) -> f64 {
        self.k_base
    }
    /// The base corner flexibility G = Uᵀ K_b⁻¹ U.
    pub fn corner_flexibility(&self) -> &Matrix4<f64> {
        &self.g
    }
    /// The corner twist stiffness s (N/m), with S = s t tᵀ, t = (1, -1, -1, 1); `None` when
    /// an edge is supported (the condensation then does not apply).
    pub fn twist_stiffness_value(&self) -> Option<f64> {
        self.twist
    }

    /// Whether mesh and edges are symmetric about x = L/2 and about z = B/2, so that the
    /// base (equal springs at all corners) is too.
    pub fn symmetry(&self) -> (bool, bool) {
        let mesh = self.base.model().mesh();
        let mirrored =
            |v: &[f64], end: f64| v.iter().zip(v.iter().rev()).all(|(a, b)| (a + b - end).abs() <= 1e-12 * end);
        let [left, right, near, far] = self.edges;
        (mirrored(mesh.xs(), mesh.length()) && left == right, mirrored(mesh.zs(), mesh.width()) && near == far)
    }

    /// Solves the base at `points`, once per class of mirror images: a point and its
    /// mirror images about the plate's symmetry lines share C and have their corner
    /// deflections permuted, so a doubly symmetric plate needs a quarter of the solves.
    pub fn probe_map(&self, points: &[(f64, f64)]) -> Result<Vec<BasePoint>, FemError> {
        let (sx, sz) = self.symmetry();
        let (l, b) = (self.base.model().props().length, self.base.model().props().width);
        let key = |v: f64, s: f64| (v / s * 1e9).round() as i64;
        let mut canonical: Vec<(f64, f64)> = Vec::new();
        let mut index = std::collections::HashMap::new();
        let mut plan = Vec::with_capacity(points.len());
        for &(x, z) in points {
            let (fx, fz) = (sx && x > l - x, sz && z > b - z);
            let (cx, cz) = (if fx { l - x } else { x }, if fz { b - z } else { z });
            let k = (key(cx, l), key(cz, b));
            let i = *index.entry(k).or_insert_with(|| {
                canonical.push((cx, cz));
                canonical.len() - 1
            });
            plan.push((i, fx, fz));
        }
        let solved = self.probe_many(&canonical)?;
        Ok(points
            .iter()
            .zip(plan)
            .map(|(&(x, z), (i, fx, fz))| {
                let s = solved[i];
                // Corners (0,0), (L,0), (0,B), (L,B): mirroring x swaps 0<->1 and 2<->3.
                let perm = |c: usize| {
                    let c = if fx { c ^ 1 } else { c };
                    if fz {
                        c ^ 2
                    } else {
                        c
                    }
                };
                BasePoint { x, z, u: Vector4::from_fn(|c, _| s.u[perm(c)]), ..s }
            })
            .collect())
    }

    /// The base at many points: by one solve each, or, where that costs more
    /// ([`Factorization::selected_inverse_pays`]), from the selected inverse of the base,
    /// C = N(p)ᵀ K_b⁻¹ N(p) on one element block and u_c = N(p)ᵀ K_b⁻¹ e_c from the four
    /// corner columns.
    pub fn probe_many(&self, points: &[(f64, f64)]) -> Result<Vec<BasePoint>, FemError> {
        if self.base.selected_inverse_pays(points.len()) {
            return self.probe_selected(points);
        }
        let responses = self.base.respond_many(points)?;
        Ok(responses
            .into_iter()
            .map(|r| BasePoint {
                x: r.x,
                z: r.z,
                compliance: r.compliance,
                // Base springs: reaction = k_b w, so w = reaction / k_b.
                u: Vector4::from_fn(|i, _| r.corners[i].reaction / self.k_base),
                residual: r.residual,
            })
            .collect())
    }

    /// The base at many points from its selected inverse. The first point is also solved:
    /// its residual stands for every point's, and its compliance must agree with the
    /// selected inverse's to [`SELECTED_AGREEMENT`].
    fn probe_selected(&self, points: &[(f64, f64)]) -> Result<Vec<BasePoint>, FemError> {
        let Some(&first) = points.first() else { return Ok(Vec::new()) };
        let inverse = self.base.selected_inverse()?;
        let model = self.base.model();
        let out = points
            .iter()
            .map(|&(x, z)| {
                let (dofs, n) = model.load(x, z)?;
                let compliance = inverse.quadratic(&dofs, &n).ok_or_else(|| {
                    FemError::Modes("selected inversion: an element's DOF pair is outside the factor's pattern; this is a defect of this crate".into())
                })?;
                let u = Vector4::from_fn(|c, _| (0..16).map(|k| n[k] * self.corner_columns[(dofs[k], c)]).sum());
                Ok(BasePoint { x, z, compliance, u, residual: 0.0 })
            })
            .collect::<Result<Vec<_>, FemError>>()?;
        // Relative to the largest compliance: a point on a supported edge has C = 0.
        let scale = out.iter().fold(0.0f64, |a, p| a.max(p.compliance.abs()));
        let solved = self.base.check_selected_inverse(&inverse, first, scale)?;
        Ok(out.into_iter().map(|p| BasePoint { residual: solved.residual, ..p }).collect())
    }

    /// The a-priori error estimate e of the rank-4 update for `corners` (module docs);
    /// `None` when condensation does not apply (supported edges), so only the update can be
    /// used.
    pub fn update_error_estimate(&self, corners: &[CornerSupport; 4]) -> Option<f64> {
        let s = self.twist?;
        let kb = self.k_base;
        let amplification = 1.0 + kb / (4.0 * s);
        let worst = corners
            .iter()
            .map(|c| match *c {
                CornerSupport::Spring(k) => ((kb / k) * amplification).max(k / kb),
                // A free corner is the update's k = 0 with exact Δ⁻¹ = -1/k_b: it loses
                // only the twist's log10(k_b/4s) digits.
                CornerSupport::Free => amplification,
                CornerSupport::Fixed => 1.0,
            })
            .fold(1.0, f64::max);
        Some(f64::EPSILON * worst)
    }

    /// The formulation [`respond`](Self::respond) tries first for `corners`: the update
    /// where its error estimate is at most [`UPDATE_ERROR_BOUND`] or where condensation does
    /// not apply, condensation otherwise.
    pub fn formulation(&self, corners: &[CornerSupport; 4]) -> Formulation {
        match self.update_error_estimate(corners) {
            Some(e) if e > UPDATE_ERROR_BOUND && self.condensable(corners) => Formulation::Condensed,
            _ => Formulation::Update,
        }
    }

    fn condensable(&self, corners: &[CornerSupport; 4]) -> bool {
        self.twist.is_some() && corners.iter().filter(|&&c| c == CornerSupport::Free).count() <= 1
    }

    /// The response of the plate with corner set `corners` at a base point, by the
    /// formulation [`formulation`](Self::formulation) chooses, checked (module docs).
    pub fn respond(&self, p: &BasePoint, corners: [CornerSupport; 4]) -> Result<PointResponse, FemError> {
        let first = self.formulation(&corners);
        match self.respond_by(p, corners, first) {
            Err(e) if first == Formulation::Update && self.condensable(&corners) => {
                // The update failed its own check: condensation is exact in algebra too and
                // well conditioned wherever it applies.
                self.respond_by(p, corners, Formulation::Condensed).map_err(|_| e)
            }
            r => r,
        }
    }

    /// The response by a given formulation, with the a-posteriori check.
    pub fn respond_by(
        &self,
        p: &BasePoint,
        corners: [CornerSupport; 4],
        formulation: Formulation,
    ) -> Result<PointResponse, FemError> {
        let model = self.base.model();
        Supports { corners, edges: self.edges }.validate(model.props().length, model.props().width)?;
        let (r, audit) = match formulation {
            Formulation::Update => self.update(p, corners)?,
            Formulation::Condensed => match self.twist {
                Some(s) if self.condensable(&corners) => self.condensed(p, corners, s),
                _ => {
                    return Err(self.failure(
                        &corners,
                        "condensation onto the corners needs free edges and at most one free corner".into(),
                    ))
                }
            },
        };
        self.check(p, &corners, &r, &audit)?;
        Ok(r)
    }

    fn failure(&self, corners: &[CornerSupport; 4], what: String) -> FemError {
        let names: Vec<String> = Corner::ALL
            .iter()
            .zip(corners)
            .map(|(c, s)| match s {
                CornerSupport::Spring(k) => format!("{} spring k = {k:e} N/m", c.name()),
                other => format!("{} {other:?}", c.name()),
            })
            .collect();
        FemError::CornerUpdate { corners: names.join(", "), k_base: self.k_base, what }
    }
}
