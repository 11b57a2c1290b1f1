//! Main contacts and chatter. A sphere struck again by a ringing plate can touch it many times
//! in quick succession with almost no impulse; how many such micro-contacts a run finds
//! depends on the mesh, the modes and the step (a bare contact count is not a property of the
//! impact), while the contacts that carry a real share of the momentum, and the final
//! velocity, are stable. The impact's contacts are therefore those whose impulse is at least a
//! stated share of m·v₀; the rest are counted with their total impulse.

use super::Contact;
use serde::Serialize;

/// The default share of m·v₀ a contact's impulse must reach to count as one of the impact's
/// main contacts (5 %).
pub const MAIN_CONTACT_SHARE: f64 = 0.05;

/// The contacts of an impact split by impulse.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactSplit {
    /// Contacts with an impulse of at least the share of m·v₀.
    pub main: usize,
    /// The others.
    pub micro: usize,
    /// The micro-contacts' total impulse, N·s.
    pub micro_impulse: f64,
}

/// Splits `contacts` at `share` of the sphere's momentum `momentum` = m·v₀ (N·s).
///
/// ```
/// use coupled::transient::chatter::split;
/// use coupled::transient::Contact;
/// let c = |impulse: f64| Contact { start: 0.0, duration: 1e-3, peak_force: 1.0, impulse, rebound_velocity: 0.0, steps: 10 };
/// let s = split(&[c(0.9), c(0.01), c(0.2), c(0.002)], 1.0, 0.05);
/// assert_eq!((s.main, s.micro), (2, 2));
/// assert!((s.micro_impulse - 0.012).abs() < 1e-15);
/// ```
pub fn split(contacts: &[Contact], momentum: f64, share: f64) -> ContactSplit {
    let threshold = share * momentum.abs();
    let micro: Vec<&Contact> = contacts.iter().filter(|c| c.impulse < threshold).collect();
    ContactSplit {
        main: contacts.len() - micro.len(),
        micro: micro.len(),
        micro_impulse: micro.iter().map(|c| c.impulse).sum(),
    }
}
