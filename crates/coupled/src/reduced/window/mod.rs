//! The rest of the window after the contacts: every mode's exact free vibration, sampled.
//!
//! Free of force, mode i's state sₖ = (qᵢ, q̇ᵢ) at sample k is Φᵢ(kT_s) s₀ ([`free_map`]).
//! The samples come in blocks of [`BLOCK`]: from the state at the sample before a block,
//! its j-th sample is Φᵢ(jT_s) times that state, j = 1..[`BLOCK`], with the maps Φᵢ(jT_s)
//! computed once per signal spec (`BlockMaps`). Within a block no sample waits for the one
//! before it, and the last sample starts the next block, so the window's [`BLOCK`]-fold
//! fewer map products also round less than a step-by-step recurrence. Every channel is then
//! `y[j] = Σᵢ Aᵢqᵢ[j] + Bᵢq̇ᵢ[j]` over the block's samples, with the block as the vector
//! dimension (no horizontal sums).
//!
//! **Arithmetic.** [`Arithmetic::Exact`] forms every product and sum in f64 as written (a
//! multiply, then an add), so a window has the same bits on every processor. In
//! [`Arithmetic::Fast`] the modes are still propagated in f64 (with fused multiply-adds), but
//! each channel's sum over the modes is formed in f32 with fused multiply-adds: twice the
//! lanes of a vector and one instruction a term. Rounding the n coefficients and states to
//! f32 and summing the n products in f32 gives, by the standard a-priori bound of a dot product
//! (Higham 2002, *Accuracy and Stability of Numerical Algorithms*, §3.1, eq. 3.5),
//! |ŷ - y| ≤ γₙ₊₂ Σᵢ|cᵢsᵢ| with γₖ = ku/(1 - ku), u = 2⁻²⁴ (the output back in f64 is
//! exact: every f32 is a f64), n the channel's terms (2N, A on q and B on q̇), plus
//! √2·2⁻¹⁰⁰(|Aᵢ| + ωᵢ|Bᵢ|) for each mode rung down below 2⁻¹⁰⁰ and set to rest (`fast`'s
//! documentation says why). Fused multiply-adds are correctly rounded wherever
//! they run, so the fast window too has the same bits on every processor.

use super::signals::free_map;
use super::target::ChannelRow;
use serde::Serialize;
use std::borrow::Cow;
use std::marker::PhantomData;
use sums::{Aligned, Parts, Term};

/// How a window's free part is summed into its channels.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Arithmetic {
    /// f64, each product then each sum in a fixed order.
    #[default]
    Exact,
    /// Each channel's sum over the modes in f32 with fused multiply-adds (the modes still
    /// propagated in f64): within γₙ₊₂ Σ|cᵢsᵢ| of the exact sum, u = 2⁻²⁴ (module documentation).
    Fast,
}

impl Arithmetic {
    /// Whether it is [`Arithmetic::Exact`] (the serialised settings leave it out then).
    pub fn is_exact(&self) -> bool {
        *self == Self::Exact
    }

    /// γₖ = ku/(1 - ku), the a-priori bound on the relative error of a k-term dot product in
    /// this arithmetic's channel sums, u its unit roundoff (Higham 2002, eq. 3.5).
    pub fn gamma(self, k: usize) -> f64 {
        let u = match self {
            Self::Exact => f64::EPSILON / 2.0,
            Self::Fast => f32::EPSILON as f64 / 2.0,
        };
        let ku = k as f64 * u;
        ku / (1.0 - ku)
    }
}

/// Samples per block.
pub const BLOCK: usize = 16;

/// One mode's f64 values over a block of samples.
pub(crate) type Block = Aligned<f64>;

/// The exact free maps Φᵢ(jT_s), j = 1..[`BLOCK`], of every mode: entry k
/// ([q←q, q←q̇, q̇←q, q̇←q̇]) of Φᵢ(jT_s) is `modes()[i][k].0[j - 1]`.
#[derive(Debug, Clone)]
pub(crate) struct BlockMaps {
    modes: Vec<[Block; 4]>,
}

impl BlockMaps {
    /// The maps for the modes `omega`, damping `zeta`, sample interval `ts`.
    pub(crate) fn new(omega: &[f64], zeta: super::ModalDamping, ts: f64) -> Self {
        let modes = omega
            .iter()
            .map(|&w| {
                let mut m = [Aligned([0.0; BLOCK]); 4];
                for j in 0..BLOCK {
                    let phi = free_map(w, zeta.at(w), (j + 1) as f64 * ts);
                    for k in 0..4 {
                        m[k].0[j] = phi[k];
                    }
                }
                m
            })
            .collect();
        Self { modes }
    }

    /// The maps by mode.
    pub(crate) fn modes(&self) -> &[[Block; 4]] {
        &self.modes
    }
}

/// Appends `count` samples to every channel of `out`, the modes propagated exactly from the
/// state (`q`, `v`) at the sample before the first: mode i's maps are the i-th of the
/// concatenated `maps`; channel c reads A·q + B·q̇ with the rows of `rows[c]`, its sums in
/// `arithmetic`. Runs on the instruction set `simd` (the same operations in the same order on
/// every one).
pub(crate) fn free_window(
    (simd, arithmetic): (pulp::Arch, Arithmetic),
    maps: &[&[[Block; 4]]],
    q: &[f64],
    v: &[f64],
    rows: &[ChannelRow],
    out: &mut [Vec<f64>],
    count: usize,
) {
    match arithmetic {
        Arithmetic::Exact => simd.dispatch(Window::<f64> { maps, q, v, rows, out, count, number: PhantomData }),
        Arithmetic::Fast => simd.dispatch(Window::<f32> { maps, q, v, rows, out, count, number: PhantomData }),
    }
}

/// The number a window stores its states and sums its channels in: f64 for the exact
/// arithmetic, f32 for the fast one (`fast`).
trait Stored: Term {
    /// One mode's block, `(q[j], q̇[j]) = Φ((j + 1)T_s)(q₀, q̇₀)` for every j, stored in this
    /// number; returns the state that starts the next block.
    fn propagate(maps: &[Block; 4], start: (f64, f64), q: &mut Aligned<Self>, v: &mut Aligned<Self>) -> (f64, f64);
    /// The state that starts the next block, `Φ(BLOCK·T_s)(q₀, q̇₀)`, as [`Stored::propagate`]
    /// returns it without forming the block's other samples.
    fn block_end(maps: &[Block; 4], start: (f64, f64)) -> (f64, f64);
    /// A channel's coefficients in this number.
    fn coefficients(c: &[f64]) -> Cow<'_, [Self]>;
    /// One number in this one.
    fn narrow(x: f64) -> Self;
    /// A sum as the output's f64.
    fn widen(self) -> f64;
}

/// The exact arithmetic: each product then each sum, in f64.
impl Stored for f64 {
    #[inline(always)]
    fn propagate(maps: &[Block; 4], (q0, v0): (f64, f64), q: &mut Block, v: &mut Block) -> (f64, f64) {
        let [p0, p1, p2, p3] = maps;
        for j in 0..BLOCK {
            q.0[j] = p0.0[j] * q0 + p1.0[j] * v0;
            v.0[j] = p2.0[j] * q0 + p3.0[j] * v0;
        }
        (q.0[BLOCK - 1], v.0[BLOCK - 1])
    }

    #[inline(always)]
    fn block_end(maps: &[Block; 4], (q0, v0): (f64, f64)) -> (f64, f64) {
        let ([p0, p1, p2, p3], l) = (maps, BLOCK - 1);
        (p0.0[l] * q0 + p1.0[l] * v0, p2.0[l] * q0 + p3.0[l] * v0)
    }

    fn coefficients(c: &[f64]) -> Cow<'_, [f64]> {
        Cow::Borrowed(c)
    }

    #[inline(always)]
    fn narrow(x: f64) -> Self {
        x
    }

    #[inline(always)]
    fn widen(self) -> f64 {
        self
    }
}

/// [`free_window`]'s arguments, and the number `T` it works in.
struct Window<'a, 'b, T> {
    maps: &'a [&'a [[Block; 4]]],
    q: &'a [f64],
    v: &'a [f64],
    rows: &'a [ChannelRow],
    out: &'b mut [Vec<f64>],
    count: usize,
    number: PhantomData<T>,
}

impl<T: Stored> pulp::WithSimd for Window<'_, '_, T> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        let Window { maps, q, v, rows, out, count, .. } = self;
        let n = q.len();
        let (mut q0, mut v0) = (q.to_vec(), v.to_vec());
        // Mode-major blocks of states: qs[i].0[j] is mode i at the block's sample j.
        let (mut qs, mut vs) = (vec![Aligned([T::ZERO; BLOCK]); n], vec![Aligned([T::ZERO; BLOCK]); n]);
        let cs: Vec<_> =
            rows.iter().map(|r| (r.a.as_deref().map(T::coefficients), r.b.as_deref().map(T::coefficients))).collect();
        let parts = Parts::new(cs.iter().map(|(a, b)| (a.as_deref(), b.as_deref())));
        let mut y = vec![[T::ZERO; BLOCK]; rows.len()];
        let mut done = 0;
        while done < count {
            let m = BLOCK.min(count - done);
            let modes = maps.iter().flat_map(|m| m.iter());
            for (((p, (qb, vb)), q0), v0) in modes.zip(qs.iter_mut().zip(vs.iter_mut())).zip(&mut q0).zip(&mut v0) {
                (*q0, *v0) = T::propagate(p, (*q0, *v0), qb, vb);
            }
            parts.block(&qs, &vs, &mut y);
            for (y, o) in y.iter().zip(out.iter_mut()) {
                o.extend(y[..m].iter().map(|&x| x.widen()));
            }
            done += m;
        }
    }
}

mod fast;
mod output;
mod sums;

pub(crate) use output::OutputMaps;

#[cfg(test)]
mod tests {
    use super::*;

    /// The sampled window against the closed-form free vibration: three modes (80 Hz to
    /// 9 kHz, ζ = 2 %) from a given state, 2.5 blocks of samples at 20 kHz; a displacement
    /// channel Σ aᵢqᵢ and a velocity channel Σ bᵢq̇ᵢ agree at every sample k with
    /// Σ aᵢ[Φᵢ(kT_s)s₀]_q and Σ bᵢ[Φᵢ(kT_s)s₀]_q̇ ([`free_map`] over the whole kT_s) to 1e-13
    /// of their largest value: blocks, their hand-over and the partial last block lose only
    /// rounding.
    #[test]
    fn blocks_are_the_closed_form_free_vibration() {
        let (zeta, ts) = (0.02, 5e-5);
        let omega = [2.0 * std::f64::consts::PI * 80.0, 7.3e3, 5.6e4];
        let (q, v) = ([1e-4, -3e-5, 2e-6], [0.02, 0.5, -0.3]);
        let (a, b) = (vec![1.0, 0.7, -2.0], vec![0.3, -1.1, 0.9]);
        let rows =
            [ChannelRow { a: Some(a.clone()), b: None, d: 0.0 }, ChannelRow { a: None, b: Some(b.clone()), d: 0.0 }];
        let count = 2 * BLOCK + BLOCK / 2;
        let maps = BlockMaps::new(&omega, super::super::ModalDamping::Ratio(zeta), ts);
        let mut out = vec![Vec::new(), Vec::new()];
        free_window((pulp::Arch::new(), Arithmetic::Exact), &[maps.modes()], &q, &v, &rows, &mut out, count);
        let exact = |k: usize| -> (f64, f64) {
            (0..3).fold((0.0, 0.0), |(d, r), i| {
                let m = free_map(omega[i], zeta, k as f64 * ts);
                (d + a[i] * (m[0] * q[i] + m[1] * v[i]), r + b[i] * (m[2] * q[i] + m[3] * v[i]))
            })
        };
        let reference: Vec<(f64, f64)> = (1..=count).map(exact).collect();
        let scale = |f: fn(&(f64, f64)) -> f64| reference.iter().map(|x| f(x).abs()).fold(0.0, f64::max);
        let (sd, sv) = (scale(|x| x.0), scale(|x| x.1));
        assert_eq!(out[0].len(), count);
        for (k, (d, r)) in reference.iter().enumerate() {
            assert!((out[0][k] - d).abs() <= 1e-13 * sd, "sample {k}: {} against {d}", out[0][k]);
            assert!((out[1][k] - r).abs() <= 1e-13 * sv, "sample {k}: {} against {r}", out[1][k]);
        }
    }

    /// A seeded stream of uniforms on [-1, 1) (xorshift64), for test states and coefficients.
    pub(super) fn uniforms() -> impl FnMut() -> f64 {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        }
    }

    /// The fast window against the closed-form free vibration: 40 modes (60 Hz to 9 kHz,
    /// ζ = 1 %) from a state of mixed signs, the last mode rung down to 3e-31 (below 2⁻¹⁰⁰, so
    /// set to rest after the first block), six channels of mixed-sign coefficients (so the
    /// sums cancel; two without a B part, one without an A part, so that the channels are
    /// summed four, two and one at a time), 3.5 blocks at 20 kHz. At every sample each
    /// channel lies within Higham's a-priori bound γₙ₊₂ Σᵢ|cᵢsᵢ| (u = 2⁻²⁴, n its terms) of
    /// the closed form, plus √2·2⁻¹⁰⁰(|Aᵢ| + ωᵢ|Bᵢ|) for the mode at rest and the exact
    /// window's 1e-13 of its largest value for the f64 propagation; it is not the exact
    /// window's result (the f32 sums are in use); and on plain x86-64 it has the same bits as
    /// on the widest instruction set, fused multiply-adds being correctly rounded on both.
    #[test]
    fn fast_sums_lie_within_their_rounding_bound() {
        let (zeta, ts, n, channels) = (0.01, 5e-5, 40, 6);
        let mut uniform = uniforms();
        let omega: Vec<f64> = (0..n).map(|i| 2.0 * std::f64::consts::PI * 60.0 * (1.0 + i as f64 * 3.7)).collect();
        let mut q: Vec<f64> = (0..n).map(|_| 1e-5 * uniform()).collect();
        let mut v: Vec<f64> = omega.iter().map(|w| 1e-5 * w * uniform()).collect();
        (q[n - 1], v[n - 1]) = (3e-31, -3e-31);
        let rows: Vec<ChannelRow> = (0..channels)
            .map(|r| ChannelRow {
                a: (r != 3).then(|| (0..n).map(|_| uniform()).collect()),
                b: (r != 2 && r != 5).then(|| omega.iter().map(|w| uniform() / w).collect()),
                d: 0.0,
            })
            .collect();
        let count = 3 * BLOCK + BLOCK / 2;
        let maps = BlockMaps::new(&omega, super::super::ModalDamping::Ratio(zeta), ts);
        let window = |arch, arithmetic| {
            let mut out = vec![Vec::new(); channels];
            free_window((arch, arithmetic), &[maps.modes()], &q, &v, &rows, &mut out, count);
            out
        };
        let fast = window(pulp::Arch::new(), Arithmetic::Fast);
        let exact = window(pulp::Arch::new(), Arithmetic::Exact);
        let zero = vec![0.0; n];
        for (r, row) in rows.iter().enumerate() {
            let (a, b) = (row.a.as_ref().unwrap_or(&zero), row.b.as_ref().unwrap_or(&zero));
            let terms = usize::from(row.a.is_some()) * n + usize::from(row.b.is_some()) * n;
            // (the sum, Σ|cᵢsᵢ|) at sample k from the closed-form states.
            let closed = |k: usize| -> (f64, f64) {
                (0..n).fold((0.0, 0.0), |(y, s), i| {
                    let m = free_map(omega[i], zeta, k as f64 * ts);
                    let (qk, vk) = (m[0] * q[i] + m[1] * v[i], m[2] * q[i] + m[3] * v[i]);
                    (y + a[i] * qk + b[i] * vk, s + (a[i] * qk).abs() + (b[i] * vk).abs())
                })
            };
            let reference: Vec<(f64, f64)> = (1..=count).map(closed).collect();
            let scale = reference.iter().map(|x| x.0.abs()).fold(0.0, f64::max);
            let rest = std::f64::consts::SQRT_2 * 2f64.powi(-100) * (a[n - 1].abs() + omega[n - 1] * b[n - 1].abs());
            let gamma = Arithmetic::Fast.gamma(terms + 2);
            for (k, (y, s)) in reference.iter().enumerate() {
                let bound = gamma * s + rest + 1e-13 * scale;
                let got = fast[r][k];
                assert!((got - y).abs() <= bound, "channel {r}, sample {k}: {got} against {y}, bound {bound:e}");
            }
        }
        assert_ne!(fast, exact, "the fast window summed in f64");
        assert_eq!(fast, window(pulp::Arch::Scalar, Arithmetic::Fast), "plain x86-64 against the widest");
    }
}
