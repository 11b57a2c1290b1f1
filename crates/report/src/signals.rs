//! `impact signals` rendered: the models, the impacts' first-contact numbers and the sensors as
//! tables, and each impact's time series as a CSV file with units in the headers.

use crate::present::rows::validity_text;
use crate::present::table::{Cell, Table};
use crate::Failure;
use coupled::reduced::plan::SceneImpact;
use output::Artifacts;
use scene::Scene;
pub use studies::signals::{compute, ImpactRow, SignalRun, SignalsData};
use studies::{progress::Silent, settings::Settings};

/// Runs the scene ([`studies::signals::compute`]) and returns the summary, the terminal
/// tables and the files.
pub fn signals(scene: &Scene) -> Result<(SignalRun, Vec<Table>, Artifacts), Failure> {
    let data = compute(scene, &Settings::default(), &Silent)?;
    let mut a = Artifacts::new();
    for (imp, row) in data.impacts.iter().zip(&data.run.impacts) {
        a.try_add(row.file.clone(), series(imp).to_csv())?;
    }
    let run = data.run;
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
