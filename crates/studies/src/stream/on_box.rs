//! The caving stream on a tail beam: the scene's lumps striking the top plate of its box
//! ([`coupled::compliance::tail_beam`]), recorded by the jacks' forces and accelerometers on
//! the top plate, scored as on the plate ([`super::run::scored`]).
//!
//! **Model.** The box on the middle mesh of its ladder ([`IN_TIME_LEVEL`]), with the lumped
//! mass of its steel and the modes the scene's `[signals]` keeps (at most what the mesh allows,
//! [`modes_for`]), damped at the scene's ratio; the truncated modes carry their static
//! correction ([`coupled::reduced::structure`]). A lump strikes the top plate's mesh node
//! nearest its drawn point among those inside the ensemble's region (the mesh's lines are at
//! most half the scene's element apart: within half a diagonal of that inside, up to a spacing
//! where the region's edge falls between lines), as the contact patch of side t there, normal
//! to the plate.
//!
//! **Channels.** Each jack's force (its pad's springs, Σ gᵀu), then each `[signals]` sensor as an
//! accelerometer at the top plate's node nearest it, reading the acceleration along the
//! contact's push (into the box).

use super::recorder::Recorder;
use super::run::{law_shift, other_lumps, scored, windowed, Condition, Target};
use super::score::Windows;
use super::transfer::Shifted;
use super::{ConditionStream, StructureFacts};
use crate::channel::ChannelInfo;
use crate::in_time::{modes_for, IN_TIME_LEVEL};
use crate::progress::Progress;
use crate::Failure;
use coupled::compliance::tail_beam::{contact_patch, TailBeamScene};
use coupled::error::ModelError;
use coupled::identification::Striking;
use coupled::reduced::stream::span::followed_part;
use coupled::reduced::stream::{Span, StreamResponse};
use coupled::reduced::structure::{Readings, StructureModel, StructureSettings, MAX_LOAD_POINTS};
use coupled::reduced::{ChannelKind, Probes};
use identify::detector::scale_flags;
use identify::measurement::Chain;
use identify::stream::{Lump, StreamStudy};
use plate_fem::shell::ShellMass;
use scene::Scene;

/// The box's model, its load points and channels.
pub(super) struct BoxModel {
    model: StructureModel,
    /// Each load point's (x, z) on the top plate, m.
    points: Vec<(f64, f64)>,
    probes: Probes,
    chain: Option<Chain>,
    infos: Vec<ChannelInfo>,
    /// What the page states of the model.
    facts: StructureFacts,
}

impl BoxModel {
    /// The box of `tb` with the scene's steel, signals and chain, its load points the mesh's
    /// top-plate nodes inside the ensemble's `region`.
    pub fn new(scene: &Scene, tb: &TailBeamScene, region: &identify::ensemble::Region) -> Result<Self, Failure> {
        let (steel, rho) = (scene.plate.material(), scene.plate.density());
        let built = tb.beam.build(steel.youngs_modulus(), steel.poisson_ratio(), tb.element, IN_TIME_LEVEL)?;
        let [xs, _, zs] = tb.beam.lines(tb.element, IN_TIME_LEVEL)?;
        let tol = 1e-9 * tb.beam.length.max(tb.beam.width);
        let inside = |v: f64, (lo, hi): (f64, f64)| v >= lo - tol && v <= hi + tol;
        let points: Vec<(f64, f64)> = (xs.iter().filter(|&&x| inside(x, region.x)))
            .flat_map(|&x| zs.iter().filter(|&&z| inside(z, region.z)).map(move |&z| (x, z)))
            .collect();
        if points.is_empty() || points.len() > MAX_LOAD_POINTS {
            return Err(format!(
                "the ensemble's region holds {} nodes of the tail beam's top plate on its mesh; allowed [1, {MAX_LOAD_POINTS}]",
                points.len()
            )
            .into());
        }
        let spacing =
            [&xs, &zs].iter().map(|l| l.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max)).fold(0.0, f64::max);
        let loads = (points.iter())
            .map(|&(x, z)| built.structure.patch_load(built.top, &contact_patch(&tb.beam, x, z)))
            .collect::<Result<Vec<_>, _>>()?;
        let groups: Vec<_> = built.jack_groups();
        let h = tb.beam.height;
        let accelerometers = (scene.signals.sensors.iter())
            .map(|&(x, z)| {
                let (node, _) = built.structure.nearest_node([x, h, z]).ok_or("a tail beam without nodes")?;
                let mut a = vec![0.0; 6 * built.structure.nodes().len()];
                // Along the contact's push, -y into the box.
                a[6 * node + 1] = -1.0;
                Ok(a)
            })
            .collect::<Result<Vec<_>, Failure>>()?;
        let mass = ShellMass::lumped(&built.structure, rho);
        let (free, massive) = mass.free_dofs(&built.restraints);
        let reduced = scene.signals.reduced();
        let most = modes_for(free, massive);
        if reduced.modes > most {
            return Err(format!(
                "signals.modes = {} is more than the tail beam's mesh allows: at most {most} (200, half its {massive} DOFs with mass, a 2 GiB Krylov basis over its {free} free DOFs); ask for fewer",
                reduced.modes
            )
            .into());
        }
        let settings = StructureSettings {
            modes: reduced.modes,
            damping: reduced.damping(),
            steps_per_contact: reduced.steps_per_contact,
            arithmetic: reduced.arithmetic,
        };
        let fact = built.structure.factorize(&built.restraints)?;
        let readings = Readings { groups: &groups, accelerometers: &accelerometers };
        let model = StructureModel::new(&fact, &mass, &loads, readings, settings)?;
        let probes = model.probes(scene.signals.window, scene.signals.rate_hz)?;
        let chain = scene.measurement.as_ref().map(|c| Chain::new(c.clone(), scene.signals.rate_hz)).transpose()?;
        let infos = channel_infos(tb, &scene.signals.sensors, &probes.kinds());
        let f = model.frequencies_hz();
        let highest = f.last().copied().unwrap_or(0.0);
        let gain = chain.as_ref().map(|c| c.gain_above(highest));
        let facts = StructureFacts {
            unknowns: fact.unknowns(),
            modes: f.len(),
            frequencies_hz: (f.first().copied().unwrap_or(0.0), highest),
            load_points: points.len(),
            spacing,
            gain_above_highest: gain,
            resolved: chain.as_ref().zip(gain).map(|(c, g)| g <= c.spec().band_tolerance),
            truncation: None,
        };
        Ok(Self { model, points, probes, chain, infos, facts })
    }
}

impl BoxModel {
    /// The same box on its lowest half of the modes, the others joining the static correction
    /// ([`StructureModel::truncated`]): the truncation's check, without a second eigensolution.
    fn halved(&self, window: f64) -> Result<(Self, usize), Failure> {
        let n = self.facts.modes / 2;
        let model = self.model.truncated(n.max(1))?;
        let probes = model.probes(window, self.probes.spec().rate_hz)?;
        let b = Self {
            model,
            points: self.points.clone(),
            probes,
            chain: self.chain.clone(),
            infos: self.infos.clone(),
            facts: self.facts.clone(),
        };
        Ok((b, n.max(1)))
    }
}

/// The name of the truncation check's shift: the main run on `modes` modes.
pub fn truncation_shift(modes: usize) -> String {
    format!("{modes} modes (truncation)")
}

/// The channels' names: a jack at its pad's centre, an accelerometer at its sensor.
fn channel_infos(tb: &TailBeamScene, sensors: &[(f64, f64)], kinds: &[ChannelKind]) -> Vec<ChannelInfo> {
    kinds
        .iter()
        .map(|&kind| match kind {
            ChannelKind::JackForce { jack } => ChannelInfo {
                kind,
                quantity: "jack force",
                at: (tb.beam.jacks[jack].x, tb.beam.jacks[jack].z),
                sensor: None,
                unit: kind.unit(),
            },
            ChannelKind::Acceleration { sensor } => ChannelInfo {
                kind,
                quantity: "acceleration",
                at: sensors[sensor],
                sensor: Some(sensor),
                unit: kind.unit(),
            },
            _ => unreachable!("a tail beam's stream records jacks and accelerometers"),
        })
        .collect()
}

/// The box struck under one way of striking.
struct OnTheBox<'a> {
    model: &'a BoxModel,
    striking: Striking,
}

impl Recorder for OnTheBox<'_> {
    fn stream(&self, lumps: &[Lump], names: &[String], at: (f64, Option<Span>)) -> Result<StreamResponse, ModelError> {
        let b = self.model;
        let lumps = followed_part(at.1, lumps, |l| l.time, (at.0, b.probes.spec().rate_hz, b.probes.spec().samples()));
        b.model.stream(&self.striking.arrivals(lumps, names)?, &b.points, &b.probes, at)
    }

    fn slowest_decay(&self) -> f64 {
        self.model.model.slowest_decay()
    }

    fn chain(&self) -> Option<&Chain> {
        self.model.chain.as_ref()
    }

    fn channels(&self) -> Vec<ChannelKind> {
        self.model.probes.kinds()
    }

    fn model_rate_hz(&self) -> f64 {
        self.model.probes.spec().rate_hz
    }

    fn modes(&self) -> usize {
        self.model.model.frequencies_hz().len()
    }
}

/// The stream study on the scene's tail beam: the main run, its sweeps (arrival rate,
/// background, lump size, contact law) and the transfer rows, as on a plate's support set.
pub(super) fn condition(
    scene: &Scene,
    (study, ensemble): (&StreamStudy, &identify::Study),
    tb: &TailBeamScene,
    progress: &dyn Progress,
) -> Result<(ConditionStream, Shifted, StructureFacts), Failure> {
    let model = BoxModel::new(scene, tb, &ensemble.ensemble.region)?;
    let on = OnTheBox { model: &model, striking: Striking::of(scene) };
    let target = Target {
        name: "tail beam on its pins and jacks",
        index: 0,
        recorder: &on,
        infos: model.infos.clone(),
        sensors: scene.signals.sensors.len(),
        extra_runs: 1,
    };
    let truncation = std::cell::RefCell::new(None);
    let sweeps = |w: &Windows| -> Result<Vec<Condition>, Failure> {
        let mut out = other_lumps((ensemble, study), (&on, w), progress)?;
        for &law in &scene.stream_law_sweep {
            let other = OnTheBox { model: &model, striking: Striking { law, ..on.striking } };
            out.push((law_shift(law), windowed(&other, (ensemble, study, study.spec.rate_per_s), w, progress)?.1));
        }
        let (half, modes) = model.halved(scene.signals.window)?;
        let on_half = OnTheBox { model: &half, striking: on.striking };
        let rows = windowed(&on_half, (ensemble, study, study.spec.rate_per_s), w, progress)?.1;
        let score = w.score("every channel", &rows, &scale_flags(on.channels().len()))?.0;
        *truncation.borrow_mut() = Some((modes, score));
        out.push((truncation_shift(modes), rows));
        Ok(out)
    };
    let (data, shifted) = scored(scene, (study, ensemble), &target, &sweeps, progress)?;
    let facts = StructureFacts { truncation: truncation.into_inner(), ..model.facts.clone() };
    Ok((data, shifted, facts))
}
