//! What the transient tests share: the paper's plate, its three bodies, Con 1 and Con 2,
//! and the strike at the paper's 0.008 m/s.

// Each test binary includes this module and uses only some of it.
#![allow(dead_code)]

use analytic::{Elastic, Plate, RockStrength, Sphere};
use coupled::supports::SupportSet;
use coupled::transient::case::striker;
use coupled::transient::Striker;
use plate_fem::Supports;

/// The paper's plate, 8 mm.
pub fn plate() -> Plate {
    Plate::new(0.4584, 0.360, 0.008, 7850.0, Elastic::new(210e9, 0.3).unwrap()).unwrap()
}

/// Coal, gangue 1 (Table 1's radius) or gangue 2.
pub fn body(name: &str) -> Sphere {
    let (rho, r, e) = match name {
        "coal" => (1380.0, 0.025, 2.26e9),
        "gangue 1" => (2400.0, 0.0207888, 16e9),
        _ => (2400.0, 0.025, 16e9),
    };
    Sphere::new(name, rho, r, Elastic::new(e, 0.28).unwrap(), RockStrength::new(10e6, 30.0).unwrap()).unwrap()
}

/// Con 1 (fixed corners) or Con 2 (corner springs).
pub fn con(i: usize) -> SupportSet {
    match i {
        1 => SupportSet::new("Con 1", Supports::con1()),
        _ => SupportSet::new("Con 2", Supports::con2(5.11545e8)),
    }
}

/// `name` striking the paper's plate at 0.008 m/s with e = 0.65.
pub fn strike(name: &str) -> Striker {
    striker(&plate(), &body(name), 0.65, 0.008)
}
