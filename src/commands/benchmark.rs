//! `millimpact benchmark`.

use std::time::Duration;

use super::Result;

use super::CommandOutput;
use super::render;
use crate::cli::{BenchmarkArgs, BenchmarkName};
use millimpact::analysis::benchmark::cor_chart::cor_chart;
use millimpact::analysis::benchmark::oblique_chart::oblique_figures;
use millimpact::analysis::benchmark::{
    BenchmarkOptions, CodeRuns, STEPS_PER_CONTACT, STORED_FOLDER, chung_ooi,
};
use millimpact::analysis::store::ReferenceOptions;
use millimpact::codes::CodeName;
use millimpact::error::{CheckFailed, UserError};

pub(super) fn benchmark(args: &BenchmarkArgs) -> Result<CommandOutput> {
    let mut warnings = Vec::new();
    let codes = if !args.codes.is_empty() {
        CodeRuns::Live(args.codes.clone())
    } else if args.live {
        CodeRuns::Live(CodeName::ALL.to_vec())
    } else {
        // The stored runs are at one resolution: another is a run now.
        if args.steps_per_contact != STEPS_PER_CONTACT {
            return Err(UserError::argument(
                "--steps-per-contact",
                args.steps_per_contact,
                format!(
                    "{STEPS_PER_CONTACT} when the stored runs are read (their resolution); give --live or --code to run the codes at another"
                ),
            )
            .into());
        }
        let reference = super::reference_folder(args.reference.as_deref(), false, &mut warnings)?;
        CodeRuns::Stored(reference.join(STORED_FOLDER))
    };
    let options = BenchmarkOptions {
        codes,
        reference: ReferenceOptions {
            steps_per_contact: Some(args.steps_per_contact),
            timeout: Duration::from_secs_f64(args.timeout),
            ..ReferenceOptions::default()
        },
    };
    if let Some(folder) = &args.chart
        && !folder.is_dir()
    {
        return Err(UserError::argument(
            "--chart",
            folder.display(),
            "an existing folder (millimpact does not create it)",
        )
        .into());
    }
    let report = match args.benchmark {
        BenchmarkName::ChungOoi => chung_ooi(&options)?,
    };
    if let Some(folder) = &args.chart {
        let mut figures = cor_chart(&report)?.figures()?;
        let cor_figures = figures.len();
        figures.extend(oblique_figures(&report)?);
        let oblique_count = figures.len() - cor_figures;
        let mut files = Vec::new();
        for figure in figures {
            for (extension, text) in [("svg", figure.svg), ("csv", figure.csv)] {
                let path = folder.join(format!("{}.{extension}", figure.id));
                super::check_output("--chart", Some(&path), &[])?;
                files.push((path, text));
            }
        }
        // Every path checked before any is written: a refused one leaves the folder as it was.
        for (path, text) in &files {
            super::write_output(path, text.as_bytes(), "COR chart")?;
        }
        warnings.push(format!(
            "the COR chart of test 3 and the charts of tests 4–8 ({oblique_count} figures): {} files in {}",
            files.len(),
            folder.display()
        ));
    }
    let failures = report.failures();
    let failure = (!failures.is_empty() || !report.missing.is_empty()).then(|| {
        CheckFailed(format!(
            "benchmark {}: {} of {} rows outside their tolerance, {} stored runs missing",
            report.benchmark,
            failures.len(),
            report.rows.len(),
            report.missing.len()
        ))
    });
    Ok(CommandOutput {
        text: render(&report, args.format)?,
        failure,
        warnings,
    })
}
