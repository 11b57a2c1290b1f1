//! The contact laws of the transient model, one file each behind one trait, [`Law`], and one
//! registry, [`LawKind::ALL`]: Hertz (elastic), Flores (eqs. 1-2, the paper's, elastic with
//! hysteretic damping) and Thornton's elastic-perfectly-plastic law.
//!
//! A law gives the contact force P(δ, δ̇) ≥ 0 on loading (δ at its largest so far) and on
//! unloading (below the largest compression δ_m, the contact's only memory), the elastic
//! energy it holds at δ (what unloading from δ would return, so that the run's energy
//! balance can tell stored from dissipated work), the permanent compression δ_p it leaves
//! (where a plastic contact opens again), and whether it stores every bit of work done on
//! it. The integrators need nothing more: within a Newmark step the contact solve
//! ([`super::contact::contact_force_after`]) brackets the root of h(P) = P - F(δ(P), δ̇(P))
//! by false position, which needs the force alone (no tangent stiffness), provided that F
//! is continuous and nondecreasing in δ and in δ̇ (then h is increasing and its root
//! unique). Every law here is; a new one must be too.
//!
//! **Adding a law** is one file in this directory, a type implementing [`Law`], declared by
//! one `mod` line and one line of the `registry!` call below. The registry makes the
//! [`ContactLaw`] variant that carries the law in a [`super::Striker`] (an enum, so that the
//! striker stays `Copy` and the hot loop dispatches on a predictable branch rather than
//! through a pointer), the [`LawKind`] a scene names, and every dispatching `match`. The
//! scene parser, the reports and the Python package read the names from [`LawKind::ALL`].
//!
//! ```
//! use coupled::transient::law::{LawKind, Thornton};
//! use coupled::transient::ContactLaw;
//! // Scene files name a law by its key; the registry lists them in the reports' order.
//! let keys: Vec<&str> = LawKind::ALL.iter().map(|l| l.key()).collect();
//! assert_eq!(keys, ["hertz", "flores", "thornton"]);
//! let kind = LawKind::from_key("thornton").unwrap();
//! assert!(!kind.is_elastic());
//! // The law's parameters come from the rock: Thornton's limiting pressure from its strength.
//! let body = analytic::Sphere::new(
//!     "coal", 1380.0, 0.025,
//!     analytic::Elastic::new(2.26e9, 0.28).unwrap(),
//!     analytic::RockStrength::new(8.39e6, 25.0).unwrap(),
//! ).unwrap();
//! let ContactLaw::Thornton(t) = kind.law_for(&body) else { unreachable!() };
//! assert_eq!(t.radius, 0.025);
//! ```

pub mod flores;
pub mod hertz;
pub mod thornton;

use analytic::Sphere;
use serde::{Serialize, Serializer};

/// What a law's force may depend on besides δ and δ̇: the striker's constants and the
/// contact's history.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactState {
    /// Contact stiffness K (eq. 3), N/m^{3/2}.
    pub k: f64,
    /// Restitution e (the Flores law's damping).
    pub restitution: f64,
    /// The approach velocity δ̇⁻ > 0 of this contact (the scale of the Flores law's damping),
    /// m/s: the impact velocity v₀ for the first contact, the relative normal velocity at
    /// touch for a later one.
    pub velocity: f64,
    /// The largest compression so far δ_m, m: loading while δ ≥ δ_m, unloading below.
    pub max_compression: f64,
}

/// A contact law: its force on loading and unloading, its stored energy and its permanent
/// compression, as functions of the compression δ > 0 (the wrappers [`Law::force`] and
/// [`Law::stored_energy`] give zero at δ ≤ 0: no adhesion), the rate δ̇ and the
/// [`ContactState`]. The force must be continuous and nondecreasing in δ and δ̇ (see the
/// module). A toy law, a linear spring P = Kδ, evaluated:
///
/// ```
/// use analytic::Sphere;
/// use coupled::transient::law::{ContactState, Law};
///
/// /// A linear spring, P = Kδ with K in N/m: elastic, no damping, no history.
/// #[derive(Clone, Copy)]
/// struct Spring;
///
/// impl Law for Spring {
///     const KEY: &'static str = "spring";
///     const NAME: &'static str = "a linear spring";
///     const ELASTIC: bool = true;
///     fn for_body(_: &Sphere) -> Self {
///         Spring
///     }
///     fn loading(&self, c: &ContactState, delta: f64, _rate: f64) -> f64 {
///         c.k * delta
///     }
///     fn energy(&self, c: &ContactState, delta: f64) -> f64 {
///         0.5 * c.k * delta * delta
///     }
///     fn conserves(&self, _: &ContactState) -> bool {
///         true
///     }
/// }
///
/// // δ = 2⁻¹⁰ m so that every product below is exact.
/// let delta = 1.0 / 1024.0;
/// let c = ContactState { k: 1.0e6, restitution: 1.0, velocity: 0.5, max_compression: delta };
/// assert_eq!(Spring.force(&c, delta, 0.3), 1.0e6 / 1024.0);
/// // Unloading defaults to the loading curve: an elastic law has no memory.
/// assert_eq!(Spring.force(&c, 0.5 * delta, -0.3), 0.5e6 / 1024.0);
/// assert_eq!(Spring.force(&c, -delta, 0.3), 0.0);
/// assert_eq!(Spring.stored_energy(&c, delta), 0.5e6 / (1024.0 * 1024.0));
/// assert_eq!(Spring.permanent_set(&c), 0.0);
/// ```
pub trait Law {
    /// The name in scene files (`contact_law = "..."`) and in the reports' tables.
    const KEY: &'static str;
    /// The name in the reports' prose.
    const NAME: &'static str;
    /// Whether the law assumes an elastic rock, so that compressions beyond the paper's
    /// yield onset δ_my (eq. 51) leave its range and the results are flagged.
    const ELASTIC: bool;

    /// The law for the rock sphere `body` (its parameters from the rock's properties).
    fn for_body(body: &Sphere) -> Self
    where
        Self: Sized;

    /// The force on loading, δ > 0 and δ ≥ δ_m, never negative (no adhesion).
    fn loading(&self, c: &ContactState, delta: f64, rate: f64) -> f64;

    /// The force on unloading, 0 < δ < δ_m, never negative: the loading curve unless the
    /// law has a memory.
    fn unloading(&self, c: &ContactState, delta: f64, rate: f64) -> f64 {
        self.loading(c, delta, rate)
    }

    /// The elastic energy held at δ > 0 after the largest compression δ_m of `c` (what
    /// unloading from δ would return).
    fn energy(&self, c: &ContactState, delta: f64) -> f64;

    /// The permanent compression δ_p left by δ_m (zero for an elastic law): the contact
    /// opens at δ = δ_p.
    fn permanent_set(&self, c: &ContactState) -> f64 {
        let _ = c;
        0.0
    }

    /// Whether the law stores all the work done on it (no damping, no plastic flow)
    /// whatever the compression, so that the run's energy error can be measured.
    fn conserves(&self, c: &ContactState) -> bool;

    /// The force at δ, δ̇: zero at δ ≤ 0, else loading or unloading by δ against δ_m.
    fn force(&self, c: &ContactState, delta: f64, rate: f64) -> f64 {
        if delta <= 0.0 {
            0.0
        } else if delta >= c.max_compression {
            self.loading(c, delta, rate)
        } else {
            self.unloading(c, delta, rate)
        }
    }

    /// The elastic energy at δ: zero at δ ≤ 0, else [`Law::energy`].
    fn stored_energy(&self, c: &ContactState, delta: f64) -> f64 {
        if delta <= 0.0 {
            0.0
        } else {
            self.energy(c, delta)
        }
    }
}

/// Declares the registry from its list of `module::Type` laws: the law types re-exported
/// here, [`ContactLaw`] (one variant per law, holding it), [`LawKind`] (one per law, without
/// parameters), [`LawKind::ALL`] in the order given, and every `match` that dispatches to
/// the laws, written once here for all of them.
macro_rules! registry {
    ($($module:ident::$law:ident),+ $(,)?) => {
        $(pub use $module::$law;)+

        /// A contact law with its parameters (K, e and v₀ are the striker's): one variant
        /// per law of the registry, holding it.
        #[derive(Debug, Clone, Copy, PartialEq, Serialize)]
        pub enum ContactLaw {
            $(#[doc = concat!("[`", stringify!($law), "`].")] $law($law),)+
        }

        /// Which contact law a scene asks for: one variant per law of the registry.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum LawKind {
            $(#[doc = concat!("[`", stringify!($law), "`].")] $law,)+
        }

        impl LawKind {
            /// The registry: every law, in the order the reports list them.
            pub const ALL: &'static [LawKind] = &[$(LawKind::$law),+];

            /// The name in scene files and tables, [`Law::KEY`].
            pub fn key(self) -> &'static str {
                match self { $(LawKind::$law => <$law as Law>::KEY,)+ }
            }

            /// The name in prose, [`Law::NAME`].
            pub fn name(self) -> &'static str {
                match self { $(LawKind::$law => <$law as Law>::NAME,)+ }
            }

            /// Whether the law assumes an elastic rock, [`Law::ELASTIC`].
            pub fn is_elastic(self) -> bool {
                match self { $(LawKind::$law => <$law as Law>::ELASTIC,)+ }
            }

            /// The law for `body`, [`Law::for_body`].
            pub fn law_for(self, body: &Sphere) -> ContactLaw {
                match self { $(LawKind::$law => ContactLaw::$law(<$law as Law>::for_body(body)),)+ }
            }
        }

        impl ContactLaw {
            /// Which law this is.
            pub fn kind(&self) -> LawKind {
                match self { $(ContactLaw::$law(_) => LawKind::$law,)+ }
            }

            /// [`Law::force`] of the law held.
            #[inline]
            pub fn force(&self, c: &ContactState, delta: f64, rate: f64) -> f64 {
                match self { $(ContactLaw::$law(l) => l.force(c, delta, rate),)+ }
            }

            /// [`Law::stored_energy`] of the law held.
            #[inline]
            pub fn stored_energy(&self, c: &ContactState, delta: f64) -> f64 {
                match self { $(ContactLaw::$law(l) => l.stored_energy(c, delta),)+ }
            }

            /// [`Law::permanent_set`] of the law held.
            #[inline]
            pub fn permanent_set(&self, c: &ContactState) -> f64 {
                match self { $(ContactLaw::$law(l) => l.permanent_set(c),)+ }
            }

            /// [`Law::conserves`] of the law held.
            pub fn conserves(&self, c: &ContactState) -> bool {
                match self { $(ContactLaw::$law(l) => l.conserves(c),)+ }
            }
        }

        $(impl From<$law> for ContactLaw {
            fn from(law: $law) -> Self {
                ContactLaw::$law(law)
            }
        })+
    };
}

registry! {
    hertz::Hertz,
    flores::Flores,
    thornton::Thornton,
}

impl LawKind {
    /// The law a scene file names by `key`, if any.
    pub fn from_key(key: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|l| l.key() == key)
    }
}

/// The paper's law, Flores (eqs. 1-2).
impl Default for LawKind {
    fn default() -> Self {
        LawKind::Flores
    }
}

/// The paper's law, Flores (eqs. 1-2).
impl Default for ContactLaw {
    fn default() -> Self {
        ContactLaw::Flores(Flores)
    }
}

/// As its key, the name scene files use.
impl Serialize for LawKind {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.key())
    }
}

impl ContactLaw {
    /// Whether the law assumes an elastic rock, [`Law::ELASTIC`].
    pub fn is_elastic(&self) -> bool {
        self.kind().is_elastic()
    }
}
