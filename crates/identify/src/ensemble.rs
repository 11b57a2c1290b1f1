//! The random-impact ensemble: where the lumps strike, how large and fast they are, and
//! what they are made of.
//!
//! An ensemble is a list of material families (coal or gangue, each with its own count and
//! its distributions of density, modulus, Poisson ratio, strength and radius), one region
//! of the plate where impacts land (uniformly), and one law of the impact speed, given as
//! a fall height h (v = √(2gh), free fall from rest) or as a velocity. Impacts are numbered
//! 0..n family by family, so every family has exactly its count.
//!
//! **Reproducibility.** Impact i draws its uniforms from its own ChaCha8 stream: the
//! generator seeded with the ensemble's seed, stream number i ([`impact_stream`]). The
//! draws of impact i therefore depend on (seed, i) only, never on which thread drew which
//! impact or in what order, and a run is bit-identical on any number of threads. Each
//! impact takes its [`UNIFORMS`] uniforms in a fixed order (x, z, speed, radius, density,
//! modulus, Poisson ratio, cohesion, friction angle), one per variable, and maps each
//! through its law's quantile ([`Distribution::quantile`]); holding a variable at its
//! median ([`Held`]) replaces one value and leaves the others exactly as they were.
//!
//! Variables are independent (no correlation of density with modulus is modelled).

use crate::distribution::Distribution;
use analytic::{Elastic, InvalidParameter, RockStrength, Sphere};
use rand_chacha::rand_core::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::Serialize;

/// Standard gravity, m/s² (CGPM 1901; exact by definition).
pub const GRAVITY: f64 = 9.80665;

/// Uniforms each impact draws, in this order: x, z, speed, radius, density, Young's
/// modulus, Poisson ratio, cohesion, friction angle.
pub const UNIFORMS: usize = 9;

/// Coal or gangue: the two classes identification tells apart.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Class {
    /// Coal, the product.
    Coal,
    /// Gangue (rock), the waste.
    Gangue,
}

impl Class {
    /// The name used in scene files and tables.
    pub fn key(self) -> &'static str {
        match self {
            Class::Coal => "coal",
            Class::Gangue => "gangue",
        }
    }
}

/// One material family of the stream: its class, how many impacts, and the laws of its
/// properties (SI units: kg/m³, Pa, -, Pa, degrees, m).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Family {
    /// A label ("coal", "mudstone", ...).
    pub name: String,
    /// Coal or gangue.
    pub class: Class,
    /// Number of impacts of this family.
    pub count: usize,
    /// Density ρ₁, kg/m³.
    pub density: Distribution,
    /// Young's modulus E₁, Pa.
    pub youngs_modulus: Distribution,
    /// Poisson ratio μ₁.
    pub poisson_ratio: Distribution,
    /// Drucker-Prager cohesion ζ, Pa.
    pub cohesion: Distribution,
    /// Internal friction angle φ, degrees.
    pub friction_angle_deg: Distribution,
    /// Sphere radius R, m.
    pub radius: Distribution,
}

/// A rectangle of the plate, x along the length and z across the width, m.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Region {
    /// [x₀, x₁].
    pub x: (f64, f64),
    /// [z₀, z₁].
    pub z: (f64, f64),
}

/// The law of the impact speed.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Speed {
    /// Free fall from rest through a height h (m): v = √(2gh).
    FallHeight(Distribution),
    /// The velocity itself, m/s.
    Velocity(Distribution),
}

/// The random-impact description.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Ensemble {
    /// Where the impacts land, uniformly.
    pub region: Region,
    /// How fast.
    pub speed: Speed,
    /// The families, in the order their impacts are numbered.
    pub families: Vec<Family>,
    /// The seed of every impact's stream.
    pub seed: u64,
}

/// Which variables are held at their medians (the others are drawn).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize)]
pub struct Held {
    /// Position at the region's centre.
    pub position: bool,
    /// Radius at its family's median.
    pub size: bool,
    /// Speed at its median.
    pub speed: bool,
    /// Density, modulus, Poisson ratio and strength at their family's medians.
    pub material: bool,
}

impl Held {
    /// Nothing held: the scene's full variability.
    pub const NONE: Held = Held { position: false, size: false, speed: false, material: false };

    /// Only `variable` held.
    pub fn only(variable: Variable) -> Held {
        let mut h = Held::NONE;
        match variable {
            Variable::Position => h.position = true,
            Variable::Size => h.size = true,
            Variable::Speed => h.speed = true,
            Variable::Material => h.material = true,
        }
        h
    }
}

/// A variable of the ensemble that can be held at its median, to see how much of the
/// classes' overlap it causes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Variable {
    /// The impact point.
    Position,
    /// The radius.
    Size,
    /// The impact speed.
    Speed,
    /// Density, modulus, Poisson ratio and strength.
    Material,
}

impl Variable {
    /// Every variable, in the order reports list them.
    pub const ALL: [Variable; 4] = [Variable::Position, Variable::Size, Variable::Speed, Variable::Material];

    /// The name used in scene files.
    pub fn key(self) -> &'static str {
        match self {
            Variable::Position => "position",
            Variable::Size => "size",
            Variable::Speed => "speed",
            Variable::Material => "material",
        }
    }
}

/// An identification study: the ensemble, the candidate sensor points of the placement
/// maps (every x with every z, m), and the variables to hold one at a time.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Study {
    /// The random impacts.
    pub ensemble: Ensemble,
    /// Candidate sensor positions along the length, m.
    pub candidates_x: Vec<f64>,
    /// Candidate sensor positions across the width, m.
    pub candidates_z: Vec<f64>,
    /// Variables held at their medians, one per extra run.
    pub hold: Vec<Variable>,
    /// Sensors the design chooses among the candidates, one at a time ([`crate::design`]);
    /// 0: no design.
    pub design_sensors: usize,
    /// Scales of the measurement chain's background at which the design is chosen again
    /// (besides the background as stated). Left out of the serialised scene when empty, so
    /// that a scene without it keeps its provenance hash.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub design_backgrounds: Vec<f64>,
}

impl Study {
    /// The candidate sensor points, x-major.
    pub fn candidates(&self) -> Vec<(f64, f64)> {
        self.candidates_x.iter().flat_map(|&x| self.candidates_z.iter().map(move |&z| (x, z))).collect()
    }

    /// Values given per candidate point in [`Study::candidates`]' order, laid out as the
    /// placement maps show them: a row per x, a column per z.
    pub fn by_x_and_z<T: Clone>(&self, values: &[T]) -> Vec<Vec<T>> {
        values.chunks(self.candidates_z.len().max(1)).map(<[T]>::to_vec).collect()
    }
}

/// One impact of the ensemble, SI units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Draw {
    /// Its number in the ensemble.
    pub index: usize,
    /// Its family's position in [`Ensemble::families`].
    pub family: usize,
    /// Its class.
    pub class: Class,
    /// Impact point x (along the length), m.
    pub x: f64,
    /// Impact point z (across the width), m.
    pub z: f64,
    /// Impact velocity, m/s.
    pub velocity: f64,
    /// Sphere radius, m.
    pub radius: f64,
    /// Density, kg/m³.
    pub density: f64,
    /// Young's modulus, Pa.
    pub youngs_modulus: f64,
    /// Poisson ratio.
    pub poisson_ratio: f64,
    /// Cohesion, Pa.
    pub cohesion: f64,
    /// Friction angle, degrees.
    pub friction_angle_deg: f64,
}

impl Draw {
    /// The sphere this impact throws, named after its family.
    pub fn sphere(&self, family_name: &str) -> Result<Sphere, InvalidParameter> {
        Sphere::new(
            family_name,
            self.density,
            self.radius,
            Elastic::new(self.youngs_modulus, self.poisson_ratio)?,
            RockStrength::new(self.cohesion, self.friction_angle_deg)?,
        )
    }
}

/// The generator of impact `index`: ChaCha8 keyed by `seed`, on stream `index`. Streams of
/// one key are independent sequences of 2⁶⁸ bytes, so impacts never share random numbers.
pub fn impact_stream(seed: u64, index: usize) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(index as u64);
    rng
}

/// A uniform on the open interval (0, 1) from the top 53 bits of one 64-bit draw, at the
/// centre of its 2⁻⁵³ cell, so that quantiles never see 0 or 1.
pub fn open_uniform(rng: &mut impl RngCore) -> f64 {
    ((rng.next_u64() >> 11) as f64 + 0.5) * (1.0 / (1u64 << 53) as f64)
}

impl Ensemble {
    /// Total number of impacts.
    pub fn len(&self) -> usize {
        self.families.iter().map(|f| f.count).sum()
    }

    /// Whether the ensemble has no impacts.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The family of impact `index` (impacts are numbered family by family).
    pub fn family_of(&self, index: usize) -> Option<usize> {
        let mut start = 0;
        for (f, fam) in self.families.iter().enumerate() {
            if index < start + fam.count {
                return Some(f);
            }
            start += fam.count;
        }
        None
    }

    /// Impacts per class: (coal, gangue).
    pub fn class_counts(&self) -> (usize, usize) {
        let count = |c: Class| self.families.iter().filter(|f| f.class == c).map(|f| f.count).sum();
        (count(Class::Coal), count(Class::Gangue))
    }

    /// Impact `index` with the variables in `held` at their medians; None beyond the end.
    pub fn draw(&self, index: usize, held: Held) -> Option<Draw> {
        Some(self.draw_of(index, self.family_of(index)?, held))
    }

    /// Impact `index` drawn from family `f` (which must exist) on the impact's own stream,
    /// with the variables in `held` at their medians: [`Ensemble::draw`] with the family
    /// given, for streams whose lumps choose their family by time.
    pub fn draw_of(&self, index: usize, f: usize, held: Held) -> Draw {
        let fam = &self.families[f];
        let mut rng = impact_stream(self.seed, index);
        let mut u = [0.0; UNIFORMS];
        for v in &mut u {
            *v = open_uniform(&mut rng);
        }
        let pick = |d: &Distribution, u: f64, hold: bool| if hold { d.median() } else { d.quantile(u) };
        let r = self.region;
        let (ux, uz) = if held.position { (0.5, 0.5) } else { (u[0], u[1]) };
        let velocity = match &self.speed {
            Speed::FallHeight(h) => (2.0 * GRAVITY * pick(h, u[2], held.speed)).sqrt(),
            Speed::Velocity(v) => pick(v, u[2], held.speed),
        };
        Draw {
            index,
            family: f,
            class: fam.class,
            x: r.x.0 + ux * (r.x.1 - r.x.0),
            z: r.z.0 + uz * (r.z.1 - r.z.0),
            velocity,
            radius: pick(&fam.radius, u[3], held.size),
            density: pick(&fam.density, u[4], held.material),
            youngs_modulus: pick(&fam.youngs_modulus, u[5], held.material),
            poisson_ratio: pick(&fam.poisson_ratio, u[6], held.material),
            cohesion: pick(&fam.cohesion, u[7], held.material),
            friction_angle_deg: pick(&fam.friction_angle_deg, u[8], held.material),
        }
    }
}

/// Runs `work` on items 0..n in parallel (rayon) and hands the results to `sink` in index
/// order, `chunk` items at a time, so that at most one chunk of results is held in memory
/// and the sink (which may write to disk) sees the same sequence on any number of threads.
/// Stops at the first error of `sink`.
pub fn for_each_ordered<R: Send, E>(
    n: usize,
    chunk: usize,
    work: impl Fn(usize) -> R + Sync,
    mut sink: impl FnMut(usize, R) -> Result<(), E>,
) -> Result<(), E> {
    let chunk = chunk.max(1);
    let mut start = 0;
    while start < n {
        let end = (start + chunk).min(n);
        let results: Vec<R> = (start..end).into_par_iter().map(&work).collect();
        for (i, r) in (start..end).zip(results) {
            sink(i, r)?;
        }
        start = end;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn family(name: &str, class: Class, count: usize, radius: Distribution) -> Family {
        Family {
            name: name.into(),
            class,
            count,
            density: Distribution::Normal { mean: 1380.0, sd: 50.0, min: 1200.0, max: 1600.0 },
            youngs_modulus: Distribution::LogNormal { median: 2.26e9, sigma_log: 0.3, min: 1e9, max: 5e9 },
            poisson_ratio: Distribution::Fixed { value: 0.28 },
            cohesion: Distribution::Uniform { min: 5e6, max: 10e6 },
            friction_angle_deg: Distribution::Fixed { value: 25.0 },
            radius,
        }
    }

    fn stream() -> Ensemble {
        Ensemble {
            region: Region { x: (0.0, 0.4584), z: (0.0, 0.36) },
            speed: Speed::FallHeight(Distribution::Uniform { min: 0.5, max: 2.0 }),
            families: vec![
                family(
                    "coal",
                    Class::Coal,
                    30,
                    Distribution::LogNormal { median: 0.025, sigma_log: 0.4, min: 0.01, max: 0.06 },
                ),
                family("gangue", Class::Gangue, 20, Distribution::Uniform { min: 0.01, max: 0.05 }),
            ],
            seed: 7,
        }
    }

    #[test]
    fn families_are_numbered_in_blocks() {
        let e = stream();
        assert_eq!(e.len(), 50);
        assert_eq!(e.class_counts(), (30, 20));
        assert_eq!((e.family_of(29), e.family_of(30), e.family_of(50)), (Some(0), Some(1), None));
    }

    #[test]
    fn draws_lie_inside_their_laws_and_fall_speed_is_free_fall() {
        let e = stream();
        for i in 0..e.len() {
            let d = e.draw(i, Held::NONE).unwrap();
            assert!((0.0..=0.4584).contains(&d.x) && (0.0..=0.36).contains(&d.z));
            // v = √(2gh) with h in [0.5, 2] m.
            let h = d.velocity * d.velocity / (2.0 * GRAVITY);
            assert!((0.5 - 1e-12..=2.0 + 1e-12).contains(&h), "h = {h}");
            assert!((0.01..=0.06).contains(&d.radius));
            assert!(d.sphere("coal").is_ok());
        }
    }

    #[test]
    fn holding_one_variable_leaves_the_others_unchanged() {
        // Common random numbers: the held run differs from the free run in that variable only.
        let e = stream();
        for i in [0, 17, 42] {
            let free = e.draw(i, Held::NONE).unwrap();
            let held = e.draw(i, Held { size: true, ..Held::NONE }).unwrap();
            assert_eq!(held.radius, e.families[free.family].radius.median());
            assert_eq!((held.x, held.z, held.velocity, held.density), (free.x, free.z, free.velocity, free.density));
            let at_centre = e.draw(i, Held { position: true, ..Held::NONE }).unwrap();
            assert_eq!((at_centre.x, at_centre.z), (0.2292, 0.18));
            assert_eq!(at_centre.radius, free.radius);
        }
    }

    #[test]
    fn streams_differ_between_impacts_and_seeds() {
        let e = stream();
        let a = e.draw(3, Held::NONE).unwrap();
        let b = e.draw(4, Held::NONE).unwrap();
        assert_ne!(a.x, b.x);
        let mut other = stream();
        other.seed = 8;
        assert_ne!(other.draw(3, Held::NONE).unwrap().x, a.x);
    }
}
