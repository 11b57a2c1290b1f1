//! The channels of the reduced model's signals. Every channel is a functional ℓ of the
//! plate's state, y = A·q + B·q̇ + C·q̈ + D P on the modes, plus the truncated modes' part:
//! ℓ's residual field R ℓ, evaluated at the struck point once per impact.

use super::corners::CornerData;
use super::signals::{ChannelKind, ChannelRows, Probes, Quantity, SignalSpec};
use super::{ModalDamping, ReducedModel};
use crate::error::ModelError;
use analytic::params::{check, Range};
use plate_fem::CornerSupport;

impl ReducedModel {
    /// Prepares `spec` on this model: every channel's coefficient rows (one solve per
    /// sensor, for its residual field) and the exact maps over 1 to
    /// [`super::window::BLOCK`] sample intervals.
    pub fn probes(&self, spec: &SignalSpec) -> Result<Probes, ModelError> {
        check("signals.window", spec.window, Range::open_closed(0.0, 10.0), "s")?;
        check("signals.rate_hz", spec.rate_hz, Range::closed(10.0, 1e7), "Hz")?;
        check("signals.samples", spec.window * spec.rate_hz, Range::closed(1.0, 1e7), "")?;
        let zeta = self.settings.damping();
        let fact = self.model.factorize(&self.set.supports)?;
        let mut rows = Vec::new();
        let mut fields = Vec::new();
        let kinematic = spec.quantities.iter().any(|q| *q != Quantity::Strain);
        for (s, &(x, z)) in spec.sensors.iter().enumerate() {
            // One residual field per functional a sensor reads: its deflection (for the
            // kinematic quantities) and its strain, each solved only if asked for.
            let deflection = if kinematic {
                fields.push(self.modes.residual_field(&fact, &fact.load_vector(x, z)?));
                Some((fields.len() - 1, self.point(x, z)?.phi))
            } else {
                None
            };
            for q in &spec.quantities {
                match (q, &deflection) {
                    (Quantity::Strain, _) => {
                        let (dofs, values) = self.model.bending_strain(x, z)?;
                        fields.push(self.modes.residual_field(&fact, &fact.functional_vector(&dofs, &values)));
                        rows.push(strain_channel(s, self.functional_modes(&dofs, &values), fields.len() - 1));
                    }
                    (q, Some((f, phi_s))) => rows.push(sensor_channel(q, s, phi_s, *f, &self.omega, zeta)),
                    (_, None) => unreachable!("a kinematic quantity makes `kinematic` true"),
                }
            }
        }
        if spec.corners {
            for c in &self.corners {
                rows.extend(corner_channel(c, &mut fields, &self.omega));
            }
        }
        Ok(Probes::new(spec, rows, fields, &self.omega, zeta))
    }
}

/// Quantity `q` at sensor `s`, whose modal values are `phi_s` and whose residual field is
/// `fields[f]`: displacement Σφᵢqᵢ, velocity Σφᵢq̇ᵢ, acceleration Σφᵢq̈ᵢ with the modal
/// equation q̈ᵢ = φᵢ(p)P - ωᵢ²qᵢ - 2ζωᵢq̇ᵢ.
fn sensor_channel(q: &Quantity, s: usize, phi_s: &[f64], f: usize, omega: &[f64], zeta: ModalDamping) -> ChannelRows {
    let n = omega.len();
    let w2 = |i: usize| omega[i] * omega[i];
    match q {
        Quantity::Displacement => ChannelRows {
            kind: ChannelKind::Displacement { sensor: s },
            a: phi_s.to_vec(),
            b: vec![0.0; n],
            c: None,
            direct: None,
            res: [Some((f, 1.0)), None, None],
            damped_inertia: false,
        },
        Quantity::Velocity => ChannelRows {
            kind: ChannelKind::Velocity { sensor: s },
            a: vec![0.0; n],
            b: phi_s.to_vec(),
            c: None,
            direct: None,
            res: [None, Some((f, 1.0)), None],
            damped_inertia: false,
        },
        Quantity::Strain => unreachable!("the strain is a channel of its own (strain_channel)"),
        Quantity::Acceleration => ChannelRows {
            kind: ChannelKind::Acceleration { sensor: s },
            a: (0..n).map(|i| -w2(i) * phi_s[i]).collect(),
            b: (0..n).map(|i| -2.0 * zeta.at(omega[i]) * omega[i] * phi_s[i]).collect(),
            c: Some(phi_s.to_vec()),
            direct: None,
            res: [None, None, Some((f, 1.0))],
            damped_inertia: false,
        },
    }
}

/// The strain at sensor `s`: the functional ℓ_ε of [`plate_fem::Model::bending_strain`] on
/// the modes, ℓ_ε(φᵢ) in `modal`, and its residual field `fields[f]`; a deflection-type
/// channel (no rate, no inertia), ε = Σ ℓ_ε(φᵢ) qᵢ + (R ℓ_ε)(p) P.
fn strain_channel(s: usize, modal: Vec<f64>, f: usize) -> ChannelRows {
    let n = modal.len();
    ChannelRows {
        kind: ChannelKind::Strain { sensor: s },
        a: modal,
        b: vec![0.0; n],
        c: None,
        direct: None,
        res: [Some((f, 1.0)), None, None],
        damped_inertia: false,
    }
}

/// The channel of corner `c`, its residual fields appended to `fields`: a spring's force
/// k w_c, or a fixed corner's reaction R_c = N_c(p)P - k_cᵀw - m_cᵀ(ẅ + modal damping), so
/// ℓ_d = -k_c and ℓ_a = -m_c. A free corner has none.
fn corner_channel(c: &CornerData, fields: &mut Vec<Vec<f64>>, omega: &[f64]) -> Option<ChannelRows> {
    let n = omega.len();
    let w2 = |i: usize| omega[i] * omega[i];
    match (c.support, &c.mass_row, &c.mass_field) {
        (CornerSupport::Spring(k), _, _) => {
            let f = fields.len();
            fields.push(c.field.clone());
            Some(ChannelRows {
                kind: ChannelKind::SpringForce { corner: c.corner },
                a: c.row.iter().map(|r| k * r).collect(),
                b: vec![0.0; n],
                c: None,
                direct: None,
                res: [Some((f, k)), None, None],
                damped_inertia: false,
            })
        }
        (CornerSupport::Fixed, Some(mass_row), Some(mass_field)) => {
            let (fk, fm) = (fields.len(), fields.len() + 1);
            fields.push(c.field.clone());
            fields.push(mass_field.clone());
            Some(ChannelRows {
                kind: ChannelKind::Reaction { corner: c.corner },
                a: (0..n).map(|i| w2(i) * mass_row[i] - c.row[i]).collect(),
                b: vec![0.0; n],
                c: Some(mass_row.iter().map(|m| -m).collect()),
                direct: Some(c.dof),
                res: [Some((fk, -1.0)), None, Some((fm, -1.0))],
                damped_inertia: true,
            })
        }
        _ => None,
    }
}
