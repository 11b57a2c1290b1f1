//! The free stretches of a stream: samples where no lump is followed, and sample intervals in
//! which the lumps followed are in flight and none can touch.

use super::envelope::lowest_deflection;
use super::Run;
use crate::reduced::signals::{dot, free_map};

impl Run<'_> {
    /// `count` samples of free vibration from the current sample.
    pub(super) fn free(&mut self, count: usize) {
        if count == 0 {
            return;
        }
        let m = self.model;
        let maps = self.probes.block_maps.modes();
        self.output.window(m.passes().0, maps, (&self.q, &self.v), &mut self.out, count);
        let zeta = m.damping();
        let tau = count as f64 * self.probes.spec.interval();
        for (i, &w) in m.omega().iter().enumerate() {
            let f = free_map(w, zeta.at(w), tau);
            let (q, v) = (self.q[i], self.v[i]);
            self.q[i] = f[0] * q + f[1] * v;
            self.v[i] = f[2] * q + f[3] * v;
        }
    }

    /// Whether no lump can touch within the next sample interval, no force acting and the
    /// modes' exact state at the interval's end in the scratch: each sphere's flight over it,
    /// less the permanent set δ_p its law opens at, stays below the lowest the plate's free
    /// deflection at its point reaches in it ([`lowest_deflection`]), so that δ ≤ δ_p.
    pub(super) fn clear_interval(&self) -> bool {
        let ts = self.probes.spec.interval();
        let (start, end) = ((&self.q[..], &self.v[..]), (&self.scratch.qh[..], &self.scratch.vh[..]));
        self.active
            .iter()
            .all(|l| l.highest(ts) - l.opens_at() < lowest_deflection(&l.phi, start, end, &self.half_period))
    }

    /// A sample interval free of force, the modes' exact map over T_s already in the scratch:
    /// every sphere on its flight (which Newmark's rule follows exactly under a constant body
    /// force), and the sample at its end.
    pub(super) fn free_interval(&mut self) {
        let ts = self.probes.spec.interval();
        let w = &mut self.scratch;
        std::mem::swap(&mut self.q, &mut w.qh);
        std::mem::swap(&mut self.v, &mut w.vh);
        for l in &mut self.active {
            let g = l.striker.gravity;
            l.u += l.v * ts + 0.5 * g * ts * ts;
            l.v += g * ts;
            l.a = g;
            l.res_v = 0.0;
            l.w_cross = 0.0;
            l.time += ts;
            l.last = (l.u - dot(&l.phi, &self.q), l.v - dot(&l.phi, &self.v));
        }
        for (row, o) in self.rows.iter().zip(self.out.iter_mut()) {
            let a = row.a.as_ref().map_or(0.0, |a| dot(a, &self.q));
            let b = row.b.as_ref().map_or(0.0, |b| dot(b, &self.v));
            o.push(a + b);
        }
    }
}
