//! The channels' sums over the modes for one block of samples, several channels at a time.
//!
//! Channel c's block is `y[j] = Σᵢ Aᵢ qᵢ[j]` then `+= Σᵢ Bᵢ q̇ᵢ[j]`, over i in order for every
//! sample j. A lone channel's sums form one chain of dependent additions per vector of its
//! block, so they run at the adder's latency; summing up to [`GROUP`] channels that share a
//! part together gives the processor that many independent chains over the same loaded
//! states, while every channel still adds its own terms in its own order: the same numbers as
//! one channel at a time, to the bit.

use super::BLOCK;

/// One mode's values over a block of samples, aligned so that vector loads of them need no
/// extra instruction.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub(crate) struct Aligned<T>(pub [T; BLOCK]);

/// A number a block's sums are formed in, and how one term is added.
pub(super) trait Term: Copy {
    /// Zero.
    const ZERO: Self;
    /// Channels summed together: as many as keep their blocks' sums and the loaded states
    /// within the sixteen vector registers of x86-64's AVX2 (a block of [`BLOCK`] values is
    /// four registers in f64, two in f32).
    const GROUP: usize;
    /// `self + c·s`, in this arithmetic's way.
    fn add_product(self, c: Self, s: Self) -> Self;
}

/// f64, the product rounded, then the sum: the exact arithmetic.
impl Term for f64 {
    const ZERO: Self = 0.0;
    const GROUP: usize = 2;
    #[inline(always)]
    fn add_product(self, c: Self, s: Self) -> Self {
        self + c * s
    }
}

/// f32 with one rounding a term (a fused multiply-add): the fast arithmetic.
impl Term for f32 {
    const ZERO: Self = 0.0;
    const GROUP: usize = 4;
    #[inline(always)]
    fn add_product(self, c: Self, s: Self) -> Self {
        c.mul_add(s, self)
    }
}

/// The channels' parts, grouped by the states they multiply: `on_q` the (channel, A) of every
/// channel with an A, `on_v` the (channel, B) of every channel with a B, each in channel order.
pub(super) struct Parts<'a, T> {
    on_q: Vec<(usize, &'a [T])>,
    on_v: Vec<(usize, &'a [T])>,
}

impl<'a, T: Term> Parts<'a, T> {
    /// The parts of channels given as (A, B), None where zero.
    pub(super) fn new(rows: impl Iterator<Item = (Option<&'a [T]>, Option<&'a [T]>)>) -> Self {
        let (mut on_q, mut on_v) = (Vec::new(), Vec::new());
        for (c, (a, b)) in rows.enumerate() {
            on_q.extend(a.map(|a| (c, a)));
            on_v.extend(b.map(|b| (c, b)));
        }
        Self { on_q, on_v }
    }

    /// Every channel's block into `y` (one per channel): the A parts on the states `qs`,
    /// then the B parts on `vs`, each channel's terms in its own order.
    #[inline(always)]
    pub(super) fn block(&self, qs: &[Aligned<T>], vs: &[Aligned<T>], y: &mut [[T; BLOCK]]) {
        for r in y.iter_mut() {
            *r = [T::ZERO; BLOCK];
        }
        part(&self.on_q, qs, y);
        part(&self.on_v, vs, y);
    }
}

/// One part of the channels that have it, four, two or one together (as many as
/// [`Term::GROUP`] allows).
#[inline(always)]
fn part<T: Term>(have: &[(usize, &[T])], states: &[Aligned<T>], y: &mut [[T; BLOCK]]) {
    let mut at = 0;
    while at < have.len() {
        // Channels of one length together (every row holds one coefficient per mode, so this
        // always holds; a shorter row would otherwise lose the terms past it).
        let same = |k: usize| have[at..at + k].iter().all(|r| r.1.len() == have[at].1.len());
        let k = [4, 2].into_iter().find(|&k| k <= T::GROUP && k <= have.len() - at && same(k)).unwrap_or(1);
        match k {
            4 => sums::<T, 4>(&have[at..at + 4], states, y),
            2 => sums::<T, 2>(&have[at..at + 2], states, y),
            _ => sums::<T, 1>(&have[at..at + 1], states, y),
        }
        at += k;
    }
}

/// `y[r] += Σᵢ cᵢ states[i]` for K rows (r, c) together, i in order.
#[inline(always)]
fn sums<T: Term, const K: usize>(rows: &[(usize, &[T])], states: &[Aligned<T>], y: &mut [[T; BLOCK]]) {
    let n = rows.iter().fold(states.len(), |n, r| n.min(r.1.len()));
    let c: [&[T]; K] = std::array::from_fn(|k| &rows[k].1[..n]);
    let mut acc: [[T; BLOCK]; K] = std::array::from_fn(|k| y[rows[k].0]);
    for (i, s) in states[..n].iter().enumerate() {
        for (a, c) in acc.iter_mut().zip(&c) {
            let ck = c[i];
            for (a, &s) in a.iter_mut().zip(&s.0) {
                *a = a.add_product(ck, s);
            }
        }
    }
    for (a, &(r, _)) in acc.iter().zip(rows) {
        y[r] = *a;
    }
}
