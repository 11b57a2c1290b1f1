//! Bounds on the free plate's deflection at a point: how far it can ever reach, and how low
//! it can go within one sample interval. They decide when a sphere out of contact cannot
//! touch (an interval taken in one exact step) and when it has left for good.
//!
//! A free, damped mode qᵢ(t) = e^(-ζᵢωᵢt)(aᵢ cos ω_d,ᵢt + bᵢ sin ω_d,ᵢt) never exceeds its
//! amplitude Aᵢ = √(qᵢ² + q̇ᵢ²/ωᵢ²) (its energy ωᵢ²qᵢ² + q̇ᵢ² does not grow), and its turning
//! points are spaced π/ω_d,ᵢ apart.

use crate::reduced::ModalDamping;

/// Σᵢ|φᵢ(p)|Aᵢ with Aᵢ = √(qᵢ² + q̇ᵢ²/ωᵢ²): no later free deflection at p reaches beyond it
/// ([`super::target`]): ωᵢ²qᵢ² + q̇ᵢ², a damped mode's energy, does not grow.
pub(super) fn reach(phi: &[f64], q: &[f64], v: &[f64], omega: &[f64]) -> f64 {
    (0..omega.len()).map(|i| amplitude(q[i], v[i], omega[i]) * phi[i].abs()).sum()
}

/// Aᵢ = √(qᵢ² + q̇ᵢ²/ωᵢ²), which no later |qᵢ(t)| of the free, damped mode exceeds.
fn amplitude(q: f64, v: f64, omega: f64) -> f64 {
    (q * q + (v / omega).powi(2)).sqrt()
}

/// The modes' (q, q̇) at one instant.
pub(super) type ModalState<'a> = (&'a [f64], &'a [f64]);

/// For each mode, (ωᵢ, whether its damped half-period π/ω_d,ᵢ exceeds the sample interval).
pub(super) type HalfPeriod = Vec<(f64, bool)>;

/// A lower bound on the free deflection w(p, t) = Σᵢφᵢ(p)qᵢ(t) over an interval, from the
/// modes' exact states at its two ends: the sum of each mode's lowest. In a mode whose damped
/// half-period π/ω_d is longer than the interval, the turning points of φᵢqᵢ(t) =
/// φᵢe^(-ζωt)(a cos ω_d t + b sin ω_d t), spaced π/ω_d apart, number at most one, and it is a
/// minimum only where φᵢq̇ᵢ turns from negative to positive: the mode's lowest is then bounded
/// by -|φᵢ|Aᵢ ([`amplitude`]), else it is the lower end. A faster mode may reach -|φᵢ|Aᵢ.
pub(super) fn lowest_deflection(phi: &[f64], (q0, v0): ModalState, (q1, v1): ModalState, modes: &HalfPeriod) -> f64 {
    let mut lowest = 0.0;
    for (i, &(omega, slow)) in modes.iter().enumerate() {
        let p = phi[i];
        lowest += if slow && !(p * v0[i] < 0.0 && p * v1[i] > 0.0) {
            (p * q0[i]).min(p * q1[i])
        } else {
            -p.abs() * amplitude(q0[i], v0[i], omega)
        };
    }
    lowest
}

/// Each mode's ωᵢ and whether its damped half-period π/(ωᵢ√(1 - ζᵢ²)) exceeds `ts`.
pub(super) fn half_periods(omega: &[f64], zeta: ModalDamping, ts: f64) -> HalfPeriod {
    let slow = |w: f64| w * (1.0 - zeta.at(w).powi(2)).sqrt() * ts < std::f64::consts::PI;
    omega.iter().map(|&w| (w, slow(w))).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A damped mode from (q₀, q̇₀) at time t, by the closed form (module docs).
    fn mode_at(omega: f64, zeta: f64, (q0, v0): (f64, f64), t: f64) -> (f64, f64) {
        let wd = omega * (1.0 - zeta * zeta).sqrt();
        let (a, b) = (q0, (v0 + zeta * omega * q0) / wd);
        let e = (-zeta * omega * t).exp();
        let (c, s) = ((wd * t).cos(), (wd * t).sin());
        let q = e * (a * c + b * s);
        let v = e * ((b * wd - zeta * omega * a) * c - (a * wd + zeta * omega * b) * s);
        (q, v)
    }

    /// Over 2,000 seeded random states of 12 modes, slow and fast, the bound is never above
    /// the deflection sampled at 4,001 instants of the interval; on every fourth draw only
    /// one slow mode is seen, and where it turns to no minimum inside the bound is its lower
    /// end, attained.
    #[test]
    fn the_lowest_deflection_bounds_the_sampled_one() {
        let ts = 5e-5;
        let omega: Vec<f64> = (0..12).map(|i| 2.0 * std::f64::consts::PI * (300.0 + 2_000.0 * i as f64)).collect();
        let zeta = 0.02;
        let modes = half_periods(&omega, ModalDamping::Ratio(zeta), ts);
        assert!(modes.iter().any(|m| m.1) && modes.iter().any(|m| !m.1), "both kinds of mode");
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let mut attained = 0;
        for draw in 0..2_000 {
            let mut phi: Vec<f64> = omega.iter().map(|_| next()).collect();
            let single = draw % 4 == 0;
            if single {
                let one = draw / 4 % modes.iter().filter(|m| m.1).count();
                phi.iter_mut().enumerate().for_each(|(i, p)| *p = if i == one { *p } else { 0.0 });
            }
            let start: Vec<(f64, f64)> = omega.iter().map(|&w| (next() * 1e-5, next() * 1e-5 * w)).collect();
            let end: Vec<(f64, f64)> = omega.iter().zip(&start).map(|(&w, &s)| mode_at(w, zeta, s, ts)).collect();
            let split = |x: &[(f64, f64)]| -> (Vec<f64>, Vec<f64>) { x.iter().copied().unzip() };
            let ((q0, v0), (q1, v1)) = (split(&start), split(&end));
            let bound = lowest_deflection(&phi, (&q0, &v0), (&q1, &v1), &modes);
            let sampled = (0..=4_000)
                .map(|k| {
                    let t = ts * k as f64 / 4_000.0;
                    omega.iter().zip(&start).zip(&phi).map(|((&w, &s), p)| p * mode_at(w, zeta, s, t).0).sum::<f64>()
                })
                .fold(f64::INFINITY, f64::min);
            // The closed form and the sum round at 1e-15 of the amplitudes (1e-5).
            assert!(bound <= sampled + 1e-18, "bound {bound:e} above the sampled lowest {sampled:e}");
            if single && (sampled - bound).abs() <= 1e-12 * sampled.abs() {
                attained += 1;
            }
        }
        assert!(attained > 100, "the bound is attained in {attained} of 500 single-mode draws");
    }

    /// The reach bounds every later deflection of the free plate (sampled over 50 periods of
    /// the slowest mode).
    #[test]
    fn no_later_deflection_exceeds_the_reach() {
        let omega = [900.0, 5_000.0, 31_000.0];
        let (phi, q, v) = ([0.7, -1.3, 0.4], [2e-6, -1e-6, 3e-7], [-4e-3, 9e-3, -2e-2]);
        let r = reach(&phi, &q, &v, &omega);
        for k in 0..200_000 {
            let t = k as f64 * 50.0 * 2.0 * std::f64::consts::PI / omega[0] / 200_000.0;
            let w: f64 = (0..3).map(|i| phi[i] * mode_at(omega[i], 0.01, (q[i], v[i]), t).0).sum();
            assert!(w.abs() <= r * (1.0 + 1e-12), "|w| = {:e} beyond the reach {r:e} at t = {t:e}", w.abs());
        }
    }
}
