//! The caving stream as `impact stream` simulates it: two acceleration sensors at 20 kHz on the
//! 80-mode plate (Con 3), the lumps of `scenes/caving-stream-detect.toml` (its ensemble, its
//! gravity) arriving at 20 a second, 10 s of stream per iteration. The reference in the same
//! run is the same plate ringing free over the same 10 s with no lumps: the arithmetic floor of
//! the propagation (modes × samples, each mode's exact 2 x 2 map and the two channels' dot
//! products), so the ratio of the two is the cost of the contacts. Before the timed runs the
//! bench prints both as real-time factors (stream seconds per second of one core).
//!
//! **The fast arithmetic** (`[signals] arithmetic = "fast"`): the same stream and free plate on
//! the model built in it, their real-time factors, and the largest difference of its signal
//! from the exact one at any sample, over the exact channel's largest value.

mod common;

use coupled::identification::Instrument;
use coupled::reduced::{Arithmetic, Channel, Quantity, ReducedModel, ReducedSettings, SignalSpec, Signals};
use criterion::{criterion_group, criterion_main, Criterion};
use identify::stream::{lumps, StreamSpec};
use impact::scene::{Scene, SceneSource};
use std::hint::black_box;

/// The detection scene at 20 kHz and 80 modes, without its measurement chain.
fn scene() -> Scene {
    let text = impact::report::STREAM_SCENES[0].1;
    let text = text[..text.find("[measurement]").expect("the scene has a chain")].to_string()
        + &text[text.find("[stream]").expect("the scene has a stream")..];
    let text = text.replace("rate_hz = 40000.0", "rate_hz = 20000.0").replace("modes = 160", "modes = 80");
    let text = text.replace("noise_sweep = [0.0, 10.0, 100.0]", "");
    Scene::parse(&text, "bench").expect("the bench's scene is valid")
}

fn stream(c: &mut Criterion) {
    let scene = scene();
    let set = &scene.conditions[2];
    let model = ReducedModel::new(&scene.plate, set, scene.signals.reduced()).unwrap();
    let spec = SignalSpec {
        quantities: vec![Quantity::Acceleration],
        corners: false,
        ..SignalSpec {
            window: scene.signals.window,
            rate_hz: scene.signals.rate_hz,
            ..SignalSpec::new(scene.signals.sensors.clone())
        }
    };
    let instrument = Instrument::new(&model, &scene.plate, &spec, &scene).unwrap();
    let ensemble = &scene.ensemble.as_ref().unwrap().ensemble;
    let names: Vec<String> = ensemble.families.iter().map(|f| f.name.clone()).collect();
    let duration = 10.0;
    let s = StreamSpec { rate_per_s: 20.0, duration, ..scene.stream.as_ref().unwrap().spec };
    let drawn = lumps(ensemble, &s).unwrap();
    let best = common::best_of_five;
    let with = best(&|| {
        black_box(instrument.stream(&drawn, &names, (duration, None)).unwrap());
    });
    let run = instrument.stream(&drawn, &names, (duration, None)).unwrap();
    let free = best(&|| {
        black_box(instrument.stream(&[], &names, (duration, None)).unwrap());
    });
    println!(
        "stream: {} lumps in {duration} s, {} contact steps ({:.0} a lump), {:.0}x real time; free plate {:.0}x real time (the floor); contacts cost {:.2}x the floor",
        drawn.len(),
        run.steps,
        run.steps as f64 / drawn.len() as f64,
        duration / with,
        duration / free,
        with / free
    );
    let fast_model = ReducedModel::new(
        &scene.plate,
        set,
        ReducedSettings { arithmetic: Arithmetic::Fast, ..scene.signals.reduced() },
    )
    .unwrap();
    let fast = Instrument::new(&fast_model, &scene.plate, &spec, &scene).unwrap();
    let fast_with = best(&|| {
        black_box(fast.stream(&drawn, &names, (duration, None)).unwrap());
    });
    let fast_free = best(&|| {
        black_box(fast.stream(&[], &names, (duration, None)).unwrap());
    });
    let fast_run = fast.stream(&drawn, &names, (duration, None)).unwrap();
    let largest = largest_difference(&run.signals, &fast_run.signals);
    println!(
        "stream, fast arithmetic: {:.0}x real time ({:.2}x the exact stream); free plate {:.0}x real time ({:.2}x the exact); \
         largest difference from the exact signal {largest:.2e} of the channel's largest value",
        duration / fast_with,
        with / fast_with,
        duration / fast_free,
        free / fast_free,
    );
    let mut g = c.benchmark_group("stream");
    g.sample_size(10);
    g.bench_function("10 s at 20 lumps/s, 2 sensors, 20 kHz, 80 modes", |b| {
        b.iter(|| black_box(instrument.stream(&drawn, &names, (duration, None)).unwrap()))
    });
    g.bench_function("reference: the free plate over 10 s", |b| {
        b.iter(|| black_box(instrument.stream(&[], &names, (duration, None)).unwrap()))
    });
    g.bench_function("10 s at 20 lumps/s, 2 sensors, 20 kHz, 80 modes, fast arithmetic", |b| {
        b.iter(|| black_box(fast.stream(&drawn, &names, (duration, None)).unwrap()))
    });
    g.finish();
}

/// The largest |fast - exact| of any sample over its exact channel's largest value.
fn largest_difference(exact: &Signals, fast: &Signals) -> f64 {
    let channel = |(e, f): (&Channel, &Channel)| {
        let top = e.samples.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        e.samples.iter().zip(&f.samples).fold(0.0f64, |m, (a, b)| m.max((a - b).abs())) / top
    };
    exact.channels.iter().zip(&fast.channels).map(channel).fold(0.0f64, f64::max)
}

criterion_group!(benches, stream);
criterion_main!(benches);
