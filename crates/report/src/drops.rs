//! `impact drops` rendered: the measured drops of a recording against the scene's model
//! ([`studies::drops`]): `drops.csv` with one row per drop and quantity (measured, predicted,
//! the bar and its parts), `drops.json` with the run's settings and every row, and the
//! terminal's summary of which drops disagree where.

use crate::present::table::{sig, unit_key, Cell, Table};
use crate::Failure;
use identify::recording::Recording;
use output::Artifacts;
use scene::Scene;
use studies::drops::{compute, DropsData};
use studies::progress::Progress;

/// The comparison of `recording` (read from `origin`) with `scene`, and its files.
pub fn drops(
    scene: &Scene,
    recording: &Recording,
    origin: &str,
    progress: &dyn Progress,
) -> Result<(Artifacts, DropsData), Failure> {
    let data = compute(scene, recording, origin, progress)?;
    let mut a = Artifacts::new();
    a.add("drops.csv", rows_table(&data).to_csv());
    a.add("drops.json", serde_json::to_string_pretty(&data)?);
    Ok((a, data))
}

/// One row per drop and quantity.
fn rows_table(d: &DropsData) -> Table {
    let headers = [
        "drop",
        "touch (s)",
        "class",
        "quantity",
        "unit",
        "measured",
        "predicted",
        "bar",
        "truncation",
        "time step",
        "chain",
        "noise sd",
        "disagrees",
        "note",
    ];
    let mut t = Table::new("", &headers);
    for drop in &d.drops {
        for r in &drop.rows {
            t.push(vec![
                Cell::Int(drop.index as u64),
                Cell::Num(drop.touch),
                drop.class.map_or("not stated", |c| c.key()).into(),
                r.quantity.as_str().into(),
                unit_key(&r.unit).into(),
                Cell::Num(r.measured),
                Cell::Num(r.predicted),
                Cell::Num(r.bar),
                Cell::Num(r.truncation),
                Cell::Num(r.step),
                Cell::Num(r.chain),
                Cell::Num(r.noise_sd),
                r.disagrees.into(),
                r.note.as_str().into(),
            ]);
        }
    }
    t
}

/// The terminal's summary: one line per drop, its largest excess over the bar.
pub fn summary_table(d: &DropsData) -> Table {
    let title = format!(
        "{} drops on {} ({}) against the model of {} modes (bars: {} modes, {} steps per contact, {} realisations of the chain's background)",
        d.drops.len(),
        d.condition,
        d.scene,
        d.modes.0,
        d.modes.1,
        sig(d.steps_per_contact.1, 3),
        d.realisations
    );
    let mut t =
        Table::new(title, &["drop", "touch (s)", "v (m/s)", "rows outside the bar", "largest |Δ|/bar", "not compared"]);
    for drop in &d.drops {
        let worst = drop
            .rows
            .iter()
            .filter(|r| r.bar > 0.0)
            .map(|r| ((r.measured - r.predicted).abs() / r.bar, r.quantity.as_str()))
            .fold(None, |a: Option<(f64, &str)>, b| match a {
                Some(a) if a.0 >= b.0 => Some(a),
                _ => Some(b),
            });
        // A count here; which rows, with their numbers, is in drops.csv.
        let outside = drop.rows.iter().filter(|r| r.disagrees).count();
        t.push(vec![
            Cell::Int(drop.index as u64),
            Cell::Num(drop.touch),
            Cell::Sig(drop.velocity, 4),
            format!("{outside} of {}", drop.rows.len()).into(),
            worst.map_or("no row has a bar".into(), |(r, q)| format!("{} ({q})", sig(r, 3)).into()),
            drop.notes.join("; ").into(),
        ]);
    }
    t
}
