//! A build's probe as every prober reports it: short runs, one per convention the drivers
//! depend on, each read against the value every hypothesis predicts, and the conventions
//! ([`Conventions`]) they establish. A probe whose number matches no hypothesis, or more than
//! one, is inconclusive and says why; a driver refuses to plan from inconclusive conventions.
//! What is run, and how, is the code's own ([`crate::codes::Prober`]).

use std::path::PathBuf;

use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::codes::conventions::Conventions;
use crate::codes::template::TemplateError;

/// A number that may be NaN, as JSON allows: `null` for NaN.
mod nan_as_null {
    use serde::{Deserialize, Deserializer, Serializer};

    pub(crate) fn serialize<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
        if x.is_finite() {
            s.serialize_f64(*x)
        } else {
            s.serialize_none()
        }
    }

    pub(crate) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
    }
}

/// One measured number.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Measured {
    /// What it is.
    pub name: String,
    /// Its value (SI; `null` in JSON when not a number).
    #[serde(with = "nan_as_null")]
    pub value: f64,
}

/// One hypothesis and the value it predicts for the probe's measured number.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Hypothesis {
    /// The hypothesis, as the verdict names it.
    pub name: String,
    /// The value it predicts (NaN, `null` in JSON, when it predicts no number: a refused run).
    #[serde(with = "nan_as_null")]
    pub expected: f64,
    /// Whether the measurement matches it.
    pub matches: bool,
}

/// The probe of one convention: what was run, what it measured, what each hypothesis
/// predicts, and the verdict.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ProbeItem {
    /// Which convention (`wall-modulus`, `coeff-restitution`, `tsuji-fit`, `touching`,
    /// `damping-velocity`).
    pub item: String,
    /// The question it answers.
    pub question: String,
    /// The input that was run (for LAMMPS: the contact model given to `fix wall/gran`) and the
    /// start state.
    pub input: String,
    /// The numbers the run gave.
    pub measured: Vec<Measured>,
    /// The hypotheses with their predictions.
    pub hypotheses: Vec<Hypothesis>,
    /// The matching hypothesis, `None` when inconclusive.
    pub verdict: Option<String>,
    /// Why it is inconclusive, or what the build said when it refused the input.
    pub note: Option<String>,
}

/// Every probe of one build, and the conventions they establish.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ProbeReport {
    /// The driver's name.
    pub code: String,
    /// The executable probed.
    pub program: PathBuf,
    /// The version the build prints.
    pub version: Option<String>,
    /// The probes, in a fixed order.
    pub items: Vec<ProbeItem>,
    /// The conventions, when every item the drivers need is conclusive.
    pub conventions: Option<Conventions>,
    /// Wall time of all probe runs, s.
    pub wall_time: f64,
    /// Where the report was kept since that probe, when it is read from there rather than
    /// probed now.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kept_in: Option<PathBuf>,
}

impl ProbeReport {
    /// Whether the build ran the probe's first, basic deck (one every build of the code runs,
    /// such as a LAMMPS wall with `damping velocity`). A build that does not is not probed
    /// further: its conventions are unknown, and a run of it fails for the same reason, with
    /// its own log.
    pub(crate) fn ran(&self) -> bool {
        self.items.first().is_some_and(|i| !i.measured.is_empty())
    }

    /// The conventions, or why the probe establishes none.
    pub(crate) fn conventions(&self) -> Result<Conventions, ProbeError> {
        self.conventions.ok_or_else(|| {
            let open: Vec<String> = self
                .items
                .iter()
                .filter(|i| i.verdict.is_none())
                .map(|i| format!("{}: {}", i.item, i.note.as_deref().unwrap_or("no verdict")))
                .collect();
            ProbeError::Inconclusive {
                code: self.code.clone(),
                program: self.program.clone(),
                open: open.join("; "),
            }
        })
    }
}

/// Why a probe gives no conventions.
#[derive(Debug, Error)]
pub enum ProbeError {
    /// The build ran the probe, but some items have no verdict.
    #[error("{code} ({}): the probe is inconclusive: {open}", program.display())]
    Inconclusive {
        /// The driver.
        code: String,
        /// The probed executable.
        program: PathBuf,
        /// The items without a verdict, each with what was seen.
        open: String,
    },
    /// The probe's input could not be rendered.
    #[error("the probe's input: {0}")]
    Template(#[from] TemplateError),
    /// The build could not be started or its scratch not prepared.
    #[error("{doing} {}: {source}", path.display())]
    Io {
        /// What was being done.
        doing: &'static str,
        /// The file or program concerned.
        path: PathBuf,
        /// The error.
        source: std::io::Error,
    },
}

/// A build that could not be probed is the build's failure, not the input's.
impl crate::error::Blame for ProbeError {
    fn is_user_error(&self) -> bool {
        false
    }
}

/// Relative agreement that counts as a match: the probes' numbers are read from 15-digit
/// output, so a true hypothesis agrees to about 1e-12 and a false one is off by a factor.
pub(crate) const MATCH_TOLERANCE: f64 = 1e-6;

/// The verdict on `measured` among `hypotheses` (name, predicted value): the one hypothesis
/// within [`MATCH_TOLERANCE`] of `scale`, or `None` with the reason.
pub(crate) fn decide(
    measured: f64,
    hypotheses: &[(&str, f64)],
    scale: f64,
) -> (Vec<Hypothesis>, Option<String>, Option<String>) {
    let list: Vec<Hypothesis> = hypotheses
        .iter()
        .map(|&(name, expected)| Hypothesis {
            name: name.to_string(),
            expected,
            matches: measured.is_finite() && (measured - expected).abs() <= MATCH_TOLERANCE * scale,
        })
        .collect();
    let hits: Vec<&Hypothesis> = list.iter().filter(|h| h.matches).collect();
    match hits.as_slice() {
        [one] => {
            let name = one.name.clone();
            (list, Some(name), None)
        }
        [] => {
            let note = format!(
                "measured {measured:e} matches no hypothesis (to {MATCH_TOLERANCE:e} of {scale:e})"
            );
            (list, None, Some(note))
        }
        _ => (
            list,
            None,
            Some("the hypotheses predict the same value here".into()),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_number_between_the_hypotheses_is_inconclusive_and_says_why() {
        let (list, verdict, note) = decide(1.2, &[("a", 1.0), ("b", 1.5)], 1.0);
        assert_eq!(verdict, None);
        assert!(list.iter().all(|h| !h.matches));
        assert!(note.unwrap().contains("matches no hypothesis"));
        let (_, verdict, note) = decide(1.0, &[("a", 1.0), ("b", 1.0)], 1.0);
        assert_eq!(verdict, None);
        assert!(note.unwrap().contains("same value"));
        let (_, verdict, _) = decide(f64::NAN, &[("a", 1.0)], 1.0);
        assert_eq!(verdict, None);
    }
}
