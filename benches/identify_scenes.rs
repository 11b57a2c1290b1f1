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
//!
//! **The fast arithmetic** (`[signals] arithmetic = "fast"`, the channels' sums in f32 with
//! fused multiply-adds): the same impacts on the same model built in it, their rate against
//! the exact run's, and what it changed: every feature's largest difference from the exact
//! run over the impacts, relative to that feature's spread (its standard deviation over them),
//! and the largest change of a feature's AUC between the families over the same impacts.

mod common;

use common::best_of_five as best;
use coupled::identification::Instrument;
use coupled::reduced::{Arithmetic, ReducedModel, ReducedSettings};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use identify::features::FEATURES;
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
            black_box(instrument.stream(&[], &names, (duration, None)).unwrap());
        };
        let (t_impacts, t_free) = (best(&run), best(&free));
        let ringing = instrument.stream(&[], &names, (duration, None)).unwrap();
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
        let fast_model = ReducedModel::new(
            &scene.plate,
            set,
            ReducedSettings { arithmetic: Arithmetic::Fast, ..reduced_settings(&scene, set).unwrap() },
        )
        .unwrap();
        let fast_instrument = Instrument::new(
            &fast_model,
            &scene.plate,
            &spec(&scene, run_sensors(&scene.signals.sensors, study, &scene.plate).0),
            &scene,
        )
        .unwrap();
        let run_fast = || {
            for d in &draws {
                black_box(fast_instrument.impact(d.clone(), &names[d.family]).unwrap());
            }
        };
        let t_fast = best(&run_fast);
        let label = format!("{file} ({})", set.name);
        print_fast(&label, (&instrument, &fast_instrument), (&draws, &names), (t_impacts, t_free, t_fast));
        g.throughput(Throughput::Elements(draws.len() as u64));
        g.bench_function(format!("{file}: {} impacts as identify's main run", draws.len()), |b| b.iter(run));
        g.bench_function(format!("{file}: reference, the free plate over the same samples"), |b| b.iter(free));
        g.bench_function(format!("{file}: {} impacts in the fast arithmetic", draws.len()), |b| b.iter(run_fast));
    }
    g.finish();
}

/// Prints the fast arithmetic's rate against the exact run's and the floor's (`times`: the
/// exact impacts, the free plate, the fast impacts) and what it changed over the `draws`.
fn print_fast(
    label: &str,
    (exact, fast): (&Instrument, &Instrument),
    (draws, names): (&[identify::Draw], &[String]),
    (t_impacts, t_free, t_fast): (f64, f64, f64),
) {
    let features = |i: &Instrument| -> Vec<Vec<f64>> {
        draws.iter().map(|d| i.impact(d.clone(), &names[d.family]).unwrap().features).collect()
    };
    let (per, auc) =
        differences(&features(exact), &features(fast), &draws.iter().map(|d| d.family).collect::<Vec<_>>());
    let per: Vec<String> = FEATURES
        .iter()
        .zip(&per)
        .map(|(f, (d, jumped))| format!("{} {d:.1e} ({:.2} % jumped)", f.key(), 100.0 * jumped))
        .collect();
    println!(
        "identify {label}, fast arithmetic: {:.0} impacts/s, {:.2}x the exact run; {:.1}x the floor; \
         largest difference over each feature's spread over the impacts: {}; largest AUC change {auc:.2e}",
        draws.len() as f64 / t_fast,
        t_impacts / t_fast,
        t_fast / t_free,
        per.join(", "),
    );
}

/// A value moved by more than this share of its column's spread is counted as having jumped
/// (a threshold crossing a sample earlier, the dominant frequency another peak's bin), not as
/// rounded.
const JUMP: f64 = 1e-3;

/// What the fast arithmetic changed over the impacts' feature rows (channel after channel,
/// [`FEATURES`] in order within each), per feature: the largest |fast - exact| relative to its
/// column's standard deviation over the impacts (columns without spread left out), and the
/// share of its values that jumped ([`JUMP`]); and over every column the largest
/// |AUC(fast) - AUC(exact)| between family 0 and the rest.
fn differences(exact: &[Vec<f64>], fast: &[Vec<f64>], family: &[usize]) -> (Vec<(f64, f64)>, f64) {
    let columns = exact.first().map_or(0, Vec::len);
    let mut per = vec![(0.0f64, 0usize, 0usize); FEATURES.len()];
    let mut auc = 0.0f64;
    for j in 0..columns {
        let e: Vec<f64> = exact.iter().map(|r| r[j]).collect();
        let f: Vec<f64> = fast.iter().map(|r| r[j]).collect();
        let mean = e.iter().sum::<f64>() / e.len() as f64;
        let sd = (e.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / e.len() as f64).sqrt();
        if sd > 0.0 && sd.is_finite() {
            let p = &mut per[j % FEATURES.len()];
            for (a, b) in e.iter().zip(&f) {
                let d = (a - b).abs() / sd;
                p.0 = p.0.max(d);
                p.1 += usize::from(d > JUMP);
                p.2 += 1;
            }
        }
        let split = |x: &[f64]| -> (Vec<f64>, Vec<f64>) {
            let first = x.iter().zip(family).filter(|(_, &k)| k == 0).map(|(v, _)| *v).collect();
            let rest = x.iter().zip(family).filter(|(_, &k)| k != 0).map(|(v, _)| *v).collect();
            (first, rest)
        };
        let ((ec, eg), (fc, fg)) = (split(&e), split(&f));
        if !ec.is_empty() && !eg.is_empty() {
            auc = auc.max((identify::roc::auc(&ec, &eg) - identify::roc::auc(&fc, &fg)).abs());
        }
    }
    (per.iter().map(|&(d, n, of)| (d, n as f64 / of.max(1) as f64)).collect(), auc)
}

criterion_group!(benches, identify_scenes);
criterion_main!(benches);
