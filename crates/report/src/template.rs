//! Named-placeholder substitution for report prose kept in Markdown templates.
//!
//! A template is Markdown with `{{name}}` placeholders; every value is formatted by the
//! report before substitution, so the numbers print exactly as the code formats them and
//! the template holds only wording. Rendering is strict in both directions: a placeholder
//! without a value and a value that no placeholder uses are errors, so a renamed or
//! misspelt name cannot silently drop a number from the report. This is all the prose
//! needs (no loops, conditions or escaping: tables are rendered by the code and passed in
//! whole), which is why no template engine is pulled in.

use std::collections::BTreeSet;

/// Why a template did not render.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum TemplateError {
    #[error("template {template}: placeholder {{{{{name}}}}} has no value")]
    Missing { template: String, name: String },
    #[error("template {template}: value {name:?} is not used by any placeholder")]
    Unused { template: String, name: String },
    #[error("template {template}: unterminated placeholder at byte {at}")]
    Unterminated { template: String, at: usize },
    #[error("template {template}: value {name:?} is given twice")]
    Duplicate { template: String, name: String },
}

/// Fills the `{{name}}` placeholders of `text` (called `template` in errors) from `values`.
pub fn render(template: &str, text: &str, values: &[(&str, String)]) -> Result<String, TemplateError> {
    let mut given = BTreeSet::new();
    for (name, _) in values {
        if !given.insert(*name) {
            return Err(TemplateError::Duplicate { template: template.into(), name: (*name).into() });
        }
    }
    let mut used = BTreeSet::new();
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(start) = rest.find("{{") {
        out.push_str(&rest[..start]);
        let after = &rest[start + 2..];
        let end = after.find("}}").ok_or_else(|| TemplateError::Unterminated {
            template: template.into(),
            at: text.len() - rest.len() + start,
        })?;
        let name = after[..end].trim();
        let (_, value) = values
            .iter()
            .find(|(n, _)| *n == name)
            .ok_or_else(|| TemplateError::Missing { template: template.into(), name: name.into() })?;
        out.push_str(value);
        used.insert(name);
        rest = &after[end + 2..];
    }
    out.push_str(rest);
    if let Some(name) = given.difference(&used).next() {
        return Err(TemplateError::Unused { template: template.into(), name: (*name).into() });
    }
    Ok(out)
}

/// A count in words for prose ("twelve runs"), in figures from 21 on.
pub fn count_words(n: usize) -> String {
    const WORDS: [&str; 21] = [
        "no",
        "one",
        "two",
        "three",
        "four",
        "five",
        "six",
        "seven",
        "eight",
        "nine",
        "ten",
        "eleven",
        "twelve",
        "thirteen",
        "fourteen",
        "fifteen",
        "sixteen",
        "seventeen",
        "eighteen",
        "nineteen",
        "twenty",
    ];
    WORDS.get(n).map_or_else(|| n.to_string(), |w| w.to_string())
}

/// Names in prose: "A", "A and B", "A, B and C".
pub fn and_list(names: &[&str]) -> String {
    match names {
        [] => String::new(),
        [one] => one.to_string(),
        [head @ .., last] => format!("{} and {last}", head.join(", ")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fills_every_placeholder() {
        let r = render("t", "a {{x}} b {{ y }} {{x}}", &[("x", "1".into()), ("y", "2".into())]);
        assert_eq!(r.unwrap(), "a 1 b 2 1");
    }

    #[test]
    fn refuses_missing_unused_and_unterminated() {
        assert!(matches!(render("t", "{{x}}", &[]), Err(TemplateError::Missing { .. })));
        assert!(matches!(render("t", "x", &[("x", "1".into())]), Err(TemplateError::Unused { .. })));
        assert!(matches!(render("t", "{{x", &[("x", "1".into())]), Err(TemplateError::Unterminated { .. })));
        assert!(matches!(
            render("t", "{{x}}", &[("x", "1".into()), ("x", "2".into())]),
            Err(TemplateError::Duplicate { .. })
        ));
    }

    #[test]
    fn counts_and_lists_read_as_prose() {
        assert_eq!(count_words(12), "twelve");
        assert_eq!(count_words(21), "21");
        assert_eq!(and_list(&["Hertz"]), "Hertz");
        assert_eq!(and_list(&["Hertz", "Flores", "Thornton"]), "Hertz, Flores and Thornton");
    }

    #[test]
    fn single_braces_are_text() {
        assert_eq!(render("t", "δ^{5/2}", &[]).unwrap(), "δ^{5/2}");
    }
}
