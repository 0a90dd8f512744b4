//! `millimpact report`.

use std::time::Duration;

use super::{Context, Result};

use super::{CommandOutput, Failure, write_output};
use crate::cli::ReportArgs;
use millimpact::analysis::mill::{MillError, MillOptions, plan, run_mill};
use millimpact::analysis::report::{
    Report, ReportOptions, ReportTable, add_decks, add_mills, build_report,
};
use millimpact::codes::liggghts::mill::MillDeck;
use millimpact::error::{CheckFailed, UserError};
use millimpact::output::files::{REPORT_MARKER, check_report_dir, replace_dir};
use millimpact::output::report_page::render_pages;

fn table_csv(t: &ReportTable) -> Result<String> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(&t.headers)?;
    for r in &t.rows {
        w.write_record(r)?;
    }
    Ok(String::from_utf8(w.into_inner()?)?)
}

fn revision() -> Option<String> {
    let out = std::process::Command::new("git")
        .args(["rev-parse", "--short=12", "HEAD"])
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
}

pub(super) fn report(args: &ReportArgs) -> Result<CommandOutput> {
    let mut warnings = Vec::new();
    // Before any work: a folder that holds someone else's files is refused, never written.
    check_report_dir("--out", &args.out)
        .map_err(|e| UserError::argument(e.option, e.path.display(), e.reason))?;
    let cases = super::cases_or_canonical(&args.cases, "report")?;
    // The decks are read before any work too: one that cannot be checked runs nothing.
    let given = super::deck::Given {
        particles: &args.deck_particle,
        variables: &args.deck_variables,
        time_limit: Duration::from_secs_f64(args.timeout),
    };
    let decks = args
        .decks
        .iter()
        .map(|path| super::deck::read(path, None, &given))
        .collect::<Result<Vec<_>>>()?;
    // And the mills: a deck or an option that cannot run is refused before any work.
    let mills = read_mills(args)?;
    let options = ReportOptions {
        live: args.live,
        reference: super::reference_folder(args.reference.as_deref(), args.live, &mut warnings)?,
        timeout: Duration::from_secs_f64(args.timeout),
        revision: revision(),
    };
    // A progress bar on a terminal, for a report that runs codes.
    let stages = cases.len() as u64 + 4 + decks.len() as u64 + mills.len() as u64;
    let bar = (args.live || !args.decks.is_empty() || !args.mills.is_empty())
        .then(|| super::progress_bar(stages, "{bar:30} {pos}/{len} {msg}"))
        .flatten();
    let mut progress = |stage: &str| {
        if let Some(bar) = &bar {
            bar.set_message(stage.to_string());
            bar.inc(1);
        }
    };
    let mut report = build_report(&cases, &options, &mut progress)?;
    let checks = decks
        .iter()
        .map(|(code, deck)| {
            progress(&format!("{}: running {code}", deck.path.display()));
            let velocities = &args.deck_impact_velocity;
            super::deck::check(*code, deck, velocities, &given, args.timeout)
        })
        .collect::<Result<Vec<_>>>()?;
    add_decks(&mut report, &checks)?;
    let compared = mills
        .iter()
        .map(|(deck, options)| {
            progress(&format!("{}: running both laws", deck.path.display()));
            run_mill(deck, options, &|_| {})
        })
        .collect::<Result<Vec<_>, _>>()?;
    add_mills(&mut report, &compared)?;
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    let (html, md) = render_pages(&report)?;
    let out = &args.out;
    let written = write_report(out, &report, &html, &md)
        .with_context(|| format!("writing the report to {}", out.display()))?;
    let figures: usize = report.parts.iter().map(|p| p.figures.len()).sum();
    let tables: usize = report.parts.iter().map(|p| p.tables.len()).sum();
    let missing = &report.failures;
    Ok(CommandOutput {
        warnings,
        text: format!(
            "report: {} ({} figures, {} tables, {} files)\n",
            out.join("index.html").display(),
            figures,
            tables,
            written
        ),
        failure: (!missing.is_empty())
            .then(|| CheckFailed(format!("report: {}", missing.join("; ")))),
    })
}

/// The report's mills with their options, each planned: a deck or an option that cannot run
/// is refused, named as the report spells its options (`--mill-time`, …).
fn read_mills(args: &ReportArgs) -> Result<Vec<(MillDeck, MillOptions)>> {
    args.mills
        .iter()
        .map(|path| {
            let deck = MillDeck::read(path).map_err(MillError::from)?;
            let options = MillOptions {
                time: args.mill_time,
                seeds: args.mill_seeds,
                timeout: Duration::from_secs_f64(args.mill_timeout),
                ..MillOptions::defaults()
            };
            plan(&deck, &options).map_err(|e| match e {
                MillError::Option {
                    deck,
                    option,
                    value,
                    allowed,
                } => Failure::from(UserError::argument(
                    &option.replacen("--", "--mill-", 1),
                    value,
                    format!("{}: {allowed}", deck.display()),
                )),
                other => other.into(),
            })?;
            Ok((deck, options))
        })
        .collect::<Result<Vec<_>>>()
}

/// Write the report's files into `out` (replaced whole); how many were written, the marker not
/// counted.
fn write_report(out: &std::path::Path, report: &Report, html: &str, md: &str) -> Result<usize> {
    let mut written = 0usize;
    replace_dir(out, |dir| {
        let mut write = |name: &str, text: &str| -> Result<()> {
            written += 1;
            write_output(&dir.join(name), text.as_bytes(), "report")
        };
        for part in &report.parts {
            for f in &part.figures {
                write(&format!("{}.svg", f.id), &f.svg)?;
                write(&format!("{}.csv", f.id), &f.csv)?;
            }
            for t in &part.tables {
                write(&format!("{}.csv", t.id), &table_csv(t)?)?;
                write(
                    &format!("{}.json", t.id),
                    &(serde_json::to_string_pretty(t)? + "\n"),
                )?;
            }
        }
        for d in &report.data {
            write(&d.name, &d.text)?;
        }
        write("index.md", md)?;
        write("index.html", html)?;
        // The marker is not counted among the report's files: it is how a later report knows
        // this folder for its own.
        write_output(
            &dir.join(REPORT_MARKER),
            format!(
                "A report of millimpact {}: `millimpact report --out` replaces this folder whole.\n",
                env!("CARGO_PKG_VERSION")
            )
            .as_bytes(),
            "report",
        )
    })?;
    Ok(written)
}
