//! A few channels' free samples straight from the block's start state, for long free
//! stretches such as a stream's between its lumps.
//!
//! Channel c reads yᶜ = Σᵢ Aᶜᵢqᵢ + Bᶜᵢq̇ᵢ, and free of force mode i's state at the block's
//! j-th sample is Φᵢ(jT_s)(qᵢ, q̇ᵢ)₀ ([`super::BlockMaps`]). So the channel's j-th sample is
//!
//! yᶜ[j] = Σᵢ Eᶜᵢ[j] qᵢ,₀ + Fᶜᵢ[j] q̇ᵢ,₀,  Eᶜᵢ[j] = AᶜᵢΦᵢ,qq(jT_s) + BᶜᵢΦᵢ,q̇q(jT_s),
//! Fᶜᵢ[j] = AᶜᵢΦᵢ,qq̇(jT_s) + BᶜᵢΦᵢ,q̇q̇(jT_s),
//!
//! the channel's own maps over a block, formed once: two products and two sums a mode,
//! sample and channel, where [`super::free_window`] propagates every mode's state to every
//! sample first (six operations a mode and sample) and then sums the channels over the
//! states (four a channel). With a few channels the propagation is most of that work, and
//! this form leaves it out: only the block's last state, which starts the next block, is
//! propagated, as [`super::free_window`] propagates it.
//!
//! A channel of one part (A on q alone: a displacement, a strain, a corner's reaction; or B
//! on q̇ alone) costs two operations of its own through the states against four through its
//! maps, so where a scene records more than three of them the states are propagated for those
//! (six operations a mode and sample, shared) and they are summed as [`super::free_window`]
//! sums them, to its bits; the channels of both parts (accelerations) still go through their
//! maps. Either way a mode and sample cost what they cost before or less.
//!
//! **Arithmetic.** In [`Arithmetic::Exact`] the sums run in f64, each product then each sum
//! (no fused multiply-adds), so a sample has the same bits on every processor; they are
//! [`super::free_window`]'s sums in another association, so the two agree to rounding. In
//! [`Arithmetic::Fast`] Eᶜᵢ, Fᶜᵢ and the block's start state are rounded once to f32 and the
//! 2n terms summed in f32 with fused multiply-adds: within γ₂ₙ₊₂ Σᵢ(|Eᶜᵢ[j]qᵢ| + |Fᶜᵢ[j]q̇ᵢ|)
//! of the exact sum (Higham 2002, eq. 3.5, u = 2⁻²⁴), the start state propagated in f64 and
//! set to rest below 2⁻¹⁰⁰ as in [`super::free_window`]'s fast arithmetic.

use super::sums::{Aligned, Parts, Term};
use super::{Arithmetic, Block, Stored, BLOCK};
use crate::reduced::target::ChannelRow;

/// Every channel's maps over a block in the window's arithmetic.
#[derive(Debug, Clone)]
pub(crate) struct OutputMaps(InNumber);

/// The maps in their number.
#[derive(Debug, Clone)]
enum InNumber {
    /// In f64, each product then each sum.
    Exact(Maps<f64>),
    /// In f32 with fused multiply-adds, the block's start state rounded to f32.
    Fast(Maps<f32>),
}

/// The channels' maps over a block, stored in the number `T`: `e[k * n + i]` is Eᶜᵢ over the
/// block's samples (module docs) for the k-th channel of `mapped`, n the modes; the channels
/// of one part, `single`, with their coefficients, summed over the propagated states.
#[derive(Debug, Clone)]
struct Maps<T> {
    modes: usize,
    mapped: Vec<usize>,
    e: Vec<Aligned<T>>,
    f: Vec<Aligned<T>>,
    single: Vec<OnePart<T>>,
}

/// A channel of one part: its number and its A or B.
#[derive(Debug, Clone)]
struct OnePart<T> {
    channel: usize,
    a: Option<Vec<T>>,
    b: Option<Vec<T>>,
}

impl OutputMaps {
    /// The maps of the channels `rows` (A and B by mode, None where zero) through the modes'
    /// block maps `maps`, formed in f64 and stored in `arithmetic`'s number.
    pub(crate) fn new(arithmetic: Arithmetic, maps: &[[Block; 4]], rows: &[ChannelRow]) -> Self {
        Self(match arithmetic {
            Arithmetic::Exact => InNumber::Exact(Maps::new(maps, rows)),
            Arithmetic::Fast => InNumber::Fast(Maps::new(maps, rows)),
        })
    }

    /// Appends `count` samples to every channel of `out`, the modes free from the state
    /// (`q`, `v`) at the sample before the first, their block maps `maps` (those the maps
    /// were formed with); on the instruction set `simd` (the same operations in the same
    /// order on every one). The state itself is the caller's to advance.
    pub(crate) fn window(
        &self,
        simd: pulp::Arch,
        maps: &[[Block; 4]],
        (q, v): (&[f64], &[f64]),
        out: &mut [Vec<f64>],
        count: usize,
    ) {
        match &self.0 {
            InNumber::Exact(m) => simd.dispatch(Samples { maps: m, block_maps: maps, q, v, out, count }),
            InNumber::Fast(m) => simd.dispatch(Samples { maps: m, block_maps: maps, q, v, out, count }),
        }
    }
}

impl<T: Stored> Maps<T> {
    /// A channel with both parts goes through its maps (four operations a mode and sample,
    /// against six shared and four its own through the states); a channel of one part, A on
    /// q alone (a displacement, a strain, a corner's reaction) or B on q̇ alone, costs two of
    /// its own through the states, so where there are several of them the states are
    /// propagated for them, as [`super::free_window`] does, to the same bits.
    fn new(maps: &[[Block; 4]], rows: &[ChannelRow]) -> Self {
        let n = maps.len();
        let both = |r: &ChannelRow| r.a.is_some() && r.b.is_some();
        let singles = rows.iter().filter(|r| !both(r)).count();
        // Four through the maps against two each and the six of the states.
        let through_states = |r: &ChannelRow| !both(r) && 4 * singles > 2 * singles + 6;
        let mapped: Vec<usize> = (0..rows.len()).filter(|&c| !through_states(&rows[c])).collect();
        let zero = Aligned([T::ZERO; BLOCK]);
        let (mut e, mut f) = (vec![zero; mapped.len() * n], vec![zero; mapped.len() * n]);
        for (k, row) in mapped.iter().map(|&c| &rows[c]).enumerate() {
            for (i, [qq, qv, vq, vv]) in maps.iter().enumerate() {
                let a = row.a.as_ref().map_or(0.0, |a| a.get(i).copied().unwrap_or(0.0));
                let b = row.b.as_ref().map_or(0.0, |b| b.get(i).copied().unwrap_or(0.0));
                for j in 0..BLOCK {
                    e[k * n + i].0[j] = T::narrow(a * qq.0[j] + b * vq.0[j]);
                    f[k * n + i].0[j] = T::narrow(a * qv.0[j] + b * vv.0[j]);
                }
            }
        }
        let part = |x: &Option<Vec<f64>>| x.as_deref().map(|c| T::coefficients(c).into_owned());
        let single = (0..rows.len())
            .filter(|&c| through_states(&rows[c]))
            .map(|c| OnePart { channel: c, a: part(&rows[c].a), b: part(&rows[c].b) })
            .collect();
        Self { modes: n, mapped, e, f, single }
    }
}

/// [`OutputMaps::window`]'s arguments.
struct Samples<'a, 'b, T> {
    maps: &'a Maps<T>,
    block_maps: &'a [[Block; 4]],
    q: &'a [f64],
    v: &'a [f64],
    out: &'b mut [Vec<f64>],
    count: usize,
}

impl<T: Stored> pulp::WithSimd for Samples<'_, '_, T> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        let Samples { maps, block_maps, q, v, out, count } = self;
        let n = maps.modes.min(q.len()).min(block_maps.len());
        let (mut q0, mut v0) = (q[..n].to_vec(), v[..n].to_vec());
        let (mut qn, mut vn) = (vec![T::ZERO; n], vec![T::ZERO; n]);
        // The channels of one part, through the states as the window sums them.
        let parts = Parts::new((0..out.len()).map(|c| {
            maps.single.iter().find(|s| s.channel == c).map_or((None, None), |s| (s.a.as_deref(), s.b.as_deref()))
        }));
        let (mut qs, mut vs) = (vec![Aligned([T::ZERO; BLOCK]); n], vec![Aligned([T::ZERO; BLOCK]); n]);
        let mut y = vec![[T::ZERO; BLOCK]; out.len()];
        let mut done = 0;
        while done < count {
            let m = BLOCK.min(count - done);
            for i in 0..n {
                (qn[i], vn[i]) = (T::narrow(q0[i]), T::narrow(v0[i]));
            }
            if maps.single.is_empty() {
                for ((p, q0), v0) in block_maps[..n].iter().zip(&mut q0).zip(&mut v0) {
                    (*q0, *v0) = T::block_end(p, (*q0, *v0));
                }
            } else {
                let states = qs.iter_mut().zip(vs.iter_mut());
                for (((p, (qb, vb)), q0), v0) in block_maps[..n].iter().zip(states).zip(&mut q0).zip(&mut v0) {
                    (*q0, *v0) = T::propagate(p, (*q0, *v0), qb, vb);
                }
                // Every row of `y` anew, the channels of one part summed.
                parts.block(&qs, &vs, &mut y);
            }
            let mut pairs = maps.mapped.chunks_exact(2);
            for (k, pair) in (&mut pairs).enumerate() {
                [y[pair[0]], y[pair[1]]] = block_pair(maps, (2 * k, 2 * k + 1), (&qn, &vn));
            }
            if let [c] = pairs.remainder() {
                y[*c] = block_one(maps, maps.mapped.len() - 1, (&qn, &vn));
            }
            for (yc, o) in y.iter().zip(out.iter_mut()) {
                o.extend(yc[..m].iter().map(|&x| x.widen()));
            }
            done += m;
        }
    }
}

/// The `k0`-th and `k1`-th mapped channels' samples over one block from the state (`q`, `v`)
/// before it:
/// y[j] = Σᵢ (Eᵢ[j] qᵢ + Fᵢ[j] q̇ᵢ), i in order, each term added in `T`'s way.
#[inline(always)]
fn block_pair<T: Term>(maps: &Maps<T>, (k0, k1): (usize, usize), (q, v): (&[T], &[T])) -> [[T; BLOCK]; 2] {
    let n = q.len();
    let (e0, f0) = (&maps.e[k0 * maps.modes..][..n], &maps.f[k0 * maps.modes..][..n]);
    let (e1, f1) = (&maps.e[k1 * maps.modes..][..n], &maps.f[k1 * maps.modes..][..n]);
    let (mut y0, mut y1) = ([T::ZERO; BLOCK], [T::ZERO; BLOCK]);
    for i in 0..n {
        let (qi, vi) = (q[i], v[i]);
        let (a0, b0, a1, b1) = (&e0[i].0, &f0[i].0, &e1[i].0, &f1[i].0);
        for j in 0..BLOCK {
            y0[j] = y0[j].add_product(a0[j], qi).add_product(b0[j], vi);
            y1[j] = y1[j].add_product(a1[j], qi).add_product(b1[j], vi);
        }
    }
    [y0, y1]
}

/// The `k`-th mapped channel's samples over one block, as [`block_pair`] forms each of its two.
#[inline(always)]
fn block_one<T: Term>(maps: &Maps<T>, k: usize, (q, v): (&[T], &[T])) -> [T; BLOCK] {
    let n = q.len();
    let (e, f) = (&maps.e[k * maps.modes..][..n], &maps.f[k * maps.modes..][..n]);
    let mut y = [T::ZERO; BLOCK];
    for i in 0..n {
        let (qi, vi, a, b) = (q[i], v[i], &e[i].0, &f[i].0);
        for j in 0..BLOCK {
            y[j] = y[j].add_product(a[j], qi).add_product(b[j], vi);
        }
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reduced::signals::free_map;
    use crate::reduced::window::BlockMaps;
    use crate::reduced::ModalDamping;

    /// The fast maps against the closed form: 40 modes (60 Hz to 9 kHz, ζ = 1 %) from a state
    /// of mixed signs, five channels of mixed-sign coefficients (two with only one part), 3.5
    /// blocks at 20 kHz. Each sample is Σᵢ Eᵢ[j]qᵢ + Fᵢ[j]q̇ᵢ over the block's start state, 2n
    /// terms formed in f32 with fused multiply-adds from Eᵢ, Fᵢ, qᵢ, q̇ᵢ each rounded once: it lies
    /// within γ₂ₙ₊₂ Σᵢ(|Eᵢ[j]qᵢ| + |Fᵢ[j]q̇ᵢ|) (Higham 2002, eq. 3.5; u = 2⁻²⁴) of the closed form,
    /// plus the f64 start states' 1e-13 of the channel's largest value. It is not the exact
    /// maps' result, and it has the same bits on plain x86-64 as on the widest instruction set.
    #[test]
    fn fast_output_maps_lie_within_their_rounding_bound() {
        let (zeta, ts, n, channels) = (0.01, 5e-5, 40, 5);
        let mut uniform = super::super::tests::uniforms();
        let omega: Vec<f64> = (0..n).map(|i| 2.0 * std::f64::consts::PI * 60.0 * (1.0 + i as f64 * 3.7)).collect();
        let q: Vec<f64> = (0..n).map(|_| 1e-5 * uniform()).collect();
        let v: Vec<f64> = omega.iter().map(|w| 1e-5 * w * uniform()).collect();
        let rows: Vec<ChannelRow> = (0..channels)
            .map(|r| ChannelRow {
                a: (r != 3).then(|| (0..n).map(|_| uniform()).collect()),
                b: (r != 2).then(|| omega.iter().map(|w| uniform() / w).collect()),
                d: 0.0,
            })
            .collect();
        let count = 3 * BLOCK + BLOCK / 2;
        let maps = BlockMaps::new(&omega, ModalDamping::Ratio(zeta), ts);
        let window = |arch, arithmetic| {
            let mut out = vec![Vec::new(); channels];
            OutputMaps::new(arithmetic, maps.modes(), &rows).window(arch, maps.modes(), (&q, &v), &mut out, count);
            out
        };
        let fast = window(pulp::Arch::new(), Arithmetic::Fast);
        let gamma = Arithmetic::Fast.gamma(2 * n + 2);
        let zero = vec![0.0; n];
        for (r, row) in rows.iter().enumerate() {
            let (a, b) = (row.a.as_ref().unwrap_or(&zero), row.b.as_ref().unwrap_or(&zero));
            // (the sample, Σ|Eq| + |Fq̇|) at sample k = block·BLOCK + j + 1, from the block's
            // closed-form start state.
            let closed = |k: usize| -> (f64, f64) {
                let (start, j) = ((k - 1) / BLOCK * BLOCK, (k - 1) % BLOCK + 1);
                (0..n).fold((0.0, 0.0), |(y, s), i| {
                    let m0 = free_map(omega[i], zeta, start as f64 * ts);
                    let (q0, v0) = (m0[0] * q[i] + m0[1] * v[i], m0[2] * q[i] + m0[3] * v[i]);
                    let m = free_map(omega[i], zeta, j as f64 * ts);
                    let (e, f) = (a[i] * m[0] + b[i] * m[2], a[i] * m[1] + b[i] * m[3]);
                    (y + e * q0 + f * v0, s + (e * q0).abs() + (f * v0).abs())
                })
            };
            let reference: Vec<(f64, f64)> = (1..=count).map(closed).collect();
            let scale = reference.iter().fold(0.0f64, |m, x| m.max(x.0.abs()));
            for (k, (y, s)) in reference.iter().enumerate() {
                let bound = gamma * s + 1e-13 * scale;
                let got = fast[r][k];
                assert!((got - y).abs() <= bound, "channel {r}, sample {k}: {got} against {y}, bound {bound:e}");
            }
        }
        assert_ne!(fast, window(pulp::Arch::new(), Arithmetic::Exact), "the fast maps summed in f64");
        assert_eq!(fast, window(pulp::Arch::Scalar, Arithmetic::Fast), "plain x86-64 against the widest");
    }

    /// The four-mode plate of the exact tests: 80 Hz to 9 kHz at ζ = 2 %, its state and the
    /// sample interval (20 kHz).
    const ZETA: f64 = 0.02;
    const TS: f64 = 5e-5;
    const OMEGA: [f64; 4] = [2.0 * std::f64::consts::PI * 80.0, 7.3e3, 2.1e4, 5.6e4];
    const STATE: ([f64; 4], [f64; 4]) = ([1e-4, -3e-5, 4e-6, 2e-6], [0.02, 0.5, -0.1, -0.3]);

    /// `rows`' exact samples over `count` samples of the four-mode plate, each within 1e-13 of
    /// its channel's largest value of the closed form Σᵢ Aᵢ[Φᵢ(kT_s)s₀]_q + Bᵢ[Φᵢ(kT_s)s₀]_q̇
    /// ([`free_map`] over the whole kT_s), and the same bits on plain x86-64 as on the widest
    /// instruction set.
    fn closed_form_samples(rows: &[ChannelRow], count: usize) -> Vec<Vec<f64>> {
        let (q, v) = STATE;
        let maps = BlockMaps::new(&OMEGA, ModalDamping::Ratio(ZETA), TS);
        let sampled = |arch| {
            let mut out = vec![Vec::new(); rows.len()];
            OutputMaps::new(Arithmetic::Exact, maps.modes(), rows).window(
                arch,
                maps.modes(),
                (&q, &v),
                &mut out,
                count,
            );
            out
        };
        let out = sampled(pulp::Arch::new());
        let zero = vec![0.0; OMEGA.len()];
        for (c, row) in rows.iter().enumerate() {
            let (a, b) = (row.a.as_ref().unwrap_or(&zero), row.b.as_ref().unwrap_or(&zero));
            let closed = |k: usize| -> f64 {
                (0..OMEGA.len())
                    .map(|i| {
                        let m = free_map(OMEGA[i], ZETA, k as f64 * TS);
                        a[i] * (m[0] * q[i] + m[1] * v[i]) + b[i] * (m[2] * q[i] + m[3] * v[i])
                    })
                    .sum()
            };
            let reference: Vec<f64> = (1..=count).map(closed).collect();
            let scale = reference.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            assert_eq!(out[c].len(), count);
            for (k, y) in reference.iter().enumerate() {
                assert!((out[c][k] - y).abs() <= 1e-13 * scale, "channel {c}, sample {k}: {} against {y}", out[c][k]);
            }
        }
        assert_eq!(out, sampled(pulp::Arch::Scalar), "plain x86-64 against the widest instruction set");
        out
    }

    /// Three channels (A alone, B alone, both: two summed as a pair, one alone, all through
    /// their maps) over 2.5 blocks: the maps formed per block, the blocks' hand-over and the
    /// partial last block lose only rounding against the closed form.
    #[test]
    fn output_maps_are_the_closed_form_free_vibration() {
        let (a, b) = (vec![1.0, 0.7, -0.4, -2.0], vec![0.3, -1.1, 0.2, 0.9]);
        let rows = [
            ChannelRow { a: Some(a.clone()), b: None, d: 0.0 },
            ChannelRow { a: None, b: Some(b.clone()), d: 0.0 },
            ChannelRow { a: Some(a), b: Some(b), d: 0.0 },
        ];
        closed_form_samples(&rows, 2 * BLOCK + BLOCK / 2);
    }

    /// Several channels of one part (three displacement-like, A alone; two velocity-like, B
    /// alone) beside one of both: the six are still the closed form, the five of one part are
    /// summed over the propagated states, and those are [`super::super::free_window`]'s
    /// samples to the bit.
    #[test]
    fn channels_of_one_part_are_the_windows_to_the_bit() {
        let coefficients = |k: f64| -> Vec<f64> { (0..4).map(|i| (k + i as f64).sin()).collect() };
        let rows: Vec<ChannelRow> = (0..6)
            .map(|c| ChannelRow {
                a: (c < 3 || c == 5).then(|| coefficients(c as f64)),
                b: (c >= 3).then(|| coefficients(10.0 + c as f64)),
                d: 0.0,
            })
            .collect();
        let count = 2 * BLOCK + 3;
        let out = closed_form_samples(&rows, count);
        let (q, v) = STATE;
        let maps = BlockMaps::new(&OMEGA, ModalDamping::Ratio(ZETA), TS);
        let mut window = vec![Vec::new(); rows.len()];
        let exact = (pulp::Arch::new(), Arithmetic::Exact);
        super::super::free_window(exact, &[maps.modes()], &q, &v, &rows, &mut window, count);
        for c in 0..5 {
            assert_eq!(out[c], window[c], "channel {c} of one part");
        }
    }
}
