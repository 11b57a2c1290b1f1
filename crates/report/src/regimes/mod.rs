//! The regime maps written up: where the paper's quasi-static balance holds, measured with the
//! transient model over plate size, thickness, sphere mass and corner-spring stiffness, set
//! beside Olsson's mass criterion, Christoforou and Yigit's characterisation, the t_c/T₁
//! criterion of the validity status and the closed-form rule of `coupled::regimes`.
//!
//! The maps compute in [`studies::regimes`] (with the paper's Flores law whatever the scene
//! names: they measure the paper's balance); here they become the page, its figures and
//! `map.csv`.

mod tables;

use crate::present::plot::{line_plot, Scale, Series};
use crate::present::table::sig;
use crate::template::render;
use crate::Failure;
use coupled::regimes::{
    FAST_CONTACT, OLSSON_QUASI_STATIC, OLSSON_WAVE_CONTROLLED, RESONANCE_FACTOR, RULE_LIMIT, SLOW_CONTACT, SLOW_FACTOR,
};
use coupled::validity::QUASI_STATIC_MIN_RATIO;
use output::Artifacts;
use scene::Scene;
pub use studies::regimes::{
    MapRow, RegimeData, Score, Slice, MAP_MESH, MAP_STEPS, RADIUS_FACTORS, SCALES, SPRINGS, THICKNESS_FACTORS,
};
use studies::study::{RegimeMaps, Study};
use studies::{
    progress::{Progress, Silent},
    settings::Settings,
};
use tables::{full_table, grid_table, mid_thickness, olsson_table, points_table, score_table, spring_table};

const TEMPLATE: &str = include_str!("../templates/regimes.md");
/// The main report's line on the study.
const FINDING: &str = include_str!("../templates/regimes-finding.md");

/// The support family whose curves the figures draw.
const CON1: &str = "Con 1";
/// The figures' y axis.
const ERROR_AXIS: &str = "|P transient/quasi-static - 1|";

/// |error| against a closed-form abscissa, one curve per sphere at the scene's size over the
/// thicknesses, for one condition.
fn curves(rows: &[MapRow], condition: &str, scale: f64, x: impl Fn(&MapRow) -> f64, radii: &[f64]) -> Vec<Series> {
    radii
        .iter()
        .map(|&radius| {
            let mut pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| {
                    r.slice == Slice::Centre && r.condition == condition && r.scale == scale && r.radius == radius
                })
                .map(|r| (x(r), r.error()))
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            Series::new(format!("R = {} mm, h over the map", sig(radius * 1e3, 3)), pts)
        })
        .collect()
}

/// A vertical line at `x` across the y range of `series`.
fn vertical(name: &str, x: f64, series: &[Series]) -> Series {
    let ys = series.iter().flat_map(|s| s.points.iter().map(|p| p.1)).filter(|y| *y > 0.0 && y.is_finite());
    let (lo, hi) = ys.fold((f64::INFINITY, 0.0f64), |(a, b), y| (a.min(y), b.max(y)));
    Series::new(name, if lo.is_finite() { vec![(x, lo), (x, hi)] } else { vec![] })
}

/// A horizontal line at `y` across the x range of `series`.
fn horizontal(name: &str, y: f64, series: &[Series]) -> Series {
    let xs = series.iter().flat_map(|s| s.points.iter().map(|p| p.0)).filter(|x| x.is_finite());
    let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)));
    Series::new(name, if lo.is_finite() { vec![(lo, y), (hi, y)] } else { vec![] })
}

/// The force error against Olsson's mass ratio and against Christoforou and Yigit's bound,
/// Con 1 at the centre of the scene's plate size.
fn mass_and_bound_plots(d: &RegimeData, a: &mut Artifacts) {
    let (rows, radii) = (&d.rows, &d.radii);
    let olsson_curves = curves(rows, CON1, 1.0, |r| r.mass_ratio.log10(), radii);
    let mut olsson_plot = olsson_curves.clone();
    olsson_plot.push(vertical("Olsson: wave controlled below 0.23", OLSSON_WAVE_CONTROLLED.log10(), &olsson_curves));
    olsson_plot.push(vertical("Olsson: quasi-static above 2", OLSSON_QUASI_STATIC.log10(), &olsson_curves));
    olsson_plot.push(horizontal("3 %", RULE_LIMIT, &olsson_curves));
    a.add(
        "olsson.svg",
        line_plot(
            "Con 1, centre, the scene's plate size: force error against Olsson's mass ratio",
            "log10(M_i/M_p)",
            ERROR_AXIS,
            &olsson_plot,
            Scale::Log,
        ),
    );
    let cy_curves = curves(rows, CON1, 1.0, |r| r.rule.parameters.error_bound().max(1e-6).log10(), radii);
    let mut cy_plot = cy_curves.clone();
    let xs: Vec<f64> = cy_curves.iter().flat_map(|s| s.points.iter().map(|p| p.0)).collect();
    let (x_lo, x_hi) = xs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    if x_lo.is_finite() {
        cy_plot.push(Series::new("measured = B", vec![(x_lo, 10f64.powf(x_lo)), (x_hi, 10f64.powf(x_hi))]));
    }
    a.add(
        "christoforou-yigit.svg",
        line_plot(
            "Con 1, centre: force error against Christoforou and Yigit's bound B",
            "log10 B",
            ERROR_AXIS,
            &cy_plot,
            Scale::Log,
        ),
    );
}

/// The force error against t_H/T₁,est on the smallest plates (they reach the slow regime),
/// and against the corner-spring stiffness on the scene's plate.
fn period_and_spring_plots(d: &RegimeData, a: &mut Artifacts) {
    let (rows, radii) = (&d.rows, &d.radii);
    let small_scale = SCALES.iter().copied().fold(f64::INFINITY, f64::min);
    let period_curves = curves(rows, CON1, small_scale, |r| r.rule.period_ratio.unwrap_or(f64::NAN).log10(), radii);
    let mut period_plot = period_curves.clone();
    period_plot.push(vertical("t_H/T₁ = 0.2 (fast below)", FAST_CONTACT.log10(), &period_curves));
    period_plot.push(vertical("t_H/T₁ = 2 (slow above)", SLOW_CONTACT.log10(), &period_curves));
    period_plot.push(horizontal("3 %", RULE_LIMIT, &period_curves));
    a.add(
        "period.svg",
        line_plot(
            "Con 1, centre, the smallest plates: force error against t_H/T₁,est",
            "log10(t_H/T₁,est)",
            ERROR_AXIS,
            &period_plot,
            Scale::Log,
        ),
    );
    let h = mid_thickness(rows);
    let spring_series: Vec<Series> = ["Con 2", "Con 3"]
        .iter()
        .flat_map(|fam| radii.iter().take(2).map(move |&radius| (fam, radius)))
        .map(|(fam, radius)| {
            let mut pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| {
                    r.slice == Slice::Centre
                        && r.family == *fam
                        && r.scale == 1.0
                        && r.thickness == h
                        && r.radius == radius
                })
                .filter_map(|r| Some((r.spring?.log10(), r.error())))
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            Series::new(format!("{fam}, R = {} mm", sig(radius * 1e3, 3)), pts)
        })
        .collect();
    a.add(
        "springs.svg",
        line_plot(
            "Centre, the scene's plate: force error against the corner-spring stiffness",
            "log10(k_T / (N/m))",
            ERROR_AXIS,
            &spring_series,
            Scale::Log,
        ),
    );
}

/// The main report's line on the study: how the closed-form rule and t_c/T₁ ≥ 0.2 fare on the
/// `cases` centre cases, and the rule on the `points_cases` cases at the scene's points.
fn main_finding(
    cases: usize,
    rule: &Score,
    ratio: &Score,
    points_cases: usize,
    points: &Score,
) -> Result<String, Failure> {
    Ok(render(
        "regimes-finding.md",
        FINDING,
        &[
            ("cases", cases.to_string()),
            ("rule_trusted", rule.trusted.to_string()),
            ("rule_wrong", rule.trusted_wrong.to_string()),
            ("rule_worst", format!("{:.1}", 100.0 * rule.worst_trusted)),
            ("ratio_trusted", ratio.trusted.to_string()),
            ("ratio_wrong", ratio.trusted_wrong.to_string()),
            ("ratio_worst", format!("{:.0}", 100.0 * ratio.worst_trusted)),
            ("points_cases", points_cases.to_string()),
            ("points_trusted", points.trusted.to_string()),
            ("points_wrong", points.trusted_wrong.to_string()),
            ("limit", format!("{}", 100.0 * RULE_LIMIT)),
            ("qs_ratio", QUASI_STATIC_MIN_RATIO.to_string()),
        ],
    )?)
}

/// The page's numbers: the run, the check and the criteria's scores.
fn numbers(scene: &Scene, d: &RegimeData) -> Vec<(&'static str, String)> {
    let (s, c) = (&d.summary, &d.check);
    vec![
        ("scene", scene.name.clone()),
        ("body", d.body.clone()),
        ("velocity", sig(d.velocity, 3)),
        ("cases", s.centre_cases.to_string()),
        ("points_cases", s.points_cases.to_string()),
        ("families", d.families.to_string()),
        ("mesh", d.mesh.to_string()),
        ("steps", d.steps.to_string()),
        ("map_secs", format!("{:.0}", d.map_secs)),
        ("threads", d.threads.to_string()),
        ("checked", c.cases.to_string()),
        ("check_force", sig(c.force, 2)),
        ("check_near", sig(c.near, 2)),
        ("check_time", sig(c.time, 2)),
        ("recount", c.recount.to_string()),
        ("check_secs", format!("{:.0}", d.check_secs)),
        ("rule_trusted", s.rule.trusted.to_string()),
        ("rule_wrong", s.rule.trusted_wrong.to_string()),
        ("rule_worst", format!("{:.1}", 100.0 * s.rule.worst_trusted)),
        ("rule_flagged", s.rule.flagged.to_string()),
        ("rule_fine", s.rule.flagged_fine.to_string()),
        ("points_trusted", s.rule_points.trusted.to_string()),
        ("points_wrong", s.rule_points.trusted_wrong.to_string()),
        ("points_flagged_fine", s.rule_points.flagged_fine.to_string()),
        ("points_flagged", s.rule_points.flagged.to_string()),
        ("trusted_time", format!("{:.1}", 100.0 * s.trusted_time)),
        ("ratio_trusted", s.ratio.trusted.to_string()),
        ("ratio_wrong", s.ratio.trusted_wrong.to_string()),
        ("ratio_worst", format!("{:.0}", 100.0 * s.ratio.worst_trusted)),
        ("large_trusted", s.large.trusted.to_string()),
        ("large_wrong", s.large.trusted_wrong.to_string()),
        ("large_worst", format!("{:.0}", 100.0 * s.large.worst_trusted)),
        ("small_cases", s.small_cases.to_string()),
        ("small_fine", s.small_fine.to_string()),
        ("small_fine_lambda", sig(s.small_fine_lambda, 2)),
        ("repeated", s.repeated.to_string()),
        ("repeated_min_zeta", sig(s.repeated_min_zeta, 2)),
        ("fast_cases", s.fast_cases.to_string()),
        ("fast_bound_holds", s.fast_bound_holds.to_string()),
        ("band_low", format!("{:.2}", s.band_low)),
        ("slow_high", format!("{:.2}", s.slow_high)),
        ("period_ratio_lo", format!("{:.3}", s.period_ratio_range.0)),
        ("period_ratio_hi", format!("{:.3}", s.period_ratio_range.1)),
        ("olsson_wave", OLSSON_WAVE_CONTROLLED.to_string()),
        ("olsson_quasi", OLSSON_QUASI_STATIC.to_string()),
        ("fast_contact", FAST_CONTACT.to_string()),
        ("slow_contact", SLOW_CONTACT.to_string()),
        ("resonance_factor", RESONANCE_FACTOR.to_string()),
        ("slow_factor", SLOW_FACTOR.to_string()),
        ("limit", format!("{}", 100.0 * RULE_LIMIT)),
        ("qs_ratio", QUASI_STATIC_MIN_RATIO.to_string()),
    ]
}

/// The maps' files and the main report's line on them.
pub fn files(scene: &Scene, d: &RegimeData) -> Result<(Artifacts, String), Failure> {
    let mut a = Artifacts::new();
    a.add("map.csv", full_table(&d.rows).to_csv());
    mass_and_bound_plots(d, &mut a);
    period_and_spring_plots(d, &mut a);
    let mut values = numbers(scene, d);
    values.extend([
        ("score_table", score_table(d, Slice::Centre).to_markdown()),
        ("points_score_table", score_table(d, Slice::Points).to_markdown()),
        ("olsson_table", olsson_table(d).to_markdown()),
        ("con1_table", grid_table(&d.rows, CON1, &d.radii).to_markdown()),
        ("spring_table", spring_table(&d.rows, &d.radii).to_markdown()),
        ("points_table", points_table(d).to_markdown()),
    ]);
    a.add("index.md", render("regimes.md", TEMPLATE, &values)?);
    let s = &d.summary;
    let finding = main_finding(s.centre_cases, &s.rule, &s.ratio, s.points_cases, &s.rule_points)?;
    Ok((a, finding))
}

/// The regime-maps report.
pub fn report(scene: &Scene) -> Result<Artifacts, Failure> {
    Ok(study(scene, &Silent)?.0)
}

/// [`report`], and its finding for the main report: one Markdown bullet line linking the
/// study (nested in the folder `regimes`).
pub fn study(scene: &Scene, progress: &dyn Progress) -> Result<(Artifacts, String), Failure> {
    let data = RegimeMaps::compute(scene, &Settings::default(), progress)?;
    files(scene, &data)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The main report's line renders every number it is given (the study itself takes
    /// minutes and runs in `impact report`).
    #[test]
    fn the_main_report_line_renders() {
        let rule = Score { trusted: 101, trusted_wrong: 0, worst_trusted: 0.017, flagged: 679, flagged_fine: 126 };
        let ratio = Score { trusted: 251, trusted_wrong: 107, worst_trusted: 0.32, ..Score::default() };
        let points = Score { trusted: 30, ..Score::default() };
        let line = main_finding(780, &rule, &ratio, 240, &points).unwrap();
        for part in [
            "780 cases",
            "in 101, 0 of them",
            "worst 1.7 %",
            "trusts 251, 107 of them wrongly (worst 32 %)",
            "on 240 cases",
            "trusts 30, 0 wrongly",
            "](regimes/index.md)",
        ] {
            assert!(line.contains(part), "{part}: {line}");
        }
    }
}
