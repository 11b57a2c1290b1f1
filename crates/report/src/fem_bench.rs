//! `impact fem-bench` rendered: the mesh ladder and the map's cost as tables.

use crate::present::table::{Cell, Table};
pub use studies::fem_bench::{bench, centre_ladder, BenchReport, Rung};

/// The bench as tables.
pub fn bench_tables(r: &BenchReport) -> Vec<Table> {
    let mut ladder = Table::new(
        "Mesh ladder: Con 1, centre compliance (reference: Richardson of the two finest)",
        &["mesh", "DOFs", "C (m/N)", "rel. error", "time (s)"],
    );
    for g in &r.ladder {
        ladder.push(vec![
            format!("{} x {}", g.nx, g.nz).into(),
            g.dofs.into(),
            g.compliance.into(),
            g.error.into(),
            g.seconds.into(),
        ]);
    }
    let mut t = Table::new(
        format!("Compliance map: {} points x 3 conditions on the {} x {} mesh", r.points, r.chosen.0, r.chosen.1),
        &["stage", "value"],
    );
    let rows: Vec<(&str, Cell)> = vec![
        ("DOFs", r.dofs.into()),
        ("stored nonzeros of K (upper)", r.nonzeros.into()),
        ("assembly + symbolic analysis (s)", r.assembly_s.into()),
        ("numeric factorization, one for all conditions (s)", r.factorization_s.into()),
        ("the base at every point: selected inverse, or solves below break-even (s)", r.probe_s.into()),
        ("rank-4 updates for Con 1-3 (s)", r.update_s.into()),
        ("total (s)", r.total_s.into()),
        ("reference: 3 factorizations + single solves (s)", r.reference_s.into()),
        ("speed-up over the reference", (r.reference_s / r.total_s).into()),
        ("max relative difference to the reference", r.max_difference_to_reference.into()),
        ("max relative residual of the base's solves", r.max_residual.into()),
        ("peak resident memory, mesh ladder to 160 x 128 (MiB)", r.peak_memory_mib.map_or(Cell::Empty, Cell::Num)),
        ("peak resident memory, the map alone (MiB)", r.map_peak_memory_mib.map_or(Cell::Empty, Cell::Num)),
    ];
    for (k, v) in rows {
        t.push(vec![k.into(), v]);
    }
    vec![ladder, t]
}
