//! The comparison's figures, with their uncertainty: block means (or means over seeds) and
//! standard errors per law with their degrees of freedom, and each difference between the laws
//! with its standard error, judged by Student's t at Welch–Satterthwaite's degrees of freedom.

use serde::{Deserialize, Serialize};

use super::contacts::{ENERGY_BINS_J, FORCE_BINS_N, REST_SPEED, bin};
use super::stats::{CONFIDENCE, Estimate, MIN_SEEDS, lag1, t_factor, welch};
use super::{BLOCKS, DEFAULT_CONTACT_EVERY, MillOptions, RunResult};
use crate::codes::liggghts::mill::{MillDeck, MillLaw, MillPlan};
use crate::output::invocation::Invocation;
use crate::output::{Section, Summary};

/// The quantity of the power draw from the torque balance of the charge's weight.
pub(crate) const WEIGHT_POWER: &str = "power draw by the torque balance (ω × the weight's torque)";

/// Whether a difference stands out of its uncertainty.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// Beyond Student's two-sided 95 % t at its degrees of freedom, with at least
    /// `MIN_SEEDS` runs per law.
    Resolved,
    /// Within Student's t of zero.
    NotResolved,
    /// Beyond Student's t, but from fewer than `MIN_SEEDS` runs per law: a hint to run more
    /// seeds, not a conclusion.
    TooFewSeeds,
}

impl std::fmt::Display for Verdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Verdict::Resolved => "resolved",
            Verdict::NotResolved => "not resolved",
            Verdict::TooFewSeeds => "beyond t, too few seeds",
        })
    }
}

/// `b − a` with the standard error of independent estimates and its Welch–Satterthwaite
/// degrees of freedom, and whether it is resolved from `seeds` runs per law.
pub fn difference(a: Estimate, b: Estimate, seeds: usize) -> (Estimate, Verdict) {
    let d = Estimate {
        mean: b.mean - a.mean,
        standard_error: a.standard_error.hypot(b.standard_error),
        degrees_of_freedom: welch(a, b),
        lag1_autocorrelation: None,
    };
    let verdict = if d.mean.abs() <= t_factor(d.degrees_of_freedom) * d.standard_error {
        Verdict::NotResolved
    } else if seeds < MIN_SEEDS {
        Verdict::TooFewSeeds
    } else {
        Verdict::Resolved
    };
    (d, verdict)
}

/// The means of `BLOCKS` consecutive blocks of `values` (the values themselves where there
/// are fewer).
fn block_means(values: &[f64]) -> Vec<f64> {
    let size = values.len() / BLOCKS;
    if size == 0 {
        return values.to_vec();
    }
    values
        .chunks(size)
        .take(BLOCKS)
        .map(|b| b.iter().sum::<f64>() / b.len() as f64)
        .collect()
}

/// The mean of `values` and its standard error from `BLOCKS` consecutive blocks, with the
/// blocks' lag-1 autocorrelation.
fn block_estimate(values: &[f64]) -> Estimate {
    let blocks = block_means(values);
    Estimate {
        lag1_autocorrelation: lag1(&blocks),
        ..spread(&blocks)
    }
}

/// Per law, the mean of `a − b` with its standard error, paired: block by block within one run
/// (the two series cover the same stretch of time), run by run over seeds.
fn paired(
    runs: &[&RunResult],
    a: impl Fn(&RunResult) -> Vec<f64>,
    b: impl Fn(&RunResult) -> Vec<f64>,
) -> Estimate {
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    if runs.len() == 1 {
        let (a, b) = (block_means(&a(runs[0])), block_means(&b(runs[0])));
        let d: Vec<f64> = a.iter().zip(&b).map(|(x, y)| x - y).collect();
        Estimate {
            lag1_autocorrelation: lag1(&d),
            ..spread(&d)
        }
    } else {
        let d: Vec<f64> = runs.iter().map(|r| mean(&a(r)) - mean(&b(r))).collect();
        spread(&d)
    }
}

/// The mean of independent `values` and its standard error, with `n − 1` degrees of freedom.
fn spread(values: &[f64]) -> Estimate {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    Estimate {
        mean,
        standard_error: (variance / n).sqrt(),
        degrees_of_freedom: Some(n - 1.0),
        lag1_autocorrelation: None,
    }
}

/// Per law, one figure's estimate: over blocks of one run, or over the runs' own means.
fn over_runs(runs: &[&RunResult], figure: impl Fn(&RunResult) -> Vec<f64>) -> Estimate {
    if runs.len() == 1 {
        block_estimate(&figure(runs[0]))
    } else {
        let means: Vec<f64> = runs
            .iter()
            .map(|r| {
                let v = figure(r);
                v.iter().sum::<f64>() / v.len() as f64
            })
            .collect();
        spread(&means)
    }
}

/// One figure under both laws.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct QuantityRow {
    /// What is measured.
    pub quantity: String,
    /// Its unit.
    pub unit: String,
    /// Under the deck's own law.
    pub written: Estimate,
    /// Under the switched law.
    pub switched: Estimate,
    /// Switched minus written.
    pub difference: Estimate,
    /// Whether the difference is resolved.
    pub verdict: Verdict,
}

/// The two routes to the power draw set against each other, per law: the power from the torque
/// on the rotating meshes minus the power from the torque balance of the charge's weight, W,
/// with its standard error (paired: block by block, or run by run over seeds). In a steady
/// rotation they agree but for what turns the charge apart from the drum (a wall that stands
/// still) and the charge's angular momentum, which averages out.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PowerBalance {
    /// Under the deck's own law.
    pub written: Estimate,
    /// Under the switched law.
    pub switched: Estimate,
}

impl PowerBalance {
    /// Whether both laws' routes agree within Student's t at their degrees of freedom.
    pub(crate) fn closes(&self) -> bool {
        [self.written, self.switched]
            .iter()
            .all(|d| d.mean.abs() <= t_factor(d.degrees_of_freedom) * d.standard_error)
    }
}

/// One bin of a collision spectrum under both laws: collisions per second (per run).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SpectrumRow {
    /// The pair of types (`"1-2"`, `"1-wall"`).
    pub pair: String,
    /// `impact_energy` (J, `½ m* v_n²` at first contact) or `peak_force` (N).
    pub spectrum: String,
    /// The bin's lower edge (`None`: from zero).
    pub low: Option<f64>,
    /// Its upper edge (`None`: unbounded).
    pub high: Option<f64>,
    /// Collisions per second under the deck's own law, with a Poisson standard error.
    pub written: Estimate,
    /// Under the switched law.
    pub switched: Estimate,
    /// Switched minus written.
    pub difference: Estimate,
    /// Whether the difference is resolved.
    pub verdict: Verdict,
}

/// A run's power and energy are traced over this many equal stretches of the rotation.
pub(crate) const TRACE_POINTS: usize = 100;

/// A run's power and energy over one stretch of the rotation (means over the stretch).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TracePoint {
    /// The stretch's middle, s from the start of the rotation.
    pub time: f64,
    /// Power from the torque on the rotating meshes, W (`None`: no row printed in the stretch).
    pub power: Option<f64>,
    /// Power from the torque balance of the charge's weight, W (`None`: no positions frame in
    /// the stretch, or the deck has no gravity).
    pub weight_power: Option<f64>,
    /// Kinetic energy of the charge, J (`None`: no row printed in the stretch).
    pub kinetic_energy: Option<f64>,
}

/// A particle's place in the drum's cross-section at the end of a run, m from the axis.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ProfilePoint {
    /// Across, toward the side the shell rises on.
    pub across: f64,
    /// Up, against gravity.
    pub up: f64,
}

/// One run as it went.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MillRun {
    /// The law.
    pub law: MillLaw,
    /// The build.
    pub code: String,
    /// The seed (0: the deck's own).
    pub seed: usize,
    /// Collisions first seen in the window.
    pub collisions: usize,
    /// Wall time, s.
    pub wall_time: f64,
    /// Power and kinetic energy through the rotation, in `TRACE_POINTS` stretches.
    pub trace: Vec<TracePoint>,
    /// The charge in the drum's cross-section at the end of the run.
    pub profile: Vec<ProfilePoint>,
}

/// The mean of the values of `series` whose time falls in each of `TRACE_POINTS` stretches of
/// `[0, rotation)`.
fn stretch_means<T>(
    series: &[T],
    rotation: f64,
    at: impl Fn(&T) -> (f64, f64),
) -> Vec<Option<f64>> {
    let mut sums = vec![(0.0, 0usize); TRACE_POINTS];
    for (time, value) in series.iter().map(at) {
        let k = (time / rotation * TRACE_POINTS as f64).floor();
        if (0.0..TRACE_POINTS as f64).contains(&k) {
            // A stretch index below TRACE_POINTS.
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let slot = &mut sums[k as usize];
            slot.0 += value;
            slot.1 += 1;
        }
    }
    sums.into_iter()
        .map(|(sum, n)| (n > 0).then(|| sum / n as f64))
        .collect()
}

/// `run`'s power and energy in `TRACE_POINTS` stretches of a rotation `rotation` s long.
fn trace(run: &RunResult, rotation: f64) -> Vec<TracePoint> {
    let power = stretch_means(&run.series, rotation, |s| (s.0, s.1));
    let energy = stretch_means(&run.series, rotation, |s| (s.0, s.2));
    let weight = stretch_means(&run.weight_power, rotation, |s| *s);
    (0..TRACE_POINTS)
        .map(|k| TracePoint {
            time: (k as f64 + 0.5) * rotation / TRACE_POINTS as f64,
            power: power[k],
            weight_power: weight[k],
            kinetic_energy: energy[k],
        })
        .collect()
}

/// The comparison.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MillReport {
    /// The deck.
    pub deck: String,
    /// The deck's own law.
    pub written_law: MillLaw,
    /// The law it is switched to.
    pub switched_law: MillLaw,
    /// The tangential and rolling models, kept in both.
    pub tangential_and_rolling: String,
    /// The time step, s.
    pub timestep: f64,
    /// Settling steps run as written before rotation.
    pub settling_steps: u64,
    /// Rotation steps run.
    pub rotation_steps: u64,
    /// Where rotation starts in the deck.
    pub rotation_from: String,
    /// Rotation time left out of the power and energy means, s.
    pub transient: f64,
    /// The time over which contacts are recorded, s (the end of the rotation).
    pub spectra_window: f64,
    /// Contacts recorded every this many steps.
    pub contact_every: u64,
    /// Runs per law.
    pub seeds: usize,
    /// The command that reproduces it.
    pub reproduce: String,
    /// The figures.
    pub quantities: Vec<QuantityRow>,
    /// How far the power from the torque on the rotating meshes and the power from the torque
    /// balance of the charge's weight are apart, per law (`None` where the deck has no gravity).
    pub power_balance: Option<PowerBalance>,
    /// The collision spectra.
    pub spectra: Vec<SpectrumRow>,
    /// The runs.
    pub runs: Vec<MillRun>,
    /// What the runs leave out of the deck.
    pub left_out: Vec<String>,
}

/// Collisions per second of `runs` whose event passes `keep`: with one run, its rate and a
/// Poisson error; with several (seeds), the mean of their rates and the error from their
/// spread, which also holds what Poisson's leaves out (the charge's arrangement differs from
/// run to run, and one window sees one arrangement).
fn rate(runs: &[&RunResult], window: f64, keep: impl Fn(&super::ContactEvent) -> bool) -> Estimate {
    let counts: Vec<f64> = runs
        .iter()
        .map(|r| r.events.iter().filter(|e| keep(e)).count() as f64)
        .collect();
    if counts.len() > 1 {
        let rates: Vec<f64> = counts.iter().map(|c| c / window).collect();
        return spread(&rates);
    }
    let count: f64 = counts.iter().sum();
    Estimate {
        mean: count / window,
        standard_error: count.sqrt() / window,
        degrees_of_freedom: None,
        lag1_autocorrelation: None,
    }
}

fn edges(edges: &[f64], k: usize) -> (Option<f64>, Option<f64>) {
    (k.checked_sub(1).map(|j| edges[j]), edges.get(k).copied())
}

/// Every pair's collision spectra, by impact energy and by peak force, under both laws.
fn spectrum_rows(
    runs: &[RunResult],
    written: &[&RunResult],
    switched: &[&RunResult],
    window: f64,
    seeds: usize,
) -> Vec<SpectrumRow> {
    let mut spectra = Vec::new();
    let mut pairs: Vec<String> = runs
        .iter()
        .flat_map(|r| r.events.iter().map(|e| e.pair.clone()))
        .collect();
    pairs.sort();
    pairs.dedup();
    for pair in &pairs {
        for (spectrum, bins) in [
            ("impact_energy", &ENERGY_BINS_J[..]),
            ("peak_force", &FORCE_BINS_N[..]),
        ] {
            for k in 0..=bins.len() {
                let keep = |e: &super::ContactEvent| {
                    e.pair == *pair
                        && bin(
                            if spectrum == "impact_energy" {
                                e.impact_energy
                            } else {
                                e.peak_force
                            },
                            bins,
                        ) == k
                };
                let (a, b) = (rate(written, window, keep), rate(switched, window, keep));
                let (difference, verdict) = difference(a, b, seeds);
                let (low, high) = edges(bins, k);
                spectra.push(SpectrumRow {
                    pair: pair.clone(),
                    spectrum: spectrum.into(),
                    low,
                    high,
                    written: a,
                    switched: b,
                    difference,
                    verdict,
                });
            }
        }
    }
    spectra
}

/// The report of finished runs.
pub(super) fn summarise(
    deck: &MillDeck,
    plan: &MillPlan,
    transient: f64,
    options: &MillOptions,
    runs: &[RunResult],
) -> MillReport {
    let (written_law, switched_law) = (deck.law, deck.law.other());
    let of = |law: MillLaw| runs.iter().filter(|r| r.law == law).collect::<Vec<_>>();
    let (written, switched) = (of(written_law), of(switched_law));
    let measured = |r: &RunResult, pick: fn(&(f64, f64, f64)) -> f64| {
        r.series
            .iter()
            .filter(|s| s.0 > transient)
            .map(pick)
            .collect::<Vec<f64>>()
    };
    let window = plan.spectra_steps as f64 * deck.timestep;
    let mut quantities = Vec::new();
    let seeds = options.seeds;
    let mut push = |quantity: &str, unit: &str, a: Estimate, b: Estimate| {
        let (difference, verdict) = difference(a, b, seeds);
        quantities.push(QuantityRow {
            quantity: quantity.into(),
            unit: unit.into(),
            written: a,
            switched: b,
            difference,
            verdict,
        });
    };
    let power = |r: &RunResult| measured(r, |s| s.1);
    let energy = |r: &RunResult| measured(r, |s| s.2);
    push(
        "power draw",
        "W",
        over_runs(&written, power),
        over_runs(&switched, power),
    );
    let held = |r: &RunResult| {
        r.weight_power
            .iter()
            .filter(|s| s.0 > transient)
            .map(|s| s.1)
            .collect::<Vec<f64>>()
    };
    let weighed = runs.iter().all(|r| !r.weight_power.is_empty());
    if weighed {
        push(
            WEIGHT_POWER,
            "W",
            over_runs(&written, held),
            over_runs(&switched, held),
        );
    }
    push(
        "mean kinetic energy",
        "J",
        over_runs(&written, energy),
        over_runs(&switched, energy),
    );
    if runs.iter().all(|r| !r.angles.is_empty()) {
        let angle = |r: &RunResult, pick: fn(&(f64, f64, f64)) -> f64| {
            r.angles
                .iter()
                .filter(|a| a.0 > transient)
                .map(pick)
                .collect::<Vec<f64>>()
        };
        let toe = |r: &RunResult| angle(r, |a| a.1);
        let shoulder = |r: &RunResult| angle(r, |a| a.2);
        push(
            "shoulder angle (from the bottom, rising side positive)",
            "deg",
            over_runs(&written, shoulder),
            over_runs(&switched, shoulder),
        );
        push(
            "toe angle (from the bottom, rising side positive)",
            "deg",
            over_runs(&written, toe),
            over_runs(&switched, toe),
        );
    }
    let mut spectra = Vec::new();
    if plan.spectra_steps > 0 {
        let rest = |r: &RunResult| r.rest_fractions.clone();
        push(
            "collisions per second",
            "1/s",
            rate(&written, window, |_| true),
            rate(&switched, window, |_| true),
        );
        push(
            &format!("fraction of contacts at rest (|v_n| < {REST_SPEED} m/s)"),
            "1",
            over_runs(&written, rest),
            over_runs(&switched, rest),
        );
        spectra = spectrum_rows(runs, &written, &switched, window, seeds);
    }
    let power_balance = weighed.then(|| PowerBalance {
        written: paired(&written, power, held),
        switched: paired(&switched, power, held),
    });
    let code_given = (options.hertz_code != MillDeck::DEFAULT_BUILD).then_some(options.hertz_code);
    let reproduce = Invocation::new("mill")
        .arg(deck.path.display())
        .option_if("--code", code_given)
        .option_if("--time", options.time)
        .option_if("--seeds", (options.seeds > 1).then_some(options.seeds))
        .option_if("--transient", options.transient)
        .option_if("--spectra-time", options.spectra_time)
        .option_if(
            "--contact-every",
            (options.contact_every != DEFAULT_CONTACT_EVERY).then_some(options.contact_every),
        )
        .to_string();
    MillReport {
        reproduce,
        power_balance,
        deck: deck.path.display().to_string(),
        written_law,
        switched_law,
        tangential_and_rolling: deck.tangential_and_rolling.clone(),
        timestep: deck.timestep,
        settling_steps: deck.settling_steps,
        rotation_steps: plan.rotation_steps,
        rotation_from: deck.rotation_from.to_string(),
        transient,
        spectra_window: window,
        contact_every: plan.contact_every,
        seeds: options.seeds,
        quantities,
        spectra,
        runs: runs
            .iter()
            .map(|r| MillRun {
                law: r.law,
                code: r.code.clone(),
                seed: r.seed,
                collisions: r.events.len(),
                wall_time: r.wall_time,
                trace: trace(r, plan.rotation_steps as f64 * deck.timestep),
                profile: r.profile.clone(),
            })
            .collect(),
        left_out: deck.left_out.clone(),
    }
}

/// One CSV row: a figure or a spectrum bin.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MillRecord {
    /// `quantity` or `spectrum`.
    pub kind: &'static str,
    /// The figure, or the spectrum (`impact_energy`, `peak_force`).
    pub quantity: String,
    /// The pair of types, for a spectrum bin.
    pub pair: Option<String>,
    /// The bin's lower edge.
    pub low: Option<f64>,
    /// The bin's upper edge.
    pub high: Option<f64>,
    /// The unit.
    pub unit: String,
    /// The deck's own law.
    pub written_law: MillLaw,
    /// Its value.
    pub written: f64,
    /// Its standard error.
    pub written_standard_error: f64,
    /// The switched law.
    pub switched_law: MillLaw,
    /// Its value.
    pub switched: f64,
    /// Its standard error.
    pub switched_standard_error: f64,
    /// Switched minus written.
    pub difference: f64,
    /// Its standard error.
    pub difference_standard_error: f64,
    /// Whether the difference is resolved.
    pub verdict: Verdict,
    /// The degrees of freedom of the difference's standard error (Welch–Satterthwaite; empty:
    /// Poisson counts, taken as normal).
    pub difference_degrees_of_freedom: Option<f64>,
}

fn pm(e: Estimate) -> String {
    format!("{:.4e} ± {:.1e}", e.mean, e.standard_error)
}

fn edge(x: Option<f64>) -> String {
    x.map_or("-".into(), |x| format!("{x:e}"))
}

impl Summary for MillReport {
    type Record = MillRecord;

    fn records(&self) -> Vec<MillRecord> {
        let quantities = self.quantities.iter().map(|q| MillRecord {
            kind: "quantity",
            quantity: q.quantity.clone(),
            pair: None,
            low: None,
            high: None,
            unit: q.unit.clone(),
            written_law: self.written_law,
            written: q.written.mean,
            written_standard_error: q.written.standard_error,
            switched_law: self.switched_law,
            switched: q.switched.mean,
            switched_standard_error: q.switched.standard_error,
            difference: q.difference.mean,
            difference_standard_error: q.difference.standard_error,
            verdict: q.verdict,
            difference_degrees_of_freedom: q.difference.degrees_of_freedom,
        });
        let spectra = self.spectra.iter().map(|s| MillRecord {
            kind: "spectrum",
            quantity: s.spectrum.clone(),
            pair: Some(s.pair.clone()),
            low: s.low,
            high: s.high,
            unit: "1/s".into(),
            written_law: self.written_law,
            written: s.written.mean,
            written_standard_error: s.written.standard_error,
            switched_law: self.switched_law,
            switched: s.switched.mean,
            switched_standard_error: s.switched.standard_error,
            difference: s.difference.mean,
            difference_standard_error: s.difference.standard_error,
            verdict: s.verdict,
            difference_degrees_of_freedom: s.difference.degrees_of_freedom,
        });
        quantities.chain(spectra).collect()
    }

    fn sections(&self) -> Vec<Section> {
        let code = |law: MillLaw| {
            self.runs
                .iter()
                .find(|r| r.law == law)
                .map_or(String::new(), |r| r.code.clone())
        };
        let written = format!("model {} ({})", self.written_law, code(self.written_law));
        let switched = format!("model {} ({})", self.switched_law, code(self.switched_law));
        let mut figures = Section::new(
            Some(format!(
                "{}: {} (as written) against {} (switched at each pair's COR), {}",
                self.deck, written, switched, self.tangential_and_rolling
            )),
            &[
                "quantity",
                "unit",
                &written,
                &switched,
                "difference",
                "verdict",
            ],
        );
        for q in &self.quantities {
            figures.rows.push(vec![
                q.quantity.clone(),
                q.unit.clone(),
                pm(q.written),
                pm(q.switched),
                pm(q.difference),
                q.verdict.to_string(),
            ]);
        }
        let uncertainty = if self.seeds > 1 {
            format!(
                "means over {} seeds, standard errors from their spread ({} degrees of freedom per law)",
                self.seeds,
                self.seeds - 1
            )
        } else {
            format!(
                "block means over {BLOCKS} consecutive blocks, standard errors from their spread ({} degrees of freedom per law)",
                BLOCKS - 1
            )
        };
        figures.notes = vec![format!(
            "Δt {:e} s; {} settling steps as written, then {} rotation steps (from {}); power and energy after the first {:.4} s of rotation, {uncertainty}; a difference is resolved beyond Student's two-sided {:.0} % t at its Welch–Satterthwaite degrees of freedom, from at least {MIN_SEEDS} seeds per law",
            self.timestep,
            self.settling_steps,
            self.rotation_steps,
            self.rotation_from,
            self.transient,
            100.0 * CONFIDENCE
        )];
        if self.seeds < MIN_SEEDS {
            figures.notes.push(format!(
                "{} seed{} per law: below {MIN_SEEDS} nothing is called resolved (one seed's blocks leave out how the charge differs from seed to seed, and a few seeds' spread is itself uncertain by a factor of two); a difference beyond t is marked \"beyond t, too few seeds\"; run --seeds {MIN_SEEDS} or more to conclude",
                self.seeds,
                if self.seeds == 1 { "" } else { "s" }
            ));
        }
        let correlated: Vec<String> = self
            .quantities
            .iter()
            .filter_map(|q| {
                let (a, b) = (
                    q.written.lag1_autocorrelation?,
                    q.switched.lag1_autocorrelation?,
                );
                Some(format!("{} {a:+.2}, {b:+.2}", q.quantity))
            })
            .collect();
        if !correlated.is_empty() {
            figures.notes.push(format!(
                "the blocks' lag-1 autocorrelation ({}, {}): {}; near zero the blocks are independent, well above it the standard errors are too small",
                self.written_law,
                self.switched_law,
                correlated.join("; ")
            ));
        }
        if let Some(balance) = self.power_balance {
            let mesh = self.quantities.iter().find(|q| q.quantity == "power draw");
            let relative = |d: Estimate, of: Option<f64>| {
                of.map_or(String::new(), |p| {
                    format!(" ({:+.0} % of {:.3} W)", 100.0 * d.mean / p, p)
                })
            };
            figures.notes.push(format!(
                "power balance, the torque on the rotating meshes minus the torque balance of the charge's weight: {} W{} under {}, {} W{} under {}: {}; in a steady rotation the two differ only by what turns the charge apart from the drum and by the charge's angular momentum, which averages out",
                pm(balance.written),
                relative(balance.written, mesh.map(|q| q.written.mean)),
                self.written_law,
                pm(balance.switched),
                relative(balance.switched, mesh.map(|q| q.switched.mean)),
                self.switched_law,
                if balance.closes() {
                    "it closes within Student's t"
                } else {
                    "it does not close within Student's t"
                }
            ));
        }
        let mut sections = vec![figures];
        if !self.spectra.is_empty() {
            let mut spectra = Section::new(
                Some(format!(
                    "collisions per second, by the impact energy ½ m* v_n² at first contact (J) and the peak normal force (N); contacts recorded every {} steps over the last {:.4} s",
                    self.contact_every, self.spectra_window
                )),
                &[
                    "pair",
                    "spectrum",
                    "from",
                    "to",
                    &written,
                    &switched,
                    "difference",
                    "verdict",
                ],
            );
            for s in &self.spectra {
                spectra.rows.push(vec![
                    s.pair.clone(),
                    s.spectrum.clone(),
                    edge(s.low),
                    edge(s.high),
                    pm(s.written),
                    pm(s.switched),
                    pm(s.difference),
                    s.verdict.to_string(),
                ]);
            }
            // The wall is named only where the spectra have wall rows: a deck whose mesh walls
            // come after its first run has none (LIGGGHTS records no wall contacts there).
            let wall = if self.spectra.iter().any(|s| s.pair.ends_with("-wall")) {
                "; the wall is the last mesh wall/gran fix (LIGGGHTS's wall/gran/local records that one)"
            } else {
                ""
            };
            spectra.notes = vec![format!(
                "a contact is seen only every recorded step: one shorter than the interval can be missed, its v_n is taken up to one interval into it and its peak is the largest force recorded{wall}; standard errors are Poisson's for one run (they leave out that one window sees one arrangement of the charge), from the runs' spread with --seeds"
            )];
            sections.push(spectra);
        }
        let mut runs = Section::new(
            Some("runs".into()),
            &["law", "code", "seed", "collisions", "wall time (s)"],
        );
        for r in &self.runs {
            runs.rows.push(vec![
                r.law.to_string(),
                r.code.clone(),
                r.seed.to_string(),
                r.collisions.to_string(),
                format!("{:.1}", r.wall_time),
            ]);
        }
        if !self.left_out.is_empty() {
            runs.notes = vec![format!(
                "left out (output only): {}",
                self.left_out.join("; ")
            )];
        }
        sections.push(runs);
        sections
    }

    fn footer(&self) -> Vec<String> {
        vec![format!("reproduce: {}", self.reproduce)]
    }
}
