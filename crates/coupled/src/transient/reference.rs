//! Classical references for the transient model: Zener's sphere on an infinite plate.

use super::contact::Striker;

/// Zener's model: the sphere on an infinite plate, whose point impedance is 8√(Dρh), so the
/// plate's point velocity is P/Z. Integrated as an ODE (RK4, `steps` per Hertz time) for an
/// undamped contact; returns P_max and the contact time (None if the sphere has not left
/// after 100 Hertz times).
pub fn zener(s: &Striker, impedance: f64, steps: usize) -> (f64, Option<f64>) {
    let dt = s.hertz_time() / steps as f64;
    // State (δ, v_s); δ̇ = v_s - P/Z, v̇_s = -P/m, P = Kδ^{3/2} for δ > 0.
    let rhs = |d: f64, v: f64| {
        let p = if d > 0.0 { s.k * d.powf(1.5) } else { 0.0 };
        (v - p / impedance, -p / s.mass, p)
    };
    let (mut d, mut v, mut t) = (0.0, s.velocity, 0.0);
    let mut pmax: f64 = 0.0;
    loop {
        let (k1d, k1v, p) = rhs(d, v);
        pmax = pmax.max(p);
        let (k2d, k2v, _) = rhs(d + 0.5 * dt * k1d, v + 0.5 * dt * k1v);
        let (k3d, k3v, _) = rhs(d + 0.5 * dt * k2d, v + 0.5 * dt * k2v);
        let (k4d, k4v, _) = rhs(d + dt * k3d, v + dt * k3v);
        let dn = d + dt / 6.0 * (k1d + 2.0 * k2d + 2.0 * k3d + k4d);
        v += dt / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        t += dt;
        if t > dt && dn <= 0.0 {
            let frac = d / (d - dn);
            return (pmax, Some(t - dt + frac * dt));
        }
        d = dn;
        if t > 100.0 * s.hertz_time() {
            return (pmax, None);
        }
    }
}
