//! What every mutated scene must pass: a refusal naming its field, or rows within the
//! invariants and tables and JSON free of NaN, inf and missing numbers.

#![allow(clippy::neg_cmp_op_on_partial_ord)]
#![allow(dead_code)]

use super::*;

/// Known: `restitution = 1e-300` (inside `RESTITUTION` = (0, 1], which has no floor) is
/// accepted; a = 2K/(5e) overflows and the balance reports "residual NaN" (see
/// `tiny_restitution_is_refused_or_computed`).
pub const ACCEPTED_BALANCE_NAN: &str = "accepted scene: balance overflows (residual NaN)";
/// Known: `solver.tolerance = 1e-15`, the lower end of `limits::SOLVER_TOLERANCE`, is
/// accepted but the bracketed Newton stalls at a relative residual of ~2e-15 (see
/// `tolerance_at_its_lower_end_converges`).
pub const ACCEPTED_NOT_CONVERGED: &str = "accepted scene: energy balance did not converge";
/// Known: springs of 1e-6 to ~5e-6 N/m (the low end of `limits::SPRING_N_PER_M`) on the
/// paper's plate, and a 100 m x 1 mm x 1 mm strip, are accepted but the plate stiffness
/// does not factor in `fundamental_periods` (see `soft_springs_compute`,
/// `long_narrow_strip_computes`).
pub const ACCEPTED_NOT_FACTORED: &str = "accepted scene: stiffness does not factor";

// ---------------------------------------------------------------- the checks

/// Failures by class, each with its count and first example.
#[derive(Default)]
pub struct Stats {
    pub generated: usize,
    pub parsed: usize,
    pub rejected: usize,
    pub beam_runs: usize,
    pub plate_runs: usize,
    pub rows_checked: usize,
    /// Clean errors from a model on an accepted scene (not panics), by kind.
    pub run_errors: BTreeMap<String, (usize, String)>,
    pub failures: BTreeMap<&'static str, (usize, String)>,
}

impl Stats {
    pub fn fail(&mut self, class: &'static str, example: impl FnOnce() -> String) {
        let e = self.failures.entry(class).or_insert_with(|| (0, String::new()));
        e.0 += 1;
        if e.0 <= EXAMPLES {
            e.1.push_str(&format!("\n    [{}] {}", e.0, clip(&example())));
        }
    }

    pub fn run_error(&mut self, kind: &str, example: String) {
        let e = self.run_errors.entry(kind.to_string()).or_insert_with(|| (0, String::new()));
        e.0 += 1;
        if e.0 <= EXAMPLES {
            e.1.push_str(&format!("\n    [{}] {}", e.0, clip(&example)));
        }
    }

    pub fn report(&self, title: &str) {
        eprintln!("== {title}");
        eprintln!(
            "generated {}, parsed {}, rejected {}, beam runs {}, plate runs {}, rows checked {}",
            self.generated, self.parsed, self.rejected, self.beam_runs, self.plate_runs, self.rows_checked
        );
        for (k, (n, ex)) in &self.run_errors {
            eprintln!("model error ({k}): {n}; first ones:{ex}");
        }
        if self.failures.is_empty() {
            eprintln!("invariant failures: none");
        }
        for (k, (n, ex)) in &self.failures {
            eprintln!("FAILURE {k}: {n}; first ones:{ex}");
        }
    }
}

/// Examples kept per class.
pub const EXAMPLES: usize = 3;

pub fn clip(s: &str) -> String {
    if s.chars().count() > 1500 {
        format!("{}... ({} chars)", s.chars().take(1500).collect::<String>(), s.chars().count())
    } else {
        s.to_string()
    }
}

/// Words of `s`, lowercased, split at anything but letters and digits.
pub fn words(s: &str) -> impl Iterator<Item = String> + '_ {
    s.split(|c: char| !c.is_ascii_alphanumeric()).filter(|w| !w.is_empty()).map(|w| w.to_ascii_lowercase())
}

pub fn has_nan_or_inf(s: &str) -> bool {
    words(s).any(|w| w == "nan" || w == "inf" || w == "infinity")
}

pub fn tolerance(s: &Scene) -> f64 {
    match s.solver {
        Method::Recursion { tolerance, .. } | Method::Bracketed { tolerance, .. } => tolerance,
    }
}

/// A copy small enough to compute: at most `points` points (first and last kept), bodies,
/// velocities and conditions.
pub fn limited(s: &Scene, points: usize, bodies: usize, velocities: usize, conditions: usize) -> Scene {
    let mut s = s.clone();
    let all = s.point_pairs();
    if all.len() > points {
        let picked = (0..points)
            .map(|i| all[if points == 1 { 0 } else { (i * (all.len() - 1) + (points - 1) / 2) / (points - 1) }])
            .collect();
        s.points = Points::Pairs { pairs: picked };
    }
    s.bodies.truncate(bodies);
    s.velocities.truncate(velocities);
    s.conditions.truncate(conditions);
    s
}

/// The row invariants and the rendered forms of `results`.
pub fn check_results(stats: &mut Stats, label: &str, scene: &Scene, results: &Results) {
    let tol = tolerance(scene);
    for r in &results.responses {
        let Some(v) = r.values() else { continue };
        stats.rows_checked += 1;
        let at = || {
            format!(
                "{label} | {:?} {} on {} at ({}, {}) v = {}: {v:?}",
                r.model, r.body, r.condition, r.x, r.z, r.velocity
            )
        };
        let mut numbers = vec![
            v.contact_force,
            v.compression,
            v.deflection,
            v.rock_total_ratio,
            v.rock_stored_ratio,
            v.plate_ratio,
            v.spring_ratio,
            v.sphere_kinetic_ratio,
        ];
        numbers.extend(
            [v.compliance, v.compliance_error, v.contact_force_error, v.compression_error].into_iter().flatten(),
        );
        numbers.extend(v.spring_forces.iter().map(|s| s.force));
        if let Evidence::Balance { residual, .. } = v.evidence {
            numbers.push(residual);
            if !(residual <= tol) {
                stats.fail("residual above the solver tolerance", at);
            }
        }
        if numbers.iter().any(|x| !x.is_finite()) {
            stats.fail("non-finite number in a response row", at);
        }
        if !(v.contact_force > 0.0) {
            stats.fail("P_max not > 0", at);
        }
        if !(v.compression > 0.0) {
            stats.fail("delta_max not > 0", at);
        }
        if v.compliance.is_some_and(|c| !(c >= 0.0)) {
            stats.fail("C not >= 0", at);
        }
        // The ratios are the balance's terms at the returned δ over E₀, so they sum to 1,
        // and the rock's total stays under 1, only as closely as the balance was solved:
        // within 1e-9 plus the residual (which a scene may loosen to 1e-3).
        let residual = match v.evidence {
            Evidence::Balance { residual, .. } => residual,
            Evidence::Transient { .. } => 0.0,
        };
        let ratios = [v.rock_total_ratio, v.rock_stored_ratio, v.plate_ratio, v.spring_ratio];
        if ratios.iter().any(|x| !(0.0..=1.0 + 1e-9 + residual).contains(x)) {
            stats.fail("energy ratio outside [0, 1]", at);
        }
        if !((v.rock_total_ratio + v.plate_ratio + v.spring_ratio - 1.0).abs() <= 1e-9 + residual) {
            stats.fail("rock total + plate + spring != 1 within 1e-9 + residual", at);
        }
        if v.validity.criteria().iter().any(|(_, c)| !c.value.is_finite() || !c.limit.is_finite()) {
            stats.fail("non-finite validity measure in a response row", at);
        }
    }
    check_yield_rows(stats, label, results);
    check_rendered(stats, label, results);
}

/// Every yield row: finite, C ≥ 0, δ_my and v_y positive, validity measures finite.
pub fn check_yield_rows(stats: &mut Stats, label: &str, results: &Results) {
    for r in &results.yields {
        let Some(v) = r.values() else { continue };
        stats.rows_checked += 1;
        let at = || format!("{label} | {:?} {} on {} at ({}, {}): {v:?}", r.model, r.body, r.condition, r.x, r.z);
        let mut numbers = vec![v.yield_compression, v.yield_velocity];
        numbers.extend([v.compliance, v.compliance_error, v.yield_velocity_error].into_iter().flatten());
        if numbers.iter().any(|x| !x.is_finite()) {
            stats.fail("non-finite number in a yield row", at);
        }
        if v.compliance.is_some_and(|c| !(c >= 0.0)) {
            stats.fail("C not >= 0", at);
        }
        if !(v.yield_compression > 0.0 && v.yield_velocity > 0.0) {
            stats.fail("delta_my or v_y not > 0", at);
        }
        if v.validity.criteria().iter().any(|(_, c)| !c.value.is_finite() || !c.limit.is_finite()) {
            stats.fail("non-finite validity measure in a yield row", at);
        }
    }
}

/// Tables (text, Markdown, CSV) and JSON: no NaN or inf token, every number cell of a
/// computed row filled, no null where a number belongs.
pub fn check_rendered(stats: &mut Stats, label: &str, results: &Results) {
    let names: Vec<&str> = results
        .responses
        .iter()
        .flat_map(|r| [r.body.as_str(), r.condition.as_str()])
        .chain(results.yields.iter().flat_map(|r| [r.body.as_str(), r.condition.as_str()]))
        .collect();
    let names_have_tokens = names.iter().any(|n| has_nan_or_inf(n));
    let tables = response_tables(results).into_iter().chain(yield_tables(results));
    for t in tables {
        let (text, md, csv) = (t.to_text(), t.to_markdown(), t.to_csv());
        if !names_have_tokens {
            for (form, s) in [("text", &text), ("markdown", &md), ("csv", &csv)] {
                if has_nan_or_inf(s) {
                    stats.fail("NaN or inf in a table", || format!("{label} | {form}:\n{s}"));
                }
            }
        }
        let mut reader = csv::ReaderBuilder::new().has_headers(true).from_reader(csv.as_bytes());
        let headers: Vec<String> = match reader.headers() {
            Ok(h) => h.iter().map(str::to_string).collect(),
            Err(e) => {
                stats.fail("CSV does not read back", || format!("{label} | {e}\n{csv}"));
                continue;
            }
        };
        // Text columns are named as such (`impact::present::columns`, the rule's one place).
        for rec in reader.records() {
            let rec = match rec {
                Ok(r) => r,
                Err(e) => {
                    stats.fail("CSV does not read back", || format!("{label} | {e}\n{csv}"));
                    break;
                }
            };
            let last = rec.get(rec.len().saturating_sub(1)).unwrap_or("");
            if last.starts_with("not applicable") {
                continue;
            }
            for (h, cell) in headers.iter().zip(rec.iter()) {
                if impact::present::columns::is_text_column(h) {
                    continue;
                }
                if !cell.parse::<f64>().is_ok_and(f64::is_finite) {
                    stats.fail("number cell of a computed CSV row empty or not a finite number", || {
                        format!("{label} | column '{h}' = '{cell}' in\n{csv}")
                    });
                }
            }
        }
    }
    match serde_json::to_value(results) {
        Ok(json) => {
            let mut nulls = Vec::new();
            json_nulls(&json, "", &mut nulls);
            if !nulls.is_empty() {
                stats.fail("null where JSON needs a number", || format!("{label} | {}", nulls.join(", ")));
            }
        }
        Err(e) => stats.fail("results do not serialise to JSON", || format!("{label} | {e}")),
    }
}

/// Paths of nulls in `v`, except the optional validity criteria and transient error
/// estimates a model does not use.
pub fn json_nulls(v: &serde_json::Value, path: &str, out: &mut Vec<String>) {
    match v {
        serde_json::Value::Null => {
            let key = path.rsplit('.').next().unwrap_or("");
            if !["elastic", "quasi_static", "recontact", "regime", "finished", "discretisation", "state_errors"]
                .contains(&key)
            {
                out.push(path.to_string());
            }
        }
        serde_json::Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                json_nulls(x, &format!("{path}[{i}]"), out);
            }
        }
        serde_json::Value::Object(o) => {
            for (k, x) in o {
                json_nulls(x, &format!("{path}.{k}"), out);
            }
        }
        _ => {}
    }
}

/// How much of an accepted scene is computed.
#[derive(Clone, Copy)]
pub struct Budget {
    /// Points, bodies, velocities, conditions for the beam.
    pub beam: (usize, usize, usize, usize),
    /// The same for the plate model; None: no plate model.
    pub plate: Option<(usize, usize, usize, usize)>,
}

pub fn compute_and_check(stats: &mut Stats, label: &str, scene: &Scene, budget: Budget) {
    let (p, b, v, c) = budget.beam;
    let s = limited(scene, p, b, v, c);
    let periods = match guarded(|| fundamental_periods(&s)) {
        Err(msg) => {
            stats.fail("panic in the models", || format!("{label} | fundamental_periods: {msg}"));
            return;
        }
        Ok(Err(e)) => {
            model_error(stats, &s, "fundamental periods", format!("{label} | {e}"));
            // The periods enter only the quasi-static criterion: check the beam's rows
            // with a stand-in of 1 s rather than not at all.
            vec![1.0; s.conditions.len()]
        }
        Ok(Ok(p)) => p,
    };
    match guarded(|| run(&s, &BeamModel { plate: &s.plate }, ModelKind::Beam, &periods)) {
        Err(msg) => stats.fail("panic in the models", || format!("{label} | beam run: {msg}")),
        Ok(Err(e)) => model_error(stats, &s, "beam run", format!("{label} | {e}")),
        Ok(Ok(r)) => {
            stats.beam_runs += 1;
            match guarded(|| {
                let mut inner = Stats::default();
                check_results(&mut inner, label, &s, &r);
                inner
            }) {
                Ok(inner) => merge(stats, inner),
                Err(msg) => stats.fail("panic while rendering", || format!("{label} | beam: {msg}")),
            }
        }
    }
    let Some((p, b, v, c)) = budget.plate else { return };
    let s = limited(scene, p, b, v, c);
    let periods = &periods[..s.conditions.len()];
    let plate = guarded(|| -> Result<Results, coupled::ModelError> {
        let model = PlateModel::compute(&s.plate, &s.conditions, &s.point_pairs(), 20, 2)?;
        run(&s, &model, ModelKind::Plate, periods)
    });
    match plate {
        Err(msg) => stats.fail("panic in the models", || format!("{label} | plate: {msg}")),
        Ok(Err(e)) => model_error(stats, &s, "plate model", format!("{label} | {e}")),
        Ok(Ok(r)) => {
            stats.plate_runs += 1;
            match guarded(|| {
                let mut inner = Stats::default();
                check_results(&mut inner, label, &s, &r);
                inner
            }) {
                Ok(inner) => merge(stats, inner),
                Err(msg) => stats.fail("panic while rendering", || format!("{label} | plate: {msg}")),
            }
        }
    }
}

/// Fewest solver iterations with which an unconverged balance is the scene's own doing.
pub const STARVED_SOLVER: u32 = 20;

/// A model's clean error on an accepted scene. A balance starved of iterations by the scene
/// is the answer it asked for; any other error means the scene reader accepted a scene the
/// models cannot compute, and is a failure class of its own.
pub fn model_error(stats: &mut Stats, scene: &Scene, kind: &str, example: String) {
    let iterations = match scene.solver {
        Method::Recursion { max_iterations, .. } | Method::Bracketed { max_iterations, .. } => max_iterations,
    };
    if example.contains("residual NaN") {
        stats.fail(ACCEPTED_BALANCE_NAN, || example);
    } else if example.contains("did not converge") && iterations < STARVED_SOLVER {
        stats.run_error(&format!("{kind}, solver starved by the scene"), example);
    } else if example.contains("did not converge") {
        stats.fail(ACCEPTED_NOT_CONVERGED, || example);
    } else if example.contains("factorization failed") {
        stats.fail(ACCEPTED_NOT_FACTORED, || example);
    } else {
        stats.fail("accepted scene: other model error", || example);
    }
}

pub fn merge(into: &mut Stats, from: Stats) {
    into.rows_checked += from.rows_checked;
    for (k, (n, ex)) in from.failures {
        let e = into.failures.entry(k).or_insert((0, ex));
        e.0 += n;
    }
}

/// Parses `text` and checks the refusal, or computes the scene and checks the results.
/// Returns the refusal's message, if any.
pub fn check_scene(
    stats: &mut Stats,
    label: &str,
    text: &str,
    hints: &[String],
    expect: Expect,
    budget: Budget,
) -> Option<String> {
    stats.generated += 1;
    let parsed = match guarded(|| Scene::parse(text, "fuzz")) {
        Err(msg) => {
            stats.fail("panic in Scene::parse", || format!("{label} | {msg}"));
            return None;
        }
        Ok(p) => p,
    };
    match parsed {
        Err(e) => {
            let msg = e.to_string();
            check_refusal(stats, label, text, hints, expect, &msg);
            Some(msg)
        }
        Ok(scene) => {
            stats.parsed += 1;
            if expect == Expect::Reject {
                stats.fail("invalid scene accepted", || label.to_string());
            }
            compute_and_check(stats, label, &scene, budget);
            None
        }
    }
}

/// A refusal: it names one of `hints` and shows NaN or inf only if the input had them.
pub fn check_refusal(stats: &mut Stats, label: &str, text: &str, hints: &[String], expect: Expect, msg: &str) {
    stats.rejected += 1;
    if expect == Expect::Accept {
        stats.fail("valid scene refused", || format!("{label} | {msg}"));
    }
    if !hints.iter().any(|h| msg.contains(h.as_str())) {
        stats.fail("refusal does not name the field", || {
            format!("message: {msg}\n      expected one of {hints:?}\n      input: {label}")
        });
    }
    if has_nan_or_inf(msg) && !has_nan_or_inf(text) {
        stats.fail("refusal shows NaN or inf the input did not have", || format!("{label} | {msg}"));
    }
}
