//! Collisions from LIGGGHTS's contact dumps (`compute pair/gran/local` and `wall/gran/local`
//! with `pos vel id force_normal`, dumped every few steps): each contact tracked from its first
//! appearance, its impact energy `½ m* v_n²` taken there and its peak normal force over its
//! appearances.
//!
//! Sampling: a contact is seen only at the recorded steps. One shorter than the interval can
//! fall between two records and be missed; one that is seen is first seen up to one interval
//! after it began (its `v_n` already slowed by that much compression), and its peak is the
//! largest recorded force, below the true peak by up to what the force changes in an interval.

use std::collections::HashMap;

use serde::Serialize;

use super::charge::{cross, dot};
use crate::codes::liggghts::mill::MillDeck;

/// Edges of the impact-energy bins, J (a bin below the first and one above the last besides).
pub(crate) const ENERGY_BINS_J: [f64; 7] = [1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2];
/// Edges of the peak-normal-force bins, N (a bin below the first and one above the last).
pub(crate) const FORCE_BINS_N: [f64; 5] = [0.1, 1.0, 10.0, 100.0, 1000.0];
/// A contact whose normal relative speed is below this is counted at rest, m/s.
pub(crate) const REST_SPEED: f64 = 1e-3;
/// Two wall records of one particle in consecutive frames are one contact when their normals
/// are within this cosine (30°): the contact slid from one facet of the mesh to the next.
const SAME_WALL_CONTACT: f64 = 0.866;

/// The atoms as dumped at the start of rotation.
#[derive(Clone, Debug, Default)]
pub struct Atoms {
    /// The step the rotation starts at.
    pub start_step: f64,
    /// Per atom id: its type and mass, kg.
    pub by_id: HashMap<u64, (u32, f64)>,
}

/// One particle's contact as recorded in one frame.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ContactSample {
    /// Normal relative speed, m/s (negative while approaching).
    pub normal_speed: f64,
    /// Normal force, N.
    pub normal_force: f64,
}

/// A collision: a contact first seen in the window.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ContactEvent {
    /// The pair of types, `"1-2"`, or `"1-wall"` against the liner.
    pub pair: String,
    /// `½ m* v_n²` at first sight, J.
    pub impact_energy: f64,
    /// The largest normal force seen, N.
    pub peak_force: f64,
}

/// `(line, reason)` of a file that cannot be read.
pub type ReadFault = (usize, String);

/// Read the atoms file (`dump custom … id type mass radius`, one frame).
pub fn read_atoms(text: &str) -> Result<Atoms, ReadFault> {
    let lines: Vec<&str> = text.lines().collect();
    let step = lines
        .get(1)
        .and_then(|l| l.trim().parse::<f64>().ok())
        .ok_or((2, "no timestep".to_string()))?;
    let start = lines
        .iter()
        .position(|l| l.starts_with("ITEM: ATOMS"))
        .ok_or((0, "no ITEM: ATOMS".to_string()))?;
    let mut by_id = HashMap::new();
    for (k, line) in lines.iter().enumerate().skip(start + 1) {
        if line.starts_with("ITEM:") {
            break;
        }
        let w: Vec<&str> = line.split_whitespace().collect();
        let parsed = (
            w.first().and_then(|x| x.parse::<u64>().ok()),
            w.get(1).and_then(|x| x.parse::<u32>().ok()),
            w.get(2).and_then(|x| x.parse::<f64>().ok()),
        );
        match parsed {
            (Some(id), Some(t), Some(m)) => {
                by_id.insert(id, (t, m));
            }
            _ => return Err((k + 1, format!("`{line}`: expected id type mass radius"))),
        }
    }
    Ok(Atoms {
        start_step: step,
        by_id,
    })
}

/// One frame of a local dump: its step and its rows.
pub type Frame = (u64, Vec<[f64; 18]>);

/// Read a local dump of 18 columns.
pub fn read_frames(text: &str) -> Result<Vec<Frame>, ReadFault> {
    let mut frames = Vec::new();
    let mut lines = text.lines().enumerate().peekable();
    while let Some((k, line)) = lines.next() {
        if line != "ITEM: TIMESTEP" {
            return Err((k + 1, format!("`{line}`: expected ITEM: TIMESTEP")));
        }
        let step = lines
            .next()
            .and_then(|(_, l)| l.trim().parse::<u64>().ok())
            .ok_or((k + 2, "no step".to_string()))?;
        lines.next();
        let n = lines
            .next()
            .and_then(|(_, l)| l.trim().parse::<usize>().ok())
            .ok_or((k + 4, "no number of entries".to_string()))?;
        // Box bounds (a header and three lines), then the entries' header.
        for _ in 0..5 {
            lines.next();
        }
        let mut rows = Vec::with_capacity(n);
        for _ in 0..n {
            let (j, line) = lines
                .next()
                .ok_or((k + 1, "a frame cut short".to_string()))?;
            let mut row = [0.0; 18];
            let mut count = 0;
            for (slot, word) in row.iter_mut().zip(line.split_whitespace()) {
                *slot = word
                    .parse()
                    .map_err(|_| (j + 1, format!("`{word}` is not a number")))?;
                count += 1;
            }
            if count != 18 {
                return Err((j + 1, format!("{count} columns, expected 18")));
            }
            rows.push(row);
        }
        frames.push((step, rows));
    }
    Ok(frames)
}

fn sub(a: &[f64], b: &[f64]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = dot(&v, &v).sqrt();
    if n > 0.0 {
        [v[0] / n, v[1] / n, v[2] / n]
    } else {
        [0.0; 3]
    }
}

/// A contact open at the last frame.
struct Open {
    pair: String,
    energy: f64,
    peak: f64,
    normal: [f64; 3],
    /// Seen in the first frame: begun before the window, not a collision of it.
    before: bool,
    seen: u64,
}

/// What a run's contact records are read with.
pub struct Recorded<'a> {
    /// The atoms' types and masses.
    pub atoms: &'a Atoms,
    /// The deck (its rotating meshes give the liner's velocity).
    pub deck: &'a MillDeck,
}

/// A tracked contact's key: a particle pair, or a particle on a facet of the recorded wall.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Key {
    Pair(u64, u64),
    Wall(u64, u64, u64),
}

/// Whole ids and indices, as the dumps write them (small whole numbers as doubles).
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
fn id(x: f64) -> u64 {
    x.round().max(0.0) as u64
}

/// A contact dump names an atom the atoms file does not hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("atom {atom} is not in the atoms file")]
pub struct UnknownAtom {
    /// The atom's id.
    pub atom: u64,
}

impl Recorded<'_> {
    fn type_and_mass(&self, atom: u64) -> Result<(u32, f64), UnknownAtom> {
        self.atoms
            .by_id
            .get(&atom)
            .copied()
            .ok_or(UnknownAtom { atom })
    }

    /// The velocity of the recorded wall at `point` (its meshes' rotation; the dump writes 0).
    fn wall_velocity(&self, mesh: usize, point: &[f64]) -> [f64; 3] {
        let name = self.deck.recorded_wall_meshes.get(mesh);
        match self.deck.rotating.iter().find(|r| Some(&r.mesh) == name) {
            Some(r) => {
                let w = r.axis.map(|a| a * r.angular_velocity);
                cross(&w, &sub(point, &r.origin))
            }
            None => [0.0; 3],
        }
    }

    /// Track every contact through the frames: the collisions first seen after the first
    /// frame, and per frame the fraction of contacts at rest.
    pub fn track(
        &self,
        pairs: &[Frame],
        walls: &[Frame],
    ) -> Result<(Vec<ContactEvent>, Vec<f64>), UnknownAtom> {
        let mut open: HashMap<Key, Open> = HashMap::new();
        let mut events = Vec::new();
        let mut rest = Vec::new();
        let wall_frames: HashMap<u64, &Vec<[f64; 18]>> =
            walls.iter().map(|(s, rows)| (*s, rows)).collect();
        let empty = Vec::new();
        for (frame, (step, rows)) in pairs.iter().enumerate() {
            let first = frame == 0;
            let mut samples: Vec<(Key, String, [f64; 3], f64, ContactSample)> = Vec::new();
            for r in rows {
                let (a, b) = (id(r[12]), id(r[13]));
                let (ta, ma) = self.type_and_mass(a)?;
                let (tb, mb) = self.type_and_mass(b)?;
                let normal = unit(sub(&r[0..3], &r[3..6]));
                let vn = dot(&sub(&r[6..9], &r[9..12]), &normal);
                let force = dot(&r[15..18], &r[15..18]).sqrt();
                let (lo, hi) = (ta.min(tb), ta.max(tb));
                samples.push((
                    Key::Pair(a.min(b), a.max(b)),
                    format!("{lo}-{hi}"),
                    normal,
                    ma * mb / (ma + mb),
                    ContactSample {
                        normal_speed: vn,
                        normal_force: force,
                    },
                ));
            }
            for r in *wall_frames.get(step).unwrap_or(&&empty) {
                let atom = id(r[14]);
                let (t, m) = self.type_and_mass(atom)?;
                let normal = unit(sub(&r[3..6], &r[0..3]));
                let mesh = usize::try_from(id(r[12])).unwrap_or(usize::MAX);
                let wall = self.wall_velocity(mesh, &r[0..3]);
                let vn = dot(&sub(&r[9..12], &wall), &normal);
                let force = dot(&r[15..18], &r[15..18]).sqrt();
                samples.push((
                    Key::Wall(atom, id(r[12]), id(r[13])),
                    format!("{t}-wall"),
                    normal,
                    m,
                    ContactSample {
                        normal_speed: vn,
                        normal_force: force,
                    },
                ));
            }
            let still = samples
                .iter()
                .filter(|s| s.4.normal_speed.abs() < REST_SPEED)
                .count();
            if !samples.is_empty() {
                rest.push(still as f64 / samples.len() as f64);
            }
            let frame_number = frame as u64;
            for (key, pair, normal, mass, sample) in samples {
                let key = match key {
                    Key::Wall(atom, ..) if !open.contains_key(&key) => {
                        // A particle sliding onto the next facet keeps its contact.
                        let moved = open
                            .iter()
                            .find(|(k, o)| {
                                matches!(k, Key::Wall(a, ..) if *a == atom)
                                    && o.seen + 1 == frame_number
                                    && dot(&o.normal, &normal) > SAME_WALL_CONTACT
                            })
                            .map(|(k, _)| *k);
                        if let Some(old) = moved
                            && let Some(o) = open.remove(&old)
                        {
                            open.insert(key, o);
                        }
                        key
                    }
                    _ => key,
                };
                let entry = open.entry(key).or_insert_with(|| Open {
                    pair,
                    energy: 0.5 * mass * sample.normal_speed * sample.normal_speed,
                    peak: 0.0,
                    normal,
                    before: first,
                    seen: frame_number,
                });
                entry.peak = entry.peak.max(sample.normal_force);
                entry.normal = normal;
                entry.seen = frame_number;
            }
            let ended: Vec<Key> = open
                .iter()
                .filter(|(_, o)| o.seen != frame_number)
                .map(|(k, _)| *k)
                .collect();
            for key in ended {
                if let Some(o) = open.remove(&key)
                    && !o.before
                {
                    events.push(ContactEvent {
                        pair: o.pair,
                        impact_energy: o.energy,
                        peak_force: o.peak,
                    });
                }
            }
        }
        // Contacts still open at the end began in the window: collisions, their peak as seen.
        let mut rest_open: Vec<Open> = open.into_values().filter(|o| !o.before).collect();
        rest_open.sort_by(|a, b| a.pair.cmp(&b.pair).then(a.energy.total_cmp(&b.energy)));
        events.extend(rest_open.into_iter().map(|o| ContactEvent {
            pair: o.pair,
            impact_energy: o.energy,
            peak_force: o.peak,
        }));
        Ok((events, rest))
    }
}

/// The bin of `value` among `edges`: 0 below the first edge, `edges.len()` from the last.
pub fn bin(value: f64, edges: &[f64]) -> usize {
    edges.iter().take_while(|&&e| value >= e).count()
}
