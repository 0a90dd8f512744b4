//! A LAMMPS data file (`read_data FILE`) as far as the deck check needs it: the number of atom
//! types, the box, and each atom of `atom_style sphere` with its type, diameter and density
//! (the columns `atom-ID atom-type diameter density x y z`, as LAMMPS's `AtomVecSphere` reads
//! them; a diameter of 0 makes the density column the atom's mass, a point particle).

use std::path::Path;

use super::{DeckError, SourceLine};
use crate::codes::script::parse_number;

/// One atom of the file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct DataAtom {
    /// Its id.
    pub id: usize,
    /// Its type.
    pub type_id: u32,
    /// Diameter, m.
    pub diameter: f64,
    /// Density, kg/m³.
    pub density: f64,
}

/// What the check reads of a data file.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct DataFile {
    /// `N atom types`.
    pub types: Option<u32>,
    /// `xlo xhi`, `ylo yhi`, `zlo zhi`, m.
    pub simulation_box: Option<[f64; 6]>,
    /// The `Atoms` section.
    pub atoms: Vec<DataAtom>,
}

/// The sections whose lines are numbers the check does not need (skipped whole).
const OTHER_SECTIONS: [&str; 10] = [
    "Velocities",
    "Masses",
    "Bonds",
    "Angles",
    "Dihedrals",
    "Impropers",
    "Ellipsoids",
    "Lines",
    "Triangles",
    "Bodies",
];

impl DataFile {
    /// The box of the file's header alone, where it reads (the script reader's `xlo` …).
    pub(crate) fn header_box(path: &Path) -> Option<[f64; 6]> {
        let text = std::fs::read_to_string(path).ok()?;
        Self::parse(path, &text).ok()?.simulation_box
    }

    /// Read the file at `path` (named by the line `at`).
    pub(crate) fn read(path: &Path, at: &SourceLine) -> Result<Self, DeckError> {
        let text = std::fs::read_to_string(path).map_err(|source| DeckError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        Self::parse(path, &text).map_err(|(line, what)| {
            DeckError::unsupported(
                SourceLine {
                    file: path.to_path_buf(),
                    line,
                },
                format!("{what} (the data file of {at})"),
                "a LAMMPS data file of atom_style sphere: a header (N atoms, N atom types, xlo xhi …), then `Atoms # sphere` with `id type diameter density x y z` lines",
            )
        })
    }

    /// The file's text read; an error is the line (from 1) and what is wrong there.
    fn parse(_path: &Path, text: &str) -> Result<Self, (usize, String)> {
        let mut file = DataFile::default();
        let mut bounds = [None; 6];
        let mut section: Option<&str> = None;
        // The first line is a title, whatever it holds.
        for (index, raw) in text.lines().enumerate().skip(1) {
            let line = index + 1;
            let (content, comment) = match raw.split_once('#') {
                Some((c, comment)) => (c.trim(), comment.trim()),
                None => (raw.trim(), ""),
            };
            if content.is_empty() {
                continue;
            }
            let words: Vec<&str> = content.split_whitespace().collect();
            if words[0] == "Atoms" {
                if !comment.is_empty() && comment != "sphere" && comment != "granular" {
                    return Err((
                        line,
                        format!("atoms of atom_style {comment}: the check reads sphere atoms"),
                    ));
                }
                section = Some("Atoms");
                continue;
            }
            if OTHER_SECTIONS.contains(&words[0]) || words[0].ends_with("Coeffs") {
                section = Some("other");
                continue;
            }
            match section {
                None => header(&words, &mut file, &mut bounds),
                Some("Atoms") => {
                    let number = |k: usize| words.get(k).and_then(|w| parse_number(w));
                    let id = words.first().and_then(|w| w.parse::<usize>().ok());
                    let t = words.get(1).and_then(|w| w.parse::<u32>().ok());
                    let (Some(id), Some(t), Some(d), Some(rho)) = (id, t, number(2), number(3))
                    else {
                        return Err((
                            line,
                            format!("`{content}` is not `id type diameter density x y z`"),
                        ));
                    };
                    if id == 0 || t == 0 || d < 0.0 || rho <= 0.0 {
                        return Err((
                            line,
                            format!(
                                "`{content}`: ids and types count from 1, diameters are not negative and densities positive"
                            ),
                        ));
                    }
                    file.atoms.push(DataAtom {
                        id,
                        type_id: t,
                        diameter: d,
                        density: rho,
                    });
                }
                Some(_) => {}
            }
        }
        if bounds.iter().all(Option::is_some) {
            file.simulation_box = Some(bounds.map(|b| b.unwrap_or_default()));
        }
        Ok(file)
    }
}

/// A header line: `N atom types`, `lo hi xlo xhi` and the like (others are skipped).
fn header(words: &[&str], file: &mut DataFile, bounds: &mut [Option<f64>; 6]) {
    match words {
        [n, "atom", "types"] => file.types = n.parse().ok(),
        [lo, hi, axis @ ("xlo" | "ylo" | "zlo"), _] => {
            let k = match *axis {
                "xlo" => 0,
                "ylo" => 2,
                _ => 4,
            };
            bounds[k] = parse_number(lo);
            bounds[k + 1] = parse_number(hi);
        }
        _ => {}
    }
}
