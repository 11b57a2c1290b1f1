//! Coal-gangue identification on one support set: the scene's random-impact ensemble
//! (crate `identify`) struck on the reduced-order model ([`crate::reduced`]), each impact's
//! signals reduced to features at once and only the features kept.
//!
//! Per support set the reduced model is built once; each impact is then drawn from its own
//! seeded stream, thrown with the scene's contact law, and its channels' features computed
//! in the worker that ran it. Results reach the caller's sink in impact order, one chunk at
//! a time ([`identify::ensemble::for_each_ordered`]), so a run is bit-identical on any
//! number of threads, the caller can stream rows to disk, and no more than one chunk of
//! records is ever held besides the feature columns.
//!
//! Each record also carries the impact's validity: δ_max/δ_my (eq. 51; beyond 1 the rock
//! yields, which an elastic contact law does not describe), t_c/T₁ (the rigid-target Hertz
//! time over the supported plate's fundamental period; the quasi-static criterion of
//! [`crate::validity`], here only a regime label, since the reduced model is transient) and
//! the number of contacts.

use crate::error::ModelError;
use crate::reduced::{ChannelKind, Quantity, ReducedModel, SignalSpec, Signals};
use crate::scene::Scene;
use crate::transient::{LawKind, Striker};
use analytic::{contact_stiffness, DruckerPrager, Plate};
use identify::ensemble::for_each_ordered;
use identify::measurement::{Chain, Measurand};
use identify::placement::FeatureTable;
use identify::{Draw, Extractor, Held, Study, FEATURES};
use serde::Serialize;

/// Impacts handed to the sink at a time: large enough to keep both cores busy between
/// the sink's turns, small enough that the chunk's records are a few MB.
pub const CHUNK: usize = 256;

/// One impact of the ensemble: what was drawn, what the contact did, its validity and
/// its channels' features.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ImpactRecord {
    /// The draw (SI units).
    pub draw: Draw,
    /// The lump's mass, kg (from the drawn radius and density).
    pub mass: f64,
    /// Largest contact force of the first contact, N.
    pub force_max: f64,
    /// Duration of the first contact, s (None if it had not ended within the window).
    pub contact_time: Option<f64>,
    /// Contacts within the window.
    pub contacts: usize,
    /// Largest compression over δ_my (eq. 51).
    pub compression_ratio: f64,
    /// The rigid-target Hertz time over T₁.
    pub hertz_time_ratio: f64,
    /// The [`FEATURES`] of each channel of the run, channel after channel in the order of
    /// [`ConditionRun::channels`] ([`ImpactRecord::channel_features`] splits them).
    pub features: Vec<f64>,
    /// Under a measurement chain, each channel's peak after the chain without its background
    /// (the signal of the signal-to-noise ratio); empty without one.
    pub clean_peaks: Vec<f64>,
    /// Under a measurement chain, the samples of all channels that clipped at the ADC's range.
    pub clipped: usize,
}

impl ImpactRecord {
    /// The [`FEATURES`] of each channel, one slice per channel.
    pub fn channel_features(&self) -> std::slice::ChunksExact<'_, f64> {
        self.features.chunks_exact(FEATURES.len())
    }
}

/// Counts of an ensemble's impacts beyond each validity criterion.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct EnsembleValidity {
    /// Impacts.
    pub impacts: usize,
    /// δ_max > δ_my: the rock yields.
    pub beyond_elastic: usize,
    /// t_c/T₁ below the quasi-static limit.
    pub not_quasi_static: usize,
    /// More than one contact.
    pub recontact: usize,
    /// A contact still on at the end of the window.
    pub unfinished: usize,
}

impl EnsembleValidity {
    fn add(&mut self, r: &ImpactRecord) {
        self.impacts += 1;
        self.beyond_elastic += usize::from(r.compression_ratio > 1.0);
        self.not_quasi_static += usize::from(r.hertz_time_ratio < crate::validity::QUASI_STATIC_MIN_RATIO);
        self.recontact += usize::from(r.contacts > 1);
        self.unfinished += usize::from(r.contact_time.is_none());
    }
}

/// An ensemble run on one support set: the features as columns, the paper's contact
/// quantities, and the validity counts.
#[derive(Debug, Clone)]
pub struct ConditionRun {
    /// The channels, in column order.
    pub channels: Vec<ChannelKind>,
    /// The features of every impact and channel.
    pub table: FeatureTable,
    /// The lump mass of every impact, kg.
    pub mass: Vec<f64>,
    /// P_max of every impact, N.
    pub force_max: Vec<f64>,
    /// The first contact's duration of every impact, s (0 if unfinished).
    pub contact_time: Vec<f64>,
    /// Validity counts.
    pub validity: EnsembleValidity,
    /// The supported plate's fundamental frequency, Hz.
    pub fundamental_hz: f64,
    /// Under a measurement chain, each impact's [`ImpactRecord::clean_peaks`], impact after
    /// impact (empty without one).
    pub clean_peaks: Vec<f64>,
    /// Under a measurement chain, the samples that clipped, over all impacts and channels.
    pub clipped: usize,
}

impl ConditionRun {
    /// The run's impacts `rows` (positions in this run), in that order: what a run of those
    /// impacts alone would have recorded, except the validity counts and clipped samples,
    /// which stay the whole run's.
    pub fn select(&self, rows: &[usize]) -> Self {
        let n = self.channels.len();
        let pick = |v: &[f64]| rows.iter().map(|&i| v[i]).collect();
        let clean_peaks = if self.clean_peaks.is_empty() {
            Vec::new()
        } else {
            rows.iter().flat_map(|&i| self.clean_peaks[i * n..(i + 1) * n].iter().copied()).collect()
        };
        Self {
            channels: self.channels.clone(),
            table: self.table.select(rows),
            mass: pick(&self.mass),
            force_max: pick(&self.force_max),
            contact_time: pick(&self.contact_time),
            validity: self.validity,
            fundamental_hz: self.fundamental_hz,
            clean_peaks,
            clipped: self.clipped,
        }
    }

    /// Channel `c`'s clean peaks (module docs of `identify::measurement`), one per impact;
    /// empty without a chain.
    pub fn clean_peaks(&self, c: usize) -> Vec<f64> {
        let n = self.channels.len();
        self.clean_peaks.iter().skip(c).step_by(n.max(1)).copied().collect()
    }
}

/// A reduced model with the probes and feature extractor of one signal spec, and the
/// measurement chain its features read the signals through, if any.
pub struct Instrument<'a> {
    model: &'a ReducedModel,
    probes: crate::reduced::Probes,
    extractor: Extractor,
    chain: Option<Chain>,
    noise_scale: f64,
    model_samples: usize,
    striking: Striking,
}

impl<'a> Instrument<'a> {
    /// Prepares `spec` on `model` for impacts on `plate` with the Flores restitution, the
    /// contact law, the gravity and the measurement chain of `scene` (the features then read
    /// the chain's samples: [`measurand`] says which channel it records as what).
    pub fn new(model: &'a ReducedModel, plate: &Plate, spec: &SignalSpec, scene: &Scene) -> Result<Self, ModelError> {
        let probes = model.probes(spec)?;
        let chain = match &scene.measurement {
            None => None,
            Some(c) => Some(Chain::new(c.clone(), spec.rate_hz)?),
        };
        let extractor = match &chain {
            None => Extractor::new(spec.samples(), spec.rate_hz),
            Some(c) => Extractor::new(c.samples(spec.samples()), c.spec().rate_hz),
        };
        let striking = Striking { steel: plate.material(), ..Striking::of(scene) };
        let model_samples = spec.samples();
        Ok(Self { model, probes, extractor, chain, noise_scale: 1.0, model_samples, striking })
    }

    /// Scales its chain's background by `scale` from now on (1: as the scene states it; 0:
    /// none, the ADC's quantisation alone).
    pub fn set_noise_scale(&mut self, scale: f64) {
        self.noise_scale = scale;
    }

    /// The model's samples of one window (before the chain's sampler).
    pub fn model_samples(&self) -> usize {
        self.model_samples
    }

    /// The feature extractor of its recorded window: the chain's samples where it has one,
    /// else the model's.
    pub fn extractor(&self) -> &Extractor {
        &self.extractor
    }

    /// The measurement chain, if any.
    pub fn chain(&self) -> Option<&Chain> {
        self.chain.as_ref()
    }

    /// The frequency of the highest mode the reduced model keeps, Hz.
    pub fn highest_mode_hz(&self) -> f64 {
        self.model.modes().omegas().last().copied().unwrap_or(0.0) / (2.0 * std::f64::consts::PI)
    }

    /// The modes the reduced model keeps.
    pub fn modes(&self) -> usize {
        self.model.modes().omegas().len()
    }

    /// The channels each impact records.
    pub fn channels(&self) -> Vec<ChannelKind> {
        self.probes.kinds()
    }

    /// The fundamental period T₁ of the supported plate, s.
    pub fn fundamental_period(&self) -> f64 {
        let w1 = self.model.modes().omegas().first().copied().unwrap_or(f64::INFINITY);
        2.0 * std::f64::consts::PI / w1
    }

    /// Throws the sphere of `draw` (of family `family_name`) and reduces its signals.
    pub fn impact(&self, draw: Draw, family_name: &str) -> Result<ImpactRecord, ModelError> {
        let (sphere, striker, hit) = self.simulate(&draw, family_name)?;
        let measured = self.measure(&hit.signals, draw.index, 0)?;
        let o = &hit.outcome;
        let delta_my = DruckerPrager::of(&sphere).yield_compression(sphere.radius(), striker.k);
        Ok(ImpactRecord {
            clean_peaks: measured.clean_peaks,
            clipped: measured.clipped,
            mass: sphere.mass(),
            force_max: o.force_max_interpolated.max(o.force_max),
            contact_time: o.contact_time,
            contacts: o.contacts.len() + usize::from(o.unfinished_contact.is_some()),
            compression_ratio: o.compression_max_interpolated.max(o.compression_max) / delta_my,
            hertz_time_ratio: striker.hertz_time() / self.fundamental_period(),
            features: measured.features,
            draw,
        })
    }

    /// The impact of `draw` on the reduced model: its sphere, striker and outcome with the
    /// model's signals.
    pub fn simulate(
        &self,
        draw: &Draw,
        family_name: &str,
    ) -> Result<(analytic::Sphere, Striker, crate::reduced::ReducedOutcome), ModelError> {
        let (sphere, striker) = self.striker(draw, family_name)?;
        let hit = self.model.impact(&striker, draw.x, draw.z, &self.probes)?;
        Ok((sphere, striker, hit))
    }

    /// The features of `signals` (an impact's model signals) as the instrument reads them:
    /// through its chain, if any, with the background of impact `noise_index` (one stream per
    /// impact, its channels drawn in order: the same impact has the same background on every
    /// model of the same channels), the touch `delay` model samples after the first sample
    /// (the window keeps its length: its last `delay` model samples are dropped).
    pub fn measure(&self, signals: &Signals, noise_index: usize, delay: usize) -> Result<MeasuredFeatures, ModelError> {
        let mut out = MeasuredFeatures {
            features: Vec::with_capacity(signals.channels.len() * FEATURES.len()),
            clean_peaks: Vec::new(),
            clipped: 0,
        };
        match &self.chain {
            None => {
                for c in &signals.channels {
                    self.extractor.push_features(FEATURES, &delayed(&c.samples, delay), &mut out.features);
                }
            }
            Some(chain) => {
                let mut rng = chain.stream(noise_index);
                for c in &signals.channels {
                    let m = chain
                        .measure(measurand(c.kind), &delayed(&c.samples, delay), self.noise_scale, &mut rng)
                        .ok_or_else(|| {
                        ModelError::Missing(format!("the measurement chain does not record {:?}", c.kind))
                    })?;
                    self.extractor.push_features(FEATURES, &m.samples, &mut out.features);
                    out.clean_peaks.push(m.clean_peak);
                    out.clipped += m.clipped;
                }
            }
        }
        Ok(out)
    }
}

/// `samples` with the touch `delay` samples later: as many samples, the first `delay` zero
/// (the plate at rest before the touch) and the last `delay` dropped.
fn delayed(samples: &[f64], delay: usize) -> std::borrow::Cow<'_, [f64]> {
    if delay == 0 {
        return std::borrow::Cow::Borrowed(samples);
    }
    let mut y = vec![0.0; delay.min(samples.len())];
    y.extend_from_slice(&samples[..samples.len() - y.len()]);
    std::borrow::Cow::Owned(y)
}

/// An impact's features as an instrument reads them ([`Instrument::measure`]).
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredFeatures {
    /// [`FEATURES`] of each channel, channel after channel.
    pub features: Vec<f64>,
    /// Each channel's peak before noise and ADC (empty without a chain).
    pub clean_peaks: Vec<f64>,
    /// Samples clipped by the ADCs, over every channel.
    pub clipped: usize,
}

impl Instrument<'_> {
    /// The sphere of `draw` (of family `family_name`) and its striker: the scene's law,
    /// restitution and gravity, the contact stiffness against the plate (eq. 3).
    pub fn striker(&self, draw: &Draw, family_name: &str) -> Result<(analytic::Sphere, Striker), ModelError> {
        self.striking.striker(draw, family_name)
    }

    /// The continuous model signals of a caving stream of `lumps` over `duration` seconds
    /// ([`crate::reduced::stream`]), the lumps' families named by `family_names`; `span` a
    /// segment of it run alone ([`crate::reduced::stream::span`]; None: the whole stream).
    pub fn stream(
        &self,
        lumps: &[identify::stream::Lump],
        family_names: &[String],
        (duration, span): (f64, Option<crate::reduced::stream::Span>),
    ) -> Result<crate::reduced::stream::StreamResponse, ModelError> {
        let window = (duration, self.probes.spec().rate_hz, self.probes.spec().samples());
        let lumps = crate::reduced::stream::span::followed_part(span, lumps, |l| l.time, window);
        let arrivals = self.striking.arrivals(lumps, family_names)?;
        match span {
            None => self.model.stream(&arrivals, &self.probes, duration),
            Some(span) => self.model.stream_span(&arrivals, &self.probes, duration, span),
        }
    }

    /// The slowest decay rate of the model's kept modes, 1/s.
    pub fn slowest_decay(&self) -> f64 {
        self.model.slowest_decay()
    }

    /// The model's sample rate, Hz.
    pub fn model_rate_hz(&self) -> f64 {
        self.probes.spec().rate_hz
    }
}

/// How a scene's lumps strike: the Flores restitution, the contact law, gravity, and the
/// struck steel (eq. 3's contact stiffness).
#[derive(Debug, Clone, Copy)]
pub struct Striking {
    /// Coefficient of restitution of the Flores law.
    pub restitution: f64,
    /// The contact law.
    pub law: LawKind,
    /// Gravity on the lumps, m/s².
    pub gravity: f64,
    /// The struck steel.
    pub steel: analytic::Elastic,
}

impl Striking {
    /// The scene's, against its plate's steel.
    pub fn of(scene: &Scene) -> Self {
        Self {
            restitution: scene.restitution,
            law: scene.contact_law,
            gravity: scene.gravity,
            steel: scene.plate.material(),
        }
    }

    /// The sphere of `draw` (of family `family_name`) and its striker.
    pub fn striker(&self, draw: &Draw, family_name: &str) -> Result<(analytic::Sphere, Striker), ModelError> {
        let sphere = draw.sphere(family_name)?;
        let striker = Striker {
            k: contact_stiffness(&sphere, self.steel),
            restitution: self.restitution,
            mass: sphere.mass(),
            velocity: draw.velocity,
            law: self.law.law_for(&sphere),
            gravity: self.gravity,
        };
        Ok((sphere, striker))
    }

    /// The arrivals of a stream's `lumps` (their families named by `family_names`): each at
    /// its time and drawn point, with its striker.
    pub fn arrivals(
        &self,
        lumps: &[identify::stream::Lump],
        family_names: &[String],
    ) -> Result<Vec<crate::reduced::stream::Arrival>, ModelError> {
        (lumps.iter())
            .map(|l| {
                let name = family_names.get(l.draw.family).map_or("", String::as_str);
                let (_, striker) = self.striker(&l.draw, name)?;
                Ok(crate::reduced::stream::Arrival { time: l.time, striker, x: l.draw.x, z: l.draw.z })
            })
            .collect()
    }
}

/// What the measurement chain records channel `kind` as.
pub fn measurand(kind: ChannelKind) -> Measurand {
    match kind {
        ChannelKind::Displacement { .. } => Measurand::Displacement,
        ChannelKind::Velocity { .. } => Measurand::Velocity,
        ChannelKind::Acceleration { .. } => Measurand::Acceleration,
        ChannelKind::Strain { .. } => Measurand::Strain,
        ChannelKind::SpringForce { .. } | ChannelKind::Reaction { .. } | ChannelKind::JackForce { .. } => {
            Measurand::SupportForce
        }
    }
}

/// What a chain records plate quantity `q` as.
pub fn measurand_of(q: Quantity) -> Measurand {
    match q {
        Quantity::Displacement => Measurand::Displacement,
        Quantity::Velocity => Measurand::Velocity,
        Quantity::Acceleration => Measurand::Acceleration,
        Quantity::Strain => Measurand::Strain,
    }
}

/// The plate quantity a chain's `m` measures at a sensor (None: a support's force).
pub fn quantity_of(m: Measurand) -> Option<Quantity> {
    [Quantity::Displacement, Quantity::Velocity, Quantity::Acceleration, Quantity::Strain]
        .into_iter()
        .find(|&q| measurand_of(q) == m)
}

/// Why an ensemble run stopped.
#[derive(Debug, thiserror::Error)]
pub enum RunError<E> {
    /// The model failed on an impact.
    #[error("impact {index}: {source}")]
    Model {
        /// The impact.
        index: usize,
        /// What failed.
        source: ModelError,
    },
    /// The sink refused a record.
    #[error(transparent)]
    Sink(E),
}

/// Which impacts of an ensemble a run strikes.
#[derive(Debug, Clone, Copy)]
pub enum Impacts<'a> {
    /// Every impact, in order.
    All,
    /// These impacts (indices into the ensemble, each below its length), in this order.
    Only(&'a [usize]),
}

impl Impacts<'_> {
    /// How many impacts of an ensemble of `n` the run strikes.
    pub fn len(&self, n: usize) -> usize {
        match self {
            Impacts::All => n,
            Impacts::Only(rows) => rows.len(),
        }
    }

    /// The ensemble's index of the run's `k`-th impact.
    pub fn index(&self, k: usize) -> usize {
        match self {
            Impacts::All => k,
            Impacts::Only(rows) => rows[k],
        }
    }
}

/// Runs `impacts` of the ensemble of `study` with `held` on `instrument`, handing each
/// record to `sink` in the run's order, and returns the features as columns.
pub fn run_condition<E>(
    study: &Study,
    (held, impacts): (Held, Impacts<'_>),
    instrument: &Instrument<'_>,
    mut sink: impl FnMut(&ImpactRecord) -> Result<(), E>,
) -> Result<ConditionRun, RunError<E>> {
    let e = &study.ensemble;
    let count = impacts.len(e.len());
    let channels = instrument.channels();
    let mut run = ConditionRun {
        channels: channels.clone(),
        table: FeatureTable::new(channels.len()),
        mass: Vec::with_capacity(count),
        force_max: Vec::with_capacity(count),
        contact_time: Vec::with_capacity(count),
        validity: EnsembleValidity::default(),
        fundamental_hz: 1.0 / instrument.fundamental_period(),
        clean_peaks: Vec::new(),
        clipped: 0,
    };
    for_each_ordered(
        count,
        CHUNK,
        |k| {
            let i = impacts.index(k);
            let missing = || (i, ModelError::Missing(format!("impact {i} is beyond the ensemble")));
            let draw = e.draw(i, held).ok_or_else(missing)?;
            let name = &e.families[draw.family].name;
            instrument.impact(draw, name).map_err(|source| (i, source))
        },
        |_, record| {
            let record = record.map_err(|(index, source)| RunError::Model { index, source })?;
            sink(&record).map_err(RunError::Sink)?;
            run.table.push(record.draw.class, &record.features);
            run.mass.push(record.mass);
            run.force_max.push(record.force_max);
            run.contact_time.push(record.contact_time.unwrap_or(0.0));
            run.validity.add(&record);
            run.clean_peaks.extend_from_slice(&record.clean_peaks);
            run.clipped += record.clipped;
            Ok(())
        },
    )?;
    Ok(run)
}
