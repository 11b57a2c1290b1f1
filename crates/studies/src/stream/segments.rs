//! A stream run and recorded in segments (`[stream] segment_s`): each segment alone from
//! rest after a warm-up (`coupled::reduced::stream::span`), recorded through the chain from
//! its warm-up's start with its background drawn in blocks (`identify::measurement::segments`),
//! so that a segment computed alone is the study's segment bit for bit.
//!
//! The warm-up is the longer of the plate's and the chain's: W = ln(1/ε)/min(r_plate, r_chain)
//! with r the slowest decay rate of each (a high-pass of corner f_h decays at 2πf_h, the
//! modes at minᵢ ζᵢωᵢ), rounded up to a whole ADC sample; the backgrounds cross-fade over
//! the same W (at most a segment).

use super::recorder::Recorder;
use super::SegmentFacts;
use crate::Failure;
use coupled::error::ModelError;
use coupled::identification::measurand;
use coupled::reduced::stream::span::{stream_samples, warm_up_s};
use coupled::reduced::stream::{Cut, Span, StreamResponse};
use identify::measurement::segments::Segment;
use identify::measurement::Chain;
use identify::stream::{Lump, Segmenting, StreamStudy};
use rayon::prelude::*;

/// How a study's streams are cut, worked out for one struck model and its chain.
#[derive(Debug, Clone, Copy)]
pub(super) struct Cutting {
    /// The cut in model samples.
    pub cut: Cut,
    /// The backgrounds' cross-fade, ADC samples.
    pub overlap: usize,
    /// The model's samples per ADC sample.
    pub decimation: usize,
    /// What the study reports of it.
    pub facts: SegmentFacts,
}

/// Most the warm-ups may add to the samples a stream runs: as many again. Beyond it the
/// segments cost more than twice the stream, and hold their warm-ups' samples beside it.
pub const MAX_ADDED_SHARE: f64 = 1.0;

/// The cut of `study`'s streams on `recorder` (None: each stream in one piece), refused
/// where the warm-ups would add more than [`MAX_ADDED_SHARE`] to the samples run: checked
/// once the model's slowest decay is known, before any stream runs.
pub(super) fn cutting(recorder: &dyn Recorder, study: &StreamStudy) -> Result<Option<Cutting>, Failure> {
    let Some(Segmenting { length, tolerance }) = study.segments else { return Ok(None) };
    let chain_decay = recorder.chain().map_or(f64::INFINITY, Chain::slowest_decay);
    let decay = recorder.slowest_decay().min(chain_decay);
    let full = warm_up_s(decay, tolerance).ok_or_else(|| {
        format!("stream.segment_s: the model has an undamped mode (slowest decay {decay} 1/s), whose past never fades; a stream on it cannot be cut")
    })?;
    // A warm-up reaching back past the stream's start runs from there.
    let warm = full.min(study.spec.duration);
    let rate = recorder.model_rate_hz();
    let decimation = recorder.chain().map_or(1, Chain::decimation);
    let cut = Cut::new(length, warm, rate, decimation);
    let total = stream_samples(study.spec.duration, rate);
    let run: usize = cut.spans(total).iter().map(|s| s.to - s.start).sum();
    let added_share = run as f64 / total as f64 - 1.0;
    if added_share > MAX_ADDED_SHARE {
        return Err(too_long_warm_up((length, study.spec.duration), (full, decay, tolerance), added_share).into());
    }
    let facts = SegmentFacts {
        added_share,
        length_s: cut.length as f64 / rate,
        warm_up_s: cut.warm_up as f64 / rate,
        tolerance,
        slowest_decay_per_s: decay,
        segments: cut.spans(total).len(),
    };
    Ok(Some(Cutting { cut, overlap: cut.warm_up.min(cut.length) / decimation, decimation, facts }))
}

/// The refusal of segments whose warm-ups W = ln(1/ε)/r (`full`, before it is capped at the
/// stream) would add `added_share` of the samples run, above [`MAX_ADDED_SHARE`]: it quotes W
/// as the decay and ε give it, and the shortest segment that would pass (S ≳ W / share).
fn too_long_warm_up(
    (length, duration): (f64, f64),
    (full, decay, tolerance): (f64, f64, f64),
    added_share: f64,
) -> String {
    let shortest = full / MAX_ADDED_SHARE;
    let advice = if shortest < duration {
        format!("lengthen the segments to at least about {shortest:.3} s or raise segment_tolerance")
    } else {
        format!(
            "the stream ({duration} s) is too short to cut at this ε: leave segment_s out or raise segment_tolerance"
        )
    };
    format!(
        "stream.segment_s = {length} s: each segment warms up for W = ln(1/ε)/r = {full:.3} s (ε = segment_tolerance = {tolerance:e}, r = {decay:.4} 1/s the slowest decay of the modes and the chain; a warm-up runs at most from the stream's start), which adds {:.0} % to the samples run, above the allowed {:.0} %; {advice}",
        100.0 * added_share,
        100.0 * MAX_ADDED_SHARE,
    )
}

/// A stream run in segments: how it was cut, which segments (number and span, in order)
/// its response puts together, and each one's warm-up samples per channel.
pub(super) struct Pieces {
    pub cutting: Cutting,
    pub spans: Vec<(usize, Span)>,
    pub warm_ups: Vec<Vec<Vec<f64>>>,
}

/// A stream's model response, whole or put together from its segments (`cutting`): their
/// recorded samples and lumps in order, their work summed.
pub(super) fn run(
    recorder: &dyn Recorder,
    (lumps, names): (&[Lump], &[String]),
    duration: f64,
    cutting: Option<Cutting>,
) -> Result<(StreamResponse, Option<Pieces>), ModelError> {
    let Some(cutting) = cutting else { return Ok((recorder.stream(lumps, names, (duration, None))?, None)) };
    let spans: Vec<(usize, Span)> =
        cutting.cut.spans(stream_samples(duration, recorder.model_rate_hz())).into_iter().enumerate().collect();
    put_together(recorder, (lumps, names), duration, cutting, spans)
}

/// Segment `b` of a stream alone, and its span; refused where the scene cuts no stream or
/// the stream has no segment `b`.
pub(super) fn one(
    recorder: &dyn Recorder,
    (lumps, names): (&[Lump], &[String]),
    duration: f64,
    (cutting, b): (Option<Cutting>, usize),
) -> Result<((StreamResponse, Option<Pieces>), Span), Failure> {
    let Some(cutting) = cutting else {
        return Err("segment: the scene's [stream] has no segment_s, so its streams are not cut".into());
    };
    let total = stream_samples(duration, recorder.model_rate_hz());
    let count = cutting.cut.spans(total).len();
    let span = cutting.cut.span(b, total).ok_or_else(|| format!("segment {b}: allowed 0 to {}", count - 1))?;
    Ok((put_together(recorder, (lumps, names), duration, cutting, vec![(b, span)])?, span))
}

/// The segments a stream of `scene`'s `study` is cut into and their length, s (None: not
/// cut), from the scene alone: what a segment number is checked against before anything is
/// built.
pub fn count(scene: &coupled::scene::Scene, study: &StreamStudy) -> Option<(usize, f64)> {
    let s = study.segments?;
    let rate = scene.signals.rate_hz;
    // The scene has checked that its chain's rate divides the model's.
    let decimation =
        scene.measurement.as_ref().map_or(Some(1), |m| identify::measurement::decimation(m.rate_hz, rate).ok())?;
    let cut = Cut::new(s.length, 0.0, rate, decimation);
    Some((cut.spans(stream_samples(study.spec.duration, rate)).len(), cut.length as f64 / rate))
}

/// Why segment `b` of `scene`'s streams cannot be asked for (None: it can): the scene cuts
/// nothing, or its streams have fewer segments. From the scene alone, before anything is
/// built.
pub fn refusal(scene: &coupled::scene::Scene, study: &StreamStudy, b: usize) -> Option<String> {
    match count(scene, study) {
        None => Some(format!("segment {b}: {}'s [stream] has no segment_s, so its streams are not cut", scene.name)),
        Some((n, _)) if b >= n => Some(format!("segment {b}: allowed 0 to {}", n - 1)),
        Some(_) => None,
    }
}

/// The segments `spans`, run in parallel and put together in order.
fn put_together(
    recorder: &dyn Recorder,
    (lumps, names): (&[Lump], &[String]),
    duration: f64,
    cutting: Cutting,
    spans: Vec<(usize, Span)>,
) -> Result<(StreamResponse, Option<Pieces>), ModelError> {
    let parts: Vec<StreamResponse> = spans
        .par_iter()
        .map(|&(_, span)| recorder.stream(lumps, names, (duration, Some(span))))
        .collect::<Result<_, _>>()?;
    let mut warm_ups = Vec::with_capacity(parts.len());
    let mut parts = parts.into_iter().zip(&spans);
    let (mut whole, &(_, first)) = parts.next().expect("a stream has a segment");
    warm_ups.push(split_warm_up(&mut whole, first));
    for (mut r, &(_, span)) in parts {
        warm_ups.push(split_warm_up(&mut r, span));
        for (w, c) in whole.signals.channels.iter_mut().zip(r.signals.channels) {
            w.samples.extend(c.samples);
        }
        whole.lumps.extend(r.lumps);
        whole.steps += r.steps;
        whole.joint_steps += r.joint_steps;
        whole.unconverged_steps += r.unconverged_steps;
        whole.released_in_contact += r.released_in_contact;
        whole.cross_residual_bound = whole.cross_residual_bound.max(r.cross_residual_bound);
    }
    Ok((whole, Some(Pieces { cutting, spans, warm_ups })))
}

/// The span's warm-up samples, taken off the front of its channels.
fn split_warm_up(r: &mut StreamResponse, span: Span) -> Vec<Vec<f64>> {
    r.signals.channels.iter_mut().map(|c| c.samples.drain(..span.warm_up()).collect()).collect()
}

/// A stream's channels recorded in segments through `chain` (module docs): segment b of
/// channel c from its warm-up samples and its own, its background from recording number
/// `recording`'s blocks.
pub(super) fn record(
    chain: &Chain,
    pieces: &Pieces,
    response: &StreamResponse,
    scale: f64,
    recording: usize,
) -> Vec<Vec<f64>> {
    let cutting = &pieces.cutting;
    let length = cutting.cut.length / cutting.decimation;
    (response.signals.channels.iter().enumerate())
        .map(|(channel, c)| {
            let mut out = Vec::new();
            let mut at = 0;
            for (&(b, span), warm) in pieces.spans.iter().zip(&pieces.warm_ups) {
                let own = span.to - span.from;
                let mut y = warm[channel].clone();
                y.extend_from_slice(&c.samples[at..at + own]);
                at += own;
                let segment = Segment { index: b, length, overlap: cutting.overlap };
                let what = (measurand(c.kind), channel);
                match chain.measure_segment(what, (&y, span.warm_up()), segment, scale, recording) {
                    Some(m) => out.extend(m.samples),
                    None => return Vec::new(),
                }
            }
            out
        })
        .collect()
}
