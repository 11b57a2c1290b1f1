//! [`super::Arithmetic::Fast`]'s window: the modes propagated in f64 as in the exact window
//! (but with fused multiply-adds), their block of states rounded once to f32, and every
//! channel's sum over the modes formed in f32 with fused multiply-adds. The error bound is in
//! the parent module's documentation.
//!
//! A mode that has rung down (between the lumps of a stream the highest modes decay by
//! e^(-ζωt), below 10⁻³⁰ of their amplitude within a tenth of a second) would reach f32's
//! subnormal range, where every multiply-add on it takes a microcode assist on x86-64 and
//! costs tens of times a normal one. A mode whose q and q̇ both fall below [`FLUSH`] = 2⁻¹⁰⁰ at
//! a block's end is therefore set to rest for the rest of the window (zeros stay zeros). A damped
//! mode's energy E = (q̇² + ω²q²)/2 never grows (Ė = -2ζωq̇² ≤ 0, any ζ ≥ 0), so from such a
//! state |q(t)| ≤ √(q₀² + q̇₀²/ω²) ≤ √2·2⁻¹⁰⁰ and |q̇(t)| ≤ √2·ω·2⁻¹⁰⁰ for ω ≥ 1 rad/s at all
//! later t: a channel loses at most √2·2⁻¹⁰⁰(|Aᵢ| + ωᵢ|Bᵢ|) for each mode set to rest, 10⁻³⁰ m
//! of modal amplitude, far below any sensor's resolution.

use super::sums::Aligned;
use super::{Block, Stored, BLOCK};
use std::borrow::Cow;

/// A mode whose state (q, q̇) at a block's end is below this in both is set to rest for the
/// rest of the window: 2⁻¹⁰⁰ ≈ 7.9e-31.
const FLUSH: f64 = 7.888_609_052_210_118e-31;

/// The fast arithmetic: states propagated in f64 with fused multiply-adds and stored in f32,
/// the channels' sums in f32 with fused multiply-adds.
impl Stored for f32 {
    /// Returns the block's last state in f64 (which starts the next block), or rest when it
    /// has rung down below [`FLUSH`].
    #[inline(always)]
    fn propagate(maps: &[Block; 4], (q0, v0): (f64, f64), q: &mut Aligned<f32>, v: &mut Aligned<f32>) -> (f64, f64) {
        let [p0, p1, p2, p3] = maps;
        let mut qd = [0.0f64; BLOCK];
        let mut vd = [0.0f64; BLOCK];
        for j in 0..BLOCK {
            qd[j] = p0.0[j].mul_add(q0, p1.0[j] * v0);
            vd[j] = p2.0[j].mul_add(q0, p3.0[j] * v0);
        }
        for j in 0..BLOCK {
            q.0[j] = qd[j] as f32;
            v.0[j] = vd[j] as f32;
        }
        let end = (qd[BLOCK - 1], vd[BLOCK - 1]);
        if end.0.abs() < FLUSH && end.1.abs() < FLUSH {
            (0.0, 0.0)
        } else {
            end
        }
    }

    /// The block's last state as [`Stored::propagate`] forms it, set to rest below [`FLUSH`].
    #[inline(always)]
    fn block_end(maps: &[Block; 4], (q0, v0): (f64, f64)) -> (f64, f64) {
        let ([p0, p1, p2, p3], l) = (maps, BLOCK - 1);
        let end = (p0.0[l].mul_add(q0, p1.0[l] * v0), p2.0[l].mul_add(q0, p3.0[l] * v0));
        if end.0.abs() < FLUSH && end.1.abs() < FLUSH {
            (0.0, 0.0)
        } else {
            end
        }
    }

    #[inline(always)]
    fn narrow(x: f64) -> Self {
        x as f32
    }

    fn coefficients(c: &[f64]) -> Cow<'_, [f32]> {
        Cow::Owned(c.iter().map(|&x| x as f32).collect())
    }

    #[inline(always)]
    fn widen(self) -> f64 {
        f64::from(self)
    }
}
