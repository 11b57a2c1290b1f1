//! The drops of a drop-test recording (`identify::recording::DropRecord`, in the units its
//! keys name) checked against their ranges and the scene they are compared with, and turned
//! into SI: each becomes the [`Draw`] the model throws for it.

use crate::{limits, SceneError, FALL_HEIGHT_M};
use analytic::params::{check, Range, FRICTION_ANGLE_DEG, POISSON_RATIO};
use identify::ensemble::GRAVITY;
use identify::recording::DropRecord;
use identify::{Class, Draw};

/// Latest touch accepted, s from the first sample (a day of recording).
pub const TOUCH_S: Range = Range::closed(0.0, 86_400.0);
/// Measured peak forces, kN (1 mN to 1 GN).
pub const FORCE_KN: Range = Range::closed(1e-6, 1e6);
/// Measured contact times, ms (1 ns to 10 s).
pub const CONTACT_TIME_MS: Range = Range::closed(1e-6, 1e4);
/// Standard deviations of measured peak forces, kN.
pub const FORCE_SD_KN: Range = Range::closed(0.0, 1e6);
/// Standard deviations of measured contact times, ms.
pub const CONTACT_TIME_SD_MS: Range = Range::closed(0.0, 1e4);

/// One drop in SI: the impact the model throws for it, and what else the recording states.
#[derive(Debug, Clone, PartialEq)]
pub struct Drop {
    /// The impact (its index is the drop's position; its class coal where none is stated).
    pub draw: Draw,
    /// Whether the recording stated the class.
    pub class_stated: bool,
    /// When the lump touched the plate, s from the first sample.
    pub touch: f64,
    /// The fall height, m, where the recording gave one.
    pub fall_height: Option<f64>,
    /// The measured peak impact force, N.
    pub force_max: Option<f64>,
    /// The measured duration of the first contact, s.
    pub contact_time: Option<f64>,
    /// The standard deviation of the measured peak force, N.
    pub force_max_sd: Option<f64>,
    /// The standard deviation of the measured contact time, s.
    pub contact_time_sd: Option<f64>,
}

/// The condition of `scene` named `name`; with no name, the scene's only one.
pub fn condition(scene: &crate::Scene, name: Option<&str>, origin: &str) -> Result<usize, SceneError> {
    let names: Vec<&str> = scene.conditions.iter().map(|c| c.name.as_str()).collect();
    let inconsistent =
        |message: String| SceneError::Inconsistent { origin: origin.to_string(), field: "condition".into(), message };
    match name {
        Some(n) => names.iter().position(|c| *c == n).ok_or_else(|| {
            inconsistent(format!("\"{n}\" is not a condition of scene {}; it has {names:?}", scene.name))
        }),
        None if names.len() == 1 => Ok(0),
        None => {
            Err(inconsistent(format!("missing: name the support set the drops were recorded on, one of {names:?}")))
        }
    }
}

/// Every drop of `records` checked and in SI, for `scene` (the point on its plate).
pub fn drops(scene: &crate::Scene, records: &[DropRecord], origin: &str) -> Result<Vec<Drop>, SceneError> {
    records.iter().enumerate().map(|(i, r)| drop(scene, i, r, origin)).collect()
}

fn drop(scene: &crate::Scene, index: usize, r: &DropRecord, origin: &str) -> Result<Drop, SceneError> {
    let field = |key: &str| format!("drops[{index}].{key}");
    let range = |key: &str, v: f64, allowed: Range, unit: &'static str| {
        check(&field(key), v, allowed, unit)
            .map_err(|source| SceneError::OutOfRange { origin: origin.to_string(), source })
    };
    let inconsistent = |key: &str, message: String| SceneError::Inconsistent {
        origin: origin.to_string(),
        field: field(key),
        message,
    };
    let touch = range("touch_s", r.touch_s, TOUCH_S, "s")?;
    let (l, b) = (scene.plate.length(), scene.plate.width());
    let x = range("point_mm[0]", r.point_mm[0], Range::closed(0.0, l * 1e3), "mm")? * 1e-3;
    let z = range("point_mm[1]", r.point_mm[1], Range::closed(0.0, b * 1e3), "mm")? * 1e-3;
    let velocity = match (r.fall_height_m, r.velocity_m_per_s) {
        // Free fall from rest under the scene's gravity (standard gravity where it states 0).
        (Some(h), None) => {
            let g = if scene.gravity > 0.0 { scene.gravity } else { GRAVITY };
            (2.0 * g * range("fall_height_m", h, FALL_HEIGHT_M, "m")?).sqrt()
        }
        (None, Some(v)) => range("velocity_m_per_s", v, limits::VELOCITY_M_PER_S, "m/s")?,
        _ => {
            return Err(inconsistent(
                "fall_height_m",
                "give exactly one of fall_height_m (free fall from rest, v = √(2gh)) or velocity_m_per_s".into(),
            ))
        }
    };
    let class = match r.class.as_deref() {
        None | Some("coal") => Class::Coal,
        Some("gangue") => Class::Gangue,
        Some(other) => return Err(inconsistent("class", format!("\"{other}\", allowed \"coal\" or \"gangue\""))),
    };
    let draw = Draw {
        index,
        family: 0,
        class,
        x,
        z,
        velocity,
        radius: range("radius_mm", r.radius_mm, limits::RADIUS_MM, "mm")? * 1e-3,
        density: range("density_kg_m3", r.density_kg_m3, limits::DENSITY_KG_M3, "kg/m³")?,
        youngs_modulus: range("youngs_modulus_gpa", r.youngs_modulus_gpa, limits::MODULUS_GPA, "GPa")? * 1e9,
        poisson_ratio: range("poisson_ratio", r.poisson_ratio, POISSON_RATIO, "")?,
        cohesion: range("cohesion_mpa", r.cohesion_mpa, limits::COHESION_MPA, "MPa")? * 1e6,
        friction_angle_deg: range("friction_angle_deg", r.friction_angle_deg, FRICTION_ANGLE_DEG, "deg")?,
    };
    let force_max = r.force_max_kn.map(|f| range("force_max_kn", f, FORCE_KN, "kN")).transpose()?.map(|f| f * 1e3);
    let contact_time =
        r.contact_time_ms.map(|t| range("contact_time_ms", t, CONTACT_TIME_MS, "ms")).transpose()?.map(|t| t * 1e-3);
    let force_max_sd =
        r.force_max_sd_kn.map(|f| range("force_max_sd_kn", f, FORCE_SD_KN, "kN")).transpose()?.map(|f| f * 1e3);
    let contact_time_sd = r
        .contact_time_sd_ms
        .map(|t| range("contact_time_sd_ms", t, CONTACT_TIME_SD_MS, "ms"))
        .transpose()?
        .map(|t| t * 1e-3);
    Ok(Drop {
        draw,
        class_stated: r.class.is_some(),
        touch,
        fall_height: r.fall_height_m,
        force_max,
        contact_time,
        force_max_sd,
        contact_time_sd,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::SceneSource;

    fn record() -> DropRecord {
        DropRecord {
            touch_s: 0.1,
            point_mm: [229.2, 180.0],
            radius_mm: 25.0,
            density_kg_m3: 2400.0,
            youngs_modulus_gpa: 16.0,
            poisson_ratio: 0.28,
            cohesion_mpa: 37.68,
            friction_angle_deg: 37.0,
            fall_height_m: Some(0.45),
            velocity_m_per_s: None,
            class: Some("gangue".into()),
            force_max_kn: None,
            contact_time_ms: Some(0.6),
            force_max_sd_kn: None,
            contact_time_sd_ms: None,
        }
    }

    #[test]
    fn a_drop_is_converted_to_si_once() {
        let scene = crate::Scene::default_scene();
        let d = &drops(&scene, &[record()], "x.json").unwrap()[0];
        assert_eq!((d.draw.x, d.draw.z, d.draw.radius), (0.2292, 0.18, 0.025));
        assert_eq!((d.draw.youngs_modulus, d.draw.cohesion), (16e9, 37.68e6));
        assert!((d.draw.velocity - (2.0 * 9.80665 * 0.45f64).sqrt()).abs() < 1e-15);
        assert_eq!((d.draw.class, d.contact_time), (Class::Gangue, Some(0.6e-3)));
    }

    #[test]
    fn every_bad_drop_names_its_field_and_value() {
        let scene = crate::Scene::default_scene();
        let err = |edit: fn(&mut DropRecord)| {
            let mut r = record();
            edit(&mut r);
            drops(&scene, &[record(), r], "x.json").unwrap_err().to_string()
        };
        let e = err(|r| r.point_mm[0] = 500.0);
        assert!(e.contains("drops[1].point_mm[0]") && e.contains("500"), "{e}");
        let e = err(|r| r.radius_mm = -1.0);
        assert!(e.contains("drops[1].radius_mm") && e.contains("-1"), "{e}");
        let e = err(|r| r.velocity_m_per_s = Some(3.0));
        assert!(e.contains("exactly one of fall_height_m"), "{e}");
        let e = err(|r| r.class = Some("shale".into()));
        assert!(e.contains("drops[1].class") && e.contains("shale"), "{e}");
        let e = err(|r| r.poisson_ratio = 0.5);
        assert!(e.contains("drops[1].poisson_ratio"), "{e}");
        let e = condition(&scene, Some("Con 9"), "x.json").unwrap_err().to_string();
        assert!(e.contains("Con 9") && e.contains("Con 1"), "{e}");
        assert!(condition(&scene, None, "x.json").is_err(), "the default scene has three conditions");
    }
}
