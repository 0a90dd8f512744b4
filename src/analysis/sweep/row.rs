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
use crate::model::figures::{Checked, Figures, quantity, suffix};
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

/// The quantities a row writes as measured: all but the force contact time (the same set as
/// [`quantity::EXACT`], here for what a source gave).
pub(crate) const WRITTEN: u8 = quantity::ALL & !quantity::FORCE_CONTACT_TIME;
/// The quantities a row compares with a reference: COR, peak deformation, peak force, contact
/// time (the peak force has a reference and no error column).
pub(crate) const COMPARED: u8 =
    quantity::COR | quantity::PEAK_DEFORMATION | quantity::PEAK_FORCE | quantity::CONTACT_TIME;
/// The compared quantities whose reference is the paper's law, exact (the COR's is a target).
pub(crate) const PAPER_EXACT: u8 = COMPARED & !quantity::COR;

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
    /// The figures the source gave: COR, peak deformation (m), peak force (N), contact time by
    /// overlap (s), its compression and restitution parts (s).
    #[serde(flatten)]
    pub measured: Figures<Option<f64>, WRITTEN>,
    /// The COR the source should realise (the closed form, or the code's target): `cor_target`.
    #[serde(flatten, serialize_with = "suffix::target")]
    pub target: Figures<Option<f64>, { quantity::COR }>,
    /// The paper's law, exact: `peak_deformation_exact`, `peak_force_exact`,
    /// `contact_time_exact`.
    #[serde(flatten, serialize_with = "suffix::exact")]
    pub exact: Figures<Option<f64>, PAPER_EXACT>,
    /// `(measured − reference) / reference`, the reference being the target COR and the exact
    /// figures: `cor_error`, `peak_deformation_error`, `contact_time_error`.
    #[serde(flatten, serialize_with = "suffix::error")]
    pub error: Checked<Option<f64>>,
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
    /// Set the figure columns: the `measured` figures, and the `reference` each compared one is
    /// written with and measured against (a NaN, and an error against one, stay empty).
    fn set_compared(
        &mut self,
        measured: &Figures<f64, WRITTEN>,
        reference: &Figures<f64, COMPARED>,
    ) {
        self.measured = measured.map(|_, &v| finite(v));
        self.target = reference
            .select::<{ quantity::COR }>()
            .map(|_, &v| finite(v));
        self.exact = reference.select::<PAPER_EXACT>().map(|_, &v| finite(v));
        self.error = Checked::from_fn(|q| relative(*measured.get(q), *reference.get(q)));
    }

    /// The figures of a method's run.
    pub(crate) fn of_method(r: &RunReport) -> PointFigures {
        let mut figures = PointFigures {
            case: Some(r.case.clone()),
            eta: finite(r.loss_coefficient),
            reduced_mass: finite(r.mass),
            contact_stiffness: finite(r.stiffness),
            exponent: finite(r.exponent),
            absorbed_energy: finite(r.absorbed_energy),
            steps: Some(r.steps),
            rhs_evaluations: Some(r.rhs_evaluations),
            timestep: r.timestep.and_then(finite),
            wall_time: finite(r.wall_time),
            ..PointFigures::default()
        };
        let measured = r.figures.select();
        let reference = r.exact.figures.select();
        figures.set_compared(&measured, &reference);
        figures
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
            absorbed_energy: finite(f.absorbed_energy),
            steps: Some(outcome.stats.steps),
            rhs_evaluations: Some(outcome.stats.rhs_evaluations),
            timestep: outcome.timestep.and_then(finite),
            wall_time: finite(outcome.wall_time),
            ..PointFigures::default()
        };
        self.set_compared(&f.select(), &exact.select());
    }

    /// The figures of a code's run (its compression and restitution times stay empty).
    pub(crate) fn of_code(f: &CodeFigures) -> PointFigures {
        let mut figures = PointFigures {
            case: Some(f.case.clone()),
            eta: finite(f.loss_coefficient),
            reduced_mass: finite(f.reduced_mass),
            contact_stiffness: finite(f.contact_stiffness),
            exponent: finite(f.exponent),
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
        };
        let mut measured = f.measured.select::<WRITTEN>();
        measured.compression_time = f64::NAN;
        measured.restitution_time = f64::NAN;
        figures.set_compared(&measured, &f.reference);
        figures
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

/// The cells of the first CSV record in `bytes`.
fn first_record(bytes: &[u8]) -> Vec<String> {
    csv::ReaderBuilder::new()
        .has_headers(false)
        .from_reader(bytes)
        .records()
        .next()
        .and_then(Result::ok)
        .map(|r| r.iter().map(String::from).collect())
        .unwrap_or_default()
}

/// The field names of a flat record type, in declaration order, as serde names them.
fn field_names<T: Serialize + Default>() -> Vec<String> {
    // Serialising a record of scalars into memory cannot fail.
    first_record(&crate::output::csv_record::header_of(&T::default()).unwrap_or_default())
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
#[cfg(test)]
pub(crate) fn key_cells(axes: &[AxisValue], source: &PointSource) -> Vec<String> {
    let mut records = CsvRecords::default();
    // Serialising scalars into memory cannot fail.
    let _ = records.push(&(AxisValues(axes), source));
    first_record(records.as_bytes())
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
    pub measured: Figures<f64, COMPARED>,
    /// What they are compared with: the COR the code should realise, the paper's law exact.
    pub reference: Figures<f64, COMPARED>,
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
    /// The reference of a code's figures: the COR `target`, the other figures of `paper_exact`.
    pub(crate) fn reference(target: f64, paper_exact: &ImpactFigures) -> Figures<f64, COMPARED> {
        Figures {
            cor: target,
            ..paper_exact.select()
        }
    }

    /// The compared figures of a code's trajectory.
    pub(crate) fn measured(m: &TrajectoryMetrics) -> Figures<f64, COMPARED> {
        Figures {
            cor: m.cor,
            peak_deformation: m.peak_deformation,
            peak_force: m.peak_force,
            contact_time: m.contact_time,
            ..Figures::default()
        }
    }

    /// The figures of a stored-style record of a single run.
    pub(crate) fn from_record(case: &Case, r: &ReferenceRecord) -> CodeFigures {
        let law = case.law();
        CodeFigures {
            case: r.case.clone(),
            loss_coefficient: law.loss_coefficient,
            reduced_mass: law.mass,
            contact_stiffness: law.stiffness,
            exponent: law.exponent,
            measured: r.figures.select(),
            reference: CodeFigures::reference(r.cor_target(), &r.paper_exact),
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
                let row = PointFigures::of_method(&report);
                assert_eq!(
                    PointFigures::of_solution(
                        &case.name,
                        &case.law(),
                        case.impact_velocity,
                        &outcome
                    ),
                    row
                );
                // The errors a row writes are the report's own.
                let e = &report.error;
                assert_eq!(row.error, e.map(|_, &v| finite(v)));
                assert_eq!(row.target.cor, finite(report.exact.figures.cor));
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
