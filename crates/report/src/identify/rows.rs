//! The rows an identification streams to disk as it runs: `impacts.csv`, one row per impact
//! of each support set's main run, and `features.csv`, one row per impact and channel. They
//! are written as the impacts arrive and never held in memory.

use crate::present::table::unit_key;
use crate::provenance::Provenance;
use crate::Failure;
use identify::features::FEATURES;
use output::{OutputDir, StreamedFile};
use std::io::Write as _;
use studies::identify::MainImpact;

/// Which row files an identification streams: `impacts.csv` always, `features.csv` (one row
/// per impact and channel, about 19 kB per impact with the default candidate grid: 112 MB for
/// `scenes/caving-stream.toml`) unless left out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RowFiles {
    /// `impacts.csv` and `features.csv`.
    All,
    /// `impacts.csv` only.
    Impacts,
}

/// The streamed files: one row per impact, one row per impact and channel.
pub(super) struct Rows {
    impacts: csv::Writer<StreamedFile>,
    features: Option<csv::Writer<StreamedFile>>,
}

/// The columns of `impacts.csv`, in SI (docs/output-format.md).
const IMPACT_HEADERS: [&str; 19] = [
    "condition",
    "impact",
    "family",
    "class",
    "x_m",
    "z_m",
    "radius_m",
    "velocity_m_per_s",
    "density_kg_per_m3",
    "youngs_modulus_Pa",
    "poisson_ratio",
    "cohesion_Pa",
    "friction_angle_rad",
    "force_max_N",
    "contact_time_s",
    "contacts",
    "delta_max_per_delta_my",
    "t_H_per_T1",
    "mass_kg",
];

/// The columns of `features.csv` before the features.
const FEATURE_ROW_HEADERS: [&str; 7] = ["condition", "impact", "class", "quantity", "x_m", "z_m", "unit"];

/// The columns of `features.csv`: [`FEATURE_ROW_HEADERS`], then one per feature of
/// [`FEATURES`], its key and its unit. A channel's features are in its own SI unit, named
/// in the row's `unit` column (`m`, `m_per_s`, `m_per_s2`, `N`); `_unit` in a column name
/// stands for it: "peak_unit", "energy_unit2_s", "duration_s", "dominant_frequency_Hz".
fn feature_headers() -> Vec<String> {
    let unit_key = |u: String| u.replace(['(', ')', '^'], "").replace('*', "_").replace('/', "_per_");
    FEATURE_ROW_HEADERS
        .iter()
        .map(|h| h.to_string())
        .chain(FEATURES.iter().map(|f| format!("{}_{}", f.key(), unit_key(f.unit("unit")))))
        .collect()
}

fn num(v: f64) -> String {
    if v.is_finite() {
        format!("{v:e}")
    } else {
        String::new()
    }
}

/// Opens `name` under `dir` in `out` with the provenance line first.
fn open_stream(
    out: &mut OutputDir,
    dir: &str,
    name: &str,
    provenance: &Provenance,
    headers: &[impl AsRef<[u8]>],
) -> Result<csv::Writer<StreamedFile>, Failure> {
    let path = if dir.is_empty() { name.to_string() } else { format!("{dir}/{name}") };
    let mut file = out.stream(&path)?;
    file.write_all(provenance.csv_line().as_bytes())?;
    let mut w = csv::Writer::from_writer(file);
    w.write_record(headers)?;
    Ok(w)
}

impl Rows {
    /// Opens the row files `files` under `dir` in `out`.
    pub(super) fn open(
        out: &mut OutputDir,
        dir: &str,
        provenance: &Provenance,
        files: RowFiles,
    ) -> Result<Self, Failure> {
        let impacts = open_stream(out, dir, "impacts.csv", provenance, &IMPACT_HEADERS)?;
        let features = match files {
            RowFiles::All => Some(open_stream(out, dir, "features.csv", provenance, &feature_headers())?),
            RowFiles::Impacts => None,
        };
        Ok(Self { impacts, features })
    }

    /// Writes one impact's row and its channels' rows.
    pub(super) fn write(&mut self, m: &MainImpact<'_>) -> Result<(), Failure> {
        let (condition, r, family, channels) = (m.condition, m.record, m.family, m.channels);
        let d = &r.draw;
        let mass = d.density * 4.0 / 3.0 * std::f64::consts::PI * d.radius.powi(3);
        self.impacts.write_record([
            condition.to_string(),
            d.index.to_string(),
            family.to_string(),
            d.class.key().to_string(),
            num(d.x),
            num(d.z),
            num(d.radius),
            num(d.velocity),
            num(d.density),
            num(d.youngs_modulus),
            num(d.poisson_ratio),
            num(d.cohesion),
            num(d.friction_angle_deg.to_radians()),
            num(r.force_max),
            r.contact_time.map_or(String::new(), num),
            r.contacts.to_string(),
            num(r.compression_ratio),
            num(r.hertz_time_ratio),
            num(mass),
        ])?;
        let Some(features) = self.features.as_mut() else { return Ok(()) };
        for (c, f) in channels.iter().zip(r.channel_features()) {
            let row = [
                condition.to_string(),
                d.index.to_string(),
                d.class.key().to_string(),
                c.quantity.to_string(),
                num(c.at.0),
                num(c.at.1),
                unit_key(c.unit),
            ];
            features.write_record(row.into_iter().chain(f.iter().map(|v| num(*v))))?;
        }
        Ok(())
    }

    /// Closes the files into `out`.
    pub(super) fn finish(self, out: &mut OutputDir) -> Result<(), Failure> {
        for w in std::iter::once(self.impacts).chain(self.features) {
            let file = w.into_inner().map_err(|e| e.into_error())?;
            out.finish_stream(file)?;
        }
        Ok(())
    }
}
