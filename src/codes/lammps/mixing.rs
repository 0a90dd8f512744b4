//! A granular contact model as a LAMMPS deck writes it ([`GranularModel`]), what a build
//! integrates for it ([`Coefficients`]), and how a build fills a pair of atom types that no
//! `pair_coeff` line sets ([`PairMixing`]): from the lines of each type with itself (`pair_coeff I I …` and `pair_coeff J J …`, as most decks are
//! written), which `pair_style granular` mixes in `init_one`. The two builds the harness drives
//! mix differently, and neither gives the pair the law a reader of the two lines expects, so the
//! deck reader ([`super::deck`]) builds the mixed pair's law as its build does and says what it
//! is in the pair's traps.
//!
//! Both builds refuse to mix two lines of different functional forms (normal, damping,
//! tangential, rolling or twisting model): "Granular pair style functional forms are different,
//! cannot mix coefficients for types I and J"; the reader refuses such a deck with the lines.
//!
//! What each build does was read in its source and measured in it: the force at step 0 of a
//! mixed pair at rest and approaching (hertz/material E = 2e11/7e10, ν = 0.3/0.2, e = 0.5/0.9,
//! damping tsuji) is the law below to the digits LAMMPS prints, and `tests/deck_live.rs` runs
//! whole impacts of mixed pairs in each build against these laws stepped as the build steps
//! them (to the precision `verify` holds stored runs to).

use super::conventions::{Conventions, TsujiFit, WallModulus};

/// A `pair_coeff` or `fix wall/gran granular` contact model as read.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct GranularModel {
    /// The normal model's name.
    pub normal: String,
    /// `k` (hooke, hertz) or `E` (hertz/material), and `d`, and `ν` (hertz/material).
    pub values: Vec<f64>,
    /// The damping model's name.
    pub damping: String,
    /// `limit_damping`.
    pub limit_damping: bool,
    /// The tangential model's name (empty where none is given).
    pub tangential: String,
    /// The rolling model's name (empty where none is given, or `none`).
    pub rolling: String,
    /// The twisting model's name (empty where none is given, or `none`).
    pub twisting: String,
    /// The model's words as written (the transplanted line keeps them).
    pub words: Vec<String>,
}

impl GranularModel {
    /// The functional form LAMMPS compares before it mixes two lines: the normal, damping,
    /// tangential, rolling and twisting models.
    pub(crate) fn form(&self) -> String {
        let mut form = format!("{} damping {}", self.normal, self.damping);
        for (word, style) in [
            ("tangential", &self.tangential),
            ("rolling", &self.rolling),
            ("twisting", &self.twisting),
        ] {
            if !style.is_empty() {
                form.push_str(&format!(" {word} {style}"));
            }
        }
        form
    }

    /// What the build integrates for this model on its own (a pair's own line, or a wall),
    /// with the wall modulus's traps.
    pub(crate) fn coefficients(
        &self,
        conventions: &Conventions,
        wall: bool,
    ) -> (Coefficients, Vec<String>) {
        let mut traps = Vec::new();
        let v = &self.values;
        let normal = match self.normal.as_str() {
            "hooke" => Normal::Hooke(v[0]),
            "hertz" => Normal::Hertz(v[0]),
            _ => {
                let (e, nu) = (v[0], v[2]);
                let e_star = match (wall, conventions.wall_modulus) {
                    (false, _) | (true, WallModulus::HalfOverOneMinusNuSquared) => {
                        own_modulus(e, nu)
                    }
                    (true, WallModulus::HalfOverOneMinusNu) => {
                        traps.push(format!("wall modulus: in this build fix wall/gran hertz/material reads E* = E/(2(1−ν)) = {:.4e} Pa, not E/(2(1−ν²)) = {:.4e} Pa (the particle's material on both sides): {:+.1} % stiffer", e / (2.0 * (1.0 - nu)), own_modulus(e, nu), 100.0 * nu));
                        e / (2.0 * (1.0 - nu))
                    }
                };
                if wall {
                    traps.push(format!("wall modulus: the wall's E and ν are the particle's material on both sides (E* = {e_star:.4e} Pa): a wall meant rigid or of another material needs another E"));
                }
                Normal::Material(e_star)
            }
        };
        let coefficients = Coefficients {
            normal,
            damping: self.damping.clone(),
            damping_number: v[1],
            limit_damping: self.limit_damping,
            tangential: self.tangential.clone(),
        };
        (coefficients, traps)
    }
}

/// How a build mixes the pair `I J` from `I I` and `J J`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PairMixing {
    /// 29 Sep 2021 (`src/GRANULAR/pair_granular.cpp`): `init_one` mixes the coefficients,
    /// each as the geometric mean of the two types' stored numbers (`tsuji`'s already turned
    /// into α by `pair_coeff`), but copies no model into the pair: the pair's normal model,
    /// damping model and `limit_damping` are whatever the uninitialised arrays hold, which in
    /// every run measured is 0, that is `hooke`, `damping velocity` and no `limit_damping`.
    /// The pair integrates `F = k δ + d δ̇` with `k = √(k₁k₂)` (for `hertz/material`
    /// `kᵢ = 4/3 Eᵢ/(2(1−νᵢ²))`, the stored prefactor) and `d = √(d₁d₂)`. A `pair_coeff I J`
    /// with `J < I` sets no pair and is refused ("Incorrect args for pair coefficients").
    CoefficientsOnly,
    /// The `GranularModel` generation (LAMMPS from 2023; the 22 Jul 2025 build): the whole
    /// model is mixed. `hertz/material` takes Hertz's two-material modulus
    /// `E* = 1/((1−ν₁²)/E₁ + (1−ν₂²)/E₂)` (`k = 4/3 E* √R*`), `hooke` and `hertz` the
    /// geometric mean of `k`, the damping number the geometric mean of the numbers typed, and
    /// the damping model converts that afterwards: `tsuji` and `coeff_restitution` turn
    /// `e = √(e₁e₂)` into α, not `√(α₁α₂)`. `limit_damping` is on when either line has it.
    /// A `pair_coeff J I` with `J > I` is read as `I J`.
    WholeModel,
}

/// A normal model's stiffness as a build holds it for a pair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Normal {
    /// `hooke`: `F = k δ`, `k` in N/m.
    Hooke(f64),
    /// `hertz`: `F = k √R* δ^1.5`.
    Hertz(f64),
    /// `hertz/material`: `F = 4/3 E* √R* δ^1.5`, `E*` in Pa.
    Material(f64),
}

impl Normal {
    /// The law's stiffness and exponent for the effective radius `r_star`.
    pub(crate) fn stiffness(self, r_star: f64) -> (f64, f64) {
        match self {
            Normal::Hooke(k) => (k, 1.0),
            Normal::Hertz(k) => (k * r_star.sqrt(), 1.5),
            Normal::Material(e_star) => (4.0 / 3.0 * e_star * r_star.sqrt(), 1.5),
        }
    }
}

/// What a build integrates for one pair (or one wall): its normal stiffness, damping model
/// with the number it is given, and whether the attractive tail is cut.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Coefficients {
    /// The normal stiffness.
    pub normal: Normal,
    /// The damping model's name.
    pub damping: String,
    /// The number the damping model is given (`e` for `tsuji` and `coeff_restitution`).
    pub damping_number: f64,
    /// `limit_damping`.
    pub limit_damping: bool,
    /// The tangential model's name (none where the build leaves it unset).
    pub tangential: String,
}

/// A mixed pair: what the build integrates, the model as the report names it, and what the
/// mixing does, said with its numbers.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct MixedPair {
    /// What the build integrates.
    pub coefficients: Coefficients,
    /// The model as the report names it.
    pub model: String,
    /// The mixing, with its numbers.
    pub traps: Vec<String>,
}

fn geometric(a: f64, b: f64) -> f64 {
    (a * b).sqrt()
}

/// `E/(2(1−ν²))`: one material against itself, as `pair_coeff I I hertz/material` stores it.
pub(crate) fn own_modulus(e: f64, nu: f64) -> f64 {
    e / (2.0 * (1.0 - nu * nu))
}

fn fit_name(fit: TsujiFit) -> &'static str {
    match fit {
        TsujiFit::Polynomial => "poly",
        TsujiFit::Sqrt2Polynomial => "√2·poly",
    }
}

impl PairMixing {
    /// Whether `pair_coeff I J` with numbers `J < I` is read as `J I` (else the build refuses
    /// it).
    pub(crate) fn reorders_types(self) -> bool {
        matches!(self, PairMixing::WholeModel)
    }

    /// The pair of types `i` (model `a`, its line `at_a`) and `j` (model `b`, line `at_b`) as
    /// this build mixes it; `a` and `b` have the same functional form.
    pub(crate) fn mix(
        self,
        conventions: &Conventions,
        (i, a, at_a): (u32, &GranularModel, &str),
        (j, b, at_b): (u32, &GranularModel, &str),
    ) -> MixedPair {
        let from = format!(
            "no pair_coeff sets the types {i} and {j}: LAMMPS mixes the pair from pair_coeff {i} {i} ({at_a}) and {j} {j} ({at_b})"
        );
        let (da, db) = (a.values[1], b.values[1]);
        match self {
            PairMixing::CoefficientsOnly => {
                // The number each line stores: hertz/material's 4/3 E/(2(1−ν²)), tsuji's α.
                let stored_k = |m: &GranularModel| match m.normal.as_str() {
                    "hertz/material" => 4.0 / 3.0 * own_modulus(m.values[0], m.values[2]),
                    _ => m.values[0],
                };
                let stored_d = |m: &GranularModel| match m.damping.as_str() {
                    "tsuji" => conventions.tsuji_fit.alpha(m.values[1]),
                    _ => m.values[1],
                };
                let (ka, kb) = (stored_k(a), stored_k(b));
                let (sa, sb) = (stored_d(a), stored_d(b));
                let k = geometric(ka, kb);
                let d = geometric(sa, sb);
                let stiffness_is = match a.normal.as_str() {
                    "hertz/material" => format!(
                        "k = √(k{i}·k{j}) of the stored 4/3 E/(2(1−ν²)) = √({ka:.6e}·{kb:.6e}) = {k:.6e}"
                    ),
                    _ => format!("k = √(k{i}·k{j}) = √({ka:e}·{kb:e}) = {k:.6e}"),
                };
                let damping_is = match a.damping.as_str() {
                    "tsuji" => format!(
                        "d = √(α{i}·α{j}) of the α tsuji stored, {fit}(e) = √({sa:.6}·{sb:.6}) = {d:.6}",
                        fit = fit_name(conventions.tsuji_fit)
                    ),
                    _ => format!("d = √(d{i}·d{j}) = √({sa:e}·{sb:e}) = {d:.6e}"),
                };
                let mut traps = vec![
                    format!("mixed: {from}"),
                    format!(
                        "mixed pair's model left unset: this build mixes the coefficients but copies no model into the pair (init_one of pair_granular.cpp), and the pair runs what its uninitialised arrays hold, 0 in the runs measured: hooke, damping velocity, no limit_damping, whatever the two lines say ({} damping {}). So F = k δ + d δ̇, linear, with {stiffness_is} used as N/m and {damping_is} used as N·s/m; give the pair a pair_coeff {i} {j} of its own",
                        a.normal, a.damping
                    ),
                ];
                if a.limit_damping || b.limit_damping {
                    traps.push("limit_damping of the lines does not reach the mixed pair in this build (its flag is left unset too): the tail is not cut".into());
                }
                MixedPair {
                    coefficients: Coefficients {
                        normal: Normal::Hooke(k),
                        damping: "velocity".into(),
                        damping_number: d,
                        limit_damping: false,
                        tangential: String::new(),
                    },
                    model: format!(
                        "hooke damping velocity (mixed from {i} {i} and {j} {j}: the model left unset)"
                    ),
                    traps,
                }
            }
            PairMixing::WholeModel => {
                let (normal, stiffness_is) = match a.normal.as_str() {
                    "hertz/material" => {
                        let (ea, nua, eb, nub) =
                            (a.values[0], a.values[2], b.values[0], b.values[2]);
                        let e_star = super::paper_plugin_modulus(ea, nua, eb, nub);
                        (
                            Normal::Material(e_star),
                            format!(
                                "E* = 1/((1−ν{i}²)/E{i} + (1−ν{j}²)/E{j}) = 1/((1−{nua}²)/{ea:e} + (1−{nub}²)/{eb:e}) = {e_star:.6e} Pa, Hertz's modulus of the two materials (k = 4/3 E* √R*)"
                            ),
                        )
                    }
                    name => {
                        let k = geometric(a.values[0], b.values[0]);
                        let normal = if name == "hooke" {
                            Normal::Hooke(k)
                        } else {
                            Normal::Hertz(k)
                        };
                        (
                            normal,
                            format!(
                                "k = √(k{i}·k{j}) = √({:e}·{:e}) = {k:.6e}",
                                a.values[0], b.values[0]
                            ),
                        )
                    }
                };
                let d = geometric(da, db);
                let damping_is = match a.damping.as_str() {
                    "tsuji" => {
                        let fit = conventions.tsuji_fit;
                        format!(
                            "damping tsuji mixes the numbers typed, e = √(e{i}·e{j}) = √({da}·{db}) = {d:.6}, and turns that into α = {name}({d:.6}) = {alpha:.6} (after mixing: not √(α{i}·α{j}) = {geo:.6})",
                            name = fit_name(fit),
                            alpha = fit.alpha(d),
                            geo = geometric(fit.alpha(da), fit.alpha(db))
                        )
                    }
                    "coeff_restitution" => format!(
                        "damping coeff_restitution mixes the numbers typed, e = √(e{i}·e{j}) = √({da}·{db}) = {d:.6}, and realises that e"
                    ),
                    _ => format!("d = √(d{i}·d{j}) = √({da:e}·{db:e}) = {d:.6e}"),
                };
                let mut traps = vec![format!("mixed: {from}: {stiffness_is}; {damping_is}")];
                if a.limit_damping != b.limit_damping {
                    traps.push(format!(
                        "limit_damping is on in pair_coeff {t} {t} only: the mixed pair takes it (on when either line has it)",
                        t = if a.limit_damping { i } else { j }
                    ));
                }
                MixedPair {
                    coefficients: Coefficients {
                        normal,
                        damping: a.damping.clone(),
                        damping_number: d,
                        limit_damping: a.limit_damping || b.limit_damping,
                        tangential: a.tangential.clone(),
                    },
                    model: format!(
                        "{} damping {} (mixed from {i} {i} and {j} {j})",
                        a.normal, a.damping
                    ),
                    traps,
                }
            }
        }
    }
}
