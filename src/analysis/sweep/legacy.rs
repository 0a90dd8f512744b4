//! `sweep`: one impact per loss coefficient over a range (the paper's Figure 3).

use anyhow::Result;
use serde::Serialize;

use crate::analysis::run::{IntegrationOptions, SweepRow, run_case};
use crate::error::UserError;
use crate::model::case::Case;
use crate::model::count::round_count;
use crate::output::{Section, Summary, sci, signed};

/// Most values a sweep may have.
pub const MAX_SWEEP_POINTS: usize = 100_000;

/// Parse `START:STOP:STEP` into the values of η it names, STOP included.
pub fn parse_range(text: &str) -> Result<Vec<f64>, UserError> {
    let allowed = "START:STOP:STEP with 0 <= START <= STOP < 1 and STEP > 0";
    let refuse = |allowed: &str| UserError::argument("--loss-coefficient", text, allowed);
    let numbers: Option<Vec<f64>> = text.split(':').map(|p| p.trim().parse().ok()).collect();
    let Some([start, stop, step]) = numbers
        .as_deref()
        .and_then(|v| <[f64; 3]>::try_from(v).ok())
    else {
        return Err(refuse(allowed));
    };
    let finite = start.is_finite() && stop.is_finite() && step.is_finite();
    if !finite || start < 0.0 || stop >= 1.0 || start > stop || step <= 0.0 {
        return Err(refuse(allowed));
    }
    // The count is checked as a float before it becomes an integer: a tiny step must be
    // refused, not wrap.
    let count = ((stop - start) / step + 1e-9).floor() + 1.0;
    if !(count.is_finite() && count <= MAX_SWEEP_POINTS as f64) {
        return Err(refuse(&format!("at most {MAX_SWEEP_POINTS} values")));
    }
    let count = round_count(count)
        .and_then(|n| usize::try_from(n).ok())
        .ok_or_else(|| refuse(&format!("at most {MAX_SWEEP_POINTS} values")))?;
    Ok((0..count).map(|i| start + i as f64 * step).collect())
}

/// The rows of a sweep.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SweepReport {
    /// One row per η.
    pub rows: Vec<SweepRow>,
    /// The command that reproduces it.
    pub command: String,
}

/// Run `case` at each η of `values`.
pub fn sweep(case: &Case, values: &[f64], options: &IntegrationOptions) -> Result<SweepReport> {
    let mut rows = Vec::with_capacity(values.len());
    for &eta in values {
        let at = case.with_loss_coefficient(eta);
        let settings = options.settings(&at, false)?;
        rows.push(run_case(&at, &settings)?.0.row());
    }
    Ok(SweepReport {
        rows,
        command: String::new(),
    })
}

impl Summary for SweepReport {
    type Record = SweepRow;

    fn records(&self) -> Vec<SweepRow> {
        self.rows.clone()
    }

    fn sections(&self) -> Vec<Section> {
        let mut t = Section::new(
            self.rows
                .first()
                .map(|r| format!("{}: COR against η by {}", r.case, r.method)),
            &[
                "η",
                "COR",
                "exact",
                "COR error",
                "peak (m)",
                "contact time (s)",
            ],
        );
        for r in &self.rows {
            t.rows.push(vec![
                r.loss_coefficient.to_string(),
                sci(r.cor),
                sci(r.cor_exact),
                signed(r.cor_error),
                sci(r.peak_deformation),
                sci(r.contact_time),
            ]);
        }
        vec![t]
    }

    fn footer(&self) -> Vec<String> {
        vec![format!("reproduce: {}", self.command)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn range_includes_its_stop() {
        let v = parse_range("0:0.9:0.1").unwrap();
        assert_eq!(v.len(), 10);
        assert!((v[9] - 0.9).abs() < 1e-12);
        assert_eq!(parse_range("0.35:0.35:0.1").unwrap(), vec![0.35]);
    }

    #[test]
    fn range_refuses_what_is_not_allowed() {
        for bad in [
            "0:1:0.1",
            "0.5:0.1:0.1",
            "0:0.5:0",
            "-0.1:0.5:0.1",
            "0:0.5",
            "a:b:c",
            "0:nan:0.1",
            "0:0.9:1e-300",
            "0:0.9:1e-6",
        ] {
            assert!(parse_range(bad).is_err(), "{bad}");
        }
    }
}
