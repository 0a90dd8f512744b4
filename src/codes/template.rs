//! Input decks from the templates in `scripts/<code>/`: placeholders `{{key}}` replaced by
//! values written so that the code reads them back exactly.

use thiserror::Error;

/// A template that could not be filled.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
#[error("template placeholder left unfilled: {placeholder}")]
pub struct TemplateError {
    /// The first unfilled placeholder and what follows it (up to 40 characters).
    pub placeholder: String,
}

/// Replace every `{{key}}` in `template` by its value; an unreplaced placeholder is an error.
pub(crate) fn fill_template(
    template: &str,
    values: &[(&str, String)],
) -> Result<String, TemplateError> {
    let mut text = template.to_string();
    for (key, value) in values {
        text = text.replace(&format!("{{{{{key}}}}}"), value);
    }
    match text.find("{{") {
        Some(at) => Err(TemplateError {
            placeholder: text[at..].chars().take(40).collect(),
        }),
        None => Ok(text),
    }
}

/// Format a float so that a code reads it back exactly (shortest round-trip form).
pub fn exact_number(x: f64) -> String {
    format!("{x:e}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fill_template_replaces_and_refuses_leftovers() {
        let filled = fill_template("a {{x}} b {{y}}", &[("x", "1".into()), ("y", "2".into())]);
        assert_eq!(filled.unwrap(), "a 1 b 2");
        let err = fill_template("a {{x}} b {{z}}", &[("x", "1".into())]).unwrap_err();
        assert!(err.placeholder.starts_with("{{z}}"), "{err}");
    }

    // A round trip is exact or it is not one.
    #[allow(clippy::float_cmp)]
    #[test]
    fn numbers_round_trip() {
        for x in [0.1, 1.0 / 3.0, 2.0e11, 6.118_735_1e-7, f64::MIN_POSITIVE] {
            assert_eq!(exact_number(x).parse::<f64>().unwrap(), x);
        }
    }
}
