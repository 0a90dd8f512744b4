//! millimpact: a validation harness for the contact law of grinding bodies (dissipative force
//! = η × gradient of the elastic energy), against exact closed forms and the DEM codes
//! LIGGGHTS, YADE, LAMMPS and Kratos.
//!
//! Layers point one way: [`model`] ← [`mod@solve`] ← [`codes`] ← [`analysis`] ← the commands;
//! [`output`] and [`error`] know nothing of the commands; the command line (clap) and the
//! commands are private modules, run through [`run_command_line`], the binary's one call.
//!
//! # A regression test of your own
//!
//! Load a case, solve it by a method, and compare with the exact figures of the paper's law:
//!
//! ```
//! use std::path::Path;
//!
//! use millimpact::{Case, Method, Settings, paper_impact, solve};
//!
//! let root = Path::new(env!("CARGO_MANIFEST_DIR"));
//! let case = Case::load(&root.join("cases/ball_plate.toml"))?;
//! let settings = Settings { method: Method::Dopri5, ..Settings::default() };
//! let outcome = solve(&case.law(), case.impact_velocity, &settings)?;
//! let exact = paper_impact(&case.law(), case.impact_velocity);
//!
//! // η = 0.35 realises e = sqrt((1 - η) / (1 + η)) = 0.693889.
//! assert!((exact.cor - (0.65f64 / 1.35).sqrt()).abs() < 1e-12);
//! assert!((outcome.figures.cor - exact.cor).abs() < 1e-9);
//! assert!((outcome.figures.peak_force / exact.peak_force - 1.0).abs() < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! A stored DEM-code reference (`reference/<code>/<case>.json`, written by
//! `millimpact reference --save`) is read back with [`find_stored`]; its realised COR sits
//! within the step error of the target, and its own law at the code's step explains its peak:
//!
//! ```
//! use std::path::Path;
//!
//! use millimpact::{CodeName, find_stored};
//!
//! let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("reference");
//! let record = find_stored(&folder, CodeName::Lammps, "ball_plate", 0.35)?
//!     .expect("LAMMPS on ball_plate at η = 0.35 is stored");
//! assert!((record.figures.cor - record.cor_target()).abs() < 1e-3);
//! assert!((record.figures.peak_deformation / record.law_at_step.peak_deformation - 1.0).abs() < 1e-6);
//! # Ok::<(), millimpact::StoreError>(())
//! ```
//!
//! The whole `verify` check (every shipped case by every method against the closed forms, and
//! every stored reference) is one call, [`verify`]:
//!
//! ```
//! use std::path::Path;
//!
//! let root = Path::new(env!("CARGO_MANIFEST_DIR"));
//! let report = millimpact::verify(&root.join("cases"), &root.join("reference"))?;
//! assert!(report.rows.len() > 28);
//! assert_eq!(report.failed(), 0);
//! # Ok::<(), millimpact::StoreError>(())
//! ```
//!
//! The library's errors are typed (`thiserror` enums, one per wing: [`StoreError`] for the
//! store and `verify`, [`CompareError`], and so on): a test can match the variant and read the
//! values it carries, and ask [`Blame::is_user_error`] whether the input was at fault (the
//! command line's exit 2):
//!
//! ```
//! use std::path::Path;
//!
//! use millimpact::{Blame, StoreError, verify};
//!
//! let root = Path::new(env!("CARGO_MANIFEST_DIR"));
//! match verify(&root.join("no-such-cases"), &root.join("reference")) {
//!     Err(error @ StoreError::CasesUnreadable { .. }) => {
//!         assert!(error.is_user_error());
//!         assert!(error.to_string().contains("no-such-cases: cannot read the folder"));
//!     }
//!     other => panic!("expected CasesUnreadable, got {other:?}"),
//! }
//! ```
//!
//! Running a code live ([`run_reference`] with [`ReferenceOptions`]) needs the code installed
//! (`bash scripts/install-dem-codes.sh`); `examples/regression_test.rs` puts these together.

#![warn(missing_docs)]

// The commands name the library as its users do (`millimpact::…`).
extern crate self as millimpact;

pub mod analysis;
pub mod codes;
pub mod error;
pub mod model;
pub mod output;
pub mod solve;

mod cli;
mod commands;

/// Run the `millimpact` command line of this process (its arguments, standard output and
/// error) and return its exit code: 0, 1 for a check that disagreed or a run that failed, 2
/// for bad input (one line naming the file, field or flag), 141 when standard output closed.
pub fn run_command_line() -> std::process::ExitCode {
    match cli::parse() {
        Ok(cli) => commands::run(&cli),
        Err(code) => code,
    }
}

pub use analysis::compare::{CompareError, CompareOptions, CompareReport, compare};
pub use analysis::store::verify::{VerifyReport, verify};
pub use analysis::store::{
    ReferenceOptions, ReferenceRecord, StoreError, find_stored, run_reference,
};
pub use codes::CodeName;
pub use error::Blame;
pub use model::case::{Case, ContactKind};
pub use model::exact::{ImpactFigures, paper_impact, restitution};
pub use output::{Format, export};
pub use solve::Method;
pub use solve::paper::{Outcome, Settings, solve};
