//! Sweep files: a base case and grid axes over any case key, over methods and codes and over
//! their step resolutions. Each point's case is the base case's TOML table edited at the
//! point's keys and read by the strict case reader, so an invalid point fails with the same
//! one-line error as a case file, in its row. Rows are flat: the point's parameters, every
//! figure `run` and `reference` report, and a status (`ok` or the error).
//!
//! ```toml
//! base = "../cases/ball_plate.toml"      # or an inline [base] table holding a case
//! [axes]
//! loss_coefficient = { start = 0.0, stop = 0.9, count = 10 }
//! "ball.radius" = [0.01, 0.02]
//! method = ["rk4-event"]
//! steps_per_period = [400]
//! code = ["lammps"]
//! steps_per_contact = [200]
//! ```
//!
//! Instead of a method and its resolution, a file may ask for an accuracy: `tolerance = 1e-10`
//! (a relative COR error) chooses the cheapest method and resolution known to meet it
//! ([`crate::analysis::precision::choice`]).

use std::path::{Path, PathBuf};

use sha2::{Digest, Sha256};
use toml::{Table, Value};

use super::error::SweepError;
use super::row::{AxisValue, PointFigures, PointSource, RowIdentity, RowStatus, SweepRow};
use crate::analysis::precision::choice::{Choice, allowed_tolerances, choose, resolution_text};
use crate::analysis::run::MIN_RTOL;
pub(crate) use crate::analysis::source::{Resolution, Source};
use crate::analysis::store::hex;
use crate::codes::CodeName;
use crate::error::Chain;
use crate::model::case::{Case, CaseError, IN_PLACE_KEYS};
use crate::solve::{Knob, Method};

/// Most points a sweep file may name.
pub(crate) const MAX_POINTS: usize = 10_000_000;

/// The keys a sweep file may have at top level.
const SWEEP_KEYS: [&str; 3] = ["base", "axes", "tolerance"];
/// Axes that choose sources and resolutions rather than case keys.
const SOURCE_AXES: [&str; 5] = [
    "method",
    "code",
    "steps_per_period",
    "rtol",
    "steps_per_contact",
];

/// One grid axis over a case key.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    /// The dotted case key.
    pub key: String,
    /// Its values.
    pub values: AxisValues,
}

/// The values of an axis: as listed, or evenly spaced and made on demand (a range of 10^6
/// values takes no memory).
#[derive(Clone, Debug, PartialEq)]
pub enum AxisValues {
    /// The values listed.
    List(Vec<Value>),
    /// `start + i × step` for `i` below `count`, the last one `last` when given (the stop of
    /// a `{ start, stop, count }` range, exactly).
    Spaced {
        /// The first value.
        start: f64,
        /// The spacing.
        step: f64,
        /// How many.
        count: usize,
        /// The last value, if it is not `start + (count - 1) × step`.
        last: Option<f64>,
    },
}

impl AxisValues {
    /// How many values.
    pub(crate) fn len(&self) -> usize {
        match self {
            AxisValues::List(v) => v.len(),
            AxisValues::Spaced { count, .. } => *count,
        }
    }

    /// Whether there are none (an axis always has one).
    pub(crate) fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Every value, in order.
    pub(crate) fn iter(&self) -> impl Iterator<Item = Value> + '_ {
        (0..self.len()).map(|i| self.get(i))
    }

    /// Value `i`.
    pub(crate) fn get(&self, i: usize) -> Value {
        match self {
            AxisValues::List(v) => v[i].clone(),
            AxisValues::Spaced {
                start,
                step,
                count,
                last,
            } => match last {
                Some(last) if i + 1 == *count => Value::Float(*last),
                _ => Value::Float(start + i as f64 * step),
            },
        }
    }
}

/// A source with the resolution it runs at; `None` for its default (or a method without a
/// knob).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ResolvedSource {
    /// The method or code.
    pub source: Source,
    /// Its resolution.
    pub resolution: Option<Resolution>,
}

/// A parsed sweep file.
#[derive(Clone, Debug)]
pub struct SweepFile {
    /// Where it was read from.
    pub path: PathBuf,
    /// The base case table.
    pub base: Table,
    /// Name of the base case.
    pub base_name: String,
    /// Where the base case came from (its file, or the sweep file for an inline base).
    pub base_path: PathBuf,
    /// Axes over case keys, in key order.
    pub axes: Vec<Axis>,
    /// The sources, each with its resolution.
    pub sources: Vec<ResolvedSource>,
    /// Hash of the normalised sweep file and base case: shards of one sweep share it.
    pub fingerprint: String,
    /// The base case, read.
    pub base_case: Case,
    /// The method and resolution chosen for the file's `tolerance`, if it gives one.
    pub tolerance: Option<Choice>,
    /// Whether every case axis is a key the case is edited at in place
    /// (`IN_PLACE_KEYS`), so that a point's case need not be read anew.
    pub in_place: bool,
}

/// One point of the grid.
#[derive(Clone, Debug, PartialEq)]
pub struct GridPoint {
    /// Its index in the whole grid (row order of an unsharded sweep).
    pub index: usize,
    /// One value per case axis.
    pub values: Vec<Value>,
    /// Who computes it, at which resolution.
    pub source: ResolvedSource,
}

/// Whether `table` is a sweep file rather than a case.
pub(crate) fn is_sweep_table(table: &Table) -> bool {
    table.contains_key("axes") || table.contains_key("base")
}

/// Read a file as TOML (a sweep file, its base case, or a file to tell the two apart).
pub(crate) fn read_table(path: &Path) -> Result<Table, CaseError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| CaseError {
        file: file.clone(),
        key: "(file)".into(),
        value: "(unreadable)".into(),
        allowed: format!("cannot read it: {e}"),
    })?;
    text.parse().map_err(|e: toml::de::Error| CaseError {
        file,
        key: "(file)".into(),
        value: "(not TOML)".into(),
        allowed: format!("invalid TOML: {}", e.message().replace('\n', " ")),
    })
}

/// The base case of a sweep file: its table, its name and where it came from (its own file,
/// or the sweep file for an inline `[base]`).
fn read_base(
    path: &Path,
    base: Option<&Value>,
    fail: impl Fn(&str, &str, &str) -> CaseError,
) -> Result<(Table, String, PathBuf), CaseError> {
    let stem = |p: &Path| {
        p.file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "case".into())
    };
    match base {
        None => Err(fail(
            "base",
            "(missing)",
            "required: a case file path or a [base] table",
        )),
        Some(Value::String(s)) => {
            let base_path = path.parent().unwrap_or(Path::new("")).join(s);
            let base = read_table(&base_path).map_err(|e| {
                fail(
                    "base",
                    &format!("\"{s}\""),
                    &format!("a case file relative to the sweep file's folder: {e}"),
                )
            })?;
            let name = stem(&base_path);
            Ok((base, name, base_path))
        }
        Some(Value::Table(t)) => Ok((t.clone(), stem(path), path.to_path_buf())),
        Some(v) => Err(fail(
            "base",
            &v.to_string(),
            "must be a case file path or a [base] table",
        )),
    }
}

/// What a sweep file's source axes ask for: methods and codes, and the resolutions each kind
/// runs at (`None`: its default).
struct SourceAxes {
    methods: Vec<Method>,
    codes: Vec<CodeName>,
    per_period: Vec<Option<u32>>,
    per_contact: Vec<Option<u32>>,
    tolerances: Vec<Option<f64>>,
}

impl Default for SourceAxes {
    fn default() -> Self {
        SourceAxes {
            methods: Vec::new(),
            codes: Vec::new(),
            per_period: vec![None],
            per_contact: vec![None],
            tolerances: vec![None],
        }
    }
}

impl SourceAxes {
    /// Read the source axis `key` (one of [`SOURCE_AXES`]); `refuse(value, allowed)` makes its
    /// error.
    fn read(
        &mut self,
        key: &str,
        values: &AxisValues,
        refuse: impl Fn(&Value, &str) -> CaseError,
    ) -> Result<(), CaseError> {
        match key {
            "method" => {
                for v in values.iter() {
                    let method = Method::from_name(v.as_str().unwrap_or_default());
                    self.methods.push(method.ok_or_else(|| {
                        refuse(
                            &v,
                            &format!("a method name; allowed: {}", Method::names().join(", ")),
                        )
                    })?);
                }
            }
            "code" => {
                for v in values.iter() {
                    let code = CodeName::from_name(v.as_str().unwrap_or_default());
                    self.codes.push(code.ok_or_else(|| {
                        refuse(
                            &v,
                            &format!("a code name; allowed: {}", CodeName::names().join(", ")),
                        )
                    })?);
                }
            }
            "rtol" => {
                self.tolerances = values
                    .iter()
                    .map(|v| match v.as_float() {
                        Some(r) if (MIN_RTOL..1.0).contains(&r) => Ok(Some(r)),
                        _ => Err(refuse(
                            &v,
                            &format!("numbers in [{MIN_RTOL:e}, 1) (adaptive methods)"),
                        )),
                    })
                    .collect::<Result<_, _>>()?;
            }
            _ => {
                let counts = values
                    .iter()
                    .map(|v| match v.as_integer() {
                        Some(n) if (4..=100_000_000).contains(&n) => Ok(u32::try_from(n).ok()),
                        _ => Err(refuse(&v, "whole numbers in [4, 100000000]")),
                    })
                    .collect::<Result<_, _>>()?;
                if key == "steps_per_period" {
                    self.per_period = counts;
                } else {
                    self.per_contact = counts;
                }
            }
        }
        Ok(())
    }

    /// The method and resolution chosen for the file's `tolerance` (`value`), which may not
    /// come with an explicit method or resolution axis.
    fn choose_for_tolerance(
        &mut self,
        value: &Value,
        axes_table: &Table,
        refuse: impl Fn(&str) -> CaseError,
    ) -> Result<Choice, CaseError> {
        let explicit: Vec<&str> = ["method", "steps_per_period", "rtol"]
            .into_iter()
            .filter(|k| axes_table.contains_key(*k))
            .collect();
        if !explicit.is_empty() {
            return Err(refuse(&format!(
                "not with axes.{}: the tolerance chooses the method and its resolution",
                explicit.join(" or axes.")
            )));
        }
        let Some(x) = value.as_float() else {
            return Err(refuse(&allowed_tolerances()));
        };
        let choice = choose(x).map_err(|e| refuse(&e.allowed))?;
        self.methods.push(choice.method);
        match choice.resolution {
            Resolution::StepsPerPeriod(n) => self.per_period = vec![Some(n)],
            Resolution::Rtol(r) => self.tolerances = vec![Some(r)],
            Resolution::StepsPerContact(_) => {}
        }
        Ok(choice)
    }

    /// Every source with each of its resolutions, methods first (`rk4-event` when the file
    /// names neither a method nor a code); a resolution axis that no source takes is refused.
    fn sources(
        mut self,
        axes_table: &Table,
        fail: impl Fn(&str, &str, &str) -> CaseError,
    ) -> Result<Vec<ResolvedSource>, CaseError> {
        if self.methods.is_empty() && self.codes.is_empty() {
            self.methods.push(Method::Rk4Event);
        }
        let takes = |knob: Knob| self.methods.iter().any(|m| m.descriptor().knob == knob);
        let unused = [
            (
                self.per_period[0].is_some() && !takes(Knob::StepsPerPeriod),
                "steps_per_period",
                "applies to fixed-step methods; the sweep has none",
            ),
            (
                self.tolerances[0].is_some() && !takes(Knob::Rtol),
                "rtol",
                "applies to adaptive methods; the sweep has none",
            ),
            (
                self.per_contact[0].is_some() && self.codes.is_empty(),
                "steps_per_contact",
                "applies to codes; the sweep has none",
            ),
        ];
        if let Some((_, key, allowed)) = unused.iter().find(|(unused, ..)| *unused) {
            return Err(fail(
                &format!("axes.{key}"),
                &axes_table[*key].to_string(),
                allowed,
            ));
        }
        let mut sources = Vec::new();
        for &method in &self.methods {
            let resolutions: Vec<Option<Resolution>> = match method.descriptor().knob {
                Knob::StepsPerPeriod => self
                    .per_period
                    .iter()
                    .map(|n| n.map(Resolution::StepsPerPeriod))
                    .collect(),
                Knob::Rtol => self
                    .tolerances
                    .iter()
                    .map(|r| r.map(Resolution::Rtol))
                    .collect(),
                Knob::None => vec![None],
            };
            sources.extend(resolutions.into_iter().map(|resolution| ResolvedSource {
                source: Source::Method(method),
                resolution,
            }));
        }
        for &code in &self.codes {
            sources.extend(self.per_contact.iter().map(|n| ResolvedSource {
                source: Source::Code(code),
                resolution: n.map(Resolution::StepsPerContact),
            }));
        }
        Ok(sources)
    }
}

/// A sweep's fingerprint: its axes and base in normal form (keys sorted, values in TOML's own
/// notation), so that formatting and comments do not change it, and the tolerance's choice
/// (rows of another choice, with other bounds, belong to another sweep).
fn fingerprint(axes_table: Table, base: &Table, tolerance: Option<&Choice>) -> String {
    let mut normal = Table::new();
    normal.insert("axes".into(), Value::Table(axes_table));
    normal.insert("base".into(), Value::Table(base.clone()));
    if let Some(choice) = tolerance {
        normal.insert("tolerance".into(), Value::Float(choice.tolerance));
        normal.insert(
            "tolerance_choice".into(),
            Value::String(format!(
                "{} at {}",
                choice.method,
                resolution_text(choice.resolution)
            )),
        );
    }
    let text = toml::to_string(&normal).unwrap_or_default();
    hex(&Sha256::digest(text.as_bytes()))[..16].to_string()
}

/// A number as written in a row: the shortest form that reads back exactly, plain for
/// moderate magnitudes and with an exponent otherwise.
pub(crate) fn number(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 || (1e-4..1e15).contains(&a) || !x.is_finite() {
        x.to_string()
    } else {
        format!("{x:e}")
    }
}

/// The normal form of a parameter cell for matching rows: a number by its value.
pub(crate) fn normal_cell(text: &str) -> String {
    match text.parse::<f64>() {
        Ok(x) if x.is_finite() => number(x),
        _ => text.to_string(),
    }
}

impl SweepFile {
    /// Read and validate a sweep file. Errors are one line naming the file, the key, the
    /// value and what is allowed.
    pub fn load(path: &Path) -> Result<SweepFile, CaseError> {
        let table = read_table(path)?;
        Self::from_table(path, &table)
    }

    /// Validate a parsed sweep file.
    pub(crate) fn from_table(path: &Path, table: &Table) -> Result<SweepFile, CaseError> {
        let file = path.display().to_string();
        let fail =
            |key: &str, value: &str, allowed: &str| CaseError::new(&file, key, value, allowed);
        if let Some((key, value)) = table
            .iter()
            .find(|(k, _)| !SWEEP_KEYS.contains(&k.as_str()))
        {
            return Err(fail(
                key,
                &value.to_string(),
                "unknown key; a sweep file takes base (a case file or table), [axes] and tolerance",
            ));
        }
        let (base, base_name, base_path) = read_base(path, table.get("base"), fail)?;
        // The base must itself be a valid case.
        let base_case = Case::from_table(
            &base,
            &base_path.display().to_string(),
            &base_name,
            &base_path,
        )?;
        let axes_table = match table.get("axes") {
            None => Table::new(),
            Some(Value::Table(t)) => t.clone(),
            Some(v) => {
                return Err(fail(
                    "axes",
                    &v.to_string(),
                    "must be a table of key = [values]",
                ));
            }
        };
        let mut axes = Vec::new();
        let mut source_axes = SourceAxes::default();
        let case_keys = crate::model::case::case_keys();
        for (key, value) in &axes_table {
            let full = format!("axes.{key}");
            let refuse = |allowed: &str| fail(&full, &value.to_string(), allowed);
            let values = axis_values(value, refuse)?;
            if values.is_empty() {
                return Err(refuse("an axis needs at least one value"));
            }
            if SOURCE_AXES.contains(&key.as_str()) {
                source_axes.read(key, &values, |v, allowed| {
                    fail(&full, &v.to_string(), allowed)
                })?;
            } else if case_keys.iter().any(|c| c == key) {
                axes.push(Axis {
                    key: key.clone(),
                    values,
                });
            } else {
                let mut allowed: Vec<&str> = case_keys.iter().map(String::as_str).collect();
                allowed.extend(SOURCE_AXES);
                return Err(refuse(&format!(
                    "unknown axis; allowed: {}",
                    allowed.join(", ")
                )));
            }
        }
        let tolerance = match table.get("tolerance") {
            None => None,
            Some(value) => Some(source_axes.choose_for_tolerance(
                value,
                &axes_table,
                |allowed| fail("tolerance", &value.to_string(), allowed),
            )?),
        };
        let sources = source_axes.sources(&axes_table, fail)?;
        let total = axes
            .iter()
            .try_fold(sources.len(), |n, a| n.checked_mul(a.values.len()));
        if total.is_none_or(|n| n > MAX_POINTS) {
            return Err(fail(
                "axes",
                "(grid)",
                &format!("at most {MAX_POINTS} points"),
            ));
        }
        let in_place = axes.iter().all(|a| IN_PLACE_KEYS.contains(&a.key.as_str()));
        Ok(SweepFile {
            path: path.to_path_buf(),
            fingerprint: fingerprint(axes_table, &base, tolerance.as_ref()),
            base,
            base_name,
            base_path,
            axes,
            sources,
            base_case,
            in_place,
            tolerance,
        })
    }

    /// The grid of a case file (`case`, read from its `base` table) over one case axis, run
    /// by one source: `sweep CASE --loss-coefficient`. Its fingerprint is of the base, the
    /// axis and the source.
    pub(crate) fn of_case(
        case: Case,
        base: Table,
        axis: Axis,
        source: ResolvedSource,
    ) -> SweepFile {
        let mut axes_table = Table::new();
        let values = match &axis.values {
            AxisValues::List(values) => Value::Array(values.clone()),
            AxisValues::Spaced { start, count, .. } => Value::Table(Table::from_iter([
                ("start".to_string(), Value::Float(*start)),
                ("stop".to_string(), axis.values.get(count - 1)),
                (
                    "count".to_string(),
                    Value::Integer(i64::try_from(*count).unwrap_or(i64::MAX)),
                ),
            ])),
        };
        axes_table.insert(axis.key.clone(), values);
        // Who computes the points, by the columns of their rows.
        let source_columns = PointSource::new(source.source, source.resolution);
        if let Ok(columns) = Value::try_from(source_columns) {
            axes_table.insert("source".to_string(), columns);
        }
        SweepFile {
            path: case.path.clone(),
            fingerprint: fingerprint(axes_table, &base, None),
            base,
            base_name: case.name.clone(),
            base_path: case.path.clone(),
            in_place: IN_PLACE_KEYS.contains(&axis.key.as_str()),
            axes: vec![axis],
            sources: vec![source],
            base_case: case,
            tolerance: None,
        }
    }

    /// How many points the grid has.
    pub(crate) fn len(&self) -> usize {
        self.axes.iter().map(|a| a.values.len()).product::<usize>() * self.sources.len()
    }

    /// Whether the grid is empty (it never is: every axis has a value).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// GridPoint `index` (the last axis varies fastest, the source fastest of all).
    pub fn point(&self, index: usize) -> GridPoint {
        let mut point = GridPoint {
            index,
            values: Vec::with_capacity(self.axes.len()),
            source: self.sources[0],
        };
        self.point_into(index, &mut point);
        point
    }

    /// Make `point` point `index`, its storage reused (points one after another, as a chunk
    /// of a sweep runs them).
    pub(crate) fn point_into(&self, index: usize, point: &mut GridPoint) {
        let mut rest = index;
        point.index = index;
        point.source = self.sources[rest % self.sources.len()];
        rest /= self.sources.len();
        point.values.resize(self.axes.len(), Value::Boolean(false));
        for (value, axis) in point.values.iter_mut().zip(&self.axes).rev() {
            *value = axis.values.get(rest % axis.values.len());
            rest /= axis.values.len();
        }
    }

    /// The points of shard `k` of `n` (1-based; every n-th point from the k-th), or all.
    pub fn points(&self, shard: Option<(usize, usize)>) -> Vec<GridPoint> {
        let indices = self.indices(shard);
        indices.into_iter().map(|i| self.point(i)).collect()
    }

    /// The indices of the points of shard `k` of `n` (1-based; every n-th point from the
    /// k-th), or of all.
    pub fn indices(&self, shard: Option<(usize, usize)>) -> Vec<usize> {
        let (k, n) = shard.unwrap_or((1, 1));
        (k - 1..self.len()).step_by(n).collect()
    }

    /// The keys of the case axes, in axis order.
    pub(crate) fn axis_keys(&self) -> Vec<String> {
        self.axes.iter().map(|a| a.key.clone()).collect()
    }

    /// The columns of a row.
    pub fn columns(&self) -> Vec<String> {
        super::row::columns(&self.axis_keys())
    }

    /// The names of the parameter columns (what a row is matched by on resume).
    pub(crate) fn key_columns(&self) -> Vec<String> {
        super::row::key_columns(&self.axis_keys())
    }

    /// The row of `point` with `figures` and `status`.
    pub(crate) fn row(
        &self,
        point: &GridPoint,
        figures: PointFigures,
        status: RowStatus,
    ) -> SweepRow {
        let mut row = SweepRow {
            identity: RowIdentity::default(),
            axes: Vec::with_capacity(self.axes.len()),
            source: PointSource::default(),
            figures,
            status,
        };
        self.set_point(&mut row, point);
        row
    }

    /// Make `row` the row of `point` (its identity, axis values and source), its storage
    /// reused: a row of this sweep's is made once per chunk and filled point after point.
    /// The figures and status are left to the caller.
    pub(crate) fn set_point(&self, row: &mut SweepRow, point: &GridPoint) {
        if row.identity.sweep != self.fingerprint {
            row.identity.sweep.clone_from(&self.fingerprint);
        }
        row.identity.point = point.index;
        row.axes.truncate(self.axes.len());
        for (i, (axis, value)) in self.axes.iter().zip(&point.values).enumerate() {
            match row.axes.get_mut(i) {
                Some(a) => {
                    if a.key != axis.key {
                        a.key.clone_from(&axis.key);
                    }
                    a.value.clone_from(value);
                }
                None => row.axes.push(AxisValue {
                    key: axis.key.clone(),
                    value: value.clone(),
                }),
            }
        }
        row.source = PointSource::new(point.source.source, point.source.resolution);
    }

    /// The row of `point` from its outcome: the figures, or the error.
    pub(crate) fn outcome_row(
        &self,
        point: &GridPoint,
        outcome: Result<PointFigures, SweepError>,
    ) -> SweepRow {
        match outcome {
            Ok(figures) => self.row(point, figures, RowStatus::ok()),
            Err(e) => self.row(
                point,
                PointFigures::default(),
                RowStatus::failed(&Chain(&e).to_string()),
            ),
        }
    }

    /// The parameter cells of `point`, in `SweepFile::key_columns` order, in the normal
    /// form rows are matched by.
    #[cfg(test)]
    pub(crate) fn key_cells(&self, point: &GridPoint) -> Vec<String> {
        let row = self.row(point, PointFigures::default(), RowStatus::default());
        super::row::key_cells(&row.axes, &row.source)
            .iter()
            .map(|c| normal_cell(c))
            .collect()
    }

    /// The case at `point`: the base table edited and read strictly.
    pub fn case(&self, point: &GridPoint) -> Result<Case, CaseError> {
        let mut table = self.base.clone();
        for (axis, value) in self.axes.iter().zip(&point.values) {
            let (holder, key) = match axis.key.split_once('.') {
                Some((t, k)) => {
                    let entry = table
                        .entry(t.to_string())
                        .or_insert_with(|| Value::Table(Table::new()));
                    match entry {
                        Value::Table(inner) => (inner, k),
                        _ => {
                            return Err(CaseError {
                                file: self.path.display().to_string(),
                                key: t.to_string(),
                                value: entry.to_string(),
                                allowed: "must be a table".into(),
                            });
                        }
                    }
                }
                None => (&mut table, axis.key.as_str()),
            };
            // η and e name one number: setting one replaces the other.
            match key {
                "loss_coefficient" => {
                    holder.remove("restitution");
                }
                "restitution" => {
                    holder.remove("loss_coefficient");
                }
                _ => {}
            }
            holder.insert(key.to_string(), value.clone());
        }
        Case::from_table(
            &table,
            &self.point_file(point),
            &self.base_name,
            &self.base_path,
        )
    }

    /// How errors name the case of `point`.
    pub(crate) fn point_file(&self, point: &GridPoint) -> String {
        format!("{} (point {})", self.path.display(), point.index)
    }
}

/// The cases of a sweep's points, one after another: each made from the last by editing it in
/// place when every axis allows ([`SweepFile::in_place`]), else read anew from the base's
/// table; the same case and the same errors either way.
pub(crate) struct PointCases<'a> {
    sweep: &'a SweepFile,
    case: Case,
}

impl<'a> PointCases<'a> {
    /// Cases of `sweep`'s points.
    pub(crate) fn new(sweep: &'a SweepFile) -> PointCases<'a> {
        PointCases {
            sweep,
            case: sweep.base_case.clone(),
        }
    }

    /// The case at `point`.
    pub fn case(&mut self, point: &GridPoint) -> Result<&Case, CaseError> {
        if !self.sweep.in_place {
            self.case = self.sweep.case(point)?;
            return Ok(&self.case);
        }
        let mut edits: [(&str, &Value); IN_PLACE_KEYS.len()] =
            [("", &Value::Boolean(false)); IN_PLACE_KEYS.len()];
        let count = self.sweep.axes.len();
        for ((edit, axis), value) in edits.iter_mut().zip(&self.sweep.axes).zip(&point.values) {
            *edit = (axis.key.as_str(), value);
        }
        // The file's name is formatted only for an error.
        self.case.apply(&edits[..count], "").map_err(|mut e| {
            e.file = self.sweep.point_file(point);
            e
        })?;
        Ok(&self.case)
    }
}

/// The values from `start` to `stop` (included, within 1e-9 of a step) `step` apart, for
/// finite `start <= stop` and `step > 0`; `None` beyond [`MAX_POINTS`] values.
pub(crate) fn stepped(start: f64, stop: f64, step: f64) -> Option<AxisValues> {
    // The count is checked as a float before it becomes an integer: a tiny step must be
    // refused, not wrap.
    let count = ((stop - start) / step + 1e-9).floor() + 1.0;
    let count = (count <= MAX_POINTS as f64)
        .then(|| crate::model::count::ceil_count(count))
        .flatten()
        .and_then(|n| usize::try_from(n).ok())?;
    Some(AxisValues::Spaced {
        start,
        step,
        count,
        last: None,
    })
}

/// The values of one axis: a list, or `{ start, stop, step }` (stop included) or
/// `{ start, stop, count }` (evenly spaced, both ends included).
fn axis_values(value: &Value, refuse: impl Fn(&str) -> CaseError) -> Result<AxisValues, CaseError> {
    let allowed =
        "a list of values, or { start, stop, step } or { start, stop, count } with start <= stop";
    match value {
        Value::Array(items) => {
            for item in items {
                if matches!(item, Value::Array(_) | Value::Table(_) | Value::Datetime(_)) {
                    return Err(refuse(&format!(
                        "{allowed}; values must be numbers, strings or booleans"
                    )));
                }
            }
            Ok(AxisValues::List(items.clone()))
        }
        Value::Table(t) => {
            for key in t.keys() {
                if !["start", "stop", "step", "count"].contains(&key.as_str()) {
                    return Err(refuse(allowed));
                }
            }
            let num = |k: &str| {
                t.get(k)
                    .and_then(|v| v.as_float().or(v.as_integer().map(|i| i as f64)))
            };
            let (Some(start), Some(stop)) = (num("start"), num("stop")) else {
                return Err(refuse(allowed));
            };
            if !(start.is_finite() && stop.is_finite() && start <= stop) {
                return Err(refuse(allowed));
            }
            match (num("step"), t.get("count").and_then(Value::as_integer)) {
                (Some(step), None) => {
                    if !(step.is_finite() && step > 0.0) {
                        return Err(refuse(allowed));
                    }
                    stepped(start, stop, step)
                        .ok_or_else(|| refuse(&format!("at most {MAX_POINTS} values")))
                }
                (None, Some(count)) => {
                    #[allow(clippy::float_cmp)] // one point names one value: the same number twice
                    let single_apart = count == 1 && start != stop;
                    let most = i64::try_from(MAX_POINTS).unwrap_or(i64::MAX);
                    if !(1..=most).contains(&count) || single_apart {
                        return Err(refuse(&format!(
                            "count in [1, {MAX_POINTS}] (1 only when start = stop)"
                        )));
                    }
                    if count == 1 {
                        return Ok(AxisValues::List(vec![Value::Float(start)]));
                    }
                    let count = usize::try_from(count)
                        .map_err(|_| refuse(&format!("at most {MAX_POINTS} values")))?;
                    Ok(AxisValues::Spaced {
                        start,
                        step: (stop - start) / (count - 1) as f64,
                        count,
                        last: Some(stop),
                    })
                }
                _ => Err(refuse(&format!("{allowed}: exactly one of step and count"))),
            }
        }
        _ => Err(refuse(allowed)),
    }
}
