//! A rotating drum of 300 steel balls in LAMMPS 2025 with the paper's law as a plugin
//! (`scripts/lammps-paper/drum.in`): the deck selects what its header says (fast tier), and the
//! live run keeps every ball in the drum, lifts the charge, bounds every speed and reads
//! non-negative pair forces through the plugin's `single()`.
//!
//! The live test FAILS (not skips) when the build is not installed.

use std::f64::consts::PI;

use millimpact::codes::CodeDriver;
use millimpact::codes::lammps::paper::LammpsPaper;
use millimpact::codes::lammps::paper_plugin_modulus as plugin_modulus;
use millimpact::model::exact;
use millimpact::model::law::PaperLaw;

mod common;

use common::root;

const DECK: &str = "scripts/lammps-paper/drum.in";

/// The balls in the deck: how many, their radii and density.
const BALLS: usize = 300;
const SMALLEST_RADIUS: f64 = 0.004;
const LARGEST_RADIUS: f64 = 0.006;
const DENSITY: f64 = 7800.0;
const ETA: f64 = 0.6;
const DRUM_RADIUS: f64 = 0.08;
const TIMESTEP: f64 = 2e-6;

fn deck_text() -> String {
    std::fs::read_to_string(root().join(DECK)).unwrap()
}

/// The deck is the mill its header describes: the plugin's law between the balls and on the
/// end caps, the stock granular law on the rotating liner, ghost velocities, lost atoms an error.
#[test]
fn the_drum_deck_selects_the_plugin_between_balls_and_the_stock_law_on_the_liner() {
    let text = deck_text();
    let lines: Vec<&str> = text.lines().collect();
    for wanted in [
        "plugin          load paperplugin.so",
        "atom_style      sphere",
        "comm_modify     vel yes",
        "pair_style      paper",
        "pair_coeff      1 1 0.6 2e11 0.3",
        "fix             integrate all nve/sphere",
        "timestep        2e-6",
        "variable        drum_radius equal 0.08",
    ] {
        assert!(lines.contains(&wanted), "{DECK}: no `{wanted}`");
    }
    assert!(
        text.contains("wall/gran/region granular hertz/material 2e11 0.5 0.3"),
        "{DECK}: no stock granular liner"
    );
    assert!(
        text.contains("rotate v_theta 0 0 0 0 1 0"),
        "{DECK}: the shell does not rotate"
    );
    assert!(
        text.contains("wall/paper hertz 0.6 2e11 0.3 2e11 0.3 yplane"),
        "{DECK}: no wall/paper end caps"
    );
    assert!(
        text.contains("lost error"),
        "{DECK}: lost atoms not an error"
    );
    assert!(
        text.contains(&format!("create_atoms    1 random {BALLS} ")),
        "{DECK}: not {BALLS} balls"
    );
}

/// One thermo row of the deck: `step time ke v_com_angle c_fastest c_reach[1] c_reach[2]
/// c_pair_force c_pair_force_max`.
#[derive(Debug, Clone, Copy)]
struct Row {
    time: f64,
    kinetic_energy: f64,
    centre_angle_degrees: f64,
    fastest: f64,
    radial_reach: f64,
    axial_reach: f64,
    smallest_pair_force: f64,
    largest_pair_force: f64,
}

/// The thermo tables of the screen output, one per `run`.
fn thermo_tables(text: &str) -> Vec<Vec<Row>> {
    let mut tables = Vec::new();
    let mut current: Option<Vec<Row>> = None;
    for line in text.lines() {
        let trimmed = line.trim();
        if trimmed.starts_with("Step ") {
            current = Some(Vec::new());
        } else if trimmed.starts_with("Loop time of ") {
            tables.extend(current.take());
        } else if let Some(rows) = current.as_mut() {
            let v: Vec<f64> = trimmed
                .split_whitespace()
                .map(|w| {
                    w.parse()
                        .unwrap_or_else(|_| panic!("thermo row `{line}`: `{w}` not a number"))
                })
                .collect();
            assert_eq!(v.len(), 9, "thermo row `{line}`");
            rows.push(Row {
                time: v[1],
                kinetic_energy: v[2],
                centre_angle_degrees: v[3],
                fastest: v[4],
                radial_reach: v[5],
                axial_reach: v[6],
                smallest_pair_force: v[7],
                largest_pair_force: v[8],
            });
        }
    }
    tables
}

/// Lines of a recorded run of the deck (LAMMPS 2025 with the plugin): two rows of each thermo
/// table, the lines that end each run and the summary lines between them.
const RECORDED_SCREEN: &str = "\
   Step          Time          KinEng      v_com_angle     c_fastest      c_reach[1]     c_reach[2]    c_pair_force  c_pair_force_max
         0  0 0 -50.362 0 -0.00868798 -0.00133992 1e+20 -1e+20
     40000  0.08 0.311724 -1.46724 0.850081 -1.03651e-05 -1.88989e-05 0 8.05112
Loop time of 8.79369 on 1 procs for 100000 steps with 300 atoms

SETTLED ke 0.00397797 angle -0.392742
OMEGA 8.57759 rad/s shell speed 0.686207 m/s
   Step          Time          KinEng      v_com_angle     c_fastest      c_reach[1]     c_reach[2]    c_pair_force  c_pair_force_max
    100000  0.2 0.00397797 -0.392742 0.384528 5.19877e-07 4.32962e-07 0 2.26215
    250000  0.5 0.137696 69.7447 0.991838 1.10898e-07 2.49679e-07 0 14.6654
Loop time of 18.5351 on 1 procs for 150000 steps with 300 atoms
";

/// The screen output is read as the live test reads it: one table per run with every column
/// in place (the ±1e20 of a reduction over no pairs kept for the test to leave out), and the
/// summary lines' numbers without their words.
#[test]
fn the_drums_screen_output_is_read_into_its_tables_and_figures() {
    let tables = thermo_tables(RECORDED_SCREEN);
    assert_eq!(tables.iter().map(Vec::len).collect::<Vec<_>>(), [2, 2]);
    let empty = tables[0][0];
    assert!(empty.smallest_pair_force > 1e19 && empty.largest_pair_force < -1e19);
    assert!(empty.radial_reach < 0.0 && empty.centre_angle_degrees < -50.0);
    let last = tables[1][1];
    assert_eq!(last.time.to_bits(), 0.5f64.to_bits());
    assert_eq!(last.kinetic_energy.to_bits(), 0.137696f64.to_bits());
    assert_eq!(last.centre_angle_degrees.to_bits(), 69.7447f64.to_bits());
    assert_eq!(last.fastest.to_bits(), 0.991838f64.to_bits());
    assert_eq!(last.axial_reach.to_bits(), 2.49679e-7f64.to_bits());
    assert_eq!(last.largest_pair_force.to_bits(), 14.6654f64.to_bits());
    assert_eq!(numbers(RECORDED_SCREEN, "OMEGA "), [8.57759, 0.686207]);
    assert_eq!(
        numbers(RECORDED_SCREEN, "SETTLED "),
        [0.00397797, -0.392742]
    );
}

/// The numbers after `prefix` on the line that starts with it, words that are not numbers left
/// out (`OMEGA 8.57 rad/s shell speed 0.686 m/s` gives `[8.57, 0.686]`).
fn numbers(text: &str, prefix: &str) -> Vec<f64> {
    text.lines()
        .find(|l| l.starts_with(prefix))
        .unwrap_or_else(|| panic!("no `{prefix}` line: {text}"))[prefix.len()..]
        .split_whitespace()
        .filter_map(|w| w.parse().ok())
        .collect()
}

fn ball_mass(radius: f64) -> f64 {
    4.0 / 3.0 * PI * radius.powi(3) * DENSITY
}

/// The paper's law between two balls of `radius` (steel, η = 0.6, the plugin's stiffness).
fn ball_pair_law(radius: f64) -> PaperLaw {
    PaperLaw {
        mass: ball_mass(radius) / 2.0,
        stiffness: 4.0 / 3.0 * plugin_modulus(2e11, 0.3, 2e11, 0.3) * (radius / 2.0).sqrt(),
        exponent: 1.5,
        loss_coefficient: ETA,
    }
}

/// The shell's speed in the deck: 75 % of the critical `sqrt(g / (R_drum - r_mean))`, times
/// the drum's radius.
fn shell_speed() -> f64 {
    0.75 * (9.81f64 / (DRUM_RADIUS - 0.005)).sqrt() * DRUM_RADIUS
}

/// The deck's step resolves the stiffest contact, two of the smallest balls, under the paper's
/// law: at least 10 steps a contact and 4 in its loading, at the shell speed and at 3 × it (the
/// speed bound of the live test). The figures printed are the deck header's.
#[test]
fn the_drum_step_resolves_the_stiffest_contact() {
    let law = ball_pair_law(SMALLEST_RADIUS);
    for speed in [shell_speed(), 3.0 * shell_speed()] {
        let impact = exact::paper_impact(&law, speed);
        let steps = impact.contact_time / TIMESTEP;
        let loading = impact.compression_time / TIMESTEP;
        println!(
            "two {SMALLEST_RADIUS} m balls at {speed:.3} m/s: contact {:.3e} s, {steps:.1} \
             steps, {loading:.1} in loading",
            impact.contact_time
        );
        assert!(
            steps >= 10.0 && loading >= 4.0,
            "{steps} steps, {loading} loading"
        );
    }
}

/// The drum runs in the installed LAMMPS 2025 with the plugin: exit 0 with every ball kept
/// (`thermo_modify lost error`, 300 atoms at the end of both runs); no ball reaches more than
/// 10 µm (a Hertz overlap, 0.25 % of the smallest radius) beyond the shell or an end cap; no
/// ball moves faster than 3 × the shell speed; the rotation lifts the charge (its centre of mass
/// more than 30° up the rising side over the second half of the rotation, from within 5° of the
/// bottom when settled, and a mean kinetic energy above 10 × the settled one); and `compute
/// pair/local` (the plugin's `single()`) reads no negative force, a largest one above a small
/// ball's weight and below the peak of a head-on impact of two large balls at twice the speed
/// bound.
#[test]
#[ignore = "live: runs LAMMPS 2025 with the paper plugin (bash scripts/test.sh)"]
fn live_a_drum_of_300_balls_turns_and_lifts_its_charge_under_the_paper_law() {
    let executable = LammpsPaper.locate().unwrap_or_else(|e| {
        panic!(
            "lammps-paper is not installed ({e}): this live test needs the LAMMPS 2025 venv and \
             its paper plugin (bash scripts/install-dem-codes.sh); it fails rather than skips"
        )
    });
    let dir = tempfile::TempDir::new().unwrap();
    let deck = root().join(DECK);
    let started = std::time::Instant::now();
    let out = executable
        .command()
        .args(["-in", deck.to_str().unwrap()])
        .args(["-log", "none", "-echo", "none", "-nocite"])
        .current_dir(dir.path())
        .env("TMPDIR", dir.path())
        .output()
        .unwrap();
    let wall = started.elapsed().as_secs_f64();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "drum: {}{text}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        text.lines().any(|l| l == format!("Created {BALLS} atoms")),
        "not {BALLS} balls created: {text}"
    );
    let loops: Vec<&str> = text
        .lines()
        .filter(|l| l.starts_with("Loop time of "))
        .collect();
    assert_eq!(loops.len(), 2, "{text}");
    for l in &loops {
        assert!(l.ends_with(&format!("with {BALLS} atoms")), "{l}");
    }
    let tables = thermo_tables(&text);
    assert_eq!(tables.len(), 2, "{text}");
    let (settle, rotate) = (&tables[0], &tables[1]);
    assert!(settle.len() > 50 && rotate.len() > 100, "{text}");
    let all = || settle.iter().chain(rotate.iter());

    let omega_and_shell = numbers(&text, "OMEGA ");
    let shell_speed = omega_and_shell[1];
    assert!(
        (shell_speed - self::shell_speed()).abs() < 1e-5,
        "the deck's shell speed {shell_speed} m/s, not {} m/s",
        self::shell_speed()
    );
    let settled = numbers(&text, "SETTLED ");
    let (settled_energy, settled_angle) = (settled[0], settled[1]);

    let radial = all().map(|r| r.radial_reach).fold(f64::MIN, f64::max);
    let axial = all().map(|r| r.axial_reach).fold(f64::MIN, f64::max);
    let fastest_settling = settle.iter().map(|r| r.fastest).fold(f64::MIN, f64::max);
    let fastest_turning = rotate.iter().map(|r| r.fastest).fold(f64::MIN, f64::max);
    let second_half: Vec<Row> = rotate[rotate.len() / 2..].to_vec();
    let mean =
        |f: fn(&Row) -> f64| second_half.iter().map(f).sum::<f64>() / second_half.len() as f64;
    let lifted_angle = mean(|r| r.centre_angle_degrees);
    let rotating_energy = mean(|r| r.kinetic_energy);
    // Rows with no pair inside the cut-off reduce over nothing (LAMMPS prints ±1e20).
    let with_pairs: Vec<&Row> = all().filter(|r| r.largest_pair_force > -1e19).collect();
    let smallest_force = with_pairs
        .iter()
        .map(|r| r.smallest_pair_force)
        .fold(f64::MAX, f64::min);
    let largest_force = with_pairs
        .iter()
        .map(|r| r.largest_pair_force)
        .fold(f64::MIN, f64::max);
    let settled_force = settle.last().unwrap().largest_pair_force;
    let force_bound =
        exact::paper_impact(&ball_pair_law(LARGEST_RADIUS), 2.0 * 3.0 * shell_speed).peak_force;
    let small_weight = ball_mass(SMALLEST_RADIUS) * 9.81;

    println!(
        "drum: {BALLS} balls, {} s settling + {} s turning at {} rad/s (shell {shell_speed} m/s), \
         wall time {wall:.1} s",
        settle.last().unwrap().time,
        rotate.last().unwrap().time - rotate[0].time,
        omega_and_shell[0]
    );
    println!(
        "settled: kinetic energy {settled_energy:e} J, centre of mass {settled_angle:.2}° from \
         the bottom, largest pair force {settled_force:.3} N"
    );
    println!(
        "turning, second half: centre of mass {lifted_angle:.1}° up the rising side, mean \
         kinetic energy {rotating_energy:.4} J ({:.0} × settled)",
        rotating_energy / settled_energy
    );
    println!(
        "fastest ball {fastest_settling:.3} m/s settling ({:.2} × shell speed), \
         {fastest_turning:.3} m/s turning ({:.2} ×); largest reach beyond the shell {radial:.2e} \
         m, beyond an end cap {axial:.2e} m; pair forces from {smallest_force} to \
         {largest_force:.1} N (bound {force_bound:.0} N, {} rows)",
        fastest_settling / shell_speed,
        fastest_turning / shell_speed,
        with_pairs.len()
    );

    assert!(radial < 1e-5, "a ball {radial} m beyond the shell");
    assert!(axial < 1e-5, "a ball {axial} m beyond an end cap");
    for fastest in [fastest_settling, fastest_turning] {
        assert!(
            fastest < 3.0 * shell_speed,
            "a ball at {fastest} m/s, above 3 × the shell speed {shell_speed} m/s"
        );
    }
    assert!(
        settled_angle.abs() < 5.0,
        "the settled charge's centre {settled_angle}° off the bottom"
    );
    assert!(
        lifted_angle > 30.0,
        "the turning charge's centre only {lifted_angle}° up"
    );
    assert!(
        rotating_energy > 10.0 * settled_energy,
        "turning {rotating_energy} J against settled {settled_energy} J"
    );
    assert!(with_pairs.len() > 100, "pair/local read no pairs: {text}");
    assert!(
        smallest_force >= 0.0,
        "an attractive pair force {smallest_force} N"
    );
    assert!(
        settled_force > small_weight,
        "the settled bed's largest pair force {settled_force} N below a small ball's weight \
         {small_weight} N"
    );
    assert!(
        largest_force < force_bound,
        "a pair force {largest_force} N above {force_bound} N"
    );
}
