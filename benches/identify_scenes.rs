//! Impacts per second of `impact identify` on the shipped identification scenes, as its main
//! run computes them: the first support set's reduced model (its modes, from the chain where
//! the scene says so), the named sensors and the candidate grid, every quantity the scene
//! records, the measurement chain where the scene has one, and the features of every channel;
//! one impact after another on one thread, the model built once outside the timing.
//!
//! **The floor**, measured in the same run: the same plate ringing free for as many samples
//! as the impacts' windows hold, at the same channels and model rate, with no contact, no
//! chain and no features (each mode's exact 2 x 2 map and one dot product per channel and
//! sample; `coupled::reduced::window`). Its FMA count, modes × samples × (4 + 2 × channels),
//! is printed beside it as a rate at the one-core FP64 peak measured on the machine of
//! `docs/performance.md` (48 GFLOP/s with FMA). The distance from the floor is the impacts'
//! time over the floor's: what the contacts, the chain and the features add to the
//! propagation.

mod common;

use common::best_of_five as best;
use coupled::identification::Instrument;
use coupled::reduced::ReducedModel;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use identify::Held;
use impact::scene::{Scene, SceneSource};
use std::hint::black_box;
use studies::identify::sensors::{reduced_settings, run_sensors, spec};

/// Impacts timed per scene: a fixed prefix of the ensemble (every impact is drawn from its
/// own seeded stream, so the prefix is a sample of the ensemble).
const IMPACTS: usize = 128;

/// The measured one-core FP64 peak with FMA, FLOP/s (docs/performance.md).
const PEAK_FLOPS: f64 = 48e9;

fn identify_scenes(c: &mut Criterion) {
    let mut g = c.benchmark_group("identify");
    g.sample_size(10);
    for (file, text) in impact::report::IDENTIFY_SCENES {
        let scene = Scene::parse(text, file).expect("a shipped scene is valid");
        let study = scene.ensemble.as_ref().expect("an identification scene has an ensemble");
        let set = &scene.conditions[0];
        let model = ReducedModel::new(&scene.plate, set, reduced_settings(&scene, set).unwrap()).unwrap();
        let sensors = run_sensors(&scene.signals.sensors, study, &scene.plate).0;
        let instrument = Instrument::new(&model, &scene.plate, &spec(&scene, sensors), &scene).unwrap();
        let e = &study.ensemble;
        let draws: Vec<_> = (0..IMPACTS.min(e.len())).map(|i| e.draw(i, Held::NONE).unwrap()).collect();
        let names: Vec<String> = e.families.iter().map(|f| f.name.clone()).collect();
        let run = || {
            for d in &draws {
                black_box(instrument.impact(d.clone(), &names[d.family]).unwrap());
            }
        };
        let window = scene.signals.window;
        let duration = window * draws.len() as f64;
        let free = || {
            black_box(instrument.stream(&[], &names, duration).unwrap());
        };
        let (t_impacts, t_free) = (best(&run), best(&free));
        let ringing = instrument.stream(&[], &names, duration).unwrap();
        let (channels, samples) = (ringing.signals.channels.len(), ringing.signals.channels[0].samples.len());
        let fma = model.modes().count() as f64 * samples as f64 * (4.0 + 2.0 * channels as f64);
        println!(
            "identify {file} ({}): {} impacts, {} modes, {channels} channels at {} Hz, {} samples each: {:.0} impacts/s on one core; \
             the free plate over the same {samples} samples {:.0} windows/s (the floor; its FMAs at the peak: {:.0} windows/s); \
             {:.1}x the floor",
            set.name,
            draws.len(),
            model.modes().count(),
            instrument.model_rate_hz(),
            samples / draws.len(),
            draws.len() as f64 / t_impacts,
            draws.len() as f64 / t_free,
            draws.len() as f64 * PEAK_FLOPS / (2.0 * fma),
            t_impacts / t_free,
        );
        g.throughput(Throughput::Elements(draws.len() as u64));
        g.bench_function(format!("{file}: {} impacts as identify's main run", draws.len()), |b| b.iter(run));
        g.bench_function(format!("{file}: reference, the free plate over the same samples"), |b| b.iter(free));
    }
    g.finish();
}

criterion_group!(benches, identify_scenes);
criterion_main!(benches);
