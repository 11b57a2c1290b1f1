//! A caving stream on the reduced plate: many lumps striking one plate, one after another and
//! at times together, recorded as one continuous signal.
//!
//! **Superposition.** The plate is linear, so its modal state (qᵢ, q̇ᵢ) carries every earlier
//! lump's response: between contacts each mode is propagated exactly
//! ([`super::signals::free_map`]), and a lump that arrives finds the plate moving. Where no
//! lump is followed the samples come straight from each block's start state through the
//! channels' own maps over a block (`window::output`; in the fast arithmetic, every
//! sample's state propagated and summed in f32, [`super::window`]). It touches at its arrival, the sphere at the plate's
//! deflection there (δ = 0, with δ = u - w(p) as in one impact), and from then on it is
//! stepped as [`super::ReducedModel::impact`] steps one impact: Newmark's rule on every mode
//! while a force acts, the exact map over a step that starts free, the contact law solved at
//! each step's end, the truncated modes as the static correction C_res(p)P.
//!
//! **Simultaneous contacts.** While K lumps are in contact the step-end forces are coupled:
//! lump j's compression is δⱼ = d₀ⱼ - Σₖ Gⱼₖ Pₖ - Δt²Pⱼ/(4mⱼ), with the modes' step
//! flexibility Gⱼₖ = Σᵢ hᵢφᵢ(pⱼ)φᵢ(pₖ) (hᵢ = 1/(ωᵢ² + 4ζᵢωᵢ/Δt + 4/Δt²), Newmark's step-end
//! deflection per unit force) plus C_res(pⱼ) on the diagonal. Each law's force is monotone in
//! its own δ and G is positive semi-definite, so the joint solve by nonlinear Gauss-Seidel
//! (each lump's scalar law solve, [`crate::transient::contact_force_after`], with the others'
//! forces held) converges (Ortega & Rheinboldt 1970, §13.4, for monotone systems with a
//! diagonally positive symmetric coupling); with one lump it is the single impact's solve.
//! The cross term of the static correction, N(pⱼ)ᵀRN(pₖ), is left out: R is kept only in
//! element blocks. Since R is positive semi-definite it is at most √(C_res(pⱼ)C_res(pₖ))
//! (Cauchy-Schwarz), and the stream reports that bound against the static compliance.
//!
//! **A lump leaves** when it makes no further contact within one impact's window after its
//! touch while the plate vibrates freely: no force, and the sphere's free flight
//! u + u̇τ + gτ²/2 over the rest of the window, less the permanent set δ_p at which its law's
//! contact opens, stays below -Σᵢ|φᵢ(p)|Aᵢ, under which no later
//! free deflection at p reaches ([`super::target`]; lumps in contact elsewhere can push the
//! plate further, so this is a proof only for the free plate); or, out of contact, at the
//! window's end, where one impact stops following it too (a lump still in contact there is
//! followed on, for four windows at most). A lump under gravity that would come back after its window
//! is not followed back, as in one impact; nor is a departed sphere checked against the
//! plate's motion from later lumps: it has fallen away.
//!
//! **Time grid.** Arrivals are placed on the model's sample grid (rounded to the nearest
//! sample, within T_s/2), so that every contact starts, as one impact's does, at a sample;
//! the contact step is T_s/m with m from the stiffest lump in contact
//! ([`super::ReducedModel::impact_with`]'s rule).
//!
//! **Segments.** A stream may be run in parts, each from rest after a warm-up in which the
//! damped modes forget the past it leaves out ([`span`]); [`ReducedModel::stream_span`] runs
//! one, so that the parts of a long stream are computed apart and put together.

mod envelope;
mod free;
pub mod span;
mod step;

use super::impact::{at_point, channel_row};
use super::signals::{dot, FreeMaps, Probes, Signals};
use super::target::ChannelRow;
use super::window::OutputMaps;
use super::{Arithmetic, Correction, ModalDamping, ReducedModel};
use crate::error::ModelError;
use crate::transient::Striker;
use analytic::params::{check, Range};
use envelope::{half_periods, reach, HalfPeriod};
use serde::Serialize;
pub use span::{Cut, Span};
use std::collections::HashMap;
use step::{flexibility, step, step_maps, Scratch, StepMaps};

/// A lump of the stream: its sphere and law, its arrival and where it strikes.
#[derive(Debug, Clone)]
pub struct Arrival {
    /// Its first touch, s from the stream's start.
    pub time: f64,
    /// The sphere, its law and speed.
    pub striker: Striker,
    /// The struck point (x, z), m.
    pub x: f64,
    /// See `x`.
    pub z: f64,
}

/// What happened to one lump.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LumpResponse {
    /// The sample of its first touch (its arrival on the sample grid).
    pub sample: usize,
    /// Contacts it made.
    pub contacts: usize,
    /// Duration of its first contact, s, to the contact step.
    pub contact_time: f64,
    /// Largest contact force, N.
    pub force_max: f64,
    /// Largest compression, m.
    pub compression_max: f64,
    /// Whether another lump was in contact in one of its contact steps.
    pub overlapped: bool,
}

/// The stream's continuous signals and what each lump did.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StreamResponse {
    /// The channels of the probes, every sample of the stream (of a span: from its start to
    /// its last recorded sample).
    pub signals: Signals,
    /// One per lump that touched before the stream's last sample (of a span: within it), in
    /// arrival order.
    pub lumps: Vec<LumpResponse>,
    /// Contact steps taken (at the contact step, between the samples; of a span: within the
    /// samples it records).
    pub steps: usize,
    /// Contact steps taken with two or more lumps in contact.
    pub joint_steps: usize,
    /// Joint steps whose Gauss-Seidel solve had not converged to 1e-12 in its iterations.
    pub unconverged_steps: usize,
    /// Lumps let go while still in contact, after four windows resting on the plate.
    pub released_in_contact: usize,
    /// The left-out cross static correction's bound √(C_res(pⱼ)C_res(pₖ)) over the smaller
    /// static compliance of the two points, largest over the pairs in contact together (0
    /// when none were).
    pub cross_residual_bound: f64,
}

/// Windows a lump still in contact is followed for at most.
const HELD_WINDOWS: usize = 4;

/// Most Gauss-Seidel sweeps of a joint solve.
const SWEEPS: usize = 200;

/// A lump while it is followed.
struct Active {
    index: usize,
    striker: Striker,
    phi: Vec<f64>,
    c_res: f64,
    static_compliance: f64,
    /// Its direct term Dⱼ in every channel.
    d: Vec<f64>,
    every: usize,
    /// Sphere displacement toward the plate (from the stream's datum), velocity, acceleration.
    u: f64,
    v: f64,
    a: f64,
    dmax: f64,
    approach: f64,
    force: f64,
    /// (δ, δ̇) at the last step end.
    last: (f64, f64),
    /// The static correction's trapezoidal velocity at the last step end.
    res_v: f64,
    /// The model's number for the struck point.
    point: usize,
    /// The other lumps' part of the static correction at its point at the last step end,
    /// Σₖ≠ⱼ N(pⱼ)ᵀRN(pₖ)Pₖ (zero where the model leaves the cross terms out).
    w_cross: f64,
    touched: usize,
    steps: usize,
    /// Time since the touch, s.
    time: f64,
    /// When the first contact opened (the start of its first step with a force), s.
    opened: Option<f64>,
    response: LumpResponse,
}

/// What a stream needs of the struck structure: its modes, and each struck point's view of
/// them. The plate ([`ReducedModel`]) and a shell structure
/// ([`super::structure::StructureModel`]) are struck through it alike.
pub(crate) trait Struck {
    /// ωᵢ of the kept modes, rad/s.
    fn omega(&self) -> &[f64];
    /// Their damping.
    fn damping(&self) -> ModalDamping;
    /// The contact step is at most the rigid-target Hertz time over this.
    fn steps_per_contact(&self) -> f64;
    /// The instruction set of the passes over the modes, and how the free samples are summed
    /// into the channels.
    fn passes(&self) -> (pulp::Arch, Arithmetic);
    /// A lump striking at (x, z): φᵢ(p), C_res(p) and each channel's direct term Dⱼ.
    fn struck_at(&self, x: f64, z: f64, probes: &Probes) -> Result<StruckAt, ModelError>;
    /// The cross static correction N(p)ᵀRN(q) of two struck points, each given by its
    /// [`StruckAt::point`] and φᵢ, where the model holds it (None: left out, and bounded in
    /// the response).
    fn cross_residual(&self, p: (usize, &[f64]), q: (usize, &[f64])) -> Option<f64> {
        let _ = (p, q);
        None
    }
}

/// A struck point as a lump of the stream sees the modes.
pub(crate) struct StruckAt {
    /// φᵢ(p).
    pub phi: Vec<f64>,
    /// The truncated modes' static correction C_res(p), m/N.
    pub c_res: f64,
    /// Each channel's direct term Dⱼ (its response per unit contact force at p).
    pub d: Vec<f64>,
    /// The model's own number for the point (its cross static correction's key).
    pub point: usize,
}

impl Struck for ReducedModel {
    fn omega(&self) -> &[f64] {
        &self.omega
    }

    fn damping(&self) -> ModalDamping {
        self.settings.damping()
    }

    fn steps_per_contact(&self) -> f64 {
        self.settings.steps_per_contact
    }

    fn passes(&self) -> (pulp::Arch, Arithmetic) {
        (self.simd, self.settings.arithmetic)
    }

    fn struck_at(&self, x: f64, z: f64, probes: &Probes) -> Result<StruckAt, ModelError> {
        let pt = self.point(x, z)?;
        let zeta = self.settings.damping();
        let field_at_p: Vec<f64> = probes.fields.iter().map(|f| at_point(&pt, f)).collect();
        let d =
            probes.rows.iter().map(|r| channel_row(r, &pt, &field_at_p, None, (pt.c_res, zeta), &pt.phi).d).collect();
        Ok(StruckAt { c_res: pt.c_res, phi: pt.phi, d, point: 0 })
    }
}

impl ReducedModel {
    /// The continuous signals of `probes` over `duration` seconds of the stream `arrivals`
    /// (in order of time; see the module). The probes' window is the longest a lump is
    /// followed after its touch.
    pub fn stream(&self, arrivals: &[Arrival], probes: &Probes, duration: f64) -> Result<StreamResponse, ModelError> {
        self.streams()?;
        stream(self, arrivals, probes, duration, None)
    }

    /// The slowest decay rate of its kept modes, minᵢ ζᵢωᵢ, 1/s: what a stream's segments
    /// warm up by ([`span::warm_up_s`]).
    pub fn slowest_decay(&self) -> f64 {
        span::slowest_decay(&self.omega, self.settings.damping())
    }

    /// Whether the model can carry a stream: its truncated modes as the static correction.
    fn streams(&self) -> Result<(), ModelError> {
        if self.settings.correction != Correction::Static {
            return Err(ModelError::Missing(
                "a stream carries the truncated modes as the static correction; set correction = \"static\"".into(),
            ));
        }
        Ok(())
    }

    /// The part `span` of [`Self::stream`], run alone from rest at its start (module
    /// [`span`]): its signals from the span's start, its lumps those arriving within it.
    pub fn stream_span(
        &self,
        arrivals: &[Arrival],
        probes: &Probes,
        duration: f64,
        span: Span,
    ) -> Result<StreamResponse, ModelError> {
        self.streams()?;
        stream(self, arrivals, probes, duration, Some(span))
    }
}

/// The stream `arrivals` on `model`, recorded by `probes` over `duration` seconds, run over
/// `span` (the whole stream: [`Span::whole`]): its signals from the span's start to its
/// end (warm-up and segment), its lumps those arriving in [`Span::from`, `Span::to`), each
/// with the stream's sample of its touch.
pub(crate) fn stream(
    model: &dyn Struck,
    arrivals: &[Arrival],
    probes: &Probes,
    duration: f64,
    span: Option<Span>,
) -> Result<StreamResponse, ModelError> {
    check("duration", duration, Range::open(0.0, f64::INFINITY), "s")?;
    for (i, a) in arrivals.iter().enumerate() {
        let earlier = if i == 0 { 0.0 } else { arrivals[i - 1].time };
        check(&format!("arrival {i}'s time"), a.time, Range::closed(earlier, f64::INFINITY), "s")?;
        // The flight bounds (`Active::highest`) hold for a body force toward the plate.
        check(&format!("arrival {i}'s gravity"), a.striker.gravity, Range::closed(0.0, f64::INFINITY), "m/s²")?;
    }
    let rate = probes.spec.rate_hz;
    let total = span::stream_samples(duration, rate);
    let span = span.unwrap_or(Span::whole(total));
    if !(span.start <= span.from && span.from < span.to && span.to <= total) {
        return Err(ModelError::Missing(format!(
            "the span {span:?} does not lie in the stream's {total} samples with its warm-up before it"
        )));
    }
    let len = span.end(total, probes.spec.samples()) - span.start;
    let first = arrivals.partition_point(|a| !span.admits(a.time, rate));
    let mut run = Run::new(model, probes, len);
    let mut next = first;
    let mut k = 0;
    while k + 1 < len {
        while next < arrivals.len() && sample_of(arrivals[next].time, rate) - span.start <= k {
            run.admit(next, &arrivals[next], k)?;
            next += 1;
        }
        if run.active.is_empty() {
            let target = arrivals.get(next).map_or(len - 1, |a| (sample_of(a.time, rate) - span.start).min(len - 1));
            run.free(target - k);
            k = target;
        } else {
            run.counting = (span.from - span.start..span.to - span.start).contains(&k);
            run.contact_interval();
            k += 1;
            run.retire(k);
        }
    }
    Ok(run.finish().within(span))
}

/// The sample an arrival at `time` falls on.
fn sample_of(time: f64, rate: f64) -> usize {
    (time * rate).round().max(0.0) as usize
}

/// The stream under way.
struct Run<'a> {
    model: &'a dyn Struck,
    probes: &'a Probes,
    rows: Vec<ChannelRow>,
    /// The channels' own maps over a block, for the free stretches.
    output: OutputMaps,
    q: Vec<f64>,
    v: Vec<f64>,
    out: Vec<Vec<f64>>,
    active: Vec<Active>,
    done: Vec<(usize, LumpResponse)>,
    maps: HashMap<usize, StepMaps>,
    /// The exact map over one sample interval.
    sample_map: FreeMaps,
    half_period: HalfPeriod,
    window_samples: usize,
    steps: usize,
    joint_steps: usize,
    unconverged_steps: usize,
    released_in_contact: usize,
    cross_residual_bound: f64,
    /// Whether the current sample interval is one the run's counts take in (its span's own).
    counting: bool,
    scratch: Scratch,
}

impl<'a> Run<'a> {
    fn new(model: &'a dyn Struck, probes: &'a Probes, total: usize) -> Self {
        let n = model.omega().len();
        let rows =
            probes.rows.iter().map(|r| ChannelRow { a: nonzero(&r.a), b: nonzero(&r.b), d: 0.0 }).collect::<Vec<_>>();
        let mut out: Vec<Vec<f64>> = rows.iter().map(|_| Vec::with_capacity(total)).collect();
        for o in &mut out {
            o.push(0.0);
        }
        let output = OutputMaps::new(model.passes().1, probes.block_maps.modes(), &rows);
        Self {
            model,
            probes,
            rows,
            output,
            q: vec![0.0; n],
            v: vec![0.0; n],
            out,
            active: Vec::new(),
            done: Vec::new(),
            maps: HashMap::new(),
            sample_map: probes.step_map(1),
            half_period: half_periods(model.omega(), model.damping(), probes.spec.interval()),
            window_samples: probes.spec.samples(),
            steps: 0,
            joint_steps: 0,
            unconverged_steps: 0,
            released_in_contact: 0,
            cross_residual_bound: 0.0,
            counting: true,
            scratch: Scratch::default(),
        }
    }

    /// Lump `index` touches at sample `k`: the sphere at the plate's deflection there.
    fn admit(&mut self, index: usize, a: &Arrival, k: usize) -> Result<(), ModelError> {
        let m = self.model;
        let StruckAt { phi, c_res, d, point } = m.struck_at(a.x, a.z, self.probes)?;
        let ts = self.probes.spec.interval();
        let every = (ts / (a.striker.hertz_time() / m.steps_per_contact())).ceil().max(1.0) as usize;
        let static_compliance = super::modal_compliance(&phi, m.omega()) + c_res;
        // The other lumps' static correction at the point, where the model carries it.
        let w_cross: f64 = (self.active.iter())
            .filter(|l| l.force != 0.0)
            .filter_map(|l| m.cross_residual((point, &phi), (l.point, &l.phi)).map(|r| r * l.force))
            .sum();
        let (w, wv) = (dot(&phi, &self.q) + w_cross, dot(&phi, &self.v));
        self.active.push(Active {
            index,
            striker: a.striker,
            c_res,
            static_compliance,
            phi,
            d,
            every,
            u: w,
            v: a.striker.velocity,
            a: a.striker.gravity,
            dmax: 0.0,
            approach: a.striker.velocity,
            force: 0.0,
            last: (0.0, a.striker.velocity - wv),
            res_v: 0.0,
            point,
            w_cross,
            touched: k,
            steps: 0,
            time: 0.0,
            opened: None,
            response: LumpResponse {
                sample: k,
                contacts: 0,
                contact_time: 0.0,
                force_max: 0.0,
                compression_max: 0.0,
                overlapped: false,
            },
        });
        Ok(())
    }

    /// One sample interval of contact steps, and the sample at its end; where no lump can
    /// touch within it, the interval in one exact step.
    fn contact_interval(&mut self) {
        if self.active.iter().all(|l| l.force == 0.0) {
            let n = self.q.len();
            let w = &mut self.scratch;
            w.qh.resize(n, 0.0);
            w.vh.resize(n, 0.0);
            self.sample_map.apply(&self.q, &self.v, &mut w.qh, &mut w.vh);
            if self.clear_interval() {
                return self.free_interval();
            }
        }
        let every = self.active.iter().map(|a| a.every).max().unwrap_or(1);
        let (model, probes) = (self.model, self.probes);
        let maps = self.maps.entry(every).or_insert_with(|| step_maps(model, probes, every));
        let mut g = flexibility(&self.active, &maps.h);
        let cross = cross_terms(model, &self.active);
        if let Some(c) = &cross {
            g.iter_mut().zip(c).for_each(|(g, c)| *g += c);
        }
        self.steps += usize::from(self.counting) * every;
        for _ in 0..every {
            let converged =
                step(&mut self.active, (&mut self.q, &mut self.v), maps, (&g, cross.as_deref()), &mut self.scratch);
            self.unconverged_steps += usize::from(self.counting && !converged);
            let in_contact: Vec<usize> = (0..self.active.len()).filter(|&j| self.active[j].force > 0.0).collect();
            if in_contact.len() > 1 {
                self.joint_steps += usize::from(self.counting);
                for (x, &j) in in_contact.iter().enumerate() {
                    self.active[j].response.overlapped = true;
                    // Where the model carries the cross terms nothing is left out.
                    for &k in in_contact[x + 1..].iter().filter(|_| cross.is_none()) {
                        let (a, b) = (&self.active[j], &self.active[k]);
                        let bound = (a.c_res * b.c_res).sqrt() / a.static_compliance.min(b.static_compliance);
                        self.cross_residual_bound = self.cross_residual_bound.max(bound);
                    }
                }
            }
        }
        for (c, (row, o)) in self.rows.iter().zip(self.out.iter_mut()).enumerate() {
            let a = row.a.as_ref().map_or(0.0, |a| dot(a, &self.q));
            let b = row.b.as_ref().map_or(0.0, |b| dot(b, &self.v));
            let direct: f64 = self.active.iter().map(|l| l.d[c] * l.force).sum();
            o.push(a + b + direct);
        }
    }

    /// Lets go of every lump that has left for good at sample `k`, or whose window has ended.
    fn retire(&mut self, k: usize) {
        let ts = self.probes.spec.interval();
        let mut kept = Vec::with_capacity(self.active.len());
        for l in std::mem::take(&mut self.active) {
            let rest = self.window_samples.saturating_sub(k - l.touched) as f64 * ts;
            // The reach is never negative, so a sphere that can come down to the plate's rest
            // position has not left, whatever the plate does: the reach is summed only where
            // it decides.
            let left = l.force == 0.0 && l.steps > 0 && {
                let clearance = l.highest(rest) - l.opens_at();
                clearance < 0.0 && clearance + reach(&l.phi, &self.q, &self.v, self.model.omega()) < 0.0
            };
            // At its window's end a lump is let go once it is out of contact (dropping a force
            // would jolt the plate), and in contact only after [`HELD_WINDOWS`] windows: a lump
            // resting on the plate, which in a mine slides off.
            let followed = k - l.touched;
            let held = followed >= HELD_WINDOWS * self.window_samples;
            if held && l.force > 0.0 {
                self.released_in_contact += usize::from(self.counting);
            }
            if left || (followed >= self.window_samples && l.force == 0.0) || held {
                self.done.push(l.response_of());
            } else {
                kept.push(l);
            }
        }
        self.active = kept;
    }

    /// The signals and every lump's response, in arrival order.
    fn finish(mut self) -> StreamResponse {
        for l in std::mem::take(&mut self.active) {
            self.done.push(l.response_of());
        }
        self.done.sort_by_key(|r| r.0);
        let lumps = self.done.into_iter().map(|(_, r)| r).collect();
        let kinds = self.probes.kinds();
        let channels =
            kinds.into_iter().zip(self.out).map(|(kind, samples)| super::Channel { kind, samples }).collect();
        StreamResponse {
            signals: Signals { rate_hz: self.probes.spec.rate_hz, channels },
            lumps,
            steps: self.steps,
            joint_steps: self.joint_steps,
            unconverged_steps: self.unconverged_steps,
            released_in_contact: self.released_in_contact,
            cross_residual_bound: self.cross_residual_bound,
        }
    }
}

impl Active {
    fn response_of(self) -> (usize, LumpResponse) {
        (self.index, self.response)
    }
}

/// The cross static corrections of the lumps followed, row-major with a zero diagonal, where
/// the model carries them (None where it leaves them out, or with fewer than two lumps).
fn cross_terms(model: &dyn Struck, active: &[Active]) -> Option<Vec<f64>> {
    let k = active.len();
    if k < 2 {
        return None;
    }
    let mut c = vec![0.0; k * k];
    for j in 0..k {
        for l in j + 1..k {
            let r = model.cross_residual((active[j].point, &active[j].phi), (active[l].point, &active[l].phi))?;
            c[j * k + l] = r;
            c[l * k + j] = r;
        }
    }
    Some(c)
}

/// A row with its zero entries all zero: None.
fn nonzero(x: &[f64]) -> Option<Vec<f64>> {
    x.iter().any(|&x| x != 0.0).then(|| x.to_vec())
}
