//! Both models along one line of the plate (constant z), for a set of support conditions:
//! the compliance, the response at maximum compression (eqs. 14, 25, 46) and the yield
//! velocity (eqs. 51-54) at every point of the line.

use crate::settings::{BASE_MESH, LEVELS, METHOD};
use crate::Failure;
use analytic::{respond, yield_velocity, DruckerPrager, PointCompliance, Response, Sphere};
use coupled::plan::impact_of;
use coupled::{BeamModel, ComplianceModel, PlateModel};
use scene::{even_points, Scene, SupportSet};

/// Both models at the points of one line for a set of conditions.
pub struct Line<'a> {
    scene: &'a Scene,
    model: PlateModel,
    /// The points along the length, m.
    pub xs: Vec<f64>,
    z: f64,
}

/// (x/L of the minimum, the minimum, x/L of the maximum, the maximum) along a line.
pub type Extremes = (f64, f64, f64, f64);

impl<'a> Line<'a> {
    /// The line z = `z` of `scene`'s plate in `points - 1` equal parts, for `conds`.
    pub fn new(scene: &'a Scene, conds: &[SupportSet], z: f64, points: usize) -> Result<Self, Failure> {
        let xs = even_points(scene.plate.length(), points);
        let pts: Vec<(f64, f64)> = xs.iter().map(|&x| (x, z)).collect();
        let model = PlateModel::compute(&scene.plate, conds, &pts, BASE_MESH, LEVELS)?;
        Ok(Self { scene, model, xs, z })
    }

    /// The compliance at x, by the plate (`plate`) or the beam.
    pub fn compliance(&self, plate: bool, c: &SupportSet, x: f64) -> Result<PointCompliance, Failure> {
        Ok(if plate {
            self.model.compliance(c, x, self.z)?.compliance
        } else {
            BeamModel { plate: &self.scene.plate }.compliance(c, x, 0.0)?.compliance
        })
    }

    /// The response of `body` at x at velocity `v`.
    pub fn response(&self, plate: bool, c: &SupportSet, body: &Sphere, x: f64, v: f64) -> Result<Response, Failure> {
        Ok(respond(&impact_of(self.scene, body, v), &self.compliance(plate, c, x)?, METHOD)?)
    }

    /// The yield velocity of `body` at x.
    pub fn vy(&self, plate: bool, c: &SupportSet, body: &Sphere, x: f64) -> Result<f64, Failure> {
        let imp = impact_of(self.scene, body, 1.0);
        let d = DruckerPrager::of(body).yield_compression(body.radius(), imp.contact_stiffness);
        Ok(yield_velocity(body, &imp, self.compliance(plate, c, x)?.total(), d))
    }

    /// Where along the line `f` is least and greatest, in units of L, and its values there:
    /// the first of values equal to rounding ([`crate::verdict::extreme_indices`]).
    pub fn extremes(&self, f: impl Fn(f64) -> Result<f64, Failure>) -> Result<Extremes, Failure> {
        let vals: Vec<f64> = self.xs.iter().map(|&x| f(x)).collect::<Result<_, _>>()?;
        let l = self.scene.plate.length();
        let (imin, imax) = crate::verdict::extreme_indices(&vals).ok_or("no value along the line is a number")?;
        Ok((self.xs[imin] / l, vals[imin], self.xs[imax] / l, vals[imax]))
    }
}

/// `f` under the beam, then under the plate.
pub fn both<T>(f: impl Fn(bool) -> Result<T, Failure>) -> Result<(T, T), Failure> {
    Ok((f(false)?, f(true)?))
}
