//! The tail beam ([`plate_fem::shell::tail_beam`]) as a compliance provider: the welded box
//! on its pins and jacks, struck on its top plate.
//!
//! As on the Mindlin plate, a shear-deformable shell has no point compliance, so the contact
//! force is spread over a square of side t (the top plate's thickness), clipped to the plate.
//! The compliance is the patch's work-conjugate mean displacement per unit force, everything
//! that moves under it included: the top plate's local bending and shear, the box's own
//! bending and twist (membrane strain of its walls), and the jacks. Its stores are the walls'
//! membrane, bending and shear energies and one store per jack.
//!
//! **Error estimate.** The ladder's (three nested meshes, the element halved; Richardson at
//! the rate the pins' singularity gives, [`PIN_RATE`], the observed rate checked against it). Not in it: the modelling spread between shell element families on box
//! sections, about 0.5-1 % (stated beside the results), and the patch size (as for the
//! Mindlin plate, ln 2 /(2π k_s G t) per factor 2 in its side).
//!
//! **Which compliance an impact sees.** Most of this compliance is the jacks' and the box's
//! rigid rotation about the pins (slow: the fundamental period is tens of milliseconds). A
//! lump's contact lasts a fraction of a millisecond, so the quasi-static balance with the whole
//! compliance is outside its range on a tail beam, and the rows say so (t_c/T₁, Olsson's mass
//! ratio); the study beside it gives the wave-controlled limit.

use super::plate::{extrapolate_at_rate, LevelCost};
use super::Estimate;
use crate::error::ModelError;
use analytic::{PointCompliance, SpringReaction, Store, StoreKind};
use plate_fem::patch::Patch;
use plate_fem::shell::tail_beam::TailBeam;
use serde::Serialize;
use std::time::Instant;

/// Meshes in the ladder: three, so that the observed rate is measured.
pub const TAIL_BEAM_LEVELS: u32 = 3;

/// The nominal convergence rate of the ladder: the pins hold a line of the end plate rigidly
/// in its plane, whose ends carry a crack-like r^(-1/2) stress singularity, so the energy and
/// the compliance converge like h, not h² (measured 1.32, 1.13, 1.01 over five meshes of a
/// 1.2 m box; clamping the whole end plate instead restores rate 2).
pub const PIN_RATE: f64 = 1.0;

/// A scene's tail beam: the box, the coarsest mesh's element side and the struck points.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TailBeamScene {
    /// The box on its pins and jacks.
    pub beam: TailBeam,
    /// The coarsest mesh's element side (m); the ladder halves it twice.
    pub element: f64,
    /// The struck points (x along the beam from the pins, z across it), m, on the top plate.
    pub points: Vec<(f64, f64)>,
}

/// The tail beam's compliances at the struck points, with its mass and fundamental frequency.
#[derive(Debug, Clone, Serialize)]
pub struct TailBeamModel {
    /// Each point (x, z) on the top plate, m, with its compliance.
    pub points: Vec<((f64, f64), Estimate)>,
    /// The meshes, coarse to fine (nx, nz: elements along the top plate's length and width).
    pub levels: Vec<LevelCost>,
    /// The finest element's side (m).
    pub finest_element: f64,
    /// The fundamental frequency f₁ (Hz) on the finest mesh, with a lumped mass.
    pub frequency: f64,
    /// |f₁ - f₁ on the mesh before| / f₁: the frequency's discretisation indicator.
    pub frequency_change: f64,
    /// The inverse iteration's last relative change of ω₁² on the finest mesh (converged
    /// below 1e-10; larger where its 500 iterations ran out).
    pub frequency_iteration: f64,
    /// The walls' mass (kg).
    pub mass: f64,
}

/// The contact patch at (x, z) on the top plate, in the top face's coordinates (z, x): a
/// square of side t centred there, clipped to the plate.
pub fn contact_patch(beam: &TailBeam, x: f64, z: f64) -> Patch {
    Patch::clipped_square(z, x, beam.top, beam.width, beam.length)
}

impl TailBeamModel {
    /// The compliances at `points` on the ladder of meshes with elements of `element` (m),
    /// then halved, `levels` ≥ 2 meshes in all; Young's modulus `e`, Poisson ratio `nu`,
    /// density `rho`.
    pub fn compute(
        beam: &TailBeam,
        (e, nu, rho): (f64, f64, f64),
        points: &[(f64, f64)],
        element: f64,
        levels: u32,
    ) -> Result<Self, ModelError> {
        let mut per_level: Vec<Vec<PointCompliance>> = Vec::new();
        let (mut costs, mut frequencies) = (Vec::new(), Vec::new());
        for level in 0..levels.max(2) {
            let t = Instant::now();
            let built = beam.build(e, nu, element, level)?;
            let f = built.structure.factorize(&built.restraints)?;
            let mut row = Vec::with_capacity(points.len());
            for &(x, z) in points {
                let (r, u) = f.respond_with_field(built.top, &contact_patch(beam, x, z))?;
                let mut stores = vec![
                    Store {
                        name: "walls membrane".into(),
                        kind: StoreKind::Plate,
                        compliance: r.membrane + r.drilling,
                    },
                    Store { name: "walls bending".into(), kind: StoreKind::Plate, compliance: r.bending },
                    Store { name: "walls shear".into(), kind: StoreKind::Plate, compliance: r.shear },
                ];
                let mut springs = Vec::new();
                for (j, range) in built.jacks.iter().enumerate() {
                    let pad = &built.restraints.springs[range.clone()];
                    let force: f64 = pad.iter().map(|s| s.force(&u)).sum();
                    let energy: f64 = pad.iter().map(|s| s.force(&u).powi(2) / s.stiffness).sum();
                    stores.push(Store { name: format!("jack {}", j + 1), kind: StoreKind::Spring, compliance: energy });
                    springs.push(SpringReaction { name: format!("jack {}", j + 1), per_unit_load: force.abs() });
                }
                row.push(PointCompliance::new(stores, springs, r.compliance)?);
            }
            // The frequency on the two finest meshes: its value and its change between them.
            if level + 2 >= levels.max(2) {
                let (omega, change) = f.fundamental(&built.structure.lumped_mass(rho));
                frequencies.push((omega / (2.0 * std::f64::consts::PI), change));
            }
            let [xs, _, zs] = beam.lines(element, level)?;
            costs.push(LevelCost {
                nx: xs.len() - 1,
                nz: zs.len() - 1,
                dofs: f.unknowns(),
                seconds: t.elapsed().as_secs_f64(),
            });
            per_level.push(row);
        }
        let n = per_level.len();
        let mut out = Vec::with_capacity(points.len());
        for (pi, &at) in points.iter().enumerate() {
            let seq: Vec<PointCompliance> = per_level.iter().map(|lv| lv[pi].clone()).collect();
            let e = extrapolate_at_rate(PIN_RATE, &seq[n - 2], &seq[n - 1], &seq)?;
            out.push((
                at,
                Estimate { compliance: e.compliance, error_estimate: e.error_estimate, asymptotic: e.asymptotic },
            ));
        }
        let finest_element = beam
            .lines(element, n as u32 - 1)?
            .iter()
            .flat_map(|l| l.windows(2).map(|w| w[1] - w[0]))
            .fold(0.0, f64::max);
        let [(f0, _), (f1, iteration)] = [frequencies[0], frequencies[1]];
        Ok(Self {
            points: out,
            levels: costs,
            finest_element,
            frequency: f1,
            frequency_change: ((f1 - f0) / f1).abs(),
            frequency_iteration: iteration,
            mass: beam.mass(rho),
        })
    }

    /// The compliance at (x, z), one of the points it was computed at.
    pub fn compliance(&self, x: f64, z: f64) -> Result<&Estimate, ModelError> {
        self.points
            .iter()
            .find(|(at, _)| *at == (x, z))
            .map(|(_, e)| e)
            .ok_or_else(|| ModelError::Missing(format!("the tail beam's compliance at ({x}, {z}) m")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use plate_fem::shell::tail_beam::Jack;

    /// A box on stiff jacks struck mid-panel: the compliance converges on the ladder, its stores
    /// sum to it, and the jacks' store is each jack's force squared over its stiffness.
    #[test]
    fn stores_sum_and_the_ladder_converges() {
        let beam = TailBeam {
            length: 1.2,
            width: 0.8,
            height: 0.2,
            top: 0.02,
            bottom: 0.02,
            webs: 0.02,
            ends: 0.02,
            ribs: vec![],
            rib: 0.02,
            diaphragms: None,
            pin_height: 0.1,
            pins: vec![[0.0, 0.8]],
            jacks: vec![Jack { x: 0.6, z: 0.4, pad: 0.1, stiffness: 1e8, angle: 1.2 }],
        };
        let m = TailBeamModel::compute(&beam, (210e9, 0.3, 7850.0), &[(0.9, 0.4)], 0.05, 3).unwrap();
        let e = m.compliance(0.9, 0.4).unwrap();
        let c = e.compliance.total();
        let sum: f64 = e.compliance.stores().iter().map(|s| s.compliance).sum();
        assert!((sum / c - 1.0).abs() < 1e-12);
        // Measured: 1.0 % (the ladder's last difference at rate 1); the extrapolation meets the
        // one from meshes of 12.5 and 6.25 mm elements to 5e-5.
        assert!(e.error_estimate < 2e-2 * c && e.asymptotic, "{e:?}");
        // The pad's springs share its stiffness; where the bottom plate bends under the pad
        // they carry unequal forces, and their energy exceeds (ΣF)²/k (equal only for a rigid
        // pad; measured 3.6 % above).
        let jack = &e.compliance.springs()[0];
        let store = e.compliance.stores().iter().find(|s| s.name == "jack 1").unwrap().compliance;
        assert!(store < 1.1 * jack.per_unit_load.powi(2) / 1e8, "{store:e}");
        // Statics: the jack's force balances the unit load's moment about the pins, with its
        // line of action through the pad: between the pad's near and far edges' arms.
        let arm = |x: f64| beam.pin_height * 1.2f64.cos() + x * 1.2f64.sin();
        assert!((0.9 / arm(0.65)..0.9 / arm(0.55)).contains(&jack.per_unit_load), "{}", jack.per_unit_load);
        assert!(m.frequency > 0.0 && m.frequency_change < 1e-2 && m.frequency_iteration < 1e-10);
    }
}
