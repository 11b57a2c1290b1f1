//! Sensor signals: what is sampled, where, how often, and the time series that come out.
//!
//! Every channel is a linear functional of the modal state and the contact force,
//! y(t) = Σᵢ Aᵢ qᵢ(t) + Σᵢ Bᵢ q̇ᵢ(t) + D(p) P(t): the coefficient rows A, B belong to the
//! channel (its sensor or corner), and D(p), the direct term of the static correction and
//! of the force itself, to the impact point p. A [`Probes`] holds the rows for one
//! [`SignalSpec`] on one [`super::ReducedModel`], so an impact only evaluates D(p).
//!
//! Between samples, after the contacts, every mode is propagated exactly: the damped free
//! vibration over one sample interval T_s is a fixed 2 x 2 map of (qᵢ, q̇ᵢ) per mode
//! ([`free_map`]), computed once per `Probes`.

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
}

impl Quantity {
    /// All three, in this order.
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
}

impl ChannelKind {
    /// SI unit of the samples.
    pub fn unit(&self) -> &'static str {
        match self {
            ChannelKind::Displacement { .. } => "m",
            ChannelKind::Velocity { .. } => "m/s",
            ChannelKind::Acceleration { .. } => "m/s^2",
            ChannelKind::SpringForce { .. } | ChannelKind::Reaction { .. } => "N",
        }
    }

    /// A short label, e.g. "acceleration s1" or "spring force corner (L, 0)".
    pub fn label(&self) -> String {
        match self {
            ChannelKind::Displacement { sensor } => format!("displacement s{}", sensor + 1),
            ChannelKind::Velocity { sensor } => format!("velocity s{}", sensor + 1),
            ChannelKind::Acceleration { sensor } => format!("acceleration s{}", sensor + 1),
            ChannelKind::SpringForce { corner } => format!("spring force {}", corner.name()),
            ChannelKind::Reaction { corner } => format!("reaction {}", corner.name()),
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

/// One channel's coefficients: y = A·q + B·q̇ + D(p) P with
/// D(p) = C·φ(p) + s·N(p)ᵀf + N_c(p).
#[derive(Debug, Clone)]
pub(crate) struct ChannelRows {
    pub kind: ChannelKind,
    pub a: Vec<f64>,
    pub b: Vec<f64>,
    /// Coefficients of φᵢ(p) in D (the modal accelerations' direct response to P).
    pub c: Option<Vec<f64>>,
    /// A residual field f (R times a load, DOFs) and its scale s: the static correction.
    pub field: Option<(Vec<f64>, f64)>,
    /// A DOF whose shape function at p enters D with weight 1 (the load carried straight
    /// into a fixed corner of the struck element).
    pub direct: Option<usize>,
}

/// A [`SignalSpec`] prepared on one reduced model: every channel's rows and the exact
/// free-vibration map over one sample interval.
#[derive(Debug, Clone)]
pub struct Probes {
    pub(crate) spec: SignalSpec,
    pub(crate) rows: Vec<ChannelRows>,
    /// Per mode, the exact map of (q, q̇) over one sample interval.
    pub(crate) sample_map: Vec<[f64; 4]>,
}

impl Probes {
    /// The spec these probes record.
    pub fn spec(&self) -> &SignalSpec {
        &self.spec
    }
    /// The channels in recording order.
    pub fn kinds(&self) -> Vec<ChannelKind> {
        self.rows.iter().map(|r| r.kind).collect()
    }
}

/// The exact map of (q, q̇) over τ for q̈ + 2ζωq̇ + ω²q = 0, ζ < 1, row-major [[q←q, q←q̇],
/// [q̇←q, q̇←q̇]]: with ω_d = ω√(1 - ζ²),
/// q(τ) = e^{-ζωτ}[q₀(cos ω_dτ + ζω/ω_d sin ω_dτ) + q̇₀ sin(ω_dτ)/ω_d],
/// q̇(τ) = e^{-ζωτ}[-q₀ ω²/ω_d sin ω_dτ + q̇₀(cos ω_dτ - ζω/ω_d sin ω_dτ)]
/// (e.g. Craig & Kurdila 2006, §5.2).
pub fn free_map(omega: f64, zeta: f64, tau: f64) -> [f64; 4] {
    let wd = omega * (1.0 - zeta * zeta).sqrt();
    let e = (-zeta * omega * tau).exp();
    let (s, c) = (wd * tau).sin_cos();
    let r = zeta * omega / wd;
    [e * (c + r * s), e * s / wd, -e * omega * omega / wd * s, e * (c - r * s)]
}
