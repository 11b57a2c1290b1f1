//! One reduced impact (module docs of [`super`]): the modal plate, extended by the residual
//! mode or carrying the static correction, struck through the full model's time loop, and
//! the rest of the window as exact free vibration at the sample times.

use super::signals::{dot, Channel, ChannelRows, FreeMaps, Probes, Signals};
use super::target::{ChannelRow, CornerPoint, ModalTarget, Recording};
use super::window::{free_window, BlockMaps};
use super::{modal_compliance, Correction, Point, ReducedModel, ReducedOutcome};
use crate::error::ModelError;
use crate::transient::{simulate_with, Outcome, PlateFacts, Striker};
use analytic::params::{check, Range};
use plate_fem::CornerSupport;

impl ReducedModel {
    /// The impact of `striker` at (x, z) with step `dt`, sampled every `every` steps, free
    /// steps by `map` (exact) or by Newmark's rule (None).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn run(
        &self,
        striker: &Striker,
        x: f64,
        z: f64,
        probes: &Probes,
        mut map: Option<FreeMaps>,
        dt: f64,
        every: usize,
    ) -> Result<ReducedOutcome, ModelError> {
        let pt = self.point(x, z)?;
        let zeta = self.settings.damping();
        let Extended { omega, phi_p, c_res, residual_mode, static_compliance } = self.extended(&pt);
        if let (Some((w, _)), Some(m)) = (residual_mode, map.as_mut()) {
            m.push(w, zeta.at(w), dt);
        }
        let field_at_p: Vec<f64> = probes.fields.iter().map(|f| at_point(&pt, f)).collect();
        let rows = probes
            .rows
            .iter()
            .map(|r| channel_row(r, &pt, &field_at_p, residual_mode, (c_res, zeta), &phi_p))
            .collect();
        let rec = Recording { rows, every, samples: probes.spec.samples() };
        let corner_points = self.corner_points(&pt, residual_mode, c_res);
        let facts = PlateFacts {
            static_compliance: Some(static_compliance),
            corner_springs: Some(self.corner_springs()),
            follow_unbounded: true,
        };
        let extra_maps = residual_mode.map(|(w, _)| BlockMaps::new(&[w], zeta, probes.spec.interval()));
        let mut target = ModalTarget::new(omega, zeta, phi_p, c_res, dt, map, corner_points, Some(rec), self.simd);
        let window = probes.spec.window;
        let outcome = simulate_with(striker, Some(&mut target), facts, dt, window + 2.0 * dt);
        let out = self.rest_of_window(&mut target, probes, extra_maps.as_ref(), every);
        let channels = probes.rows.iter().zip(out).map(|(r, samples)| Channel { kind: r.kind, samples }).collect();
        Ok(ReducedOutcome {
            outcome,
            signals: Signals { rate_hz: probes.spec.rate_hz, channels },
            dt,
            static_compliance,
            residual_compliance: pt.c_res,
            residual_mode_hz: residual_mode.map(|(w, _)| w / (2.0 * std::f64::consts::PI)),
        })
    }

    /// The first contact alone of `striker` at (x, z) with the time step `dt`, to `t_max` at
    /// most: the reduced counterpart of [`crate::transient::TransientCase::first_contact`],
    /// for the first contact's quantities without signals (its largest compression δ_max
    /// brackets the transient yield velocity, [`crate::yield_root`]). The loop is
    /// [`simulate_with`] on the modal plate of [`Self::impact`] (the same modes, correction
    /// and damping; free steps exact) without the static compliance, so it stops at the first
    /// separation as the full model's first-contact run does; with the full model's Δt both
    /// sample δ at the same instants and differ only by the modal truncation. Nothing is
    /// recorded and the model is not changed.
    pub fn first_contact(&self, striker: &Striker, x: f64, z: f64, dt: f64, t_max: f64) -> Result<Outcome, ModelError> {
        check("dt", dt, Range::open(0.0, f64::INFINITY), "s")?;
        let pt = self.point(x, z)?;
        let zeta = self.settings.damping();
        let Extended { omega, phi_p, c_res, residual_mode, .. } = self.extended(&pt);
        let map = FreeMaps::new(&omega, zeta, dt);
        let corner_points = self.corner_points(&pt, residual_mode, c_res);
        let facts = PlateFacts { corner_springs: Some(self.corner_springs()), ..PlateFacts::default() };
        let mut target = ModalTarget::new(omega, zeta, phi_p, c_res, dt, Some(map), corner_points, None, self.simd);
        Ok(simulate_with(striker, Some(&mut target), facts, dt, t_max))
    }

    /// The modes the struck point `pt` is followed on: the kept ones, extended by the residual
    /// mode where the settings ask for it, with φᵢ(p), the static correction left at p
    /// (C_res(p) with the static correction, 0 when the residual mode or nothing carries it)
    /// and the FE static compliance Σφᵢ(p)²/ωᵢ² + C_res(p).
    fn extended(&self, pt: &Point) -> Extended {
        let static_compliance = modal_compliance(&pt.phi, &self.omega) + pt.c_res;
        let residual_mode = self.residual_mode(pt, static_compliance);
        let (mut omega, mut phi_p) = (self.omega.clone(), pt.phi.clone());
        let c_res = match residual_mode {
            Some((w, root_m)) => {
                omega.push(w);
                phi_p.push(pt.c_res / root_m);
                0.0
            }
            None if self.settings.correction == Correction::Static => pt.c_res,
            None => 0.0,
        };
        Extended { omega, phi_p, c_res, residual_mode, static_compliance }
    }

    /// The corner spring stiffnesses in [`plate_fem::Corner::ALL`] order, N/m (0 where a
    /// corner is free or held).
    fn corner_springs(&self) -> [f64; 4] {
        self.set.supports.corners.map(|c| match c {
            CornerSupport::Spring(k) => k,
            _ => 0.0,
        })
    }

    /// The truncated modes as one more mode, (ω_ψ, √m_ψ) with ω_ψ² = C_res/m_ψ (the residual
    /// shape ψ = RN normalised, ψ̂ = ψ/√m_ψ, ψ̂ᵀN = C_res/√m_ψ), where the settings ask for it.
    /// Without compliance or mass left to carry (all modes kept, to rounding) there is none.
    fn residual_mode(&self, pt: &Point, static_compliance: f64) -> Option<(f64, f64)> {
        let m_res = pt.m_res.filter(|_| self.settings.correction == Correction::ResidualMode)?;
        (pt.c_res > 1e-12 * static_compliance && m_res > 0.0).then(|| ((pt.c_res / m_res).sqrt(), m_res.sqrt()))
    }

    /// The moving corners at the struck point: their rows on the (extended) modes, their
    /// static-correction part d (the residual field at p when `c_res` > 0) and spring k.
    fn corner_points(&self, pt: &Point, residual_mode: Option<(f64, f64)>, c_res: f64) -> [Option<CornerPoint>; 4] {
        let mut corner_points: [Option<CornerPoint>; 4] = Default::default();
        for c in &self.corners {
            if c.support != CornerSupport::Fixed {
                let spring = if let CornerSupport::Spring(k) = c.support { k } else { 0.0 };
                let mut row = c.row.clone();
                let d = match residual_mode {
                    Some((_, root_m)) => {
                        row.push(at_point(pt, &c.field) / root_m);
                        0.0
                    }
                    None => {
                        if c_res > 0.0 {
                            at_point(pt, &c.field)
                        } else {
                            0.0
                        }
                    }
                };
                corner_points[c.corner.index()] = Some(CornerPoint { row, d, spring });
            }
        }
        corner_points
    }

    /// The samples of the window: on to the next sample step (or, time-stepped, to the end),
    /// then exact free vibration at the sample times; per channel.
    fn rest_of_window(
        &self,
        target: &mut ModalTarget,
        probes: &Probes,
        extra_maps: Option<&BlockMaps>,
        every: usize,
    ) -> Vec<Vec<f64>> {
        let want = probes.spec.samples();
        if !probes.rows.is_empty() && target.recorded() < want {
            if target.exact() {
                let gap = (target.recorded() * every).saturating_sub(target.steps());
                target.advance_free(gap);
            } else {
                while target.recorded() < want {
                    target.advance_free(1);
                }
            }
        }
        let recorded = target.recorded();
        let mut out = std::mem::take(&mut target.out);
        if recorded < want && recorded > 0 {
            let (q, v) = target.state();
            let maps = [probes.block_maps.modes(), extra_maps.map_or(&[], |m| m.modes())];
            free_window((self.simd, self.settings.arithmetic), &maps, q, v, target.rows(), &mut out, want - recorded);
        }
        out
    }
}

/// The modes one impact is followed on ([`ReducedModel::extended`]).
struct Extended {
    /// ωᵢ, the residual mode's last where there is one.
    omega: Vec<f64>,
    /// φᵢ(p) on the same modes.
    phi_p: Vec<f64>,
    /// The static correction at p, m/N (0 when the residual mode carries it).
    c_res: f64,
    /// The residual mode (ω_ψ, √m_ψ), if any.
    residual_mode: Option<(f64, f64)>,
    /// The FE static compliance at p, m/N.
    static_compliance: f64,
}

/// A field's value at the struck point, Σ N_k(p) f_k over the struck element.
pub(super) fn at_point(pt: &Point, f: &[f64]) -> f64 {
    (0..16).map(|k| pt.shape[k] * f[pt.dofs[k]]).sum()
}

/// Channel `r` at the struck point, y = A·q + B·q̇ + D P on the (extended) modes (free of
/// force, D P drops out): with the residual mode, the channel's residual functionals on ψ̂
/// extend A and B; with the static correction, ℓ_d(R N) joins D (a displacement, no rate).
pub(super) fn channel_row(
    r: &ChannelRows,
    pt: &Point,
    field_at_p: &[f64],
    residual_mode: Option<(f64, f64)>,
    (c_res, zeta): (f64, super::ModalDamping),
    phi_p: &[f64],
) -> ChannelRow {
    let ell = |k: usize| r.res[k].map_or(0.0, |(f, s)| s * field_at_p[f]);
    let mut a = r.a.clone();
    let mut b = r.b.clone();
    let mut d = r.c.as_ref().map_or(0.0, |c| dot(c, &pt.phi))
        + r.direct.map_or(0.0, |dof| (0..16).filter(|&k| pt.dofs[k] == dof).map(|k| pt.shape[k]).sum());
    match residual_mode {
        Some((w, root_m)) => {
            let (ld, lv, la) = (ell(0) / root_m, ell(1) / root_m, ell(2) / root_m);
            a.push(ld - w * w * la);
            b.push(if r.damped_inertia { lv } else { lv - 2.0 * zeta.at(w) * w * la });
            d += la * phi_p[phi_p.len() - 1];
        }
        // The static correction: a displacement, no rate.
        None => d += if c_res > 0.0 { ell(0) } else { 0.0 },
    }
    let nonzero = |x: Vec<f64>| x.iter().any(|&x| x != 0.0).then_some(x);
    ChannelRow { a: nonzero(a), b: nonzero(b), d }
}
