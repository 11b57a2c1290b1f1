//! The quasi-static error over plate size and thickness: the scene's plate scaled in length
//! and width and made thinner and thicker, under Con 1, struck at its centre by the first body
//! at the first velocity, the transient P_max against the quasi-static plate's, beside t_c/T₁.

use crate::settings::{Settings, DYNAMIC_MESH, STEPS_PER_CONTACT};
use crate::Failure;
use analytic::{respond, Condition};
use coupled::plan::{impact_of, scene_striker};
use coupled::transient::{TransientCase, TransientSettings};
use coupled::validity::QUASI_STATIC_MIN_RATIO;
use coupled::{ComplianceModel, PlateModel};
use scene::{Scene, SupportSet};
use serde::Serialize;

/// The plate sizes of the map, as multiples of the scene's length and width.
pub const SCALES: [f64; 3] = [0.5, 1.0, 2.0];
/// The thicknesses of the map, m.
pub const THICKNESSES: [f64; 5] = [2e-3, 4e-3, 8e-3, 16e-3, 32e-3];

/// One plate of the map.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SizeRow {
    /// Length and width over the scene's.
    pub scale: f64,
    /// Thickness h, m.
    pub thickness: f64,
    /// Fundamental period T₁ under Con 1, s.
    pub period: f64,
    /// The first contact's duration, s; `None` if the sphere had not separated.
    pub contact_time: Option<f64>,
    /// The transient force at maximum compression (the paper's P_max), N.
    pub force_at_max_compression: f64,
    /// P_max of the quasi-static plate, N.
    pub quasi_static_force: f64,
    /// Transient over quasi-static P_max, minus 1.
    pub error: f64,
}

impl SizeRow {
    /// (t_c/T₁, transient/quasi-static P_max), where the contact ended.
    pub fn point(&self) -> Option<(f64, f64)> {
        self.contact_time.map(|ct| (ct / self.period, 1.0 + self.error))
    }
}

/// What the map shows in numbers.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SizeMapFindings {
    /// The largest |transient/QS - 1| where t_c/T₁ ≥ [`QUASI_STATIC_MIN_RATIO`]; `None` if no
    /// plate of the map reaches it.
    pub slow_error: Option<f64>,
    /// The fastest contact's (t_c/T₁, transient/QS).
    pub fastest: Option<(f64, f64)>,
}

/// The map: every size of [`SCALES`] at every thickness of [`THICKNESSES`], size by size.
pub fn size_map(scene: &Scene, settings: &Settings) -> Result<Vec<SizeRow>, Failure> {
    let body = scene.bodies.first().ok_or("no body")?;
    let v = scene.velocities.first().copied().unwrap_or(0.008);
    let s = scene_striker(scene, body, v);
    let imp = impact_of(scene, body, v);
    let base = &scene.plate;
    let cond = SupportSet::preset("Con 1", Condition::BothFixed);
    let mut rows = Vec::new();
    for scale in SCALES {
        for h in THICKNESSES {
            let plate =
                analytic::Plate::new(base.length() * scale, base.width() * scale, h, base.density(), base.material())?;
            let case = TransientCase::new(&plate, TransientSettings { elements: DYNAMIC_MESH, ..Default::default() })?;
            let t1 = case.fundamental_period(&cond.supports)?;
            let (x, z) = (plate.length() / 2.0, plate.width() / 2.0);
            let o = case.first_contact(&cond, &s, x, z, STEPS_PER_CONTACT)?;
            let qs = PlateModel::compute(
                &plate,
                std::slice::from_ref(&cond),
                &[(x, z)],
                settings.base_mesh,
                settings.levels,
            )?;
            let rp = respond(&imp, &qs.compliance(&cond, x, z)?.compliance, settings.method)?;
            let p_at_max = s.force_at_max_compression(o.compression_max_interpolated);
            rows.push(SizeRow {
                scale,
                thickness: h,
                period: t1,
                contact_time: o.contacts.first().map(|c| c.duration),
                force_at_max_compression: p_at_max,
                quasi_static_force: rp.contact_force,
                error: p_at_max / rp.contact_force - 1.0,
            });
        }
    }
    Ok(rows)
}

/// The map's findings from its rows: the largest error where the contact is slow against the
/// plate and the error at the fastest contact.
pub fn findings(rows: &[SizeRow]) -> SizeMapFindings {
    let pts: Vec<(f64, f64)> = rows.iter().filter_map(SizeRow::point).collect();
    let slow_error = pts
        .iter()
        .filter(|p| p.0 >= QUASI_STATIC_MIN_RATIO)
        .map(|p| (p.1 - 1.0).abs())
        .fold(None, |m: Option<f64>, e| Some(m.map_or(e, |m| m.max(e))));
    let fastest = pts.iter().copied().min_by(|a, b| a.0.total_cmp(&b.0));
    SizeMapFindings { slow_error, fastest }
}
