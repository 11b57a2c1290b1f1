//! The naming rule of every CSV column the program writes, in one place (described for
//! readers in docs/output-format.md).
//!
//! A column name is a key: words of ASCII letters and digits joined by `_`, the quantity
//! first and its SI unit last (`x_m`, `v_m_per_s`, `P_max_N`, `energy_J`); a dimensionless
//! quantity has no unit part. The key form is [`KEY_PATTERN`]; a word that is a unit outside
//! SI or outside this style ([`NON_SI_WORDS`]: `mm`, `ms`, `GPa`, `deg`, a lower-case `n`
//! or `hz`, ...) marks a column that was not converted.
//!
//! A column holds numbers (every cell a finite number, or empty where the value does not
//! exist) unless its name's last word is one of [`TEXT_WORDS`]: then it holds text (a name, a
//! label, a verdict). A yes/no column is numeric, 1 or 0. A number with a remark is two
//! columns, the number and `<name>_note`; a point is two, `<name>_x`/`<name>_z` in its unit.

/// The form of every column name: words of ASCII letters and digits joined by single
/// underscores, starting with a letter.
pub const KEY_PATTERN: &str = r"^[A-Za-z][A-Za-z0-9]*(_[A-Za-z0-9]+)*$";

/// The last words of a column name that mark the column as text; every other column is
/// numeric.
pub const TEXT_WORDS: &[&str] = &[
    "body",
    "case",
    "class",
    "condition",
    "evidence",
    "family",
    "file",
    "flags",
    "label",
    "law",
    "mesh",
    "model",
    "name",
    "note",
    "point",
    "quantity",
    "reason",
    "reference",
    "regime",
    "series",
    "slice",
    "statement",
    "table",
    "unit",
    "validity",
    "verdict",
];

/// Words that are units outside SI, or SI units not in the key style (`n` for `N`, `hz` for
/// `Hz`, `m_s` for `m_per_s`, `kg_m3` for `kg_per_m3`); none may appear in a column name.
pub const NON_SI_WORDS: &[&str] = &[
    "mm", "cm", "um", "ms", "us", "kN", "kn", "kPa", "MPa", "GPa", "kpa", "mpa", "gpa", "deg", "degree", "degrees",
    "percent", "pct", "hz", "km",
];

/// Pairs of adjacent words that spell a compound unit outside the key style.
const NON_SI_PAIRS: &[(&str, &str)] = &[("m", "s"), ("kg", "m3"), ("n", "m"), ("n", "s")];

/// Whether the column `key` holds text (its last word is one of [`TEXT_WORDS`]).
pub fn is_text_column(key: &str) -> bool {
    key.rsplit('_').next().is_some_and(|w| TEXT_WORDS.contains(&w))
}

/// Why `key` is not a column name in the program's style, or `None` if it is.
pub fn key_problem(key: &str) -> Option<String> {
    let words: Vec<&str> = key.split('_').collect();
    let shape = key.as_bytes().first().is_some_and(u8::is_ascii_alphabetic)
        && words.iter().all(|w| !w.is_empty() && w.bytes().all(|b| b.is_ascii_alphanumeric()));
    if !shape {
        return Some(format!("not of the key form {KEY_PATTERN}"));
    }
    if let Some(w) = words.iter().find(|w| NON_SI_WORDS.contains(w)) {
        return Some(format!("'{w}' is not an SI unit in the key style"));
    }
    // A lower-case `n` is newtons only as the unit, i.e. the last word.
    if words.len() > 1 && words.last() == Some(&"n") {
        return Some("'n' is not an SI unit in the key style (newtons are 'N')".into());
    }
    for w in words.windows(2) {
        if NON_SI_PAIRS.contains(&(w[0], w[1])) {
            return Some(format!("'{}_{}' is not an SI unit in the key style", w[0], w[1]));
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_in_the_style_pass_and_others_are_named() {
        for ok in ["x_m", "v_m_per_s", "P_max_N", "C_m_per_N", "t_c_per_T1", "energy_unit2_s", "dominant_frequency_Hz"]
        {
            assert_eq!(key_problem(ok), None, "{ok}");
        }
        for (bad, why) in [
            ("x_mm", "'mm'"),
            ("force_max_n", "'n'"),
            ("v_m_s", "'m_s'"),
            ("density_kg_m3", "'kg_m3'"),
            ("youngs_modulus_gpa", "'gpa'"),
            ("point (mm)", "key form"),
            ("_x", "key form"),
            ("a__b", "key form"),
            ("frequency_hz", "'hz'"),
        ] {
            let p = key_problem(bad).unwrap_or_else(|| panic!("{bad} passed"));
            assert!(p.contains(why), "{bad}: {p}");
        }
    }

    #[test]
    fn text_columns_are_marked_by_their_last_word() {
        for t in ["body", "condition", "rule_regime", "tolerance_verdict", "point", "load_point", "quantity"] {
            assert!(is_text_column(t), "{t}");
        }
        for n in ["x_m", "contacts", "body_mass_kg", "stable", "P_max_N"] {
            assert!(!is_text_column(n), "{n}");
        }
    }
}
