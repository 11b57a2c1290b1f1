//! Sensor signals: what is sampled, where, how often, and the time series that come out.
//!
//! Every channel is a linear functional of the modal state and the contact force,
//! y(t) = Σᵢ Aᵢ qᵢ(t) + Σᵢ Bᵢ q̇ᵢ(t) + D(p) P(t): the coefficient rows A, B belong to the
//! channel (its sensor or corner), and D(p), the direct term of the static correction and
//! of the force itself, to the impact point p. A [`Probes`] holds the rows for one
//! [`SignalSpec`] on one [`super::ReducedModel`], so an impact only evaluates D(p).
//!
//! Between samples, after the contacts, every mode is propagated exactly: the damped free
//! vibration over a time τ is a 2 x 2 map of (qᵢ, q̇ᵢ) per mode ([`free_map`]); the maps over
//! 1 to [`super::window::BLOCK`] sample intervals are computed once per `Probes`.

use plate_fem::Corner;
use serde::Serialize;

/// The sampled window and the sensor points of an impact's signals (SI units).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SignalSpec {
    /// Length of the window from first touch, s (default 20 ms).
    pub window: f64,
    /// Sampling rate, Hz (default 20 kHz).
    pub rate_hz: f64,
    /// Sensor points (x, z), m.
    pub sensors: Vec<(f64, f64)>,
    /// Which plate quantities each sensor records (default all three).
    pub quantities: Vec<Quantity>,
    /// Whether to record the corner channels: spring forces at spring corners, reactions at
    /// fixed corners (default true).
    pub corners: bool,
}

impl SignalSpec {
    /// Default window, s: 20 ms, about 1.6 fundamental periods of the paper's plate (80 Hz)
    /// and 20 or more contact times.
    pub const DEFAULT_WINDOW: f64 = 0.020;
    /// Default sampling rate, Hz: 20 kHz, whose Nyquist frequency (10 kHz) lies above the
    /// contact's spectrum (its main lobe ends near 1/t_c, 1-6 kHz for the paper's rocks at
    /// 0.008-3 m/s) and at the top of the default modes.
    pub const DEFAULT_RATE_HZ: f64 = 20_000.0;

    /// The default window and rate, every quantity at `sensors`, the corners included.
    pub fn new(sensors: Vec<(f64, f64)>) -> Self {
        Self {
            window: Self::DEFAULT_WINDOW,
            rate_hz: Self::DEFAULT_RATE_HZ,
            sensors,
            quantities: Quantity::ALL.to_vec(),
            corners: true,
        }
    }

    /// Number of samples, at t_k = k/rate for k = 0, 1, ... while t_k < window (the first at
    /// the first touch).
    pub fn samples(&self) -> usize {
        (self.window * self.rate_hz - 1e-9).ceil().max(1.0) as usize
    }

    /// The sample interval 1/rate, s.
    pub fn interval(&self) -> f64 {
        1.0 / self.rate_hz
    }
}

/// A plate quantity at a sensor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Quantity {
    /// Deflection w, m (positive along the impact).
    Displacement,
    /// ẇ, m/s.
    Velocity,
    /// ẅ, m/s².
    Acceleration,
    /// The bending strain along x on the unstruck face, ε_x = -(h/2) ∂²w/∂x²
    /// ([`plate_fem::Model::bending_strain`]); recorded only when asked for (a strain gauge),
    /// not among [`Quantity::ALL`].
    Strain,
}

impl Quantity {
    /// The three kinematic quantities every sensor records by default, in this order.
    pub const ALL: [Quantity; 3] = [Quantity::Displacement, Quantity::Velocity, Quantity::Acceleration];
}

/// What a channel records.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum ChannelKind {
    /// Plate deflection at sensor `sensor` (index into [`SignalSpec::sensors`]), m.
    Displacement {
        /// Sensor index.
        sensor: usize,
    },
    /// Plate velocity at a sensor, m/s.
    Velocity {
        /// Sensor index.
        sensor: usize,
    },
    /// Plate acceleration at a sensor, m/s².
    Acceleration {
        /// Sensor index.
        sensor: usize,
    },
    /// Bending strain along x on the unstruck face at a sensor (dimensionless).
    Strain {
        /// Sensor index.
        sensor: usize,
    },
    /// Force in the spring (prop or jack) at a corner, k·w_c, N (positive in compression,
    /// i.e. pushing against the impact).
    SpringForce {
        /// The corner.
        corner: Corner,
    },
    /// Reaction of a fixed corner, N (positive against the impact).
    Reaction {
        /// The corner.
        corner: Corner,
    },
    /// Force of a spring group of a shell structure (a jack on its pad), Σ gᵀu = Σ k d̂·u over
    /// its springs, N (signed along the springs' directions as the structure gives them).
    JackForce {
        /// The group's index.
        jack: usize,
    },
}

impl ChannelKind {
    /// SI unit of the samples.
    pub fn unit(&self) -> &'static str {
        match self {
            ChannelKind::Displacement { .. } => "m",
            ChannelKind::Velocity { .. } => "m/s",
            ChannelKind::Acceleration { .. } => "m/s^2",
            ChannelKind::Strain { .. } => "1",
            ChannelKind::SpringForce { .. } | ChannelKind::Reaction { .. } | ChannelKind::JackForce { .. } => "N",
        }
    }

    /// A short label, e.g. "acceleration s1" or "spring force corner (L, 0)".
    pub fn label(&self) -> String {
        match self {
            ChannelKind::Displacement { sensor } => format!("displacement s{}", sensor + 1),
            ChannelKind::Velocity { sensor } => format!("velocity s{}", sensor + 1),
            ChannelKind::Acceleration { sensor } => format!("acceleration s{}", sensor + 1),
            ChannelKind::Strain { sensor } => format!("strain s{}", sensor + 1),
            ChannelKind::SpringForce { corner } => format!("spring force {}", corner.name()),
            ChannelKind::Reaction { corner } => format!("reaction {}", corner.name()),
            ChannelKind::JackForce { jack } => format!("jack {} force", jack + 1),
        }
    }
}

/// One sampled time series.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Channel {
    /// What it records.
    pub kind: ChannelKind,
    /// Samples at t_k = k/rate, in the unit of `kind`.
    pub samples: Vec<f64>,
}

/// The signals of one impact.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Signals {
    /// Sampling rate, Hz.
    pub rate_hz: f64,
    /// The channels, in the order of [`Probes::kinds`].
    pub channels: Vec<Channel>,
}

impl Signals {
    /// The sample times t_k = k/rate, s.
    pub fn times(&self) -> Vec<f64> {
        let n = self.channels.first().map_or(0, |c| c.samples.len());
        (0..n).map(|k| k as f64 / self.rate_hz).collect()
    }

    /// The channel of `kind`, if recorded.
    pub fn channel(&self, kind: ChannelKind) -> Option<&Channel> {
        self.channels.iter().find(|c| c.kind == kind)
    }
}

/// One channel as linear functionals of the plate's fields: y = ℓ_d(w) + ℓ_v(ẇ) + ℓ_a(ẅ)
/// (+ the load carried straight into a fixed corner). On the modes this is
/// y = A·q + B·q̇ + C·φ(p) P with Aᵢ = ℓ_d(φᵢ) - ωᵢ²ℓ_a(φᵢ), Bᵢ = ℓ_v(φᵢ) - 2ζωᵢℓ_a(φᵢ),
/// Cᵢ = ℓ_a(φᵢ) (from q̈ᵢ = φᵢ(p)P - ωᵢ²qᵢ - 2ζωᵢq̇ᵢ). The truncated modes enter through the
/// residual fields Rℓ (by reciprocity ℓ(RN(p)) = N(p)ᵀRℓ), as a static correction or as the
/// residual mode.
#[derive(Debug, Clone)]
pub(crate) struct ChannelRows {
    pub kind: ChannelKind,
    pub a: Vec<f64>,
    pub b: Vec<f64>,
    /// Cᵢ = ℓ_a(φᵢ), if the channel has an acceleration part.
    pub c: Option<Vec<f64>>,
    /// A DOF whose shape function at p enters with weight 1 (the load carried straight into
    /// a fixed corner of the struck element).
    pub direct: Option<usize>,
    /// ℓ_d, ℓ_v, ℓ_a as residual fields (indices into [`Probes::fields`]) with scales.
    pub res: [Option<(usize, f64)>; 3],
    /// A reaction: its inertia functional carries the modal damping force too, so that B = 0.
    pub damped_inertia: bool,
}

/// A [`SignalSpec`] prepared on one reduced model: every channel's rows and the exact
/// free-vibration maps over 1 to [`super::window::BLOCK`] sample intervals.
#[derive(Debug, Clone)]
pub struct Probes {
    pub(crate) spec: SignalSpec,
    pub(crate) rows: Vec<ChannelRows>,
    /// Residual fields Rℓ of the channels' functionals (DOFs).
    pub(crate) fields: Vec<Vec<f64>>,
    /// The exact maps of (q, q̇) over 1 to [`super::window::BLOCK`] sample intervals.
    pub(crate) block_maps: super::window::BlockMaps,
    /// The maps over T_s/m for m = 1, 2, ..., built when first needed (the step of every
    /// impact whose contact needs m steps per sample).
    pub(crate) step_maps: Vec<std::sync::OnceLock<FreeMaps>>,
    pub(crate) omega: Vec<f64>,
    pub(crate) zeta: super::ModalDamping,
}

impl Probes {
    /// Most steps per sample whose maps are cached.
    const CACHED: usize = 512;

    pub(crate) fn new(
        spec: &SignalSpec,
        rows: Vec<ChannelRows>,
        fields: Vec<Vec<f64>>,
        omega: &[f64],
        zeta: super::ModalDamping,
    ) -> Self {
        Self {
            spec: spec.clone(),
            rows,
            fields,
            block_maps: super::window::BlockMaps::new(omega, zeta, spec.interval()),
            step_maps: (0..Self::CACHED).map(|_| std::sync::OnceLock::new()).collect(),
            omega: omega.to_vec(),
            zeta,
        }
    }

    /// The exact map over T_s/`every` for the model's modes, cached.
    pub(crate) fn step_map(&self, every: usize) -> FreeMaps {
        match self.step_maps.get(every.saturating_sub(1)) {
            Some(slot) if every > 0 => {
                slot.get_or_init(|| FreeMaps::new(&self.omega, self.zeta, self.spec.interval() / every as f64)).clone()
            }
            _ => FreeMaps::new(&self.omega, self.zeta, self.spec.interval() / every.max(1) as f64),
        }
    }

    /// The spec these probes record.
    pub fn spec(&self) -> &SignalSpec {
        &self.spec
    }
    /// The channels in recording order.
    pub fn kinds(&self) -> Vec<ChannelKind> {
        self.rows.iter().map(|r| r.kind).collect()
    }
}

/// The maps of (q, q̇) of every free mode over one interval (exact, or Newmark's step),
/// stored by entry (four arrays over the modes) so that stepping every mode is a vector
/// operation.
#[derive(Debug, Clone, Default)]
pub(crate) struct FreeMaps {
    m: [Vec<f64>; 4],
}

impl FreeMaps {
    /// The exact maps over τ for the modes `omega`, damping `zeta` ([`free_map`]).
    pub(crate) fn new(omega: &[f64], zeta: super::ModalDamping, tau: f64) -> Self {
        Self::by_mode(omega.iter().map(|&w| free_map(w, zeta.at(w), tau)))
    }

    /// Newmark's maps over Δt for the modes `omega`, damping `zeta` ([`newmark_map`]).
    pub(crate) fn newmark(omega: &[f64], zeta: super::ModalDamping, dt: f64) -> Self {
        Self::by_mode(omega.iter().map(|&w| newmark_map(w, zeta.at(w), dt)))
    }

    fn by_mode(maps: impl Iterator<Item = [f64; 4]>) -> Self {
        let maps: Vec<[f64; 4]> = maps.collect();
        Self { m: std::array::from_fn(|k| maps.iter().map(|m| m[k]).collect()) }
    }

    /// The maps with zero maps appended up to `len` modes.
    pub(crate) fn padded(mut self, len: usize) -> Self {
        for m in &mut self.m {
            m.resize(len.max(m.len()), 0.0);
        }
        self
    }

    /// The four entries [q←q, q←q̇, q̇←q, q̇←q̇], each over the modes.
    pub(crate) fn entries(&self) -> [&[f64]; 4] {
        [&self.m[0], &self.m[1], &self.m[2], &self.m[3]]
    }

    /// (q, q̇) ← map (q, q̇), written to (`q_out`, `v_out`).
    #[inline(always)]
    pub(crate) fn apply(&self, q: &[f64], v: &[f64], q_out: &mut [f64], v_out: &mut [f64]) {
        let [m0, m1, m2, m3] = &self.m;
        let n = q.len();
        let (m0, m1, m2, m3, v) = (&m0[..n], &m1[..n], &m2[..n], &m3[..n], &v[..n]);
        let (q_out, v_out) = (&mut q_out[..n], &mut v_out[..n]);
        for i in 0..n {
            q_out[i] = m0[i] * q[i] + m1[i] * v[i];
            v_out[i] = m2[i] * q[i] + m3[i] * v[i];
        }
    }

    /// Appends the map of one more mode.
    pub(crate) fn push(&mut self, omega: f64, zeta: f64, tau: f64) {
        let m = free_map(omega, zeta, tau);
        for (v, x) in self.m.iter_mut().zip(m) {
            v.push(x);
        }
    }
}

/// Σ aᵢbᵢ with eight independent partial sums, so that the compiler can vectorize it (a
/// plain sum fixes the order of the additions and cannot be).
#[inline(always)]
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0f64; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for k in 0..8 {
            acc[k] += x[k] * y[k];
        }
    }
    let tail: f64 = ra.iter().zip(rb).map(|(x, y)| x * y).sum();
    (acc[0] + acc[4]) + (acc[1] + acc[5]) + (acc[2] + acc[6]) + (acc[3] + acc[7]) + tail
}

/// The exact map of (q, q̇) over τ for q̈ + 2ζωq̇ + ω²q = 0, ζ < 1, row-major [[q←q, q←q̇],
/// [q̇←q, q̇←q̇]]: with ω_d = ω√(1 - ζ²),
/// q(τ) = e^{-ζωτ}[q₀(cos ω_dτ + ζω/ω_d sin ω_dτ) + q̇₀ sin(ω_dτ)/ω_d],
/// q̇(τ) = e^{-ζωτ}[-q₀ ω²/ω_d sin ω_dτ + q̇₀(cos ω_dτ - ζω/ω_d sin ω_dτ)]
/// (e.g. Craig & Kurdila 2006, §5.2). A mode damped at or beyond critical (ζ ≥ 1, which
/// Rayleigh's stiffness part gives the highest modes) takes the same formula continued to
/// imaginary ω_d (`overdamped_map`).
pub fn free_map(omega: f64, zeta: f64, tau: f64) -> [f64; 4] {
    if zeta >= 1.0 {
        return overdamped_map(omega, zeta, tau);
    }
    let wd = omega * (1.0 - zeta * zeta).sqrt();
    let e = (-zeta * omega * tau).exp();
    let (s, c) = (wd * tau).sin_cos();
    let r = zeta * omega / wd;
    [e * (c + r * s), e * s / wd, -e * omega * omega / wd * s, e * (c - r * s)]
}

/// [`free_map`] for ζ ≥ 1: with ω_s = ω√(ζ² - 1) the cosine becomes cosh ω_sτ and
/// sin(ω_dτ)/ω_d becomes sinh(ω_sτ)/ω_s (τ at ζ = 1), each multiplied by e^{-ζωτ} as the sum
/// of the two decaying exponentials e^{-(ζω ∓ ω_s)τ}, so that nothing overflows.
fn overdamped_map(omega: f64, zeta: f64, tau: f64) -> [f64; 4] {
    let ws = omega * (zeta * zeta - 1.0).sqrt();
    let (slow, fast) = ((-(zeta * omega - ws) * tau).exp(), (-(zeta * omega + ws) * tau).exp());
    let c = 0.5 * (slow + fast);
    let s1 = if ws > 0.0 { (slow - fast) / (2.0 * ws) } else { tau * (-omega * tau).exp() };
    let r = zeta * omega;
    [c + r * s1, s1, -omega * omega * s1, c - r * s1]
}

/// Newmark's average-acceleration step of q̈ + 2ζωq̇ + ω²q = 0 over Δt as a map of (q, q̇),
/// row-major as [`free_map`], the step-start acceleration taken from the equation of motion:
/// with h = 1/(ω² + 4ζω/Δt + 4/Δt²),
/// qₙ₊₁ = h[(4/Δt² - ω² + 4ζω/Δt)qₙ + (4/Δt)q̇ₙ] and q̇ₙ₊₁ = (2/Δt)(qₙ₊₁ - qₙ) - q̇ₙ, i.e.
/// q̇ₙ₊₁ = h[-(4ω²/Δt)qₙ + (4/Δt² - ω² - 4ζω/Δt)q̇ₙ] (Newmark 1959; for ζ = 0 a rotation
/// of (ωq, q̇) by 2 arctan(ωΔt/2), determinant 1). The entries are written out so that
/// nothing cancels: (2/Δt)(qₙ₊₁ - qₙ) would lose the small ω²Δt² of the slow modes.
pub fn newmark_map(omega: f64, zeta: f64, dt: f64) -> [f64; 4] {
    let (w2, c) = (omega * omega, 4.0 / (dt * dt));
    let d = 4.0 * zeta * omega / dt;
    let h = 1.0 / (w2 + d + c);
    [h * (c - w2 + d), h * 4.0 / dt, -h * 4.0 * w2 / dt, h * (c - w2 - d)]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Beyond critical damping the map still solves q̈ + 2ζωq̇ + ω²q = 0: against the
    /// closed form of the overdamped oscillator released from q₀ = 1 at rest,
    /// q = (r₁e^{r₂t} - r₂e^{r₁t})/(r₁ - r₂) with r₁,₂ = -ζω ± ω√(ζ² - 1), and at ζ = 1
    /// against (1 + ωt)e^{-ωt}; and it is finite where e^{-ζωτ} cosh(ω_sτ) would overflow.
    #[test]
    fn free_map_beyond_critical_damping() {
        let (w, t) = (2.0 * std::f64::consts::PI * 300.0, 1.7e-3);
        for z in [1.0 + 1e-4, 1.5, 40.0] {
            let ws = w * ((z * z) - 1.0_f64).sqrt();
            let (r1, r2) = (-z * w + ws, -z * w - ws);
            let exact = (r1 * (r2 * t).exp() - r2 * (r1 * t).exp()) / (r1 - r2);
            let m = free_map(w, z, t);
            assert!((m[0] - exact).abs() <= 1e-6 * exact.abs().max(1e-300), "ζ = {z}: {} vs {exact}", m[0]);
        }
        let m = free_map(w, 1.0, t);
        let exact = (1.0 + w * t) * (-w * t).exp();
        assert!((m[0] / exact - 1.0).abs() < 1e-12, "{} vs {exact}", m[0]);
        assert!(free_map(1e7, 50.0, 1.0).iter().all(|x| x.is_finite()));
    }

    /// The damped free vibration against its defining properties: maps compose
    /// (Φ(τ₁)Φ(τ₂) = Φ(τ₁ + τ₂)); after one damped period 2π/ω_d a displacement returns
    /// scaled by exactly e^{-ζωT_d} with no velocity; and Newmark's average-acceleration
    /// rule on q̈ + 2ζωq̇ + ω²q = 0 converges to it at second order (halving Δt divides the
    /// error at t = 3 periods by 4 ± 0.2).
    #[test]
    fn free_map_is_the_damped_oscillator() {
        let (w, z) = (2.0 * std::f64::consts::PI * 500.0, 0.02);
        let (a, b) = (free_map(w, z, 1.3e-4), free_map(w, z, 2.1e-4));
        let ab = [
            a[0] * b[0] + a[1] * b[2],
            a[0] * b[1] + a[1] * b[3],
            a[2] * b[0] + a[3] * b[2],
            a[2] * b[1] + a[3] * b[3],
        ];
        let c = free_map(w, z, 3.4e-4);
        for k in 0..4 {
            assert!((ab[k] - c[k]).abs() <= 1e-12 * c[k].abs().max(1.0), "{ab:?} {c:?}");
        }
        let td = 2.0 * std::f64::consts::PI / (w * (1.0 - z * z).sqrt());
        let m = free_map(w, z, td);
        assert!((m[0] - (-z * w * td).exp()).abs() < 1e-12 && m[2].abs() < 1e-9 * w, "{m:?}");
        let newmark = |steps: usize| -> f64 {
            let dt = 3.0 * td / steps as f64;
            let (mut q, mut v, mut acc) = (1.0, 0.0, -w * w);
            let h = 1.0 / (w * w + 4.0 * z * w / dt + 4.0 / (dt * dt));
            for _ in 0..steps {
                let qn = h * (4.0 / (dt * dt) * (q + dt * v) + acc + 2.0 * z * w * (2.0 * q / dt + v));
                let vn = 2.0 * (qn - q) / dt - v;
                acc = -w * w * qn - 2.0 * z * w * vn;
                (q, v) = (qn, vn);
            }
            (q - free_map(w, z, 3.0 * td)[0]).abs()
        };
        let (e1, e2) = (newmark(600), newmark(1200));
        assert!((e1 / e2 - 4.0).abs() < 0.2, "{e1:e} {e2:e}");
    }

    /// Newmark's map against the rule in its textbook form, which carries the acceleration
    /// as a third variable (qₙ₊₁ = qₙ + Δt q̇ₙ + Δt²/4 (q̈ₙ + q̈ₙ₊₁), q̇ₙ₊₁ = q̇ₙ + Δt/2 (q̈ₙ + q̈ₙ₊₁),
    /// q̈ₙ₊₁ from the equation of motion, solved for qₙ₊₁): 500 steps of a slow and a fast
    /// mode (ωΔt = 0.01 and 20) agree to 1e-11 of the amplitude A (velocities: of A·2/Δt,
    /// the scale of the textbook form's own rounding in (2/Δt)(qₙ₊₁ - qₙ), at most 500ε of
    /// it over 500 steps), and undamped the map has determinant 1 (the rule conserves
    /// ω²q² + q̇²) to 1e-15.
    #[test]
    fn newmark_map_is_the_average_acceleration_rule() {
        let dt = 1e-5;
        for (w, z) in [(1e3, 0.0), (1e3, 0.05), (2e6, 0.0), (2e6, 0.05)] {
            let m = newmark_map(w, z, dt);
            let (mut q, mut v) = (1.0, 0.3 * w);
            let (mut qt, mut vt, mut at) = (q, v, -w * w * q - 2.0 * z * w * v);
            for _ in 0..500 {
                (q, v) = (m[0] * q + m[1] * v, m[2] * q + m[3] * v);
                // qₙ₊₁(1 + Δt²/4 ω² + Δt²/4 · 2ζω · 2/Δt) = qₙ + Δt q̇ₙ + Δt²/4 q̈ₙ + Δt²/4 · 2ζω((2/Δt)qₙ + q̇ₙ)
                let k = 1.0 + 0.25 * dt * dt * w * w + z * w * dt;
                let qn = (qt + dt * vt + 0.25 * dt * dt * at + 0.5 * z * w * dt * dt * (2.0 * qt / dt + vt)) / k;
                let vn = 2.0 * (qn - qt) / dt - vt;
                at = -w * w * qn - 2.0 * z * w * vn;
                (qt, vt) = (qn, vn);
                let a = (q * q + v * v / (w * w)).sqrt();
                assert!(
                    (q - qt).abs() < 1e-11 * a && (v - vt).abs() < 1e-11 * a * 2.0 / dt,
                    "{w} {z}: {q} {qt}, {v} {vt}"
                );
            }
            if z == 0.0 {
                assert!((m[0] * m[3] - m[1] * m[2] - 1.0).abs() < 1e-15, "{m:?}");
            }
        }
    }

    /// Undamped, Newmark's rule turns (ωq, q̇) by θ = 2 arctan(ωΔt/2) per step, so n steps are
    /// q = q₀ cos nθ + (q̇₀/ω) sin nθ exactly. The map keeps that to rounding even on a slow
    /// mode, where (2/Δt)(qₙ₊₁ - qₙ) would cancel log₁₀(1/ωΔt) digits: over 300 steps of
    /// Δt = 1.5 µs an 80 Hz mode (ωΔt = 7.5e-4) stays within 2e-14 of its amplitude (measured
    /// 7e-15; the cancelling form drifts to 2e-12), a 9 kHz one within 1e-13 (measured 3e-14:
    /// its phase gathers a rounding of θ every step, 300ε ≈ 7e-14).
    #[test]
    fn newmark_map_is_a_rotation() {
        let dt = 1.5e-6;
        for (hz, tol) in [(80.0, 2e-14), (9000.0, 1e-13)] {
            let w = 2.0 * std::f64::consts::PI * hz;
            let m = newmark_map(w, 0.0, dt);
            let theta = (4.0 * w * dt).atan2(4.0 - w * w * dt * dt);
            let (q0, v0) = (1.0, 0.7 * w);
            let a = (q0 * q0 + v0 * v0 / (w * w)).sqrt();
            let (mut q, mut v) = (q0, v0);
            for n in 1..=300 {
                (q, v) = (m[0] * q + m[1] * v, m[2] * q + m[3] * v);
                let (s, c) = (n as f64 * theta).sin_cos();
                let (qe, ve) = (q0 * c + v0 / w * s, -q0 * w * s + v0 * c);
                assert!((q - qe).abs() < tol * a && (v - ve).abs() < tol * a * w, "{w}, step {n}: {q} {qe}, {v} {ve}");
            }
        }
    }
}
