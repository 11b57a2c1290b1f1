//! The check of the modal truncation in a support set's section: what it struck again and,
//! on every impact, how well subsamples would have stood for it.

use crate::present::table::{sig, Cell, Table};
use crate::template::render;
use crate::Failure;
use studies::identify::check::COVERAGE_REPEATS;
use studies::identify::{ConditionResult, AUC_RESOLUTION};

const WHOLE: &str = include_str!("../templates/identify/check-whole.md");
const SAMPLE: &str = include_str!("../templates/identify/check-sample.md");

/// The truncation check's paragraph for support set `r` on `modes` modes.
pub(super) fn markdown(r: &ConditionResult, modes: usize) -> Result<String, Failure> {
    let c = &r.truncation_check;
    let half_modes = (modes / 2).max(1).to_string();
    if c.sampled {
        return Ok(render(
            "identify/check-sample.md",
            SAMPLE,
            &[
                ("impacts", c.impacts.to_string()),
                ("of", c.of.to_string()),
                ("half_modes", half_modes),
                ("fraction", analytic::params::compact(c.fraction)),
            ],
        )?);
    }
    let beyond = format!("misses beyond both it and {}", sig(AUC_RESOLUTION, 2));
    let mut table = Table::new(
        "",
        &[
            "share of each family",
            "impacts",
            "changes compared",
            "within the 95 % interval",
            &beyond,
            "median miss",
            "largest miss",
            "same verdict on the ranking",
        ],
    );
    for s in &c.coverage {
        let v = &s.coverage;
        table.push(vec![
            Cell::Text(sig(v.fraction, 2)),
            Cell::Text(v.impacts.to_string()),
            Cell::Text(v.compared.to_string()),
            Cell::Text(format!("{} %", sig(100.0 * v.covered, 3))),
            Cell::Text(format!("{} %", sig(100.0 * v.beyond_tolerance, 2))),
            Cell::Text(sig(v.median_miss, 2)),
            Cell::Text(sig(v.largest_miss, 2)),
            Cell::Text(format!("{} %", sig(100.0 * s.same_verdict, 3))),
        ]);
    }
    Ok(render(
        "identify/check-whole.md",
        WHOLE,
        &[
            ("impacts", c.of.to_string()),
            ("half_modes", half_modes),
            ("repeats", COVERAGE_REPEATS.to_string()),
            ("resolution", sig(AUC_RESOLUTION, 2)),
            ("table", table.to_markdown()),
        ],
    )?)
}
