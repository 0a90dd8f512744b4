//! One sweep row as a typed value: the point's identity, its case-axis values, who computed it
//! at which resolution, its figures and its status. The CSV header and the JSON-lines keys are
//! the serde names of these fields, read from the types themselves, so a label cannot part
//! from its value.

use std::io::Write;

use serde::ser::{SerializeMap, SerializeTuple};
use serde::{Serialize, Serializer};

use crate::analysis::run::RunReport;
use crate::analysis::source::{Resolution, Source};
use crate::analysis::store::ReferenceRecord;
use crate::codes::CodeName;
use crate::model::case::Case;
use crate::model::exact::ImpactFigures;
use crate::model::law::PaperLaw;
use crate::model::trajectory::TrajectoryMetrics;
use crate::output::csv_record::{CsvRecords, RecordError};
use crate::solve::Method;
use crate::solve::paper::Outcome;

/// Which sweep and which of its points a row belongs to.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct RowIdentity {
    /// The sweep's fingerprint (shards of one sweep share it).
    pub sweep: String,
    /// The point's index in the whole grid.
    pub point: usize,
}

/// One value of a case axis, under its dotted case key.
#[derive(Clone, Debug, PartialEq)]
pub struct AxisValue {
    /// The dotted case key (`ball.radius`, `loss_coefficient`).
    pub key: String,
    /// Its value at the point.
    pub value: toml::Value,
}

/// Who computed a point and at which resolution: the method or the code, and the knob that
/// belongs to it. The columns that do not apply stay empty.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct PointSource {
    /// The method.
    pub method: Option<Method>,
    /// The DEM code.
    pub code: Option<CodeName>,
    /// Steps per undamped period (fixed-step methods).
    pub steps_per_period: Option<u32>,
    /// Steps per elastic contact time (codes).
    pub steps_per_contact: Option<u32>,
    /// Relative tolerance (adaptive methods).
    pub rtol: Option<f64>,
}

impl PointSource {
    /// The columns of `source` at `resolution` (`None`: its default).
    pub(crate) fn new(source: Source, resolution: Option<Resolution>) -> PointSource {
        let (method, code) = match source {
            Source::Method(method) => (Some(method), None),
            Source::Code(code) => (None, Some(code)),
        };
        PointSource {
            method,
            code,
            steps_per_period: Resolution::steps_per_period(resolution),
            steps_per_contact: Resolution::steps_per_contact(resolution),
            rtol: Resolution::rtol(resolution),
        }
    }
}

/// The figures of a point; a column a source does not report stays empty.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct PointFigures {
    /// Case name.
    pub case: Option<String>,
    /// Loss coefficient η of the case.
    pub eta: Option<f64>,
    /// Reduced mass, kg.
    pub reduced_mass: Option<f64>,
    /// Contact stiffness C, N/m^n.
    pub contact_stiffness: Option<f64>,
    /// Exponent n.
    pub exponent: Option<f64>,
    /// COR realised.
    pub cor: Option<f64>,
    /// COR the source should realise (the closed form, or the code's target).
    pub cor_target: Option<f64>,
    /// `(cor − cor_target) / cor_target`.
    pub cor_error: Option<f64>,
    /// Peak deformation, m.
    pub peak_deformation: Option<f64>,
    /// Peak deformation of the paper's law, exact, m.
    pub peak_deformation_exact: Option<f64>,
    /// Relative error of the peak deformation.
    pub peak_deformation_error: Option<f64>,
    /// Peak force, N.
    pub peak_force: Option<f64>,
    /// Peak force of the paper's law, exact, N.
    pub peak_force_exact: Option<f64>,
    /// Contact time by overlap, s.
    pub contact_time: Option<f64>,
    /// Contact time of the paper's law, exact, s.
    pub contact_time_exact: Option<f64>,
    /// Relative error of the contact time.
    pub contact_time_error: Option<f64>,
    /// Compression part of the contact time, s.
    pub compression_time: Option<f64>,
    /// Restitution part of the contact time, s.
    pub restitution_time: Option<f64>,
    /// Absorbed energy, J.
    pub absorbed_energy: Option<f64>,
    /// Steps run.
    pub steps: Option<u64>,
    /// Right-hand-side evaluations (methods).
    pub rhs_evaluations: Option<u64>,
    /// Time step, s (fixed-step methods and codes).
    pub timestep: Option<f64>,
    /// Wall time, s: a method's solve, or a code's process from start to exit (its start-up
    /// included; a batch's divided among its impacts).
    pub wall_time: Option<f64>,
    /// The code's own loop time, s (a batch's divided among its impacts).
    pub loop_time: Option<f64>,
    /// Wall time of everything a code point took, s: sizing its run (the build's probe
    /// included, where this point's sizing made it), the process, reading and checking its
    /// output (a batch's divided among its impacts, each adding its own sizing).
    pub whole_wall_time: Option<f64>,
    /// COR of the code's own law, exact.
    pub own_law_cor: Option<f64>,
    /// COR of the code's own law stepped as the code steps it.
    pub own_law_stepped_cor: Option<f64>,
    /// The code's version as it prints it.
    pub code_version: Option<String>,
    /// Impacts in the process that ran the point.
    pub batch: Option<usize>,
}

/// A number, or an empty cell where it is not a number.
fn finite(x: f64) -> Option<f64> {
    (!x.is_nan()).then_some(x)
}

fn relative(value: f64, reference: f64) -> Option<f64> {
    finite((value - reference) / reference)
}

impl PointFigures {
    /// The figures of a method's run.
    pub(crate) fn of_method(r: &RunReport) -> PointFigures {
        PointFigures {
            case: Some(r.case.clone()),
            eta: finite(r.loss_coefficient),
            reduced_mass: finite(r.mass),
            contact_stiffness: finite(r.stiffness),
            exponent: finite(r.exponent),
            cor: finite(r.cor),
            cor_target: finite(r.exact.cor),
            cor_error: finite(r.error.cor),
            peak_deformation: finite(r.peak_deformation),
            peak_deformation_exact: finite(r.exact.peak_deformation),
            peak_deformation_error: finite(r.error.peak_deformation),
            peak_force: finite(r.peak_force),
            peak_force_exact: finite(r.exact.peak_force),
            contact_time: finite(r.contact_time),
            contact_time_exact: finite(r.exact.contact_time),
            contact_time_error: finite(r.error.contact_time),
            compression_time: finite(r.compression_time),
            restitution_time: finite(r.restitution_time),
            absorbed_energy: finite(r.absorbed_energy),
            steps: Some(r.steps),
            rhs_evaluations: Some(r.rhs_evaluations),
            timestep: r.timestep.and_then(finite),
            wall_time: finite(r.wall_time),
            ..PointFigures::default()
        }
    }

    /// The figures of a method's `outcome` on the case named `case` with `law` at
    /// `impact_velocity`: what [`PointFigures::of_method`] gives for the run's report, without
    /// the report's other parts (the elastic Hertz figures, the warnings).
    #[cfg(test)]
    pub(crate) fn of_solution(
        case: &str,
        law: &PaperLaw,
        impact_velocity: f64,
        outcome: &Outcome,
    ) -> PointFigures {
        let mut figures = PointFigures::default();
        figures.set_solution(case, law, impact_velocity, outcome);
        figures
    }

    /// Make these the figures of [`PointFigures::of_solution`], the case name's storage
    /// reused (a chunk of a sweep fills one row point after point).
    pub(crate) fn set_solution(
        &mut self,
        case: &str,
        law: &PaperLaw,
        impact_velocity: f64,
        outcome: &Outcome,
    ) {
        let exact = crate::model::exact::paper_impact(law, impact_velocity);
        let f = &outcome.figures;
        let error = |value: f64, reference: f64| finite((value - reference) / reference);
        let mut name = self.case.take().unwrap_or_default();
        if name != case {
            name.clear();
            name.push_str(case);
        }
        *self = PointFigures {
            case: Some(name),
            eta: finite(law.loss_coefficient),
            reduced_mass: finite(law.mass),
            contact_stiffness: finite(law.stiffness),
            exponent: finite(law.exponent),
            cor: finite(f.cor),
            cor_target: finite(exact.cor),
            cor_error: error(f.cor, exact.cor),
            peak_deformation: finite(f.peak_deformation),
            peak_deformation_exact: finite(exact.peak_deformation),
            peak_deformation_error: error(f.peak_deformation, exact.peak_deformation),
            peak_force: finite(f.peak_force),
            peak_force_exact: finite(exact.peak_force),
            contact_time: finite(f.contact_time),
            contact_time_exact: finite(exact.contact_time),
            contact_time_error: error(f.contact_time, exact.contact_time),
            compression_time: finite(f.compression_time),
            restitution_time: finite(f.restitution_time),
            absorbed_energy: finite(f.absorbed_energy),
            steps: Some(outcome.stats.steps),
            rhs_evaluations: Some(outcome.stats.rhs_evaluations),
            timestep: outcome.timestep.and_then(finite),
            wall_time: finite(outcome.wall_time),
            ..PointFigures::default()
        };
    }

    /// The figures of a code's run.
    pub(crate) fn of_code(f: &CodeFigures) -> PointFigures {
        let m = &f.metrics;
        let p = &f.paper_exact;
        PointFigures {
            case: Some(f.case.clone()),
            eta: finite(f.loss_coefficient),
            reduced_mass: finite(f.reduced_mass),
            contact_stiffness: finite(f.contact_stiffness),
            exponent: finite(f.exponent),
            cor: finite(m.cor),
            cor_target: finite(f.cor_target),
            cor_error: relative(m.cor, f.cor_target),
            peak_deformation: finite(m.peak_deformation),
            peak_deformation_exact: finite(p.peak_deformation),
            peak_deformation_error: relative(m.peak_deformation, p.peak_deformation),
            peak_force: finite(m.peak_force),
            peak_force_exact: finite(p.peak_force),
            contact_time: finite(m.contact_time),
            contact_time_exact: finite(p.contact_time),
            contact_time_error: relative(m.contact_time, p.contact_time),
            steps: Some(f.steps),
            timestep: finite(f.timestep),
            wall_time: finite(f.wall_time),
            loop_time: f.loop_time.and_then(finite),
            whole_wall_time: finite(f.whole_wall_time),
            own_law_cor: finite(f.own_law_cor),
            own_law_stepped_cor: finite(f.own_law_stepped_cor),
            code_version: Some(f.code_version.clone()),
            batch: Some(f.batch),
            ..PointFigures::default()
        }
    }
}

/// Whether a point was computed, and if not, why.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct RowStatus {
    /// `ok`, or the error on one line.
    pub status: String,
}

impl RowStatus {
    /// The status of a computed point.
    pub(crate) const OK: &'static str = "ok";

    /// A computed point.
    pub fn ok() -> RowStatus {
        RowStatus {
            status: Self::OK.to_string(),
        }
    }

    /// Make this the status of a computed point, its storage reused.
    pub(crate) fn set_ok(&mut self) {
        if !self.is_ok() {
            self.status.clear();
            self.status.push_str(Self::OK);
        }
    }

    /// A point that failed with `error` (kept on one line).
    pub fn failed(error: &str) -> RowStatus {
        RowStatus {
            status: error.replace(['\n', '\r'], " "),
        }
    }

    /// Whether the point was computed.
    pub(crate) fn is_ok(&self) -> bool {
        self.status == Self::OK
    }
}

/// One row of a sweep's output.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SweepRow {
    /// The sweep and the point.
    pub identity: RowIdentity,
    /// The point's case-axis values, in the sweep file's axis order.
    pub axes: Vec<AxisValue>,
    /// Who computed it.
    pub source: PointSource,
    /// What it gave (empty for a failed point).
    pub figures: PointFigures,
    /// `ok` or the error.
    pub status: RowStatus,
}

/// The field names of a flat record type, in declaration order, as serde names them.
fn field_names<T: Serialize + Default>() -> Vec<String> {
    // Serialising a record of scalars into memory cannot fail.
    let header = crate::output::csv_record::header_of(&T::default()).unwrap_or_default();
    csv::ReaderBuilder::new()
        .has_headers(false)
        .from_reader(header.as_slice())
        .records()
        .next()
        .and_then(Result::ok)
        .map(|r| r.iter().map(String::from).collect())
        .unwrap_or_default()
}

/// The columns of a sweep's rows, given its case-axis keys: identity, axes, source, figures,
/// status.
pub(crate) fn columns(axis_keys: &[String]) -> Vec<String> {
    let mut c = field_names::<RowIdentity>();
    c.extend(axis_keys.iter().cloned());
    c.extend(field_names::<PointSource>());
    c.extend(field_names::<PointFigures>());
    c.extend(field_names::<RowStatus>());
    c
}

/// The columns a row is matched by on resume: the case axes and the source.
pub(crate) fn key_columns(axis_keys: &[String]) -> Vec<String> {
    let mut c = axis_keys.to_vec();
    c.extend(field_names::<PointSource>());
    c
}

/// The cells of the key columns (`key_columns`) as the row writes them: the axis values and
/// the source, through the same serialisation as the CSV record.
pub fn key_cells(axes: &[AxisValue], source: &PointSource) -> Vec<String> {
    let mut records = CsvRecords::default();
    // Serialising scalars into memory cannot fail.
    let _ = records.push(&(AxisValues(axes), source));
    csv::ReaderBuilder::new()
        .has_headers(false)
        .from_reader(records.as_bytes())
        .records()
        .next()
        .and_then(Result::ok)
        .map(|r| r.iter().map(String::from).collect())
        .unwrap_or_default()
}

/// The case-axis values of a row as one serde sequence (a CSV record's middle fields).
struct AxisValues<'a>(&'a [AxisValue]);

impl Serialize for AxisValues<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut seq = serializer.serialize_tuple(self.0.len())?;
        for a in self.0 {
            seq.serialize_element(&a.value)?;
        }
        seq.end()
    }
}

/// The case-axis values of a row as map entries (a JSON line's keys).
struct AxisEntries<'a>(&'a [AxisValue]);

impl Serialize for AxisEntries<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.0.len()))?;
        for a in self.0 {
            map.serialize_entry(&a.key, &a.value)?;
        }
        map.end()
    }
}

/// A row as one JSON object: every part's fields flattened, in column order.
#[derive(Serialize)]
struct JsonRow<'a> {
    #[serde(flatten)]
    identity: &'a RowIdentity,
    #[serde(flatten)]
    axes: AxisEntries<'a>,
    #[serde(flatten)]
    source: &'a PointSource,
    #[serde(flatten)]
    figures: &'a PointFigures,
    #[serde(flatten)]
    status: &'a RowStatus,
}

impl SweepRow {
    /// The row as one flat record: every part's fields in column order (a CSV record's
    /// fields, through any serde serialiser of records).
    pub fn record(&self) -> impl Serialize + '_ {
        (
            &self.identity,
            AxisValues(&self.axes),
            &self.source,
            &self.figures,
            &self.status,
        )
    }

    /// Append the row as one CSV record (no header) to `records`: the bytes the csv crate's
    /// writer gives [`SweepRow::record`].
    pub fn write_csv(&self, records: &mut CsvRecords) -> Result<(), RecordError> {
        records.push(&self.record())
    }

    /// Append the row as one JSON line to `out`.
    pub(crate) fn write_json_line<W: Write>(&self, out: &mut W) -> std::io::Result<()> {
        serde_json::to_writer(
            &mut *out,
            &JsonRow {
                identity: &self.identity,
                axes: AxisEntries(&self.axes),
                source: &self.source,
                figures: &self.figures,
                status: &self.status,
            },
        )?;
        out.write_all(b"\n")
    }
}

/// What a code point's row is made of, whether it ran alone or in a batch.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct CodeFigures {
    /// Case name.
    pub case: String,
    /// The case's loss coefficient η.
    pub loss_coefficient: f64,
    /// The case's reduced mass, kg.
    pub reduced_mass: f64,
    /// The case's contact stiffness C, N/m^n.
    pub contact_stiffness: f64,
    /// The case's exponent n.
    pub exponent: f64,
    /// The code's figures.
    pub metrics: TrajectoryMetrics,
    /// The COR the code should realise.
    pub cor_target: f64,
    /// The paper's law, exact.
    pub paper_exact: ImpactFigures,
    /// Steps run.
    pub steps: u64,
    /// Time step, s.
    pub timestep: f64,
    /// Process wall time (a batch's divided among its impacts), s.
    pub wall_time: f64,
    /// The code's own loop time, s.
    pub loop_time: Option<f64>,
    /// Wall time of everything the point took (sizing, probe, process, reading), s; NaN when
    /// not known.
    pub whole_wall_time: f64,
    /// COR of the code's own law, exact.
    pub own_law_cor: f64,
    /// COR of the code's own law stepped as the code steps.
    pub own_law_stepped_cor: f64,
    /// Version string.
    pub code_version: String,
    /// Impacts in the process that ran it.
    pub batch: usize,
}

impl CodeFigures {
    /// The figures of a stored-style record of a single run.
    pub fn from_record(case: &Case, r: &ReferenceRecord) -> CodeFigures {
        let law = case.law();
        CodeFigures {
            case: r.case.clone(),
            loss_coefficient: law.loss_coefficient,
            reduced_mass: law.mass,
            contact_stiffness: law.stiffness,
            exponent: law.exponent,
            metrics: r.figures,
            cor_target: r.cor_target(),
            paper_exact: r.paper_exact,
            steps: r.steps,
            timestep: r.timestep,
            wall_time: r.wall_time,
            loop_time: r.loop_time,
            whole_wall_time: r.whole_wall_time.unwrap_or(f64::NAN),
            own_law_cor: r.law_exact.cor,
            own_law_stepped_cor: r.law_at_step.cor,
            code_version: r.code_version.clone(),
            batch: 1,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The figures a sweep builds from a solution are those of the run's report.
    #[test]
    fn figures_of_a_solution_are_those_of_its_report() {
        use crate::analysis::run::{IntegrationOptions, run_case};
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/ball_plate.toml");
        let base = Case::load(&path).unwrap();
        for method in [Method::Rk4Event, Method::Dopri5, Method::Rk4, Method::Exact] {
            for eta in [0.0, 0.35, 0.9999] {
                let case = base.with_loss_coefficient(eta);
                let options = IntegrationOptions {
                    method,
                    ..IntegrationOptions::default()
                };
                let (report, outcome) =
                    run_case(&case, &options.settings(&case, false).unwrap()).unwrap();
                assert_eq!(
                    PointFigures::of_solution(
                        &case.name,
                        &case.law(),
                        case.impact_velocity,
                        &outcome
                    ),
                    PointFigures::of_method(&report)
                );
            }
        }
    }

    #[test]
    fn the_header_follows_the_fields() {
        let c = columns(&["ball.radius".to_string()]);
        assert_eq!(&c[..3], ["sweep", "point", "ball.radius"]);
        assert_eq!(
            &c[3..8],
            [
                "method",
                "code",
                "steps_per_period",
                "steps_per_contact",
                "rtol"
            ]
        );
        assert_eq!(c.last().map(String::as_str), Some("status"));
        assert!(c.contains(&"own_law_stepped_cor".to_string()));
    }
}
