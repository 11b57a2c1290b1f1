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
//! propagated, as [`super::free_window`] propagates it. The sums run in f64, each product
//! then each sum (no fused multiply-adds), so a sample has the same bits on every
//! processor; they are the same sums as [`super::free_window`]'s in another association, so
//! the two agree to rounding (γ₄ₙ Σᵢ(|Eᶜᵢq| + |Fᶜᵢq̇|) and its own, Higham 2002, eq. 3.5).

use super::sums::Aligned;
use super::{Block, BLOCK};
use crate::reduced::target::ChannelRow;

/// Every channel's maps over a block, channel-major: `e[c * n + i]` is Eᶜᵢ over the block's
/// samples (module docs), n the modes.
#[derive(Debug, Clone)]
pub(crate) struct OutputMaps {
    modes: usize,
    e: Vec<Block>,
    f: Vec<Block>,
}

impl OutputMaps {
    /// The maps of the channels `rows` (A and B by mode, None where zero) through the modes'
    /// block maps `maps`.
    pub(crate) fn new(maps: &[[Block; 4]], rows: &[ChannelRow]) -> Self {
        let n = maps.len();
        let zero = Aligned([0.0; BLOCK]);
        let (mut e, mut f) = (vec![zero; rows.len() * n], vec![zero; rows.len() * n]);
        for (c, row) in rows.iter().enumerate() {
            for (i, [qq, qv, vq, vv]) in maps.iter().enumerate() {
                let a = row.a.as_ref().map_or(0.0, |a| a.get(i).copied().unwrap_or(0.0));
                let b = row.b.as_ref().map_or(0.0, |b| b.get(i).copied().unwrap_or(0.0));
                for j in 0..BLOCK {
                    e[c * n + i].0[j] = a * qq.0[j] + b * vq.0[j];
                    f[c * n + i].0[j] = a * qv.0[j] + b * vv.0[j];
                }
            }
        }
        Self { modes: n, e, f }
    }

    /// Appends `count` samples to every channel of `out`, the modes free from the state
    /// (`q`, `v`) at the sample before the first, their block maps `maps` (those the maps
    /// were formed with); on the instruction set `simd` (the same operations in the same
    /// order on every one).
    pub(crate) fn window(
        &self,
        simd: pulp::Arch,
        maps: &[[Block; 4]],
        (q, v): (&[f64], &[f64]),
        out: &mut [Vec<f64>],
        count: usize,
    ) {
        simd.dispatch(Samples { maps: self, block_maps: maps, q, v, out, count });
    }
}

/// [`OutputMaps::window`]'s arguments.
struct Samples<'a, 'b> {
    maps: &'a OutputMaps,
    block_maps: &'a [[Block; 4]],
    q: &'a [f64],
    v: &'a [f64],
    out: &'b mut [Vec<f64>],
    count: usize,
}

impl pulp::WithSimd for Samples<'_, '_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        let Samples { maps, block_maps, q, v, out, count } = self;
        let n = maps.modes.min(q.len()).min(block_maps.len());
        let (mut q0, mut v0) = (q[..n].to_vec(), v[..n].to_vec());
        let channels = out.len();
        let mut done = 0;
        while done < count {
            let m = BLOCK.min(count - done);
            let mut c = 0;
            // Two channels together: independent chains of sums over the same states.
            while c + 1 < channels {
                let [y0, y1] = block_pair(maps, (c, c + 1), (&q0, &v0));
                out[c].extend_from_slice(&y0[..m]);
                out[c + 1].extend_from_slice(&y1[..m]);
                c += 2;
            }
            if c < channels {
                let y = block_one(maps, c, (&q0, &v0));
                out[c].extend_from_slice(&y[..m]);
            }
            for ((p, q0), v0) in block_maps[..n].iter().zip(&mut q0).zip(&mut v0) {
                let [p0, p1, p2, p3] = p;
                let l = BLOCK - 1;
                (*q0, *v0) = (p0.0[l] * *q0 + p1.0[l] * *v0, p2.0[l] * *q0 + p3.0[l] * *v0);
            }
            done += m;
        }
    }
}

/// Channels `c0` and `c1`'s samples over one block from the state (`q`, `v`) before it:
/// y[j] = Σᵢ (Eᵢ[j] qᵢ + Fᵢ[j] q̇ᵢ), i in order.
#[inline(always)]
fn block_pair(maps: &OutputMaps, (c0, c1): (usize, usize), (q, v): (&[f64], &[f64])) -> [[f64; BLOCK]; 2] {
    let n = q.len();
    let (e0, f0) = (&maps.e[c0 * maps.modes..][..n], &maps.f[c0 * maps.modes..][..n]);
    let (e1, f1) = (&maps.e[c1 * maps.modes..][..n], &maps.f[c1 * maps.modes..][..n]);
    let (mut y0, mut y1) = ([0.0; BLOCK], [0.0; BLOCK]);
    for i in 0..n {
        let (qi, vi) = (q[i], v[i]);
        let (a0, b0, a1, b1) = (&e0[i].0, &f0[i].0, &e1[i].0, &f1[i].0);
        for j in 0..BLOCK {
            y0[j] = y0[j] + a0[j] * qi;
            y0[j] = y0[j] + b0[j] * vi;
            y1[j] = y1[j] + a1[j] * qi;
            y1[j] = y1[j] + b1[j] * vi;
        }
    }
    [y0, y1]
}

/// Channel `c`'s samples over one block, as [`block_pair`] forms each of its two.
#[inline(always)]
fn block_one(maps: &OutputMaps, c: usize, (q, v): (&[f64], &[f64])) -> [f64; BLOCK] {
    let n = q.len();
    let (e, f) = (&maps.e[c * maps.modes..][..n], &maps.f[c * maps.modes..][..n]);
    let mut y = [0.0; BLOCK];
    for i in 0..n {
        let (qi, vi, a, b) = (q[i], v[i], &e[i].0, &f[i].0);
        for j in 0..BLOCK {
            y[j] = y[j] + a[j] * qi;
            y[j] = y[j] + b[j] * vi;
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

    /// Against the closed-form free vibration: four modes (80 Hz to 9 kHz, ζ = 2 %) from a
    /// given state, 2.5 blocks at 20 kHz, three channels (A alone, B alone, both: two summed
    /// as a pair, one alone). Every sample lies within 1e-13 of the channel's largest value of
    /// Σᵢ Aᵢ[Φᵢ(kT_s)s₀]_q + Bᵢ[Φᵢ(kT_s)s₀]_q̇ ([`free_map`] over the whole kT_s): the maps
    /// formed per block, the blocks' hand-over and the partial last block lose only rounding.
    #[test]
    fn output_maps_are_the_closed_form_free_vibration() {
        let (zeta, ts) = (0.02, 5e-5);
        let omega = [2.0 * std::f64::consts::PI * 80.0, 7.3e3, 2.1e4, 5.6e4];
        let (q, v) = ([1e-4, -3e-5, 4e-6, 2e-6], [0.02, 0.5, -0.1, -0.3]);
        let a = vec![1.0, 0.7, -0.4, -2.0];
        let b = vec![0.3, -1.1, 0.2, 0.9];
        let rows = [
            ChannelRow { a: Some(a.clone()), b: None, d: 0.0 },
            ChannelRow { a: None, b: Some(b.clone()), d: 0.0 },
            ChannelRow { a: Some(a.clone()), b: Some(b.clone()), d: 0.0 },
        ];
        let count = 2 * BLOCK + BLOCK / 2;
        let maps = BlockMaps::new(&omega, ModalDamping::Ratio(zeta), ts);
        let mut out = vec![Vec::new(); 3];
        OutputMaps::new(maps.modes(), &rows).window(pulp::Arch::new(), maps.modes(), (&q, &v), &mut out, count);
        let closed = |k: usize, (ca, cb): (&[f64], &[f64])| -> f64 {
            (0..omega.len())
                .map(|i| {
                    let m = free_map(omega[i], zeta, k as f64 * ts);
                    ca[i] * (m[0] * q[i] + m[1] * v[i]) + cb[i] * (m[2] * q[i] + m[3] * v[i])
                })
                .sum()
        };
        let zero = vec![0.0; omega.len()];
        for (c, (ca, cb)) in [(&a, &zero), (&zero, &b), (&a, &b)].into_iter().enumerate() {
            let reference: Vec<f64> = (1..=count).map(|k| closed(k, (ca, cb))).collect();
            let scale = reference.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            assert_eq!(out[c].len(), count);
            for (k, y) in reference.iter().enumerate() {
                assert!((out[c][k] - y).abs() <= 1e-13 * scale, "channel {c}, sample {k}: {} against {y}", out[c][k]);
            }
        }
        let mut scalar = vec![Vec::new(); 3];
        OutputMaps::new(maps.modes(), &rows).window(pulp::Arch::Scalar, maps.modes(), (&q, &v), &mut scalar, count);
        assert_eq!(out, scalar, "plain x86-64 against the widest instruction set");
    }
}
