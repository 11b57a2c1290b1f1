//! Running a scene with the models a caller picks: the one entry point the command line and
//! the Python package share, so that both give the same numbers for the same scene. It
//! refuses requests beyond the memory and transient-run budgets before computing anything.

use crate::progress::Progress;
use crate::settings::{BASE_MESH, LEVELS};
use crate::Failure;
use coupled::compliance::mindlin::{MINDLIN_BASE_MESH, MINDLIN_LEVELS};
use coupled::compliance::MindlinModel;
use coupled::plan::{fundamental_periods, run, run_transient_observed, transient_case_count, ModelKind, Results};
use coupled::{BeamModel, PlateModel};
use scene::{Analysis, Scene};

/// Most transient runs one request may ask for: a response costs about 10 (its error
/// estimate runs the case at half and double the step and the mesh, and a finer level where
/// the tolerance asks for one), a yield velocity at most 25 (the estimate at its start and a
/// bracketed root in v to 1e-6, usually 5-10 runs; counted at the most). On the 20-element
/// mesh a run takes 0.05-0.15 s here, so 2000 of them a few minutes; at the default tolerance
/// some cases run on the 40-element mesh, about four times dearer, so a request at the limit
/// can take tens of minutes (`--tolerance 1e-3` keeps the paper's cases on the first). A run
/// that the stopping rule does not end early follows the sphere through every contact for up
/// to 200 Hertz times ([`coupled::transient::case::WINDOW_HERTZ_TIMES`]): a heavy sphere struck
/// again and again by a thin plate costs up to a few times a single contact's run.
pub const MAX_TRANSIENT_RUNS: usize = 2000;

/// Most Mindlin patch responses one request may ask for (support sets x points): each is a
/// solve and an energy pass on each of the ladder's three meshes, about 0.1 s together on the
/// paper's plate, so the limit is a few minutes.
pub const MAX_MINDLIN_POINTS: usize = 2000;

/// Memory a result row takes, bytes, through to its JSON: measured 3.7 KB on a 10,000-point
/// sweep of the default scene (240,000 rows in 0.9 GB).
pub const BYTES_PER_ROW: f64 = 4096.0;
/// What one request may hold in memory: a sixth of this machine's 24 GiB.
pub const MEMORY_BUDGET_BYTES: f64 = 4.0 * 1024.0 * 1024.0 * 1024.0;

/// The model named `key` ("beam", "plate", "transient", "mindlin"), or every model for "all".
pub fn model_kinds(key: &str) -> Option<Vec<ModelKind>> {
    if key == "all" {
        return Some(ModelKind::ALL.to_vec());
    }
    ModelKind::ALL.into_iter().find(|m| m.key() == key).map(|m| vec![m])
}

/// Checks that the scene's rows fit the memory budget and its transient runs the run budget.
pub fn check_budget(scene: &Scene, models: &[ModelKind]) -> Result<(), Failure> {
    let per_point = scene.bodies.len()
        * scene.conditions.len()
        * models.len()
        * (if scene.wants(Analysis::Responses) { scene.velocities.len() } else { 0 }
            + usize::from(scene.wants(Analysis::YieldVelocity)));
    let rows = per_point * scene.points.len();
    let bytes = rows as f64 * BYTES_PER_ROW;
    if bytes > MEMORY_BUDGET_BYTES {
        let most = (MEMORY_BUDGET_BYTES / BYTES_PER_ROW) as usize / per_point.max(1);
        return Err(format!(
            "the request is {} points giving {rows} result rows, about {:.1} GB in memory; the budget is {:.0} GB, so at most {most} points for this scene and these models",
            scene.points.len(),
            bytes / 1e9,
            MEMORY_BUDGET_BYTES / 1e9
        )
        .into());
    }
    // Read scenes were checked when read; a sweep's points (`--count`) are checked here.
    let responses = if scene.wants(Analysis::Responses) { scene.velocities.len() } else { 0 };
    let (sets, bodies, points) = (scene.conditions.len(), scene.bodies.len(), scene.points.len());
    let yields = scene.wants(Analysis::YieldVelocity);
    if let Some(why) = scene::limits::quasi_static_excess(sets, points, bodies, responses, yields) {
        return Err(why.into());
    }
    if models.contains(&ModelKind::Mindlin) && sets * points > MAX_MINDLIN_POINTS {
        return Err(format!(
            "--model mindlin: the scene asks for {} patch responses ({sets} [[conditions]] x {points} points), more than the {MAX_MINDLIN_POINTS} one command computes (each about 0.1 s on three meshes); use fewer points or the plate model for the sweep",
            sets * points
        )
        .into());
    }
    if models.contains(&ModelKind::Transient) {
        let cases = scene.bodies.len() * scene.conditions.len() * scene.points.len();
        let responses = if scene.wants(Analysis::Responses) { 10 * cases * scene.velocities.len() } else { 0 };
        let yields = if scene.wants(Analysis::YieldVelocity) { 25 * cases } else { 0 };
        let runs = responses + yields;
        if runs > MAX_TRANSIENT_RUNS {
            return Err(format!(
                "--model transient: the scene asks for about {runs} transient runs ({cases} body-support-point cases; {responses} for responses with their error estimates, {yields} for yield velocities), more than the {MAX_TRANSIENT_RUNS} one command runs (a few minutes); use fewer points or the plate model for the sweep"
            )
            .into());
        }
    }
    Ok(())
}

/// Transient runs a case of the transient comparison costs with its error estimate, as a
/// response row of [`check_budget`] does.
pub const RUNS_PER_TRANSIENT_CASE: usize = 10;

/// Checks the transient comparison of `impact dynamic` (and the report) before any work:
/// at least one case, and its runs within [`MAX_TRANSIENT_RUNS`], the budget `solve --model
/// transient` keeps.
pub fn check_transient_comparison(scene: &Scene) -> Result<(), Failure> {
    let (sets, bodies) = (scene.conditions.len(), scene.bodies.len());
    let (velocities, points) = (scene.velocities.len(), scene.transient_points.len());
    let cases = sets * bodies * velocities * points;
    if cases == 0 {
        return Err(format!(
            "the transient study needs at least one case: velocities.m_per_s has {velocities} velocities, [[bodies]] {bodies} bodies and the transient points ([transient] pairs_mm, else [points]) {points}"
        )
        .into());
    }
    let runs = RUNS_PER_TRANSIENT_CASE * cases;
    if runs > MAX_TRANSIENT_RUNS {
        return Err(format!(
            "the transient study asks for about {runs} transient runs ({cases} cases: {sets} [[conditions]] x {bodies} [[bodies]] x {velocities} velocities.m_per_s x {points} transient points, [transient] pairs_mm or else [points], each with its error estimate), more than the {MAX_TRANSIENT_RUNS} one command runs; give [transient] pairs_mm a few points"
        )
        .into());
    }
    Ok(())
}

/// The scene's rows by each requested model, in the order given: the responses and yield
/// velocities the scene's analyses ask for, each row with its error estimate and validity.
pub fn results(scene: &Scene, models: &[ModelKind], progress: &dyn Progress) -> Result<Results, Failure> {
    check_budget(scene, models)?;
    let mut all = Results { scene: scene.name.clone(), responses: vec![], yields: vec![] };
    // The Mindlin model finds its own periods (with shear and rotary inertia).
    let quasi_static = models.iter().any(|m| matches!(m, ModelKind::Beam | ModelKind::Plate));
    let periods = if quasi_static { fundamental_periods(scene)? } else { vec![] };
    for &kind in models {
        let r = match kind {
            ModelKind::Beam => run(scene, &BeamModel { plate: &scene.plate }, kind, &periods)?,
            ModelKind::Plate => {
                let model =
                    PlateModel::compute(&scene.plate, &scene.conditions, &scene.point_pairs(), BASE_MESH, LEVELS)?;
                run(scene, &model, kind, &periods)?
            }
            ModelKind::Mindlin => {
                let model = MindlinModel::compute(
                    &scene.plate,
                    &scene.conditions,
                    &scene.point_pairs(),
                    MINDLIN_BASE_MESH,
                    MINDLIN_LEVELS,
                )?;
                run(scene, &model, kind, &model.periods)?
            }
            ModelKind::Transient => {
                progress.start(transient_case_count(scene), "transient cases");
                let r = run_transient_observed(scene, &mut || progress.advance(1))?;
                progress.finish();
                r
            }
        };
        all.extend(r);
    }
    Ok(all)
}

/// One line on the rows: how many, how many valid, and what the others are beyond.
pub fn status_line(results: &Results) -> String {
    let s = results.summary();
    let mut parts = vec![format!("{} results, {} inside every validity criterion", s.computed, s.valid)];
    for (n, what) in [
        (s.beyond_elastic, "beyond the elastic range (v above the yield velocity of the same model)"),
        (s.not_quasi_static, "not quasi-static (t_c/T₁ < 0.2)"),
        (s.outside_regime_rule, "outside the quasi-static regime rule (closed-form bound on the force error > 3 %)"),
        (s.beyond_thin_plate, "beyond the plate theory's range (h/min(L, B) > 0.05 for the beam and Kirchhoff's plate, > 0.2 for Mindlin's)"),
        (s.recontact, "with a second contact to follow"),
        (s.unfinished, "with the impact unfinished at the end of the window (a later contact may follow)"),
        (s.above_tolerance, "with a discretisation error estimate above the tolerance (the budget ran out)"),
        (s.not_applicable, "not applicable (the beam describes only Con 1-3)"),
    ] {
        if n > 0 {
            parts.push(format!("{n} {what}"));
        }
    }
    format!("status: {}", parts.join("; "))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn model_names_are_the_command_line_ones() {
        assert_eq!(model_kinds("beam"), Some(vec![ModelKind::Beam]));
        assert_eq!(model_kinds("mindlin"), Some(vec![ModelKind::Mindlin]));
        assert_eq!(model_kinds("all").map(|m| m.len()), Some(4));
        assert_eq!(model_kinds("fem"), None);
    }
}
