//! What the benches share: the least disturbed of repeated wall-clock timings, printed
//! beside criterion's statistics as a ratio against a reference timed in the same run.

use std::time::Instant;

/// The shortest of five runs of `f`, s: on a shared machine the least disturbed.
pub fn best_of_five(f: &dyn Fn()) -> f64 {
    (0..5)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}
