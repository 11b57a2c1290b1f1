//! How a long computation tells its caller how far it is, without knowing whether anyone is
//! watching: a terminal bar, a log line every few seconds, a Python callback or nothing.

/// Progress of a computation in counted steps (cases, runs, impacts). Shared (`&self`,
/// `Sync`) because the steps of an ensemble finish on several threads at once.
///
/// ```
/// use studies::progress::{Progress, Silent};
/// fn work(p: &dyn Progress) {
///     p.start(3, "cases");
///     for _ in 0..3 {
///         p.advance(1);
///     }
///     p.finish();
/// }
/// work(&Silent);
/// ```
pub trait Progress: Sync {
    /// A stage of `len` steps named `what` begins.
    fn start(&self, len: usize, what: &str);
    /// `n` more steps of the current stage are done.
    fn advance(&self, n: usize);
    /// The current stage is done.
    fn finish(&self) {}
}

/// Progress nobody watches.
#[derive(Debug, Default, Clone, Copy)]
pub struct Silent;

impl Progress for Silent {
    fn start(&self, _len: usize, _what: &str) {}
    fn advance(&self, _n: usize) {}
}
