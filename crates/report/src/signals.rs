//! `impact signals`: the scene's impacts through the reduced-order model
//! (coupled::reduced), their first-contact numbers with the truncation error and validity,
//! and the sensor and corner time series as CSV files with units in the headers.

use crate::present::rows::{slug, validity_text};
use crate::present::table::{Cell, Table};
use crate::Failure;
use coupled::reduced::plan::{run, ModelSummary, SceneImpact};
use output::Artifacts;
use scene::Scene;
use serde::Serialize;

/// What `impact signals` computed.
#[derive(Debug, Serialize)]
pub struct SignalRun {
    /// The reduced model of each support set.
    pub models: Vec<ModelSummary>,
    /// Every impact, its time series left out (they are in the CSV files).
    pub impacts: Vec<ImpactRow>,
}

/// One impact's numbers (SI).
#[derive(Debug, Serialize)]
pub struct ImpactRow {
    /// Support set name.
    pub condition: String,
    /// Body name.
    pub body: String,
    /// Impact point (x, z), m.
    pub point: (f64, f64),
    /// Velocity, m/s.
    pub velocity: f64,
    /// First-contact quantities and their truncation errors.
    pub quantities: coupled::transient::Quantities,
    /// The errors.
    pub errors: coupled::transient::Quantities,
    /// Contacts in the window.
    pub contacts: usize,
    /// Validity criteria.
    pub validity: coupled::Validity,
    /// The CSV file of its time series, relative to the output directory.
    pub file: String,
}

/// Runs the scene and returns the summary, the terminal tables and the files.
pub fn signals(scene: &Scene) -> Result<(SignalRun, Vec<Table>, Artifacts), Failure> {
    let (models, impacts) = run(scene)?;
    let mut a = Artifacts::new();
    let mut rows = Vec::with_capacity(impacts.len());
    for (k, imp) in impacts.iter().enumerate() {
        let file = format!(
            "signals/{}/{}-{:04}.csv",
            slug(&scene.conditions[imp.condition].name),
            slug(&scene.bodies[imp.body].name),
            k + 1
        );
        a.try_add(file.clone(), series(imp).to_csv())?;
        let o = &imp.result.outcome;
        rows.push(ImpactRow {
            condition: scene.conditions[imp.condition].name.clone(),
            body: scene.bodies[imp.body].name.clone(),
            point: imp.point,
            velocity: imp.velocity,
            quantities: imp.quantities,
            errors: imp.errors,
            contacts: o.contacts.len() + usize::from(o.unfinished_contact.is_some()),
            validity: imp.validity,
            file,
        });
    }
    let run = SignalRun { models, impacts: rows };
    let tables = vec![model_table(scene, &run), impact_table(&run), sensor_table(scene)];
    for (name, t) in ["models.csv", "impacts.csv", "sensors.csv"].into_iter().zip(&tables) {
        a.add(name, t.to_csv());
    }
    a.add("signals.json", serde_json::to_string_pretty(&run)?);
    Ok((run, tables, a))
}

/// One impact's time series: t and every channel, units in the headers.
fn series(imp: &SceneImpact) -> Table {
    let s = &imp.result.signals;
    let mut headers = vec!["t (s)".to_string()];
    headers.extend(s.channels.iter().map(|c| format!("{} ({})", c.kind.label(), c.kind.unit())));
    let refs: Vec<&str> = headers.iter().map(String::as_str).collect();
    let mut t = Table::new("", &refs);
    for (k, time) in s.times().into_iter().enumerate() {
        let mut row = vec![Cell::Num(time)];
        row.extend(s.channels.iter().map(|c| Cell::Num(c.samples[k])));
        t.push(row);
    }
    t
}

fn model_table(scene: &Scene, run: &SignalRun) -> Table {
    let sig = &scene.signals;
    let mut t = Table::new(
        format!(
            "reduced models: {} ms at {} Hz, modal damping ratio {}",
            sig.window * 1e3,
            sig.rate_hz,
            sig.damping_ratio
        ),
        &["condition", "modes N", "f_1 (Hz)", "f_N (Hz)", "worst mode residual", "elements", "steps per contact"],
    );
    for m in &run.models {
        t.push(vec![
            m.condition.as_str().into(),
            Cell::Int(m.settings.modes as u64),
            Cell::Num(m.frequency_range_hz.0),
            Cell::Num(m.frequency_range_hz.1),
            Cell::Num(m.worst_residual),
            Cell::Int(m.settings.elements as u64),
            Cell::Num(m.settings.steps_per_contact),
        ]);
    }
    t
}

fn impact_table(run: &SignalRun) -> Table {
    let mut t = Table::new(
        "impacts: first contact (errors: change from N/2 modes, an upper estimate of the truncation error)",
        &[
            "condition",
            "body",
            "x (mm)",
            "z (mm)",
            "v (m/s)",
            "peak force (N)",
            "peak force error (N)",
            "contact time (s)",
            "contact time error (s)",
            "restitution",
            "restitution error",
            "contacts",
            "validity",
            "file",
        ],
    );
    for r in &run.impacts {
        let (q, e) = (&r.quantities, &r.errors);
        t.push(vec![
            r.condition.as_str().into(),
            r.body.as_str().into(),
            Cell::Num(r.point.0 * 1e3),
            Cell::Num(r.point.1 * 1e3),
            Cell::Num(r.velocity),
            Cell::Num(q.peak_force),
            Cell::Num(e.peak_force),
            Cell::Num(q.contact_time),
            Cell::Num(e.contact_time),
            Cell::Num(q.restitution),
            Cell::Num(e.restitution),
            Cell::Int(r.contacts as u64),
            validity_text(&r.validity).into(),
            r.file.as_str().into(),
        ]);
    }
    t
}

fn sensor_table(scene: &Scene) -> Table {
    let mut t = Table::new("sensors", &["sensor", "x (mm)", "z (mm)"]).csv_name("sensor", &["sensor_name"]);
    for (i, (x, z)) in scene.signals.sensors.iter().enumerate() {
        t.push(vec![format!("s{}", i + 1).into(), Cell::Num(x * 1e3), Cell::Num(z * 1e3)]);
    }
    t
}
