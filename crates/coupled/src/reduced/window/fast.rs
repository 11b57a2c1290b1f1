//! [`super::Arithmetic::Fast`]'s window: the modes propagated in f64 as in the exact window
//! (but with fused multiply-adds), their block of states rounded once to f32, and every
//! channel's sum over the modes formed in f32 with fused multiply-adds. The error bound is in
//! the parent module's documentation.
//!
//! A mode that has rung down (between the lumps of a stream the highest modes decay by
//! e^(-ζωt), below 10⁻³⁰ of their amplitude within a tenth of a second) would reach f32's
//! subnormal range, where every multiply-add on it takes a microcode assist on x86-64 and
//! costs tens of times a normal one. A mode whose q and q̇ both fall below [`FLUSH`] = 2⁻¹⁰⁰ at
//! a block's end is therefore set to rest for the rest of the window (zeros stay zeros). From
//! such a state, for ω ≥ 1 rad/s and ζ ≤ 1/2, |q(t)| ≤ |q₀|(1 + ζ/√(1-ζ²)) + |q̇₀|/ω_d ≤ 3·2⁻¹⁰⁰
//! and |q̇(t)| ≤ 3ω·2⁻¹⁰⁰ for all later t, so a channel loses at most 3·2⁻¹⁰⁰(|Aᵢ| + ωᵢ|Bᵢ|)
//! for each mode set to rest: 10⁻³⁰ m of modal amplitude, far below any sensor's resolution.

use super::super::target::ChannelRow;
use super::sums::{Aligned, Parts};
use super::{Block, BLOCK};

/// One mode's f32 values over a block of samples.
type Block32 = Aligned<f32>;

/// A channel's coefficients rounded to f32: A on q, B on q̇.
struct Row32 {
    a: Option<Vec<f32>>,
    b: Option<Vec<f32>>,
}

impl Row32 {
    fn new(row: &ChannelRow) -> Self {
        let round = |c: &Vec<f64>| c.iter().map(|&x| x as f32).collect();
        Self { a: row.a.as_ref().map(round), b: row.b.as_ref().map(round) }
    }
}

/// [`super::free_window`]'s arguments.
pub(super) struct Window<'a, 'b> {
    pub maps: &'a [&'a [[Block; 4]]],
    pub q: &'a [f64],
    pub v: &'a [f64],
    pub rows: &'a [ChannelRow],
    pub out: &'b mut [Vec<f64>],
    pub count: usize,
}

impl pulp::WithSimd for Window<'_, '_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        let Window { maps, q, v, rows, out, count } = self;
        let n = q.len();
        let rows: Vec<Row32> = rows.iter().map(Row32::new).collect();
        let (mut q0, mut v0) = (q.to_vec(), v.to_vec());
        let (mut qs, mut vs) = (vec![Aligned([0.0; BLOCK]); n], vec![Aligned([0.0; BLOCK]); n]);
        let parts = Parts::new(rows.iter().map(|r| (r.a.as_deref(), r.b.as_deref())));
        let mut y = vec![[0.0f32; BLOCK]; rows.len()];
        let mut done = 0;
        while done < count {
            let m = BLOCK.min(count - done);
            let modes = maps.iter().flat_map(|m| m.iter());
            for (((p, (qb, vb)), q0), v0) in modes.zip(qs.iter_mut().zip(vs.iter_mut())).zip(&mut q0).zip(&mut v0) {
                (*q0, *v0) = propagate(p, (*q0, *v0), qb, vb);
                if q0.abs() < FLUSH && v0.abs() < FLUSH {
                    (*q0, *v0) = (0.0, 0.0);
                }
            }
            parts.block(&qs, &vs, &mut y);
            for (y, o) in y.iter().zip(out.iter_mut()) {
                o.extend(y[..m].iter().map(|&x| f64::from(x)));
            }
            done += m;
        }
    }
}

/// A mode whose state (q, q̇) at a block's end is below this in both is set to rest for the
/// rest of the window: 2⁻¹⁰⁰ ≈ 7.9e-31.
const FLUSH: f64 = 7.888_609_052_210_118e-31;

/// One mode's block: `(q[j], q̇[j]) = Φ((j + 1)T_s)(q₀, q̇₀)` in f64 with fused multiply-adds,
/// stored rounded to f32; returns the block's last state in f64, which starts the next block.
#[inline(always)]
fn propagate(maps: &[Block; 4], (q0, v0): (f64, f64), q: &mut Block32, v: &mut Block32) -> (f64, f64) {
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
    (qd[BLOCK - 1], vd[BLOCK - 1])
}
