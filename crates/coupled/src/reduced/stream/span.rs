//! A stream cut in time: segments of one length, each run alone from rest after a warm-up,
//! so that segments computed apart (one task each, on any machine) put together to the
//! stream's signal bit for bit.
//!
//! **Why a warm-up is enough.** The plate is linear and damped: what happened before a
//! segment's warm-up reaches its first recorded sample through the free response, whose
//! mode i has decayed by e^{-ζᵢωᵢW} after a warm-up W. With the slowest decay rate
//! r = minᵢ ζᵢωᵢ, a warm-up W = ln(1/ε)/r leaves at most a share ε of the plate's state at
//! the warm-up's start in the first recorded sample, and less later. The contacts of the
//! warm-up's lumps see the state without that share, so their forces move by about as
//! much; the bound is the free plate's, and the tests measure the whole difference against
//! the stream run in one piece. (A filter fed by the plate whose own rate is close to r
//! forgets as rW·e^{-rW}: a factor rW = ln(1/ε) more, which the recording's warm-up takes
//! as it comes.)
//!
//! **What is counted.** The contact steps, joint steps and lumps let go that a span reports
//! are those of its own samples [from, to), so that the counts of the segments add up to
//! those of the stream; the work of the warm-ups is not in them.
//!
//! **What a segment is.** Segment b records the samples [bS, (b+1)S) of a stream of S-sample
//! segments. It starts from rest W samples earlier (at 0 for the first), admits every lump
//! arriving from then on, and runs past its end until every lump that arrived within it has
//! left (at most four windows after its touch), so that those lumps'
//! responses are complete; it reports the lumps that arrived within [bS, (b+1)S). A stream
//! cut into segments *is* the concatenation of its segments: run whole or apart, it is the
//! same numbers.

use super::{sample_of, StreamResponse, HELD_WINDOWS};
use crate::reduced::ModalDamping;
use std::ops::Range;

/// The samples one segment of a stream runs and records: it starts from rest at `start`,
/// records [`from`, `to`) and reports the lumps arriving in it. Model samples from the
/// stream's first.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Span {
    /// The warm-up's first sample: the plate at rest there.
    pub start: usize,
    /// The first sample recorded.
    pub from: usize,
    /// One past the last sample recorded.
    pub to: usize,
}

impl Span {
    /// The whole stream of `total` samples, from rest at its start.
    pub fn whole(total: usize) -> Self {
        Self { start: 0, from: 0, to: total }
    }

    /// The warm-up's samples, [start, from).
    pub fn warm_up(&self) -> usize {
        self.from - self.start
    }

    /// The sample the run stops at in a stream of `total` samples: the stream's end, or
    /// the last sample at which a lump touching before `to` can still be followed.
    pub(super) fn end(&self, total: usize, window_samples: usize) -> usize {
        if self.to >= total {
            total
        } else {
            (self.to + HELD_WINDOWS * window_samples + 1).min(total)
        }
    }

    /// Whether a lump arriving at `time` is one the span reports: its touch in
    /// [`from`, `to`).
    pub fn reports(&self, time: f64, rate_hz: f64) -> bool {
        (self.from..self.to).contains(&sample_of(time, rate_hz))
    }

    /// The arrivals at `times` (s) a span of a stream of `total` samples at `rate_hz`, its
    /// window `window_samples` long, runs: from the first touching at or after its start to
    /// the last touching before the sample it stops at. The others never touch within it,
    /// so a span given only these runs as with all of them; the caller need not build the
    /// rest. All of them where `times` is out of order (the stream refuses it, naming it).
    pub fn followed(&self, times: &[f64], total: usize, (rate_hz, window_samples): (f64, usize)) -> Range<usize> {
        if !times.is_sorted_by(|a, b| a <= b) {
            return 0..times.len();
        }
        let end = self.end(total, window_samples);
        let from = times.partition_point(|&t| !self.admits(t, rate_hz));
        let to = times.partition_point(|&t| sample_of(t, rate_hz) < end);
        from..to.max(from)
    }

    /// Whether a lump arriving at `time` is followed in this span.
    pub(super) fn admits(&self, time: f64, rate_hz: f64) -> bool {
        sample_of(time, rate_hz) >= self.start
    }
}

/// The part of `items` (in time order, each arriving at `time`) that `span` follows
/// ([`Span::followed`]) in a stream `duration` seconds long at `rate_hz` with a window of
/// `window_samples`; all of them for the whole stream (None).
pub fn followed_part<T>(
    span: Option<Span>,
    items: &[T],
    time: impl Fn(&T) -> f64,
    (duration, rate_hz, window_samples): (f64, f64, usize),
) -> &[T] {
    let Some(span) = span else { return items };
    let times: Vec<f64> = items.iter().map(time).collect();
    &items[span.followed(&times, stream_samples(duration, rate_hz), (rate_hz, window_samples))]
}

/// A stream's cut: segments of `length` samples, each with `warm_up` samples before it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cut {
    /// Samples a segment records.
    pub length: usize,
    /// Samples it runs from rest before the first it records.
    pub warm_up: usize,
}

impl Cut {
    /// Segments of `length_s` seconds after a warm-up of `warm_up_s`, at `rate_hz`, both
    /// rounded up to whole multiples of `align` samples (an ADC reading every `align`-th
    /// model sample then reads the same samples in every segment).
    pub fn new(length_s: f64, warm_up_s: f64, rate_hz: f64, align: usize) -> Self {
        let align = align.max(1);
        // A warm-up longer than any stream (a nearly undamped model) saturates rather than wraps.
        let whole = |s: f64| {
            let samples = (s * rate_hz - 1e-9).ceil().clamp(0.0, (usize::MAX / 2) as f64) as usize;
            samples.div_ceil(align).saturating_mul(align)
        };
        Self { length: whole(length_s).max(align), warm_up: whole(warm_up_s) }
    }

    /// The segments of a stream of `total` samples, in order.
    pub fn spans(&self, total: usize) -> Vec<Span> {
        (0..total.div_ceil(self.length)).filter_map(|b| self.span(b, total)).collect()
    }

    /// Segment `b` of a stream of `total` samples (None past its end).
    pub fn span(&self, b: usize, total: usize) -> Option<Span> {
        let from = b.checked_mul(self.length).filter(|&f| f < total)?;
        Some(Span { start: from.saturating_sub(self.warm_up), from, to: (from + self.length).min(total) })
    }
}

/// The samples of a stream `duration` seconds long at `rate_hz`: the first at its start, the
/// last before its end.
pub fn stream_samples(duration: f64, rate_hz: f64) -> usize {
    (duration * rate_hz - 1e-9).ceil().max(1.0) as usize
}

/// The slowest decay rate of modes `omega` damped as `damping`, r = minᵢ ζᵢωᵢ, 1/s.
pub(crate) fn slowest_decay(omega: &[f64], damping: ModalDamping) -> f64 {
    omega.iter().map(|&w| damping.at(w) * w).fold(f64::INFINITY, f64::min)
}

/// The warm-up, s, after which the state a damped model had at its start has decayed to
/// the share `tolerance` ε ∈ (0, 1): ln(1/ε)/r for the slowest decay rate r (module docs);
/// None for a model with an undamped mode, whose past never fades, or ε outside (0, 1).
pub fn warm_up_s(slowest_decay: f64, tolerance: f64) -> Option<f64> {
    let fades = slowest_decay > 0.0 && slowest_decay.is_finite() && tolerance > 0.0 && tolerance < 1.0;
    fades.then(|| (1.0 / tolerance).ln() / slowest_decay)
}

impl StreamResponse {
    /// The run over `span` as the span reports it: the lumps that arrived within it, each
    /// with the stream's sample of its touch, and the signals up to the span's last recorded
    /// sample (from its start).
    pub(super) fn within(mut self, span: Span) -> Self {
        self.lumps.iter_mut().for_each(|l| l.sample += span.start);
        self.lumps.retain(|l| (span.from..span.to).contains(&l.sample));
        for c in &mut self.signals.channels {
            c.samples.truncate(span.to - span.start);
        }
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_tile_the_stream() {
        let cut = Cut::new(0.0105, 0.002, 1000.0, 4);
        assert_eq!((cut.length, cut.warm_up), (12, 4));
        let spans = cut.spans(30);
        assert_eq!(spans.len(), 3);
        assert_eq!(spans[0], Span { start: 0, from: 0, to: 12 });
        assert_eq!(spans[1], Span { start: 8, from: 12, to: 24 });
        assert_eq!(spans[2], Span { start: 20, from: 24, to: 30 });
        assert_eq!(cut.span(3, 30), None);
        assert!(spans.windows(2).all(|w| w[0].to == w[1].from));
    }

    #[test]
    fn the_warm_up_is_the_decay_to_the_tolerance() {
        // e^{-rW} = ε.
        let w = warm_up_s(2.0, 1e-6).unwrap();
        assert!(((-2.0 * w).exp() - 1e-6).abs() < 1e-18);
        assert_eq!(warm_up_s(0.0, 1e-6), None);
    }
}
