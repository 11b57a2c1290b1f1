//! Materials and bodies of Table 1: the elastic plate and the rock spheres.

use crate::params::{check, InvalidParameter, FRICTION_ANGLE_DEG, POISSON_RATIO, POSITIVE};
use serde::Serialize;

/// An isotropic linear elastic material.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Elastic {
    youngs_modulus: f64,
    poisson_ratio: f64,
}

impl Elastic {
    /// `youngs_modulus` in Pa, `poisson_ratio` in (0, 0.5).
    pub fn new(youngs_modulus: f64, poisson_ratio: f64) -> Result<Self, InvalidParameter> {
        Ok(Self {
            youngs_modulus: check("youngs_modulus", youngs_modulus, POSITIVE, "Pa")?,
            poisson_ratio: check("poisson_ratio", poisson_ratio, POISSON_RATIO, "")?,
        })
    }
    /// Young's modulus E (Pa).
    pub fn youngs_modulus(&self) -> f64 {
        self.youngs_modulus
    }
    /// Poisson's ratio μ (ν for the plate).
    pub fn poisson_ratio(&self) -> f64 {
        self.poisson_ratio
    }
    /// The compliance term (1 - μ²)/E of eq. 4.
    pub fn contact_compliance(&self) -> f64 {
        (1.0 - self.poisson_ratio * self.poisson_ratio) / self.youngs_modulus
    }
}

/// Drucker-Prager strength of the rock: cohesion ζ (Pa) and internal friction angle φ.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RockStrength {
    cohesion: f64,
    friction_angle_deg: f64,
}

impl RockStrength {
    /// `cohesion` ζ in Pa (positive), `friction_angle_deg` φ in degrees, in (0, 90).
    pub fn new(cohesion: f64, friction_angle_deg: f64) -> Result<Self, InvalidParameter> {
        Ok(Self {
            cohesion: check("cohesion", cohesion, POSITIVE, "Pa")?,
            friction_angle_deg: check("friction_angle", friction_angle_deg, FRICTION_ANGLE_DEG, "deg")?,
        })
    }
    /// Cohesion ζ (Pa).
    pub fn cohesion(&self) -> f64 {
        self.cohesion
    }
    /// Internal friction angle φ (degrees).
    pub fn friction_angle_deg(&self) -> f64 {
        self.friction_angle_deg
    }
}

/// A rock sphere (coal or gangue) of Table 1.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sphere {
    /// A label for reports ("coal", "gangue 1", ...).
    pub name: String,
    density: f64,
    radius: f64,
    material: Elastic,
    strength: RockStrength,
}

impl Sphere {
    /// `density` kg/m³, `radius` m.
    pub fn new(
        name: impl Into<String>,
        density: f64,
        radius: f64,
        material: Elastic,
        strength: RockStrength,
    ) -> Result<Self, InvalidParameter> {
        Ok(Self {
            name: name.into(),
            density: check("density", density, POSITIVE, "kg/m^3")?,
            radius: check("radius", radius, POSITIVE, "m")?,
            material,
            strength,
        })
    }
    /// Density ρ₁ (kg/m³).
    pub fn density(&self) -> f64 {
        self.density
    }
    /// Radius R₁ (m).
    pub fn radius(&self) -> f64 {
        self.radius
    }
    /// Elastic constants E₁, μ₁ of the rock.
    pub fn material(&self) -> Elastic {
        self.material
    }
    /// Drucker-Prager strength ζ, φ of the rock.
    pub fn strength(&self) -> RockStrength {
        self.strength
    }
    /// m = ρ (4/3) π R³.
    pub fn mass(&self) -> f64 {
        self.density * 4.0 / 3.0 * std::f64::consts::PI * self.radius.powi(3)
    }
}

/// The rectangular steel plate: length L along the beam axis, width B, thickness h.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Plate {
    length: f64,
    width: f64,
    thickness: f64,
    density: f64,
    material: Elastic,
}

impl Plate {
    /// Sizes in m, density in kg/m³.
    pub fn new(
        length: f64,
        width: f64,
        thickness: f64,
        density: f64,
        material: Elastic,
    ) -> Result<Self, InvalidParameter> {
        Ok(Self {
            length: check("length", length, POSITIVE, "m")?,
            width: check("width", width, POSITIVE, "m")?,
            thickness: check("thickness", thickness, POSITIVE, "m")?,
            density: check("density", density, POSITIVE, "kg/m^3")?,
            material,
        })
    }
    /// Length L along the beam axis (m).
    pub fn length(&self) -> f64 {
        self.length
    }
    /// Width B (m).
    pub fn width(&self) -> f64 {
        self.width
    }
    /// Thickness h (m).
    pub fn thickness(&self) -> f64 {
        self.thickness
    }
    /// Density ρ₂ (kg/m³).
    pub fn density(&self) -> f64 {
        self.density
    }
    /// Elastic constants E₂, μ₂ of the plate.
    pub fn material(&self) -> Elastic {
        self.material
    }
    /// Beam bending stiffness E₂I₂ with I₂ = B h³/12 (section II-A, before eq. 11).
    pub fn beam_bending_stiffness(&self) -> f64 {
        self.material.youngs_modulus * self.width * self.thickness.powi(3) / 12.0
    }
    /// Plate flexural rigidity D = E h³ / 12(1 - ν²).
    pub fn flexural_rigidity(&self) -> f64 {
        let nu = self.material.poisson_ratio;
        self.material.youngs_modulus * self.thickness.powi(3) / (12.0 * (1.0 - nu * nu))
    }
    /// Copy with another width.
    pub fn with_width(&self, width: f64) -> Result<Self, InvalidParameter> {
        Self::new(self.length, width, self.thickness, self.density, self.material)
    }
    /// Copy with another length (the plate-length study of Figs. 14-16).
    pub fn with_length(&self, length: f64) -> Result<Self, InvalidParameter> {
        Self::new(length, self.width, self.thickness, self.density, self.material)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn sphere_mass_is_that_of_a_ball() {
        let s = Sphere::new("s", 1000.0, 0.1, Elastic::new(1e9, 0.3).unwrap(), RockStrength::new(1e6, 30.0).unwrap())
            .unwrap();
        assert_relative_eq!(s.mass(), 4.0 / 3.0 * std::f64::consts::PI, max_relative = 1e-15);
    }

    #[test]
    fn gangue_1_has_the_mass_of_the_coal_sphere() {
        // design.md section 2: gangue sphere 1 has the coal sphere's mass (R = 20.7888 mm).
        let el = Elastic::new(1e9, 0.28).unwrap();
        let st = RockStrength::new(1e6, 30.0).unwrap();
        let coal = Sphere::new("coal", 1380.0, 0.025, el, st).unwrap();
        let g1 = Sphere::new("g1", 2400.0, 0.0207888, el, st).unwrap();
        // R is printed to 6 significant digits, so the masses agree to ~3 x 5e-7.
        assert_relative_eq!(coal.mass(), g1.mass(), max_relative = 2e-6);
    }

    #[test]
    fn constructors_reject_bad_values() {
        assert!(Elastic::new(0.0, 0.3).is_err());
        assert!(Elastic::new(1e9, 0.5).is_err());
        assert!(RockStrength::new(1e6, 90.0).is_err());
        assert!(Plate::new(f64::NAN, 1.0, 1.0, 1.0, Elastic::new(1e9, 0.3).unwrap()).is_err());
    }
}
