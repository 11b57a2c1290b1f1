//! The sentence a page carries when its windows were summed in the fast arithmetic.

use crate::present::table::sig;
use crate::template::render;
use crate::Failure;
use coupled::reduced::Arithmetic;

const FAST: &str = include_str!("templates/arithmetic-fast.md");

/// Nothing for the exact arithmetic; for the fast one, what it does and its bound on `modes`
/// modes, as a paragraph after a blank line: a channel has at most 2N + 2 terms (A on q, B on
/// q̇, the residual mode's pair where it is kept), so γ of 2N + 4.
pub(crate) fn paragraph(arithmetic: Arithmetic, modes: usize) -> Result<String, Failure> {
    if arithmetic.is_exact() {
        return Ok(String::new());
    }
    let terms = 2 * modes + 2;
    let text = render(
        "arithmetic-fast.md",
        FAST,
        &[("terms", terms.to_string()), ("gamma", sig(arithmetic.gamma(terms + 2), 2))],
    )?;
    Ok(format!("\n{text}"))
}
