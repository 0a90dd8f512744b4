//! What a run reports, and the text forms it is printed in (table, JSON, CSV, Markdown).
//! Field names are a contract with the tools that read them: extend, do not rename.

use std::io::Write;
use std::path::Path;

use comfy_table::{Table, presets::UTF8_FULL_CONDENSED};
use serde::Serialize;

use crate::case::Case;
use crate::exact::{self, HertzElastic, ImpactFigures};
use crate::solve::paper::{Outcome, Sample};
use crate::solve::{Method, Stats};

/// Output format of a command.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// An aligned table for people.
    Table,
    /// One JSON document.
    Json,
    /// CSV with a header row.
    Csv,
    /// A Markdown table.
    Markdown,
}

/// The closed-form figures a run is compared with.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ExactFigures {
    /// COR.
    pub cor: f64,
    /// Peak deformation, m.
    pub peak_deformation: f64,
    /// Peak force, N.
    pub peak_force: f64,
    /// Contact time, s.
    pub contact_time: f64,
    /// Absorbed energy, J.
    pub absorbed_energy: f64,
}

/// Relative errors `(run - exact) / exact`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RelativeErrors {
    /// Of the COR.
    pub cor: f64,
    /// Of the peak deformation.
    pub peak_deformation: f64,
    /// Of the contact time.
    pub contact_time: f64,
}

/// One impact by one method: everything `millimpact run` prints.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunReport {
    /// Case name.
    pub case: String,
    /// Scene name.
    pub scene: &'static str,
    /// Method name.
    pub method: &'static str,
    /// Unilateral or bilateral.
    pub contact: &'static str,
    /// Loss coefficient η.
    pub loss_coefficient: f64,
    /// Impact speed, m/s.
    pub impact_velocity: f64,
    /// Reduced mass, kg.
    pub mass: f64,
    /// Contact stiffness C, N/m^n.
    pub stiffness: f64,
    /// How C was computed for a ball scene: "hertz" (`(4/3) E* sqrt(R*)`) or "paper" (the
    /// paper's printed `a E sqrt(R) / (1 - ν²)`); "rod" for the rod's `π D² E / (4H)`.
    pub stiffness_convention: &'static str,
    /// Exponent n.
    pub exponent: f64,
    /// COR.
    pub cor: f64,
    /// Peak deformation, m.
    pub peak_deformation: f64,
    /// Peak force, N.
    pub peak_force: f64,
    /// Contact time, s.
    pub contact_time: f64,
    /// Compression part of the contact time, s.
    pub compression_time: f64,
    /// Restitution part of the contact time, s.
    pub restitution_time: f64,
    /// Absorbed energy, J.
    pub absorbed_energy: f64,
    /// Accepted steps.
    pub steps: u64,
    /// Right-hand-side evaluations.
    pub rhs_evaluations: u64,
    /// Wall time of the integration, s.
    pub wall_time: f64,
    /// Fixed step, s (fixed-step methods).
    pub timestep: Option<f64>,
    /// Closed forms.
    pub exact: ExactFigures,
    /// Relative errors against the closed forms.
    pub error: RelativeErrors,
    /// Elastic Hertz figures (ball scenes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hertz_elastic: Option<HertzElastic>,
    /// Bilateral contact: speed at each passage through zero approach, m/s.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub crossing_speeds: Vec<f64>,
}

fn relative(value: f64, reference: f64) -> f64 {
    (value - reference) / reference
}

impl RunReport {
    /// Assemble the report of `outcome` for `case` by `method`.
    pub fn new(case: &Case, method: Method, outcome: &Outcome) -> RunReport {
        let law = case.law();
        let exact: ImpactFigures = exact::paper_impact(&law, case.impact_velocity);
        let f = &outcome.figures;
        let hertz_elastic = match (
            case.scene.effective_modulus(),
            case.scene.effective_radius(),
        ) {
            (Some(e), Some(r)) => Some(exact::hertz_elastic(law.mass, e, r, case.impact_velocity)),
            _ => None,
        };
        let Stats {
            steps,
            rhs_evaluations,
            ..
        } = outcome.stats;
        RunReport {
            case: case.name.clone(),
            scene: case.scene.kind().name(),
            method: method.name(),
            contact: match case.contact {
                crate::solve::paper::ContactKind::Unilateral => "unilateral",
                crate::solve::paper::ContactKind::Bilateral => "bilateral",
            },
            loss_coefficient: law.loss_coefficient,
            impact_velocity: case.impact_velocity,
            mass: law.mass,
            stiffness: law.stiffness,
            stiffness_convention: match (case.scene.kind(), case.stiffness) {
                (crate::scene::SceneKind::RodEnd, _) => "rod",
                (_, crate::scene::StiffnessConvention::Hertz) => "hertz",
                (_, crate::scene::StiffnessConvention::Paper) => "paper",
            },
            exponent: law.exponent,
            cor: f.cor,
            peak_deformation: f.peak_deformation,
            peak_force: f.peak_force,
            contact_time: f.contact_time,
            compression_time: f.compression_time,
            restitution_time: f.restitution_time,
            absorbed_energy: f.absorbed_energy,
            steps,
            rhs_evaluations,
            wall_time: outcome.wall_time,
            timestep: outcome.timestep,
            exact: ExactFigures {
                cor: exact.cor,
                peak_deformation: exact.peak_deformation,
                peak_force: exact.peak_force,
                contact_time: exact.contact_time,
                absorbed_energy: exact.absorbed_energy,
            },
            error: RelativeErrors {
                cor: relative(f.cor, exact.cor),
                peak_deformation: relative(f.peak_deformation, exact.peak_deformation),
                contact_time: relative(f.contact_time, exact.contact_time),
            },
            hertz_elastic,
            crossing_speeds: outcome.crossing_speeds.clone(),
        }
    }

    /// The flat row of a sweep (one line of CSV).
    pub fn row(&self) -> SweepRow {
        SweepRow {
            case: self.case.clone(),
            method: self.method,
            loss_coefficient: self.loss_coefficient,
            cor: self.cor,
            cor_exact: self.exact.cor,
            cor_error: self.error.cor,
            peak_deformation: self.peak_deformation,
            peak_deformation_exact: self.exact.peak_deformation,
            peak_deformation_error: self.error.peak_deformation,
            peak_force: self.peak_force,
            contact_time: self.contact_time,
            contact_time_exact: self.exact.contact_time,
            contact_time_error: self.error.contact_time,
            compression_time: self.compression_time,
            restitution_time: self.restitution_time,
            absorbed_energy: self.absorbed_energy,
            steps: self.steps,
            rhs_evaluations: self.rhs_evaluations,
            wall_time: self.wall_time,
        }
    }

    /// The human table.
    pub fn table(&self) -> String {
        let mut t = new_table(&["figure", "run", "exact", "relative error"]);
        let rows: [(&str, f64, f64, Option<f64>); 6] = [
            ("COR", self.cor, self.exact.cor, Some(self.error.cor)),
            (
                "peak deformation (m)",
                self.peak_deformation,
                self.exact.peak_deformation,
                Some(self.error.peak_deformation),
            ),
            (
                "peak force (N)",
                self.peak_force,
                self.exact.peak_force,
                Some(relative(self.peak_force, self.exact.peak_force)),
            ),
            (
                "contact time (s)",
                self.contact_time,
                self.exact.contact_time,
                Some(self.error.contact_time),
            ),
            (
                "absorbed energy (J)",
                self.absorbed_energy,
                self.exact.absorbed_energy,
                None,
            ),
            (
                "compression time (s)",
                self.compression_time,
                f64::NAN,
                None,
            ),
        ];
        for (name, run, exact, error) in rows {
            t.add_row(vec![
                name.to_string(),
                sci(run),
                if exact.is_nan() {
                    "".into()
                } else {
                    sci(exact)
                },
                error.map(|e| format!("{e:+.2e}")).unwrap_or_default(),
            ]);
        }
        let mut text = format!(
            "{} ({}, {}): method {}, η = {}, M = {} kg, C = {}, n = {}\n{t}\n",
            self.case,
            self.scene,
            self.contact,
            self.method,
            self.loss_coefficient,
            sci(self.mass),
            sci(self.stiffness),
            self.exponent
        );
        text += &format!(
            "steps {}, rhs evaluations {}, wall time {}",
            self.steps,
            self.rhs_evaluations,
            seconds(self.wall_time)
        );
        if let Some(dt) = self.timestep {
            text += &format!(", Δt = {} s", sci(dt));
        }
        text.push('\n');
        if self.stiffness_convention == "paper" {
            text += "stiffness: the paper's printed coefficient a E sqrt(R) / (1 - ν²), not Hertz's (4/3) E* sqrt(R*)\n";
        }
        if let Some(h) = &self.hertz_elastic {
            text += &format!(
                "elastic Hertz: peak deformation {} m, contact time {} s\n",
                sci(h.peak_deformation),
                sci(h.contact_time)
            );
        }
        if !self.crossing_speeds.is_empty() {
            let speeds: Vec<String> = self.crossing_speeds.iter().map(|s| sci(*s)).collect();
            text += &format!(
                "speeds through zero approach (m/s): {}\n",
                speeds.join(", ")
            );
        }
        text
    }
}

/// One row of `millimpact sweep`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SweepRow {
    /// Case name.
    pub case: String,
    /// Method.
    pub method: &'static str,
    /// η.
    pub loss_coefficient: f64,
    /// COR.
    pub cor: f64,
    /// Exact COR.
    pub cor_exact: f64,
    /// Relative error of the COR.
    pub cor_error: f64,
    /// Peak deformation, m.
    pub peak_deformation: f64,
    /// Exact peak deformation, m.
    pub peak_deformation_exact: f64,
    /// Relative error of the peak deformation.
    pub peak_deformation_error: f64,
    /// Peak force, N.
    pub peak_force: f64,
    /// Contact time, s.
    pub contact_time: f64,
    /// Exact contact time, s.
    pub contact_time_exact: f64,
    /// Relative error of the contact time.
    pub contact_time_error: f64,
    /// Compression time, s.
    pub compression_time: f64,
    /// Restitution time, s.
    pub restitution_time: f64,
    /// Absorbed energy, J.
    pub absorbed_energy: f64,
    /// Steps.
    pub steps: u64,
    /// RHS evaluations.
    pub rhs_evaluations: u64,
    /// Wall time, s.
    pub wall_time: f64,
}

/// A table in the crate's style.
pub fn new_table(headers: &[&str]) -> Table {
    let mut t = Table::new();
    t.load_style(UTF8_FULL_CONDENSED);
    t.set_header(headers.to_vec());
    t
}

/// A table in Markdown.
pub fn markdown_table(headers: &[&str], rows: &[Vec<String>]) -> String {
    let mut text = format!("| {} |\n", headers.join(" | "));
    text += &format!("|{}\n", "---|".repeat(headers.len()));
    for row in rows {
        text += &format!("| {} |\n", row.join(" | "));
    }
    text
}

/// Seven significant digits in scientific form.
pub fn sci(x: f64) -> String {
    if x.is_nan() {
        "n/a".to_string()
    } else {
        format!("{x:.6e}")
    }
}

/// A duration in convenient units.
pub fn seconds(s: f64) -> String {
    if s >= 1.0 {
        format!("{s:.3} s")
    } else if s >= 1e-3 {
        format!("{:.3} ms", s * 1e3)
    } else {
        format!("{:.2} µs", s * 1e6)
    }
}

/// Serialise rows as CSV with a header.
pub fn csv_string<T: Serialize>(rows: &[T]) -> anyhow::Result<String> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    for row in rows {
        writer.serialize(row)?;
    }
    Ok(String::from_utf8(writer.into_inner()?)?)
}

/// Write `bytes` to `path` atomically: a temporary file beside it, renamed into place.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    std::fs::create_dir_all(dir)?;
    let mut tmp = tempfile::NamedTempFile::new_in(dir)?;
    tmp.write_all(bytes)?;
    tmp.as_file().sync_all()?;
    // A temporary file is private (0600); a result is for everyone who may read the folder.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        tmp.as_file()
            .set_permissions(std::fs::Permissions::from_mode(0o644))?;
    }
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

/// One row of a trajectory file.
#[derive(Serialize)]
struct TrajectoryRow {
    t: f64,
    y: f64,
    #[serde(rename = "y_dot")]
    v: f64,
    elastic_force: f64,
    dissipative_force: f64,
    energy: f64,
}

/// The trajectory as CSV: time (s), approach (m), approach rate (m/s), elastic force (N),
/// dissipative force (N) and mechanical energy (J, kinetic plus elastic).
pub fn trajectory_csv(case: &Case, samples: &[Sample]) -> anyhow::Result<String> {
    let law = case.law();
    let bilateral = case.contact == crate::solve::paper::ContactKind::Bilateral;
    let rows: Vec<TrajectoryRow> = samples
        .iter()
        .map(|s| {
            let in_contact = s.y > 0.0 || (bilateral && s.y != 0.0);
            let elastic = if in_contact {
                law.stiffness * s.y.abs().powf(law.exponent) * s.y.signum()
            } else {
                0.0
            };
            let direction = (s.y * s.v).signum();
            // Out of contact there is no force at all (not a negative zero).
            let dissipative = if elastic == 0.0 {
                0.0
            } else {
                law.loss_coefficient * elastic * direction
            };
            let potential = if in_contact {
                law.stiffness * s.y.abs().powf(law.exponent + 1.0) / (law.exponent + 1.0)
            } else {
                0.0
            };
            TrajectoryRow {
                t: s.t,
                y: s.y,
                v: s.v,
                elastic_force: elastic,
                dissipative_force: dissipative,
                energy: 0.5 * law.mass * s.v * s.v + potential,
            }
        })
        .collect();
    csv_string(&rows)
}
