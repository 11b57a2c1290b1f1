//! The plate FE verification report (`reports/fem/index.md`): every check of the plate elements
//! with its reference, measured convergence rates and the extreme cases.
//!
//! The checks compute in [`studies::fem_verification`]; here they become the page, its tables
//! (CSV beside each) and the convergence figure.

mod tables;

use crate::present::plot::{series_csv, Axis, Plot, Series};
use crate::template::render;
use crate::Failure;
use output::Artifacts;
use scene::Scene;
use studies::fem_verification::classical::{LEVY, OFF_CENTRE, OFF_CENTRE_POINT};
use studies::fem_verification::paper_plate::{ASPECT_RATIOS, SHORT_SIDE, THICKNESS_RATIOS};
pub use studies::fem_verification::{FemVerificationData, PAPER_K_T};
use studies::progress::{Progress, Silent};
use studies::settings::Settings;
use studies::study::{FemVerification, Study};
use tables::{
    convergence_table, extreme_table, levy_table, mesh, mindlin_growth_table, mindlin_thick_table, narrow_table,
    paper_table, skfem_table, timing_table, update_table,
};

/// The report's prose: every section runs every time, so one template holds them all.
const TEMPLATE: &str = include_str!("../templates/fem_verification.md");
/// The Reissner-Mindlin section's prose.
const MINDLIN: &str = include_str!("../templates/fem_verification_mindlin.md");

/// The centre deflection coefficient of the simply supported square plate under a point
/// load as Timoshenko & Woinowsky-Krieger print it (Table 23), beside our summed series.
const TIMOSHENKO_TABLE_23: &str = "0.01160";

/// A length in mm as the prose writes it: to 0.1 mm, no trailing zeros.
fn mm(v: f64) -> String {
    ((v * 1e4).round() / 10.0).to_string()
}

/// The convergence figure: relative error of the point compliance against the element size
/// h (over the plate length L) on log-log axes, with the slope-2 line the r² ln r singularity
/// of the point-load Green's function predicts, drawn parallel to the first ladder (a third
/// below its finest point).
fn convergence_figure(ladders: &[(String, Vec<(f64, f64)>)]) -> Plot {
    let mut plot = Plot::new(
        "Plate FE: error of the point compliance against element size",
        Axis::log("h / L"),
        Axis::log("|C_FE / C_exact - 1|"),
    );
    for (name, pts) in ladders {
        plot = plot.with(Series::new(name.clone(), pts.clone()));
    }
    if let Some(&(h0, e0)) = ladders.first().and_then(|l| l.1.last()) {
        let (lo, hi) = ladders
            .iter()
            .flat_map(|l| l.1.iter().map(|p| p.0))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), h| (a.min(h), b.max(h)));
        // A third below the first ladder's finest point, so it runs beside the data, not on it.
        let e0 = e0 / 3.0;
        plot = plot
            .with(Series::guide("slope 2 (O(h²))", vec![(lo, e0 * (lo / h0).powi(2)), (hi, e0 * (hi / h0).powi(2))]));
    }
    plot
}

/// The rate between a ladder's two finest meshes as the prose prints it.
fn rate(r: Option<f64>) -> String {
    r.map_or_else(|| "-".into(), |r| format!("{r:.3}"))
}

/// The placeholders of the sections on the classical plates and the scene's plate.
fn plate_values(d: &FemVerificationData) -> Vec<(&'static str, String)> {
    let (ol, ow) = OFF_CENTRE;
    let (ox, oz) = OFF_CENTRE_POINT;
    let (l, b) = (d.plate.length, d.plate.width);
    let p = &d.paper_plate;
    // The rates as printed, each once (the support sets share the corner's mesh behaviour).
    let mut corner_rates: Vec<String> = p.corner_rates.iter().map(|(_, r)| format!("{r:.2}")).collect();
    corner_rates.dedup();
    let corner_conditions: Vec<&str> = p.corner_rates.iter().map(|(c, _)| c.as_str()).collect();
    vec![
        ("navier_coefficient", format!("{:.7}", d.navier_coefficient)),
        ("timoshenko_coefficient", TIMOSHENKO_TABLE_23.into()),
        ("navier_table", convergence_table(&d.navier).to_markdown()),
        ("off_length", ol.to_string()),
        ("off_width", ow.to_string()),
        ("off_x", ox.to_string()),
        ("off_z", oz.to_string()),
        ("off_centre_table", convergence_table(&d.off_centre).to_markdown()),
        ("levy_length", LEVY.0.to_string()),
        ("levy_width", LEVY.1.to_string()),
        ("levy_table", levy_table(&d.levy).to_markdown()),
        ("narrow_coefficient", format!("{:.2}", -d.narrow_coefficient)),
        ("paper_aspect", format!("{:.3}", b / l)),
        ("narrow_table", narrow_table(&d.narrow).to_markdown()),
        ("paper_length", mm(l)),
        ("paper_width", mm(b)),
        ("paper_thickness", mm(d.plate.thickness)),
        ("coarsest", mesh(p.coarsest)),
        ("finest", mesh(p.finest)),
        ("corner_rates", corner_rates.join(", ")),
        ("corner_point", p.corner_point.clone()),
        ("corner_conditions", corner_conditions.join(", ")),
        ("paper_table", paper_table(p).to_markdown()),
    ]
}

/// The placeholders of the sections on the corner update, the extreme cases, scikit-fem and
/// the summary.
fn check_values(d: &FemVerificationData) -> Vec<(&'static str, String)> {
    let (u, s) = (&d.update, &d.skfem);
    let (l, b) = (d.plate.length, d.plate.width);
    let version_list = s.versions.iter().map(|(k, v)| format!("{k} {v}")).collect::<Vec<_>>().join(", ");
    let finest = |m: Option<(usize, usize)>| m.map_or_else(String::new, mesh);
    vec![
        ("base_factor", format!("{:.0e}", u.k_base * l * b / d.plate.rigidity)),
        ("base_stiffness", format!("{:.3e}", u.base_stiffness)),
        ("update_mesh", mesh(u.mesh)),
        ("update_bound", format!("{:e}", u.bound)),
        ("window_from", format!("{:.1e}", u.window.0)),
        ("window_to", format!("{:.1e}", u.window.1)),
        ("update_difference", format!("{:.0e}", u.paper_difference)),
        ("paper_k", format!("{PAPER_K_T:.1e}")),
        ("update_table", update_table(u).to_markdown()),
        ("thickest", THICKNESS_RATIOS[THICKNESS_RATIOS.len() - 1].to_string()),
        ("aspect_from", ASPECT_RATIOS[0].to_string()),
        ("aspect_to", ASPECT_RATIOS[ASPECT_RATIOS.len() - 1].to_string()),
        ("short_side", SHORT_SIDE.to_string()),
        ("extreme_table", extreme_table(&d.extremes).to_markdown()),
        ("versions", version_list),
        ("bfs_finest", finest(s.bfs_finest)),
        ("argyris_finest", finest(s.argyris_finest)),
        ("skfem_table", skfem_table(s).to_markdown()),
        ("timing_table", timing_table(s).to_markdown()),
        ("navier_rate_summary", rate(d.navier.finest_rate)),
        ("navier_rate", rate(d.navier.finest_rate)),
        ("navier_richardson", format!("{:.1e}", d.navier_richardson)),
        ("levy_worst", format!("{:.1e}", d.levy_worst)),
        ("narrow_summary", format!("{:.2}", -d.narrow_coefficient)),
        ("update_summary", format!("{:.0e}", u.paper_difference)),
        ("skfem_worst", format!("{:.1e}", s.worst)),
        ("off_rate", rate(d.off_centre.finest_rate)),
    ]
}

/// The placeholders of the Reissner-Mindlin section.
fn mindlin_values(m: &studies::fem_verification::mindlin::MindlinVerification) -> Vec<(&'static str, String)> {
    use crate::present::table::percent;
    use studies::fem_verification::mindlin::{REDDY_UNIFORM, THIN};
    let rates: Vec<String> = m.thick.iter().map(|l| format!("{} (h/L = {})", rate(l.rate), l.ratio)).collect();
    let worst = m.thick.iter().map(|l| l.extrapolated_error.abs()).fold(0.0, f64::max);
    let (_, (mx, mz), (bx, bz)) = THIN;
    vec![
        ("uniform", format!("{:.4e}", m.uniform)),
        ("reddy", format!("{REDDY_UNIFORM:.3e}")),
        ("thick_table", mindlin_thick_table(m).to_markdown()),
        ("rates", rates.join(" and ")),
        ("extrapolated", format!("{worst:.1e}")),
        ("thin_ratio", format!("{:e}", m.thin.ratio)),
        ("thin_mindlin_mesh", mesh((mx, mz))),
        ("thin_mindlin", percent(m.thin.mindlin / m.thin.series - 1.0)),
        ("thin_bfs_mesh", mesh((bx, bz))),
        ("thin_bfs", percent(m.thin.bfs / m.thin.series - 1.0)),
        ("predicted", format!("{:.4e}", m.growth.predicted)),
        ("growth_table", mindlin_growth_table(m).to_markdown()),
    ]
}

/// The verification's files from its data.
pub fn files(d: &FemVerificationData) -> Result<Artifacts, Failure> {
    let mut a = Artifacts::new();
    let (ol, ow) = OFF_CENTRE;
    let (ox, oz) = OFF_CENTRE_POINT;
    let convergence = convergence_figure(&[
        ("Navier, square, centre".to_string(), d.navier.errors.clone()),
        (format!("Navier, {ol} x {ow} m, at ({ox}, {oz})"), d.off_centre.errors.clone()),
    ]);
    a.add("navier-square.csv", convergence_table(&d.navier).to_csv());
    a.add("convergence.svg", convergence.svg());
    a.add("convergence.csv", series_csv(&convergence.series, "h/L", "rel. error"));
    a.add("navier-off-centre.csv", convergence_table(&d.off_centre).to_csv());
    a.add("levy-simple-free.csv", levy_table(&d.levy).to_csv());
    a.add("narrow-plate-vs-beam.csv", narrow_table(&d.narrow).to_csv());
    a.add("paper-plate-convergence.csv", paper_table(&d.paper_plate).to_csv());
    a.add("corner-update.csv", update_table(&d.update).to_csv());
    a.add("extreme-cases.csv", extreme_table(&d.extremes).to_csv());
    a.add("skfem-comparison.csv", skfem_table(&d.skfem).to_csv());
    let mut values = plate_values(d);
    values.extend(check_values(d));
    a.add("mindlin-series.csv", mindlin_thick_table(&d.mindlin).to_csv());
    a.add("mindlin-node-supports.csv", mindlin_growth_table(&d.mindlin).to_csv());
    let page = render("fem_verification.md", TEMPLATE, &values)?;
    let mindlin = render("fem_verification_mindlin.md", MINDLIN, &mindlin_values(&d.mindlin))?;
    a.add("index.md", page + &mindlin);
    Ok(a)
}

/// Writes the report.
pub fn report(scene: &Scene) -> Result<Artifacts, Failure> {
    study(scene, &Silent)
}

/// [`report`], reporting its progress.
pub fn study(scene: &Scene, progress: &dyn Progress) -> Result<Artifacts, Failure> {
    files(&FemVerification::compute(scene, &Settings::default(), progress)?)
}
