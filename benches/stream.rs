//! The caving stream as `impact stream` simulates it: two acceleration sensors at 20 kHz on the
//! 80-mode plate (Con 3), the lumps of `scenes/caving-stream-detect.toml` (its ensemble, its
//! gravity) arriving at 20 a second, 10 s of stream per iteration. The reference in the same
//! run is the same plate ringing free over the same 10 s with no lumps: the floor of the
//! sampling (modes × channels × samples: each channel's own maps over a block of samples times
//! the block's start state, two products and two sums a term), so the ratio of the two is the
//! cost of the contacts. Before the timed runs the
//! bench prints both as real-time factors (stream seconds per second of one core).
//!
//! **The fast arithmetic** (`[signals] arithmetic = "fast"`): the same stream and free plate on
//! the model built in it, their real-time factors, and the largest difference of its signal
//! from the exact one at any sample, over the exact channel's largest value.
//!
//! **Segments** (`[stream] segment_s`): a 60 s stream of the same lumps in one piece on one
//! core, against the same stream cut into 15 s segments (warm-up by the plate's slowest decay
//! to ε = 1e-9), the segments run in parallel on every core: the wall-clock real-time factors
//! of both, the samples the warm-ups add, and the largest difference of the cut stream's
//! signal from the one piece's over the channel's largest value.

mod common;

use coupled::identification::Instrument;
use coupled::reduced::stream::span::{stream_samples, warm_up_s};
use coupled::reduced::stream::Cut;
use coupled::reduced::{Arithmetic, Channel, Quantity, ReducedModel, ReducedSettings, SignalSpec, Signals};
use criterion::{criterion_group, criterion_main, Criterion};
use identify::stream::{lumps, StreamSpec};
use impact::scene::{Scene, SceneSource};
use rayon::prelude::*;
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
    segmented(&instrument, &model, &scene, &names);
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

/// The 60 s stream in one piece against its 15 s segments run in parallel (module docs).
fn segmented(instrument: &Instrument<'_>, model: &ReducedModel, scene: &Scene, names: &[String]) {
    let duration = 60.0;
    let ensemble = &scene.ensemble.as_ref().unwrap().ensemble;
    let s = StreamSpec { rate_per_s: 20.0, duration, ..scene.stream.as_ref().unwrap().spec };
    let drawn = lumps(ensemble, &s).unwrap();
    let t0 = std::time::Instant::now();
    let whole = instrument.stream(&drawn, names, (duration, None)).unwrap();
    let one_piece = t0.elapsed().as_secs_f64();
    let rate = scene.signals.rate_hz;
    let warm = warm_up_s(model.slowest_decay(), 1e-9).unwrap();
    let cut = Cut::new(15.0, warm, rate, 1);
    let spans = cut.spans(stream_samples(duration, rate));
    let t0 = std::time::Instant::now();
    let parts: Vec<_> = spans
        .par_iter()
        .map(|&span| (span, instrument.stream(&drawn, names, (duration, Some(span))).unwrap()))
        .collect();
    let apart = t0.elapsed().as_secs_f64();
    let mut largest = 0.0f64;
    for (k, w) in whole.signals.channels.iter().enumerate() {
        let top = w.samples.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (span, r) in &parts {
            let own = &r.signals.channels[k].samples[span.warm_up()..];
            let d = own.iter().zip(&w.samples[span.from..span.to]).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            largest = largest.max(d / top);
        }
    }
    let run: usize = spans.iter().map(|s| s.to - s.start).sum();
    println!(
        "segments: a {duration} s stream in one piece {:.0}x real time on one core; in {} segments of 15 s after a warm-up of {warm:.1} s \
         (r = {:.2} 1/s, ε = 1e-9; {:.0} % more samples), in parallel on {} cores, {:.0}x real time ({:.2}x the one piece); \
         largest difference from the one piece {largest:.1e} of the channel's largest value",
        duration / one_piece,
        spans.len(),
        model.slowest_decay(),
        100.0 * (run as f64 / whole.signals.channels[0].samples.len() as f64 - 1.0),
        rayon::current_num_threads(),
        duration / apart,
        one_piece / apart,
    );
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
