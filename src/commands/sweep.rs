//! `millimpact sweep`: a sweep file's grid (rows appended as they finish, resumable,
//! shardable), or a case over a range of η.

use std::io::Write;
use std::path::Path;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use super::{Context, Result};

use super::run::integration_options;
use super::{CommandOutput, check_output, write_output};
use crate::cli::SweepArgs;
use millimpact::analysis::precision::choice::choose;
use millimpact::analysis::source::Resolution;
use millimpact::analysis::source::Source;
use millimpact::analysis::sweep::eta::{EtaSweep, loss_coefficient_axis};
use millimpact::analysis::sweep::grid::{SweepFile, is_sweep_table, read_table};
use millimpact::analysis::sweep::point::GridOptions;
use millimpact::analysis::sweep::resume::{Resumed, point_keys, read_resumed};
use millimpact::analysis::sweep::rows::{EncodedRows, RowFormat, RowWriter};
use millimpact::analysis::sweep::run_grid;
use millimpact::error::{CheckFailed, UserError};
use millimpact::model::case::Case;
use millimpact::model::exact;
use millimpact::output::Format;
use millimpact::output::files::write_atomic_with;
use millimpact::output::invocation::Invocation;
use millimpact::output::restitution_plot::restitution_svg;

/// Raised by Ctrl-C: no new point starts, finished rows are kept.
static STOP: AtomicBool = AtomicBool::new(false);

pub(super) fn sweep(args: &SweepArgs) -> Result<CommandOutput> {
    let table = read_table(&args.case);
    if let Ok(table) = &table
        && is_sweep_table(table)
    {
        let sweep = SweepFile::from_table(&args.case, table)?;
        sweep.base_case.refuse_oblique("sweep")?;
        return sweep_file(args, &sweep);
    }
    let case = Case::load(&args.case)?;
    case.refuse_oblique("sweep")?;
    check_output("--plot", args.plot.as_deref(), &[&args.case])?;
    let Some(range) = &args.loss_coefficient else {
        return Err(UserError::CaseArgument {
            case: case.path.display().to_string(),
            option: "--loss-coefficient".into(),
            value: "(missing)".into(),
            allowed: "required with a case file (a sweep file has a base and [axes])".into(),
        }
        .into());
    };
    let axis = loss_coefficient_axis(range, &case.path.display().to_string())?;
    let format = Format::from_name(&args.format).ok_or_else(|| {
        UserError::argument(
            "--format",
            &args.format,
            "jsonl is for sweep files; a case over --loss-coefficient takes table, json, csv or markdown",
        )
    })?;
    let mut options = integration_options(&args.integration);
    let mut command = Invocation::new("sweep")
        .arg(case.path.display())
        .option("--loss-coefficient", range);
    match args.tolerance {
        Some(tolerance) => {
            let choice = choose(tolerance)
                .map_err(|e| UserError::argument("--tolerance", tolerance, e.allowed))?;
            eprintln!("note: {}", choice.sentence());
            options.method = choice.method;
            options.steps_per_period = Resolution::steps_per_period(Some(choice.resolution));
            options.rtol = Resolution::rtol(Some(choice.resolution));
            command = command.option("--tolerance", format!("{tolerance:e}"));
        }
        None => {
            command = command
                .option("--method", options.method)
                .option_if("--steps-per-period", options.steps_per_period)
                .option_if("--timestep", options.timestep)
                .option_if("--rtol", options.rtol);
        }
    }
    let (name, method) = (case.name.clone(), options.method);
    let sweep = EtaSweep::new(case, table?, axis, options, jobs(args), command.to_string());
    // Rows go to standard output as they are done.
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    let points = match sweep.write(format, &mut out, args.plot.is_some()) {
        Ok(points) => points,
        Err(e) if broken_pipe(&e) => return Ok(CommandOutput::passed(String::new())),
        Err(e) => return Err(e.into()),
    };
    if let Err(e) = out.flush() {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            return Ok(CommandOutput::passed(String::new()));
        }
        return Err(e).context("writing the sweep's rows");
    }
    if let Some(path) = &args.plot {
        let svg = restitution_svg(&name, method.name(), &points, &exact::restitution)?;
        write_output(path, svg.as_bytes(), "figure")?;
    }
    Ok(CommandOutput::passed(String::new()))
}

/// Whether `e` is a closed pipe (the reader has gone: what it read is what it wanted).
fn broken_pipe(e: &(dyn std::error::Error + 'static)) -> bool {
    std::iter::successors(Some(e), |e| e.source()).any(|c| {
        c.downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
    })
}

/// Worker threads: `--jobs`, or the number of cores.
fn jobs(args: &SweepArgs) -> usize {
    args.jobs.map(|j| j as usize).unwrap_or_else(|| {
        std::thread::available_parallelism()
            .map(|n| n.get())
            .unwrap_or(1)
    })
}

fn refuse_for_sweep_files(args: &SweepArgs) -> Result<(), UserError> {
    let file = args.case.display().to_string();
    let refuse = |option: &str, value: String| UserError::CaseArgument {
        case: file.clone(),
        option: option.into(),
        value,
        allowed: "not for a sweep file: give methods, codes and resolutions in its [axes]".into(),
    };
    let i = &args.integration;
    if let Some(v) = &args.loss_coefficient {
        return Err(refuse("--loss-coefficient", v.clone()));
    }
    if let Some(v) = &args.plot {
        return Err(refuse("--plot", v.display().to_string()));
    }
    if let Some(v) = args.tolerance {
        return Err(UserError::CaseArgument {
            case: file.clone(),
            option: "--tolerance".into(),
            value: format!("{v:e}"),
            allowed: "not for a sweep file: give `tolerance = ...` in the file".into(),
        });
    }
    let given = [
        (
            "--steps-per-period",
            i.steps_per_period.map(|v| v.to_string()),
        ),
        ("--timestep", i.timestep.map(|v| v.to_string())),
        ("--rtol", i.rtol.map(|v| v.to_string())),
        (
            "--method",
            (i.method != millimpact::solve::Method::Rk4Event).then(|| i.method.to_string()),
        ),
    ];
    match given.into_iter().find_map(|(option, v)| Some((option, v?))) {
        Some((option, v)) => Err(refuse(option, v)),
        None => Ok(()),
    }
}

fn sweep_file(args: &SweepArgs, sweep: &SweepFile) -> Result<CommandOutput> {
    refuse_for_sweep_files(args)?;
    if let Some(choice) = &sweep.tolerance {
        eprintln!("note: {}", choice.sentence());
    }
    let mut format = RowFormat::from_name(&args.format).ok_or_else(|| {
        UserError::argument(
            "--format",
            &args.format,
            "a sweep file's rows are csv or jsonl",
        )
    })?;
    let columns = sweep.columns();
    let mut indices: Vec<usize> = sweep.indices(args.shard);
    let (out, resumed) = open_rows(args, sweep, &mut format, &mut indices)?;
    let has_codes = sweep
        .sources
        .iter()
        .any(|s| matches!(s.source, Source::Code(_)));
    let flush_every = if has_codes {
        Duration::ZERO
    } else {
        Duration::from_millis(50)
    };
    let writer = RowWriter::new(
        out,
        format,
        &columns,
        resumed.has_header,
        flush_every,
        resumed.kept_lines,
    )
    .context("writing the sweep's rows")?;
    let options = GridOptions {
        jobs: jobs(args),
        timeout: Duration::from_secs_f64(args.timeout),
        periods: args.integration.periods,
        batch: args.batch as usize,
        timestep: None,
    };
    let bar = super::progress_bar(
        indices.len() as u64,
        "{bar:40} {pos}/{len} points  {per_sec}  ETA {eta}",
    );
    let _ = ctrlc::set_handler(|| {
        // The codes running now end at once; the rows already finished are kept.
        if STOP.swap(true, Ordering::SeqCst) {
            // A second Ctrl-C: leave now.
            millimpact::codes::runner::stop_all_codes_and_exit(130);
        }
        millimpact::codes::runner::stop_all_codes();
    });
    let mut writer = writer;
    let notes = Mutex::new(Vec::<String>::new());
    let note = |text: String| notes.lock().unwrap_or_else(|e| e.into_inner()).push(text);
    // The one writer: rows come encoded from the threads that computed them.
    let mut write = |rows: EncodedRows| {
        let count = rows.rows as u64;
        writer.write_encoded(rows)?;
        if let Some(bar) = &bar {
            bar.inc(count);
        }
        Ok(())
    };
    let written = run_grid(sweep, &indices, &options, &STOP, format, &mut write, &note);
    for text in notes.into_inner().unwrap_or_else(|e| e.into_inner()) {
        eprintln!("note: {text}");
    }
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    let flushed = writer.flush();
    if let Some(e) = written.err().or(flushed.err()) {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            return Ok(CommandOutput::passed(String::new()));
        }
        return Err(e).context("writing the sweep's rows");
    }
    Ok(outcome(args, &writer, resumed.kept_rows))
}

/// Where the rows go: standard output, or `--out`, a new file or one continued with
/// `--resume`: then its rows are read, the points they hold leave `indices`, the format is
/// the file's own, and the file is rewritten without the rows to run again.
fn open_rows(
    args: &SweepArgs,
    sweep: &SweepFile,
    format: &mut RowFormat,
    indices: &mut Vec<usize>,
) -> Result<(Box<dyn Write + Send>, Resumed)> {
    let Some(path) = &args.out else {
        return Ok((
            Box::new(std::io::BufWriter::new(std::io::stdout())),
            Resumed::default(),
        ));
    };
    check_output("--out", Some(path), &[&args.case, &sweep.base_path])?;
    let held = std::fs::metadata(path).is_ok_and(|m| m.len() > 0);
    if held && !args.resume {
        return Err(UserError::argument(
            "--out",
            path.display(),
            "the file exists and is not empty: give --resume to continue it, or remove it",
        )
        .into());
    }
    let resumed = if held {
        resume(path, sweep, format, indices)?
    } else {
        Resumed::default()
    };
    let file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(path)
        .with_context(|| format!("opening {}", path.display()))?;
    Ok((Box::new(std::io::BufWriter::new(file)), resumed))
}

/// Continue the rows of `path`: the points done leave `indices`, and failed rows, a row cut
/// off by a kill and rows a later one replaced go (the kept rows are copied as they were and
/// the file is swapped in whole).
fn resume(
    path: &Path,
    sweep: &SweepFile,
    format: &mut RowFormat,
    indices: &mut Vec<usize>,
) -> Result<Resumed> {
    let resumed = read_resumed(path, sweep)?;
    if let Some(f) = resumed.format {
        *format = f;
    }
    // The points done, by their keys, a block at a time (points are not all held).
    let mut left = Vec::with_capacity(indices.len());
    for block in indices.chunks(4096) {
        let points: Vec<_> = block.iter().map(|&i| sweep.point(i)).collect();
        let keys = point_keys(sweep, &points)?;
        left.extend(
            block
                .iter()
                .zip(&keys)
                .filter(|(_, k)| !resumed.done.contains(*k))
                .map(|(&i, _)| i),
        );
    }
    *indices = left;
    if resumed.rewrites() {
        write_atomic_with(path, |out| resumed.copy_kept(path, out))
            .with_context(|| format!("rewriting {}", path.display()))?;
    }
    let mut again = Vec::new();
    if resumed.retried > 0 {
        again.push(format!(
            "{} failed point{}",
            resumed.retried,
            if resumed.retried == 1 { "" } else { "s" }
        ));
    }
    if resumed.torn {
        again.push("the point of the last row, cut off mid-line".to_string());
    }
    if !again.is_empty() {
        eprintln!(
            "note: resuming {}: {} rows kept; run again: {}",
            path.display(),
            resumed.kept_rows,
            again.join(", ")
        );
    }
    Ok(resumed)
}

/// How a sweep that wrote its rows ends: passed; interrupted (continue with `--resume`); or
/// with failed points, which fail the command unless `--allow-failures`. A failed point is a
/// row like any other: the sweep went on and its output is whole; the exit status says that
/// it is not all computed.
fn outcome<W: Write>(args: &SweepArgs, writer: &RowWriter<W>, kept_rows: usize) -> CommandOutput {
    let place = args
        .out
        .as_deref()
        .map(Path::display)
        .map(|d| d.to_string())
        .unwrap_or_else(|| "standard output".into());
    let points_in_output = kept_rows + writer.written;
    let failures =
        (!writer.failed.is_empty()).then(|| writer.failed.summary(points_in_output, &place));
    let failed = |text: String| CommandOutput {
        warnings: Vec::new(),
        text: String::new(),
        failure: Some(CheckFailed(text)),
    };
    if STOP.load(Ordering::SeqCst) {
        let mut text = format!(
            "interrupted: {} rows written to {place}; continue with --resume",
            writer.written
        );
        if let Some(failures) = &failures {
            text = format!("{text} (it retries the failed ones); {failures}");
        }
        return failed(text);
    }
    let Some(failures) = failures else {
        return CommandOutput::passed(String::new());
    };
    if args.allow_failures {
        let mut output = CommandOutput::passed(String::new());
        output.warnings.push(failures);
        return output;
    }
    let retry = if args.out.is_some() {
        "; --resume retries them"
    } else {
        "; --out FILE keeps the rows for --resume to retry them"
    };
    failed(format!("{failures}{retry}, --allow-failures exits 0"))
}
