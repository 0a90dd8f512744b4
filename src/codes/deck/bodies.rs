//! The particles of a deck: the atoms a LAMMPS-family script makes (`create_atoms`, `set`, an
//! insertion fix) with the sizes its lines give them, and the list of bodies every reader hands
//! back, one per size of each type, with the sizes given on the command line (`--particle`)
//! in place of the deck's own.

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use super::data::DataAtom;
use super::{DeckBody, DeckError, DeckOptions, Partner, SourceLine, UserDeck, sphere_mass};
use crate::codes::script::Command;

/// A size as a script's lines give it: diameter (m), density (kg/m³) and mass (kg), each
/// where a line sets it.
pub(crate) type Size = [Option<f64>; 3];

/// A whole number of a script (a type, an atom id), or the error of a line where it is not
/// one: `what` names the number, `supported` what a line must give.
pub(crate) fn whole_number(
    x: f64,
    at: &SourceLine,
    what: &str,
    supported: &str,
) -> Result<u32, DeckError> {
    if x >= 1.0 && x.fract() == 0.0 && x <= f64::from(u32::MAX) {
        // A positive whole number below u32::MAX: the conversion is exact.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        Ok(x as u32)
    } else {
        Err(at.refuse(format!("{what} `{x}`"), supported))
    }
}

/// How a code's atom commands (`create_box`, `create_atoms`, `set`) read: the dialect's own
/// words where the two codes differ.
pub(crate) struct AtomSyntax {
    /// A whole number of the line (its word, what it is called), as the code's messages say.
    pub whole: fn(f64, &Command, &str) -> Result<u32, DeckError>,
    /// What `set type N`'s N is called where it is not a number.
    pub type_label: &'static str,
    /// Whether `mass M` sizes an atom (a density is formed from it and the diameter).
    pub mass: bool,
    /// The keywords that make atoms of a new type out of the selected ones.
    pub makes: &'static [&'static str],
    /// Any other keyword's check: the error of one the code does not have.
    pub refuses: fn(&Command, &str) -> Result<(), DeckError>,
}

/// The atoms a script makes, by type, with the sizes its `set` lines give types and atoms.
#[derive(Debug, Default)]
pub(crate) struct Atoms {
    /// Each type with atoms, with the first line that makes them.
    pub of_type: BTreeMap<u32, SourceLine>,
    /// Types whose atoms a `set … type N` (or an insertion) made, with that line's text.
    made_by: HashMap<u32, String>,
    /// Types an insertion fix makes during the run (no `set` reaches them).
    inserted: Vec<u32>,
    /// The type of each atom `create_atoms … single` made, by atom id − 1.
    single: Vec<u32>,
    /// The size `set type N` gives each type.
    of_type_size: HashMap<u32, Size>,
    /// The size `set atom N` gives each atom.
    of_atom_size: HashMap<usize, Size>,
    /// Types with particles from other lines (LIGGGHTS' particle templates).
    elsewhere: Vec<u32>,
    /// The groups whose atoms the reader knows by type (`group ID type T …`), by ID; a group
    /// of a region or of atom ids is not here.
    groups: HashMap<String, Vec<u32>>,
}

impl Atoms {
    /// Particles of type `t` come from a line of the code's own (a particle template).
    pub(crate) fn made_elsewhere(&mut self, t: u32) {
        self.elsewhere.push(t);
    }

    /// `group ID type T1 T2 …` (or `T1:T2` ranges): the group of those types' atoms;
    /// any other form (a region, ids, a formula) makes a group whose atoms the reader does
    /// not know.
    pub(crate) fn group(&mut self, c: &Command) {
        let Some(id) = c.words.get(1) else { return };
        let types: Option<Vec<u32>> = match c.words.get(2).map(String::as_str) {
            Some("type") if c.words.len() > 3 => c.words[3..]
                .iter()
                .map(|w| match w.split_once(':') {
                    Some((lo, hi)) => {
                        let (lo, hi): (u32, u32) = (lo.parse().ok()?, hi.parse().ok()?);
                        (hi >= lo && hi - lo < 1024).then(|| (lo..=hi).collect::<Vec<u32>>())
                    }
                    None => w.parse::<u32>().ok().map(|t| vec![t]),
                })
                .collect::<Option<Vec<Vec<u32>>>>()
                .map(|v| v.concat()),
            _ => None,
        };
        match types {
            Some(t) => {
                self.groups.insert(id.clone(), t);
            }
            None => {
                self.groups.remove(id);
            }
        }
    }

    /// The types of the atoms group `id` holds now, where the reader knows them: `all` is
    /// every type with atoms.
    fn group_types(&self, id: &str) -> Option<Vec<u32>> {
        if id == "all" {
            return Some(self.of_type.keys().copied().collect());
        }
        self.groups.get(id).map(|types| {
            types
                .iter()
                .copied()
                .filter(|t| self.of_type.contains_key(t))
                .collect()
        })
    }

    /// The atoms of a data file (`read_data` at `at`), their ids after those of the atoms
    /// made before where the line adds them (`add append`).
    pub(crate) fn read_data(&mut self, atoms: &[DataAtom], at: &SourceLine, append: bool) {
        let offset = if append { self.single.len() } else { 0 };
        for a in atoms {
            let id = a.id + offset;
            self.of_type.entry(a.type_id).or_insert_with(|| at.clone());
            if self.single.len() < id {
                // Ids the file skips hold no atom: type 0 is no type.
                self.single.resize(id, 0);
            }
            self.single[id - 1] = a.type_id;
            // A diameter of 0 is a point particle whose density column is its mass.
            let size = if a.diameter > 0.0 {
                [Some(a.diameter), Some(a.density), None]
            } else {
                [Some(a.diameter), None, Some(a.density)]
            };
            self.of_atom_size.insert(id, size);
        }
    }

    /// `create_atoms T …` at `at`; `single` for one atom (which has an id).
    pub(crate) fn create(&mut self, t: u32, at: &SourceLine, single: bool) {
        self.of_type.entry(t).or_insert_with(|| at.clone());
        if single {
            self.single.push(t);
        }
    }

    /// An insertion fix (`c`) that makes atoms of type `t` during the run, of one diameter and
    /// one density where the line gives them.
    pub(crate) fn insert(
        &mut self,
        t: u32,
        c: &Command,
        diameter: Option<f64>,
        density: Option<f64>,
    ) {
        self.of_type.entry(t).or_insert_with(|| c.at.clone());
        self.made_by.entry(t).or_insert_with(|| c.text.clone());
        self.inserted.push(t);
        let slot = self.of_type_size.entry(t).or_default();
        slot[0] = slot[0].or(diameter);
        slot[1] = slot[1].or(density);
    }

    /// `set atom|type N … diameter D density RHO [mass M] [type T …]`: the sizes it gives and
    /// the types it makes; whether it sets atoms the reader knows (else it sets a group or a
    /// region, and is left out).
    pub(crate) fn set(&mut self, c: &Command, syntax: &AtomSyntax) -> Result<bool, DeckError> {
        let pick = |key: &str| -> Result<Option<f64>, DeckError> {
            match c.words.iter().position(|w| w == key) {
                Some(k) => c.number(k + 1, key).map(Some),
                None => Ok(None),
            }
        };
        let values = [
            pick("diameter")?,
            pick("density")?,
            if syntax.mass { pick("mass")? } else { None },
        ];
        let merge = |slot: &mut Size| {
            for (s, v) in slot.iter_mut().zip(values) {
                *s = v.or(*s);
            }
        };
        // The size the atoms this line selects have once it is done (where the reader knows it).
        let selected = match c.word(1, "atom or type")? {
            "type" => {
                let t = (syntax.whole)(c.number(2, syntax.type_label)?, c, "type")?;
                let slot = self.of_type_size.entry(t).or_default();
                merge(slot);
                Some(*slot)
            }
            "atom" => {
                let id = (syntax.whole)(c.number(2, "the atom id")?, c, "atom")? as usize;
                let slot = self.of_atom_size.entry(id).or_default();
                merge(slot);
                Some(*slot)
            }
            // Every atom of the group's types, those with a size of their own too, as
            // LAMMPS sets each atom the group holds.
            "group" => match self.group_types(c.word(2, "the group")?) {
                Some(types) if !types.is_empty() => {
                    for t in &types {
                        merge(self.of_type_size.entry(*t).or_default());
                        for (index, atom_type) in self.single.iter().enumerate() {
                            if atom_type == t
                                && let Some(slot) = self.of_atom_size.get_mut(&(index + 1))
                            {
                                merge(slot);
                            }
                        }
                    }
                    // The size the selected atoms share, where they are of one type.
                    match types.as_slice() {
                        [t] => self.of_type_size.get(t).copied(),
                        _ => Some([None; 3]),
                    }
                }
                _ => None,
            },
            _ => None,
        };
        // The selected atoms keep their size and density as they change type.
        let mut makes = false;
        for (k, word) in c.words.iter().enumerate().skip(3) {
            if !syntax.makes.contains(&word.as_str()) {
                (syntax.refuses)(c, word)?;
                continue;
            }
            let t = (syntax.whole)(c.number(k + 1, "the new atom type")?, c, word)?;
            makes = true;
            let exists = self.of_type.contains_key(&t) || self.elsewhere.contains(&t);
            self.of_type.entry(t).or_insert_with(|| c.at.clone());
            self.made_by.entry(t).or_insert_with(|| c.text.clone());
            if let Some(size) = selected {
                let slot = self.of_type_size.entry(t).or_default();
                // A type with no atoms yet takes the selected atoms' size whole (a
                // `set type N …` before this line set no atom of it).
                if exists {
                    for (s, v) in slot.iter_mut().zip(size) {
                        *s = s.or(v);
                    }
                } else {
                    *slot = size;
                }
            }
        }
        Ok(selected.is_some() || makes)
    }
}

/// The bodies of a deck as they are found: one per size of each type, the types given on the
/// command line taking their size from it.
pub(crate) struct Bodies<'o> {
    bodies: Vec<DeckBody>,
    options: &'o DeckOptions,
}

impl<'o> Bodies<'o> {
    /// None yet; a type 0 given on the command line is refused (types count from 1).
    pub(crate) fn new(path: &Path, options: &'o DeckOptions) -> Result<Self, DeckError> {
        if let Some(p) = options.particles.iter().find(|p| p.type_id == 0) {
            return Err(DeckError::Lacking {
                file: path.to_path_buf(),
                what: format!(
                    "--particle {}:{}:{}: atom types count from 1",
                    p.type_id, p.radius, p.density
                ),
                supported: "--particle TYPE:RADIUS:DENSITY with TYPE an atom type of the deck"
                    .into(),
            });
        }
        Ok(Self {
            bodies: Vec::new(),
            options,
        })
    }

    /// Whether the command line gives type `t`'s size (the deck's own is then not read).
    pub(crate) fn given(&self, t: u32) -> bool {
        self.options.particles.iter().any(|p| p.type_id == t)
    }

    /// A body of type `t`, unless one of that size and density is already there.
    pub(crate) fn push(&mut self, t: u32, radius: f64, density: f64, from: String) {
        // The same size read twice is the same number, bit for bit.
        #[allow(clippy::float_cmp)]
        let known = self
            .bodies
            .iter()
            .any(|b| b.type_id == t && b.radius == radius && b.density == density);
        if !known {
            self.bodies.push(DeckBody {
                type_id: t,
                radius,
                density,
                mass: sphere_mass(radius, density),
                youngs_modulus: None,
                poisson_ratio: None,
                from,
            });
        }
    }

    /// The bodies of `atoms`: each atom's own size, else its type's; a type whose size the
    /// lines do not give is refused (`mass_words`: how the code's lines may give it besides a
    /// density, in the message).
    pub(crate) fn push_atoms(&mut self, atoms: &Atoms, mass_words: &str) -> Result<(), DeckError> {
        for (t, at) in &atoms.of_type {
            if self.given(*t) {
                continue;
            }
            let of_type = atoms.of_type_size.get(t).copied().unwrap_or_default();
            let size = |own: Size| -> Option<(f64, f64)> {
                let d = own[0].or(of_type[0])?;
                let r = d / 2.0;
                let density = own[1]
                    .or(of_type[1])
                    .or_else(|| own[2].or(of_type[2]).map(|m| m / sphere_mass(r, 1.0)))?;
                Some((r, density))
            };
            let mut found = false;
            for (index, atom_type) in atoms.single.iter().enumerate() {
                if atom_type == t
                    && let Some((radius, density)) = size(
                        atoms
                            .of_atom_size
                            .get(&(index + 1))
                            .copied()
                            .unwrap_or_default(),
                    )
                {
                    self.push(*t, radius, density, format!("atom {} ({at})", index + 1));
                    found = true;
                }
            }
            if !found {
                let (radius, density) = size([None; 3]).ok_or_else(|| {
                    at.refuse(
                        match atoms.made_by.get(t) {
                            Some(text) => format!(
                                "atoms of type {t} come from `{text}` without a diameter and density{mass_words} the reader can know for them"
                            ),
                            None => format!(
                                "atoms of type {t} are created without a diameter and density{mass_words} set for them"
                            ),
                        },
                        &if atoms.inserted.contains(t) {
                            format!(
                                "--particle {t}:RADIUS:DENSITY (atoms inserted during the run take no `set`)"
                            )
                        } else {
                            format!(
                                "`set type {t} diameter D density RHO`, or --particle {t}:RADIUS:DENSITY"
                            )
                        },
                    )
                })?;
                self.push(*t, radius, density, format!("set type {t} ({at})"));
            }
        }
        Ok(())
    }

    /// The bodies found with those the command line gives; none is refused (`none`: what the
    /// deck lacks, in the code's words).
    pub(crate) fn finish(mut self, path: &Path, none: &str) -> Result<Vec<DeckBody>, DeckError> {
        for p in &self.options.particles {
            self.push(
                p.type_id,
                p.radius,
                p.density,
                format!("--particle {}:{}:{}", p.type_id, p.radius, p.density),
            );
        }
        if self.bodies.is_empty() {
            return Err(DeckError::Lacking {
                file: path.to_path_buf(),
                what: none.into(),
                supported: "give them with --particle TYPE:RADIUS:DENSITY".into(),
            });
        }
        Ok(self.bodies)
    }
}

/// Most distinct radii one type (of one density) keeps as bodies of their own: a pack with
/// more is polydisperse, and is checked by size classes (every size against every other would
/// be tens of thousands of impacts: a mill of 242 radii forms ~29,600 pairs).
pub const MAX_SIZES: usize = 5;
/// The size classes a polydisperse type is grouped into: equal counts of its distinct radii,
/// smallest to largest.
pub const SIZE_CLASSES: usize = 3;

/// The radius a size class is checked at: its middle size (of an even count, the smaller of
/// the two middle ones, so that it is a size the deck has).
fn class_median(radii: &[f64]) -> f64 {
    radii[(radii.len() - 1) / 2]
}

/// A radius in mm, to four significant digits, for the notes.
fn mm(radius: f64) -> String {
    format!("{:.4} mm", radius * 1e3)
}

impl UserDeck {
    /// The deck with each polydisperse type (more than [`MAX_SIZES`] distinct radii of one type
    /// and density) grouped into [`SIZE_CLASSES`] classes of equal count by radius, each
    /// checked at its median size: its pairs, with every other class and every wall, are the
    /// pairs of those bodies. Each class is named among the notes (its radius range, how many
    /// sizes it holds and their spread about the median) and in its body's `from`. A deck with
    /// fewer sizes is returned as it is.
    pub fn in_size_classes(mut self) -> Self {
        // The bodies of each type and density, by index.
        let mut groups: BTreeMap<(u32, u64), Vec<usize>> = BTreeMap::new();
        for (k, b) in self.bodies.iter().enumerate() {
            groups
                .entry((b.type_id, b.density.to_bits()))
                .or_default()
                .push(k);
        }
        let mut keep = vec![true; self.bodies.len()];
        let mut notes = Vec::new();
        for ((t, _), mut members) in groups {
            if members.len() <= MAX_SIZES {
                continue;
            }
            members.sort_by(|a, b| self.bodies[*a].radius.total_cmp(&self.bodies[*b].radius));
            let n = members.len();
            let (smallest, largest) = (
                self.bodies[members[0]].radius,
                self.bodies[members[n - 1]].radius,
            );
            let mut classes = Vec::new();
            for c in 0..SIZE_CLASSES {
                // Equal counts, the remainder spread over the first classes.
                let (lo, hi) = (c * n / SIZE_CLASSES, (c + 1) * n / SIZE_CLASSES);
                let class = &members[lo..hi];
                let radii: Vec<f64> = class.iter().map(|k| self.bodies[*k].radius).collect();
                let median = class_median(&radii);
                let chosen = class[(class.len() - 1) / 2];
                for k in class {
                    keep[*k] = *k == chosen;
                }
                let (first, last) = (radii[0], radii[radii.len() - 1]);
                let spread = format!(
                    "−{:.1} %/+{:.1} % of its median",
                    100.0 * (median - first) / median,
                    100.0 * (last - median) / median
                );
                let body = &mut self.bodies[chosen];
                body.from = format!(
                    "median of size class {} of {SIZE_CLASSES} of type {t} ({} sizes, R {}–{}); {}",
                    c + 1,
                    class.len(),
                    mm(first),
                    mm(last),
                    body.from
                );
                classes.push(format!(
                    "class {} R {}–{} ({} sizes, checked at R {}, spread {spread})",
                    c + 1,
                    mm(first),
                    mm(last),
                    class.len(),
                    mm(median)
                ));
            }
            notes.push(format!(
                "type {t}'s other sizes: {n} radii from {} to {}, more than {MAX_SIZES}, grouped into {SIZE_CLASSES} size classes of equal count, each checked at its median size: {}",
                mm(smallest),
                mm(largest),
                classes.join("; ")
            ));
        }
        if notes.is_empty() {
            return self;
        }
        // The new index of each body kept.
        let mut index = vec![None; self.bodies.len()];
        let mut next = 0;
        for (k, kept) in keep.iter().enumerate() {
            if *kept {
                index[k] = Some(next);
                next += 1;
            }
        }
        self.contacts = std::mem::take(&mut self.contacts)
            .into_iter()
            .filter_map(|mut c| {
                c.body = index[c.body]?;
                if let Partner::Body(o) = c.partner {
                    c.partner = Partner::Body(index[o]?);
                }
                Some(c)
            })
            .collect();
        let mut k = 0;
        self.bodies.retain(|_| {
            k += 1;
            keep[k - 1]
        });
        self.left_out.extend(notes);
        self
    }
}
