//! Impact regimes: when the quasi-static balance holds, by the published criteria, by a
//! closed-form rule, and by measurement.
//!
//! The paper's balance (eqs. 14, 25, 46) assumes that the plate deforms statically while the
//! sphere is in contact. Two published characterisations say when that holds:
//!
//! - **Olsson's mass criterion** (R. Olsson, "Mass criterion for wave controlled impact
//!   response of composite plates", Composites Part A 31 (2000) 879-887): the response type
//!   is governed by the impactor-to-plate mass ratio M_i/M_p. Small-mass impacts, M_i/M_p
//!   below about a quarter (0.23 in the paper), are wave controlled: the contact ends before
//!   the flexural waves have reached the boundaries, and the boundary conditions do not
//!   matter. Large-mass impacts, M_i/M_p above about 2, are quasi-static (boundary
//!   controlled): the plate deflects in its static shape. In between the response is mixed.
//!   ([`mass_ratio`], [`OlssonRegime`].)
//! - **Christoforou and Yigit's characterisation** (A. P. Christoforou, A. S. Yigit,
//!   "Characterization of impact in composite plates", Composite Structures 43 (1998) 15-24;
//!   "Effect of flexibility on low velocity impact response", J. Sound Vib. 217 (1998)
//!   563-578): with the contact linearised to a spring k_α, the impact of a mass M on a plate
//!   depends on two numbers, the relative stiffness λ = k_α/k_bs (contact against the
//!   plate's static point stiffness k_bs = 1/C) and the loss factor
//!   ζ = (1/16)√(M k_α/(ρhD)). The quasi-static asymptote is the mass on the two springs in
//!   series, peak force F̄_qs = 1/√(1 + λ); the infinite-plate asymptote (the plate as the
//!   dashpot 8√(Dρh) of an infinite plate, no boundaries) is a damped oscillator with damping
//!   ratio ζ, F̄_∞ = exp(-ζ arccos ζ/√(1 - ζ²)); both are normalised by v√(M k_α), the
//!   half-space value. Small λ is the half-space limit: the plate is stiff against the
//!   contact and neither its statics nor its waves matter. ([`ChristoforouYigit`].)
//!
//! A finite plate is struck by a sphere whose contact is short against the plate's period:
//! early in the contact only the plate near the load moves, as in the infinite plate, and
//! the force follows the infinite-plate asymptote, which lies above the quasi-static one when
//! the plate's impedance is high against the contact (small ζ). The quasi-static balance then
//! underestimates the force by up to F̄_∞/F̄_qs - 1 = F̄_∞(ζ)√(1 + λ) - 1
//! ([`ChristoforouYigit::error_bound`]); a slow contact (large t_c/T₁) leaves the plate time
//! to take its static shape and the error goes to zero. This crate's transient model
//! measures the error between those limits ([`measure`]); the report of the regime maps sets
//! the measured error beside both criteria.
//!
//! **The rule** ([`RuleInputs`], [`rule`]), applicable before anything is run, from closed
//! forms only: the Hertz contact time t_H, an estimate T₁,est of the fundamental period
//! ([`period_estimate`]: the paper's beam, Dunkerley's combination with the springs), λ and ζ
//! (C the static compliance at the point: the beam's closed form, or the plate model's). It
//! bounds the quasi-static balance's force error by
//!
//! - B (Christoforou and Yigit's infinite-plate bound) for a fast contact, t_H/T₁,est < 0.2
//!   with ζ < 1;
//! - 2λ/(1 + λ) between 0.2 and 2, where the plate's first mode resonates with the pulse and
//!   deflects more than statically (the error is negative there: the balance overstates the
//!   force), and wherever no closed-form period is known;
//! - 0.35λ/(1 + λ) for a slow contact, t_H/T₁,est ≥ 2;
//!
//! and trusts the balance where the bound is at most 3 %. λ/(1 + λ) is the plate's share of
//! the two springs in series. The thresholds and factors are envelopes of the measured map
//! (the regime-maps report shows every case against them and counts the rule's mistakes).

use crate::discretisation::plate_properties;
use crate::error::ModelError;
use crate::supports::SupportSet;
use crate::transient::{simulate_with, Outcome, PlateFacts, SpringMass, Striker, TransientCase};
use crate::validity::Criterion;
use analytic::{Condition, Plate};
use plate_fem::dynamics::Newmark;
use serde::Serialize;

/// Olsson's bound below which a small-mass impact is wave controlled: M_i/M_p < 0.23.
pub const OLSSON_WAVE_CONTROLLED: f64 = 0.23;
/// Olsson's bound above which a large-mass impact is quasi-static: M_i/M_p > 2.
pub const OLSSON_QUASI_STATIC: f64 = 2.0;

/// The impactor-to-plate mass ratio M_i/M_p of Olsson's criterion.
pub fn mass_ratio(sphere_mass: f64, plate: &Plate) -> f64 {
    sphere_mass / (plate.density() * plate.length() * plate.width() * plate.thickness())
}

/// Olsson's response types by the mass ratio.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum OlssonRegime {
    /// M_i/M_p < 0.23: small mass, wave controlled.
    WaveControlled,
    /// 0.23 ≤ M_i/M_p ≤ 2: between the two.
    Mixed,
    /// M_i/M_p > 2: large mass, quasi-static.
    QuasiStatic,
}

impl OlssonRegime {
    /// The regime of a mass ratio.
    pub fn of(mass_ratio: f64) -> Self {
        if mass_ratio < OLSSON_WAVE_CONTROLLED {
            OlssonRegime::WaveControlled
        } else if mass_ratio > OLSSON_QUASI_STATIC {
            OlssonRegime::QuasiStatic
        } else {
            OlssonRegime::Mixed
        }
    }

    /// Its name in tables.
    pub fn key(self) -> &'static str {
        match self {
            OlssonRegime::WaveControlled => "wave controlled",
            OlssonRegime::Mixed => "mixed",
            OlssonRegime::QuasiStatic => "quasi-static",
        }
    }
}

/// Christoforou and Yigit's parameters of one impact (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ChristoforouYigit {
    /// The linearised contact stiffness k_α, N/m: the linear spring with Hertz's peak force
    /// on a rigid target, k_α = P_H²/(M v²), so that the half-space values agree.
    pub contact_stiffness: f64,
    /// λ = k_α C, C the plate's static compliance at the point (springs included).
    pub relative_stiffness: f64,
    /// ζ = √(M k_α)/(16√(ρhD)), the damping ratio of the mass on the contact spring against
    /// the infinite plate's point impedance 8√(Dρh).
    pub loss_factor: f64,
}

impl ChristoforouYigit {
    /// The parameters of `s` striking `plate` at a point of static compliance `compliance`.
    pub fn of(s: &Striker, plate: &Plate, compliance: f64) -> Self {
        Self::with_peak(plate, s.mass, s.velocity, s.hertz_force(), compliance)
    }

    /// The parameters with the contact linearised to the spring k_α = P²/(m v²) that gives
    /// the rigid-target peak force `peak` of a mass `mass` at `velocity` (Hertz's for
    /// [`Self::of`]; another law's where its restitution lowers the peak).
    pub fn with_peak(plate: &Plate, mass: f64, velocity: f64, peak: f64, compliance: f64) -> Self {
        let k_alpha = peak * peak / (mass * velocity * velocity);
        let props = plate_properties(plate);
        let rho_h = props.density * props.thickness;
        Self {
            contact_stiffness: k_alpha,
            relative_stiffness: k_alpha * compliance,
            loss_factor: (mass * k_alpha).sqrt() / (16.0 * (rho_h * props.rigidity()).sqrt()),
        }
    }

    /// The quasi-static asymptote F̄_qs = 1/√(1 + λ): the mass on the contact and plate
    /// springs in series, peak force over the half-space value v√(M k_α).
    pub fn quasi_static_force(&self) -> f64 {
        1.0 / (1.0 + self.relative_stiffness).sqrt()
    }

    /// The infinite-plate asymptote F̄_∞(ζ): the peak force of the mass on the contact spring
    /// against the dashpot 8√(Dρh), over v√(M k_α). The indentation obeys
    /// ü + 2ζω u̇ + ω²u = 0, u(0) = 0, u̇(0) = v, whose maximum is (v/ω)exp(-ζ φ/√|1 - ζ²|),
    /// φ = arccos ζ (ζ < 1) or arccosh ζ (ζ > 1); at ζ = 1 it is (v/ω)/e.
    pub fn infinite_plate_force(&self) -> f64 {
        let z = self.loss_factor;
        if (z - 1.0).abs() < 1e-9 {
            (-1.0f64).exp()
        } else if z < 1.0 {
            (-z * z.acos() / (1.0 - z * z).sqrt()).exp()
        } else {
            (-z * z.acosh() / (z * z - 1.0).sqrt()).exp()
        }
    }

    /// The closed-form bound on the quasi-static balance's error in the force,
    /// B = F̄_∞/F̄_qs - 1 (the infinite-plate response over the quasi-static one, zero where
    /// the infinite plate is the softer).
    pub fn error_bound(&self) -> f64 {
        (self.infinite_plate_force() / self.quasi_static_force() - 1.0).max(0.0)
    }
}

/// A closed-form estimate of the fundamental period T₁ of the paper's supported plate under
/// Con 1-3 (None for any other support set): the paper's beam (E I, span L, simply supported
/// at the corner pairs, ω_b = (π/L)²√(EI/ρA)) combined with the rigid-body mode on the
/// springs by Dunkerley's formula 1/ω² = 1/ω_b² + 1/ω_s², which bounds ω₁ from below:
/// ω_s² = 4k_T/M_p for Con 2 (the plate bouncing on its four springs) and 6k_T/M_p for Con 3
/// (rotating about the fixed end, inertia M_pL²/3, springs 2k_T at arm L).
pub fn period_estimate(plate: &Plate, set: &SupportSet) -> Option<f64> {
    let h = plate.thickness();
    let e = plate.material().youngs_modulus();
    let l = plate.length();
    let m_p = plate.density() * l * plate.width() * h;
    let beam = (std::f64::consts::PI / l).powi(2) * (e * h * h / (12.0 * plate.density())).sqrt();
    let springs = match set.beam_condition()? {
        Condition::BothFixed => f64::INFINITY,
        Condition::BothSprings { k_t } => (4.0 * k_t / m_p).sqrt(),
        Condition::FixedAndSprings { k_t } => (6.0 * k_t / m_p).sqrt(),
    };
    let omega = 1.0 / (1.0 / (beam * beam) + 1.0 / (springs * springs)).sqrt();
    Some(2.0 * std::f64::consts::PI / omega)
}

/// The error in the force the rule guards: the quasi-static balance is trusted where the
/// rule's bound on its error is at most this.
pub const RULE_LIMIT: f64 = 0.03;
/// t_H/T₁,est below which the contact is fast: the plate near the load responds as the
/// infinite plate, and Christoforou and Yigit's bound B applies (with ζ < 1).
pub const FAST_CONTACT: f64 = 0.2;
/// t_H/T₁,est from which the contact is slow: the plate follows the force statically.
pub const SLOW_CONTACT: f64 = 2.0;
/// Between fast and slow, |error| ≤ 2λ/(1 + λ): the plate's first mode, driven by a pulse of
/// about its own period, deflects up to twice its static deflection and takes energy the
/// balance gives the rock (measured down to -1.99λ/(1 + λ) on the map).
pub const RESONANCE_FACTOR: f64 = 2.0;
/// Slow contacts: |error| ≤ 0.35λ/(1 + λ) (measured at most 0.32λ/(1 + λ) on the map).
pub const SLOW_FACTOR: f64 = 0.35;

/// The rule's inputs for one case, all closed form.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RuleInputs {
    /// Christoforou and Yigit's parameters.
    pub parameters: ChristoforouYigit,
    /// t_H/T₁,est (None where the support set has no closed-form period).
    pub period_ratio: Option<f64>,
}

/// Which part of the rule applies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ContactSpeed {
    /// t_H/T₁,est < [`FAST_CONTACT`] and ζ < 1: the infinite-plate bound.
    Fast,
    /// In between, or no closed-form period: the resonance bound.
    Resonant,
    /// t_H/T₁,est ≥ [`SLOW_CONTACT`].
    Slow,
}

impl RuleInputs {
    /// The inputs for `s` on `plate` held by `set`, at a point of static compliance `compliance`.
    pub fn of(s: &Striker, plate: &Plate, set: &SupportSet, compliance: f64) -> Self {
        Self {
            parameters: ChristoforouYigit::of(s, plate, compliance),
            period_ratio: period_estimate(plate, set).map(|t1| s.hertz_time() / t1),
        }
    }

    /// The regime the rule puts the case in.
    pub fn speed(&self) -> ContactSpeed {
        match self.period_ratio {
            Some(r) if r < FAST_CONTACT && self.parameters.loss_factor < 1.0 => ContactSpeed::Fast,
            Some(r) if r >= SLOW_CONTACT => ContactSpeed::Slow,
            _ => ContactSpeed::Resonant,
        }
    }

    /// The rule's bound on |P_max transient/quasi-static - 1|: B for a fast contact,
    /// 2λ/(1 + λ) in between, 0.35λ/(1 + λ) for a slow one.
    pub fn error_bound(&self) -> f64 {
        let p = &self.parameters;
        let share = p.relative_stiffness / (1.0 + p.relative_stiffness);
        match self.speed() {
            ContactSpeed::Fast => p.error_bound(),
            ContactSpeed::Resonant => RESONANCE_FACTOR * share,
            ContactSpeed::Slow => SLOW_FACTOR * share,
        }
    }

    /// Whether the rule trusts the quasi-static balance: its bound is at most [`RULE_LIMIT`].
    pub fn trusts(&self) -> bool {
        self.error_bound() <= RULE_LIMIT
    }
}

/// The rule as a validity criterion: its bound on the quasi-static force error against
/// [`RULE_LIMIT`].
pub fn rule(inputs: RuleInputs) -> Criterion {
    Criterion::at_most("closed-form bound on the quasi-static force error", inputs.error_bound(), RULE_LIMIT)
}

/// One measured case of the regime map: the transient impact against the quasi-static
/// balance on the same plate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Measured {
    /// The force at maximum compression of the transient first contact (the law's force at
    /// δ̇ = 0 on the interpolant), N.
    pub transient_force: f64,
    /// The transient first contact's duration, s (None if it had not ended in the window).
    pub transient_time: Option<f64>,
    /// Contacts until the sphere left for good (or the window ended).
    pub contacts: usize,
    /// The force at the largest compression of the whole impact (every contact), N.
    pub impact_force: f64,
    /// From the first touch to the end of the last contact, s (None if a contact was still
    /// going on at the end of the window).
    pub impact_time: Option<f64>,
    /// The quasi-static balance's P_max = Kδ_max^{3/2} (eq. 14 with the plate's C), N.
    pub quasi_static_force: f64,
    /// The quasi-static model's contact time: the sphere on a massless spring of compliance
    /// C with the same contact law, s.
    pub quasi_static_time: Option<f64>,
    /// Time step of both runs, s.
    pub time_step: f64,
    /// Steps of the transient run.
    pub steps: usize,
}

impl Measured {
    /// The quasi-static balance's error in the first contact's force, transient/QS - 1.
    pub fn force_error(&self) -> f64 {
        self.transient_force / self.quasi_static_force - 1.0
    }

    /// The quasi-static model's error in the first contact's duration, transient/QS - 1.
    pub fn time_error(&self) -> Option<f64> {
        Some(self.transient_time? / self.quasi_static_time? - 1.0)
    }

    /// The error in the whole impact's largest force, transient/QS - 1.
    pub fn impact_force_error(&self) -> f64 {
        self.impact_force / self.quasi_static_force - 1.0
    }

    /// The error in the whole impact's duration, transient/QS - 1.
    pub fn impact_time_error(&self) -> Option<f64> {
        Some(self.impact_time? / self.quasi_static_time? - 1.0)
    }
}

/// The quasi-static model in time: `s` against a massless spring of compliance `compliance`
/// (the plate without inertia), stepped with `dt` until the first separation.
///
/// With an elastic law the contact time converges at second order (against the energy
/// integral: 1e-6 at 2000 steps). The spring's velocity comes from the trapezoidal rule, and
/// a massless spring has no inertia to keep it consistent: the t^{3/2} onset of the Hertz
/// force leaves an alternating error of order √Δt in it, which the Flores damping term feels.
/// With Flores the contact time then converges at about first order: 3e-5 at 200 steps per
/// contact for λ ≈ 6, 1.3e-3 for λ ≈ 64 (measured against 6400 steps), far below the
/// quasi-static model's own error in the regime maps.
pub fn quasi_static_run(s: &Striker, compliance: f64, dt: f64, t_max: f64) -> Outcome {
    let mut spring = SpringMass::new(0.0, 1.0 / compliance, dt);
    simulate_with(s, Some(&mut spring), PlateFacts::default(), dt, t_max)
}

/// Measures one case of the regime map: `s` at (x, z) on `case`'s plate held by `set`, whose
/// quasi-static compliance there is `compliance` and whose quasi-static P_max is `qs_force`;
/// `facts` are the plate's ([`TransientCase::facts`]), for the stopping rule. The time step
/// is the quasi-static contact time over `steps` (and at most the Hertz time over
/// `steps`/2), so that slow contacts on soft plates cost no more steps than fast ones. The
/// transient run follows every contact until the sphere has left for good or 20
/// quasi-static contact times have passed.
#[allow(clippy::too_many_arguments)]
pub fn measure(
    case: &TransientCase,
    set: &SupportSet,
    facts: PlateFacts,
    s: &Striker,
    (x, z): (f64, f64),
    compliance: f64,
    qs_force: f64,
    steps: f64,
) -> Result<Measured, ModelError> {
    let t_h = s.hertz_time();
    // The contact and plate springs in series stretch the Hertz time by about √(1 + λ).
    let lambda = ChristoforouYigit::of(s, case.plate(), compliance).relative_stiffness;
    let t_guess = t_h * (1.0 + lambda).sqrt();
    let qs = quasi_static_run(s, compliance, t_guess / steps, 20.0 * t_guess);
    let t_qs = qs.contact_time.unwrap_or(t_guess);
    let dt = (t_qs / steps).min(2.0 * t_h / steps);
    let qs = quasi_static_run(s, compliance, dt, 20.0 * t_qs);
    let mut nm = Newmark::new(case.model(), set.supports, dt, x, z)?;
    let o = simulate_with(s, Some(&mut nm), facts, dt, 20.0 * t_qs);
    let deepest = o.history.iter().chain(&o.later_history).map(|h| h.compression).fold(0.0, f64::max);
    let impact_time = match (o.contacts.first(), o.contacts.last(), o.unfinished_contact) {
        (Some(first), Some(last), None) => Some(last.start + last.duration - first.start),
        _ => None,
    };
    Ok(Measured {
        transient_force: s.force_at_max_compression(o.compression_max_interpolated),
        transient_time: o.contacts.first().map(|c| c.duration),
        contacts: o.contacts.len() + usize::from(o.unfinished_contact.is_some()),
        impact_force: s.force_at_max_compression(deepest.max(o.compression_max_interpolated)),
        impact_time,
        quasi_static_force: qs_force,
        quasi_static_time: qs.contacts.first().map(|c| c.duration),
        time_step: dt,
        steps: o.steps_total,
    })
}
