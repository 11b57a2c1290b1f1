//! # Coal-gangue identification over random impact ensembles
//!
//! The paper closes (section IV.D) by asserting that coal and gangue can be told apart from
//! the support's response when they strike it. This crate turns that claim into a
//! measurement: draw many random impacts (positions, sizes, speeds, material spread), reduce
//! each sensor signal to a few features, and ask how well each feature at each sensor
//! separates coal from gangue (ROC AUC with its uncertainty) and how well a classifier on
//! a sensor's features does (cross-validated accuracy). It knows nothing of plates or files:
//! the signals come from the caller (the reduced-order model of crate `coupled`).
//!
//! It reads top-down:
//! - [`distribution`]: laws of one variable (uniform, normal, lognormal, Rosin-Rammler,
//!   choice), truncated and sampled by inverse transform;
//! - [`ensemble`]: the random-impact description, each impact drawn from its own seeded
//!   stream (bit-identical on any number of threads), and an ordered parallel runner;
//! - [`features`]: the features of a sampled signal, one implementation each of a small
//!   trait and one registry (peak, RMS, energy, duration, dominant frequency, spectral
//!   centroid);
//! - [`stream`]: a continuous caving stream: Poisson arrivals marked coal or gangue by a
//!   time profile of the gangue share, each lump drawn as an ensemble impact;
//! - [`detect`]: gangue detection over sliding windows of a stream: the windows' truth,
//!   cross-validation by time blocks, and the operating answer (delay from the onset of the
//!   change, false alarms per hour);
//! - [`detector`]: a trained window detector saved as JSON and applied to a new recording;
//! - [`recording`]: a recorded signal (a JSON sidecar beside a CSV) as the detector reads it;
//! - [`roc`]: the AUC (Mann-Whitney), DeLong's standard error and a bootstrap interval;
//! - [`classify`]: a ridge logistic regression fitted by Newton/IRLS and its stratified
//!   cross-validated accuracy;
//! - [`measurement`]: the measurement chain between the plate and a feature (the sensor's
//!   band, the anti-aliasing filter, the sampler, a seeded background of a PSD and tonal
//!   lines, the ADC), and Welch's PSD estimate;
//! - [`subsample`]: a stratified random subsample of an ensemble, and how well the change
//!   of an AUC measured on it stands for the whole ensemble's;
//! - [`placement`]: the features of an ensemble as columns, the AUC of every channel and
//!   feature, the best sensor, and placement maps.
//!
//! ```
//! use identify::distribution::Distribution;
//! use identify::ensemble::{Class, Ensemble, Family, Held, Region, Speed};
//! use identify::features::Extractor;
//! use identify::placement::{best, separabilities, FeatureTable};
//!
//! let family = |name: &str, class, density: f64| Family {
//!     name: name.into(),
//!     class,
//!     count: 50,
//!     density: Distribution::Normal { mean: density, sd: 0.05 * density, min: 0.8 * density, max: 1.2 * density },
//!     youngs_modulus: Distribution::Fixed { value: 2.26e9 },
//!     poisson_ratio: Distribution::Fixed { value: 0.28 },
//!     cohesion: Distribution::Fixed { value: 8.39e6 },
//!     friction_angle_deg: Distribution::Fixed { value: 25.0 },
//!     radius: Distribution::LogNormal { median: 0.025, sigma_log: 0.1, min: 0.01, max: 0.06 },
//! };
//! let stream = Ensemble {
//!     region: Region { x: (0.0, 0.4584), z: (0.0, 0.36) },
//!     speed: Speed::FallHeight(Distribution::Uniform { min: 0.5, max: 2.0 }),
//!     families: vec![family("coal", Class::Coal, 1380.0), family("gangue", Class::Gangue, 2400.0)],
//!     seed: 1,
//! };
//! // A stand-in for a sensor: a tone whose amplitude is the impact's momentum.
//! let rate = 20_000.0;
//! let extractor = Extractor::new(400, rate);
//! let mut table = FeatureTable::new(1);
//! for i in 0..stream.len() {
//!     let d = stream.draw(i, Held::NONE).unwrap();
//!     let mass = d.density * 4.0 / 3.0 * std::f64::consts::PI * d.radius.powi(3);
//!     let signal: Vec<f64> =
//!         (0..400).map(|k| mass * d.velocity * (2.0 * std::f64::consts::PI * 500.0 * k as f64 / rate).sin()).collect();
//!     table.push(d.class, &extractor.features(&signal));
//! }
//! let s = best(&separabilities(&table), &[]).unwrap();
//! // Gangue is 1.74 times denser, so its momentum reads higher, but sizes and speeds
//! // overlap: ln(momentum) differs by ln 1.74 = 0.55 between the classes and spreads by
//! // about 0.36 within each (3 × 0.1 from ln R, 0.2 from ln v), so the AUC of two normals,
//! // Φ(0.55/(0.36√2)) = 0.86, with a standard error of about 0.04 at 50 + 50 impacts.
//! assert_eq!(s.feature.key(), "peak");
//! assert!((s.auc.auc - 0.86).abs() < 0.1, "{}", s.auc.auc);
//! ```

#![warn(missing_docs)]

pub mod classify;
pub mod design;
pub mod detect;
pub mod detector;
pub mod distribution;
pub mod ensemble;
pub mod features;
pub mod measurement;
pub mod placement;
pub mod recording;
pub mod roc;
pub mod stream;
pub mod subsample;

pub use distribution::Distribution;
pub use ensemble::{Class, Draw, Ensemble, Family, Held, Region, Speed, Study, Variable};
pub use features::{Extractor, Feature, FEATURES};
pub use roc::Auc;
