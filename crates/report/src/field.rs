//! The plate's deflection field in words: what a field scaled to an impact's quasi-static
//! P_max is, and the caveat where the quasi-static balance is not trusted. The field itself
//! computes in [`studies::field`]; `crate::present::vtk` writes it as .vtu, with the bending
//! stresses and the elements at the load marked.

use crate::template::render;
use crate::Failure;
use coupled::plan::ResponseValues;
use coupled::Validity;
pub use studies::field::{field, quasi_static_impact, CellData, FieldFile, PointData};

const P_MAX: &str = include_str!("templates/field/p-max.md");
const CAVEAT: &str = include_str!("templates/field/caveat.md");

/// The sentence that a quasi-static field does not describe the plate of a case the
/// quasi-static balance is not trusted for (its quasi-static or regime-rule criterion fails);
/// empty where it is trusted.
pub fn quasi_static_caveat(v: &Validity) -> Result<String, Failure> {
    let untrusted = v.quasi_static.is_some_and(|c| !c.valid) || v.regime.is_some_and(|c| !c.valid);
    Ok(if untrusted { render("field/caveat.md", CAVEAT, &[])? } else { String::new() })
}

/// What a field scaled to the quasi-static P_max of `case` is, in words: the force, its
/// error, the model, the case (`what`) and its validity.
pub fn p_max_text(case: &ResponseValues, what: &str) -> Result<String, Failure> {
    use crate::present::table::sig;
    Ok(render(
        "field/p-max.md",
        P_MAX,
        &[
            ("p_max", sig(case.contact_force, 4)),
            ("p_max_error", case.contact_force_error.map_or("not estimated".into(), |e| sig(e, 2))),
            ("what", what.to_string()),
            ("validity", crate::present::rows::validity_text(&case.validity)),
            ("caveat", quasi_static_caveat(&case.validity)?),
        ],
    )?)
}
