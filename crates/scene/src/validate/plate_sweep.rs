//! `[stream] plate_sweep`: the other plates each support set's detector is carried to. An
//! entry changes some of `[plate]`'s keys and keeps the rest; the plate it makes is checked as
//! `[plate]` is, and it must carry what the stream study puts on the scene's plate: the
//! sensors (at the same points, in mm), the support sets, the lumps' region and the modes.
//!
//! ```toml
//! [stream]
//! plate_sweep = [
//!     { thickness_mm = 12.0 },                    # the plate made thicker
//!     { length_mm = 600.0, width_mm = 450.0 },    # another support's larger plate
//!     { youngs_modulus_gpa = 70.0, poisson_ratio = 0.33, density_kg_m3 = 2700.0 },  # a rig's aluminium plate
//! ]
//! ```

use super::{other, validate_condition, validate_plate, Invalid, MM};
use crate::limits;
use crate::raw::{RawPlate, RawScene};
use analytic::params::compact;
use analytic::Plate;
use coupled::reduced::SignalSettings;
use coupled::scene::OtherPlate;
use identify::ensemble::Region;
use serde::Deserialize;

/// One entry of `plate_sweep` as TOML reads it: the `[plate]` keys it changes.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawPlateChange {
    #[serde(default)]
    length_mm: Option<f64>,
    #[serde(default)]
    width_mm: Option<f64>,
    #[serde(default)]
    thickness_mm: Option<f64>,
    #[serde(default)]
    youngs_modulus_gpa: Option<f64>,
    #[serde(default)]
    poisson_ratio: Option<f64>,
    #[serde(default)]
    density_kg_m3: Option<f64>,
}

impl RawPlateChange {
    /// `plate` with this entry's keys in place of its own.
    fn applied_to(&self, plate: &RawPlate) -> RawPlate {
        RawPlate {
            length_mm: self.length_mm.unwrap_or(plate.length_mm),
            width_mm: self.width_mm.unwrap_or(plate.width_mm),
            thickness_mm: self.thickness_mm.unwrap_or(plate.thickness_mm),
            youngs_modulus_gpa: self.youngs_modulus_gpa.unwrap_or(plate.youngs_modulus_gpa),
            poisson_ratio: self.poisson_ratio.unwrap_or(plate.poisson_ratio),
            density_kg_m3: self.density_kg_m3.unwrap_or(plate.density_kg_m3),
        }
    }

    /// The shift in words, from the keys given in the file's units, in `[plate]`'s order
    /// ("plate 600 mm long, 450 mm wide"); None where the entry gives none.
    fn shift(&self) -> Option<String> {
        let parts: Vec<String> = [
            self.length_mm.map(|v| format!("{} mm long", compact(v))),
            self.width_mm.map(|v| format!("{} mm wide", compact(v))),
            self.thickness_mm.map(|v| format!("{} mm thick", compact(v))),
            self.youngs_modulus_gpa.map(|v| format!("E = {} GPa", compact(v))),
            self.poisson_ratio.map(|v| format!("ν = {}", compact(v))),
            self.density_kg_m3.map(|v| format!("ρ = {} kg/m³", compact(v))),
        ]
        .into_iter()
        .flatten()
        .collect();
        (!parts.is_empty()).then(|| format!("plate {}", parts.join(", ")))
    }
}

/// The scene's `[stream] plate_sweep`, each entry a plate that carries the scene's support
/// sets, `signals`' sensors and modes and the lumps' region (`ensemble`'s, where the scene
/// gives one; else the swept plate's whole face). Refused on a tail beam, whose stream strikes
/// the box.
pub(super) fn validate(
    raw: &RawScene,
    on_plate: bool,
    signals: &SignalSettings,
    ensemble: Option<&identify::Study>,
) -> Result<Vec<OtherPlate>, Invalid> {
    let (Some(stream), Some(ensemble)) = (&raw.stream, ensemble) else { return Ok(Vec::new()) };
    if stream.plate_sweep.is_empty() {
        return Ok(Vec::new());
    }
    if !on_plate {
        return Err(other(
            "stream.plate_sweep",
            "sweeps the plate; a tail beam's stream strikes the box, whose walls have their own (leave it out)",
        ));
    }
    let region_given = raw.ensemble.as_ref().is_some_and(|e| e.region.is_some());
    let mut out = Vec::with_capacity(stream.plate_sweep.len());
    for (k, change) in stream.plate_sweep.iter().enumerate() {
        let table = format!("stream.plate_sweep[{k}]");
        let Some(shift) = change.shift() else {
            return Err(other(
                table,
                "changes nothing; give at least one of length_mm, width_mm, thickness_mm, youngs_modulus_gpa, poisson_ratio, density_kg_m3",
            ));
        };
        let plate = validate_plate(&change.applied_to(&raw.plate), &table)?;
        carries(&table, &plate, raw, signals)?;
        let region = if region_given {
            on_it(&table, &plate, ensemble.ensemble.region)?
        } else {
            Region { x: (0.0, plate.length()), z: (0.0, plate.width()) }
        };
        out.push(OtherPlate { shift, plate, region });
    }
    Ok(out)
}

/// Whether `plate` carries the scene's support sets, sensors and modes; the refusal names the
/// entry `table` and what does not fit.
fn carries(table: &str, plate: &Plate, raw: &RawScene, signals: &SignalSettings) -> Result<(), Invalid> {
    let (l_mm, w_mm) = (plate.length() / MM, plate.width() / MM);
    for (i, c) in raw.conditions.iter().enumerate() {
        if let Err(e) = validate_condition(i, c, plate) {
            let why = match e {
                Invalid::Range(p) => p.to_string(),
                Invalid::Other { field, message } => format!("{field}: {message}"),
            };
            return Err(other(table, format!("the {l_mm} x {w_mm} mm plate does not carry conditions[{i}]: {why}")));
        }
    }
    for (j, &(x, z)) in signals.sensors.iter().enumerate() {
        if !within(x, plate.length()) || !within(z, plate.width()) {
            return Err(other(
                table,
                format!(
                    "signals.sensors_mm[{j}] = ({}, {}) mm is off the {l_mm} x {w_mm} mm plate; the sensors stay where the scene puts them, so each must lie in [0, {l_mm}] x [0, {w_mm}] mm",
                    compact(x / MM),
                    compact(z / MM)
                ),
            ));
        }
    }
    // Under the chain's rule each plate keeps the modes its own mesh resolves and the chain needs.
    let most = limits::max_modes(l_mm, w_mm);
    if signals.modes > most && !signals.modes_from_chain {
        return Err(other(
            table,
            format!(
                "signals.modes = {} is more than the {l_mm} x {w_mm} mm plate's mesh resolves ({most}); give at most {most} modes",
                signals.modes
            ),
        ));
    }
    Ok(())
}

/// The scene's `region` if it lies on `plate`.
fn on_it(table: &str, plate: &Plate, region: Region) -> Result<Region, Invalid> {
    if within(region.x.1, plate.length()) && within(region.z.1, plate.width()) {
        return Ok(region);
    }
    let (l_mm, w_mm) = (plate.length() / MM, plate.width() / MM);
    Err(other(
        table,
        format!(
            "ensemble.region reaches ({}, {}) mm, off the {l_mm} x {w_mm} mm plate; the lumps strike where the scene's region puts them, so it must lie in [0, {l_mm}] x [0, {w_mm}] mm (without a region they strike the whole plate)",
            compact(region.x.1 / MM),
            compact(region.z.1 / MM)
        ),
    ))
}

/// Whether a coordinate `v` (m) lies on a side of length `side` (m): within the rounding a
/// millimetre number picks up on the way to metres.
fn within(v: f64, side: f64) -> bool {
    v <= side * (1.0 + 1e-12)
}
