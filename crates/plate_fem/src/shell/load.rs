//! The contact load on a structure's face: a uniform pressure over a disc, wherever the
//! elements' edges fall.
//!
//! A sphere's contact force is spread over a disc of radius r about the struck point, in the
//! plane of the struck element, pressing along its normal: the load of unit resultant is
//! f = ∫_disc N_k/(πr²) dA at each node k of the elements under the disc. The integral runs
//! over the disc itself, not over elements, so the load is the same on every mesh of the same
//! face and a ladder of meshes converges to one compliance. It is taken by a polar product
//! rule, Gauss-Legendre in the radius (weight ρ dρ) and the trapezoidal rule in the angle
//! ([`DISC_RULE`]); where element edges cross the disc the integrand has kinks, so the rule is
//! not exact there (its error is measured in the tests).

use super::quad::Quad;
use super::structure::Structure;
use crate::FemError;
use nalgebra::Vector3;

/// Points of the polar rule: radial Gauss-Legendre points and angles.
pub const DISC_RULE: (usize, usize) = (12, 48);

/// Gauss-Legendre points and weights on [0, 1], n of them: the roots of P_n by Newton's
/// iteration on the three-term recurrence, from Tricomi's initial guesses.
fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    (p0, p1) = (p1, ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64);
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            ((1.0 - x) / 2.0, 1.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// An element in its own plane: the quadrilateral (corners about its centroid), the centroid,
/// the axes e₁, e₂, e₃, its reach (the farthest corner from the centroid) and its warp (the
/// farthest corner from its plane).
struct Placed {
    quad: Quad,
    centroid: Vector3<f64>,
    axes: [Vector3<f64>; 3],
    reach: f64,
    warp: f64,
}

/// How far off an element's plane the struck point may be given, as a fraction of the disc's
/// diameter (the wall's thickness): it is projected onto the plane.
const OFF_PLANE: f64 = 1e-3;

impl Structure {
    /// The element `e`'s geometry in its own plane.
    fn placed(&self, e: usize) -> Result<Placed, FemError> {
        let el = &self.elements[e];
        let corners = el.nodes.map(|n| self.nodes[n]);
        let centroid = corners.iter().sum::<Vector3<f64>>() / 4.0;
        let axes = [0, 1, 2].map(|r| el.axes.row(r).transpose());
        let xy = corners.map(|c| [(c - centroid).dot(&axes[0]), (c - centroid).dot(&axes[1])]);
        let reach = corners.iter().map(|c| (c - centroid).norm()).fold(0.0, f64::max);
        let warp = corners.iter().map(|c| (c - centroid).dot(&axes[2]).abs()).fold(0.0, f64::max);
        Ok(Placed { quad: Quad::new(xy)?, centroid, axes, reach, warp })
    }

    /// The load of unit resultant spread uniformly over the disc of `radius` (m) about the
    /// point `centre` of one of `elements` (the struck face), normal to it (along -e₃ of the
    /// element that holds the centre), with the polar rule of `rule` points (radial, angular).
    /// A centre within 1e-3 of the diameter off the element's plane is projected onto
    /// it. Refused if the radius is not positive and finite, the centre lies on none of
    /// `elements`, or the disc reaches beyond those of them in the same plane (over an edge of
    /// the face or across a fold).
    pub fn disc_load(
        &self,
        centre: [f64; 3],
        radius: f64,
        elements: &[usize],
        rule: (usize, usize),
    ) -> Result<Vec<f64>, FemError> {
        if !(radius.is_finite() && radius > 0.0) {
            return Err(FemError::Mesh(format!("a contact disc of radius {radius} m: it must be positive and finite")));
        }
        let centre = Vector3::from(centre);
        let placed = elements.iter().map(|&e| self.placed(e).map(|q| (e, q))).collect::<Result<Vec<_>, _>>()?;
        // The element holding `p` within `tol` of its plane (beyond its own warp), parallel to
        // `plane` where given: (element, parameters, its placement).
        let locate = |p: &Vector3<f64>, plane: Option<&Vector3<f64>>, tol: f64| {
            placed.iter().find_map(|(e, q)| {
                let d = p - q.centroid;
                let near = d.norm() <= q.reach * (1.0 + 1e-9) + tol;
                let on_plane = d.dot(&q.axes[2]).abs() <= tol + q.warp;
                let parallel = plane.is_none_or(|n| n.dot(&q.axes[2]).abs() > 1.0 - 1e-9);
                (near && on_plane && parallel)
                    .then(|| q.quad.locate([d.dot(&q.axes[0]), d.dot(&q.axes[1])]).map(|at| (*e, at, q)))?
            })
        };
        let (_, _, struck) = locate(&centre, None, OFF_PLANE * 2.0 * radius).ok_or_else(|| {
            FemError::Mesh(format!("the struck point {:?} m lies on no element of the struck face", centre.as_slice()))
        })?;
        let normal = struck.axes[2];
        let centre = centre - normal * (centre - struck.centroid).dot(&normal);
        let e1 = if normal.x.abs() < 0.9 { Vector3::x() } else { Vector3::y() };
        let e1 = (e1 - normal * e1.dot(&normal)).normalize();
        let e2 = normal.cross(&e1);
        let mut f = vec![0.0; self.dofs()];
        let pressure = 1.0 / (std::f64::consts::PI * radius * radius);
        let (radial, angular) = rule;
        for (s, ws) in gauss_legendre(radial.max(1)) {
            let rho = s * radius;
            for j in 0..angular.max(3) {
                let theta = std::f64::consts::TAU * j as f64 / angular.max(3) as f64;
                let p = centre + (e1 * theta.cos() + e2 * theta.sin()) * rho;
                let (e, (xi, eta), _) = locate(&p, Some(&normal), 1e-6 * radius).ok_or_else(|| {
                    FemError::Mesh(format!(
                        "the contact disc of radius {radius} m about {:?} m reaches beyond the flat part of the struck face (over its edge or a fold) at {:?} m",
                        centre.as_slice(),
                        p.as_slice()
                    ))
                })?;
                // ∫ over the disc: weight ρ dρ dθ = radius² s ds dθ.
                let w = ws * s * radius * radius * std::f64::consts::TAU / angular.max(3) as f64 * pressure;
                for (&node, n) in self.elements[e].nodes.iter().zip(Quad::shape(xi, eta)) {
                    for i in 0..3 {
                        f[6 * node + i] -= w * n * normal[i];
                    }
                }
            }
        }
        Ok(f)
    }
}
