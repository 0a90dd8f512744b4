//! LIGGGHTS with the paper's law (`liggghts-paper`) on contacts at rest, run live on decks
//! written as LIGGGHTS users write them (gravity, `fix wall/gran ... store_force yes`, thermo
//! variables, `insert/pack`):
//!
//! - balls resting on a plate and on each other carry their weight with a force that does not
//!   alternate from step to step (`model paper` and `model paper/linear`, η = 0.3 and 0.6);
//! - a non-rotating ball (`fix nve`: no rotation, so static friction alone holds it) with
//!   μ = 0.5 holds on a 25° incline and slides at 28° (atan μ = 26.57°), η = 0.3 and 0.6;
//! - a bed of 128 spheres poured into a box comes to rest as LIGGGHTS's hertz does with the
//!   same tangential model, and its floor carries it with a force that does not alternate.
//!
//! Before the sign of ẏ was resolved to one step (normal_model_paper.h, `branchFactor`), the
//! half-step velocity of a resting contact flipped every step and the force alternated between
//! about (1 + η) and (1 − η) times the load; each test here failed on that build.
//!
//! The live tests FAIL (not skip) when the build is not installed.

use std::process::Command;

use millimpact::codes::CodeDriver;
use millimpact::codes::liggghts::paper::LiggghtsPaper;

const GRAVITY: f64 = 9.81;
const DENSITY: f64 = 7800.0;
const RADIUS: f64 = 0.005;
const TIMESTEP: f64 = 1e-6;
const FRICTION: f64 = 0.5;

/// Mass of one ball as LIGGGHTS's `set density` forms it, kg.
fn ball_mass() -> f64 {
    4.0 * std::f64::consts::PI / 3.0 * RADIUS.powi(3) * DENSITY
}

/// The normal model's lines: its style and its per-type properties, steel for `paper`, a
/// stiffness of 1e7 N/m for `paper/linear`.
fn contact(model: &str, eta: f64) -> String {
    let eta_line = format!(
        "fix m3 all property/global lossCoefficient peratomtypepair 2 {eta} {eta} {eta} {eta}"
    );
    let friction = format!(
        "fix m4 all property/global coefficientFriction peratomtypepair 2 {FRICTION} {FRICTION} {FRICTION} {FRICTION}"
    );
    let material = match model {
        "paper" => "fix m1 all property/global youngsModulus peratomtype 2e11 2e11\n\
                    fix m2 all property/global poissonsRatio peratomtype 0.3 0.3"
            .to_string(),
        "paper/linear" => "fix m1 all property/global kn peratomtypepair 2 1e7 1e7 1e7 1e7\n\
                           fix m2 all property/global kt peratomtypepair 2 2.857e6 2.857e6 2.857e6 2.857e6"
            .to_string(),
        "hertz" => "fix m1 all property/global youngsModulus peratomtype 2e11 2e11\n\
                    fix m2 all property/global poissonsRatio peratomtype 0.3 0.3"
            .to_string(),
        other => panic!("no deck for model {other}"),
    };
    let damping = if model == "hertz" {
        let e = ((1.0 - eta) / (1.0 + eta)).sqrt();
        format!(
            "fix m3 all property/global coefficientRestitution peratomtypepair 2 {e} {e} {e} {e}"
        )
    } else {
        eta_line
    };
    format!("{material}\n{damping}\n{friction}")
}

/// A deck's head: SI units, a box, the contact model `model` with loss coefficient η, the
/// step and gravity along `gravity` (a unit vector).
fn head(model: &str, eta: f64, region: &str, gravity: [f64; 3]) -> String {
    let settings = if model == "hertz" {
        " tangential_damping off"
    } else {
        ""
    };
    format!(
        "atom_style      granular
atom_modify     map array
boundary        f f f
newton          off
communicate     single vel yes
units           si
hard_particles  yes
region          domain block {region} units box
create_box      2 domain
neighbor        0.001 bin
neigh_modify    delay 0
{contact}
pair_style      gran model {model} tangential history{settings}
pair_coeff      * *
timestep        {TIMESTEP}
fix             gravi all gravity {GRAVITY} vector {} {} {}
",
        gravity[0],
        gravity[1],
        gravity[2],
        contact = contact(model, eta),
    )
}

/// Run `deck` with the installed build in a fresh folder; the thermo rows whose columns are
/// all numbers, each as its numbers.
fn run_deck(deck: &str) -> Vec<Vec<f64>> {
    let executable = LiggghtsPaper.locate().unwrap_or_else(|e| {
        panic!(
            "liggghts-paper is not installed ({e}): this live test needs LIGGGHTS built with the \
             paper's model (bash scripts/build-liggghts-paper.sh); it fails rather than skips"
        )
    });
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in.deck");
    std::fs::write(&input, deck).unwrap();
    let output = Command::new(&executable.program)
        .envs(executable.env.iter().map(|(k, v)| (k, v)))
        .args(["-in", "in.deck", "-log", "none", "-echo", "none"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success() && !stdout.contains("ERROR"),
        "liggghts-paper failed on\n{deck}\n{stdout}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    thermo_rows(&stdout)
}

/// The rows of LIGGGHTS's thermo output: lines of numbers only, after a `Step` header.
fn thermo_rows(stdout: &str) -> Vec<Vec<f64>> {
    let mut rows = Vec::new();
    let mut in_table = false;
    for line in stdout.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.first() == Some(&"Step") {
            in_table = true;
            continue;
        }
        let numbers: Option<Vec<f64>> = words.iter().map(|w| w.parse().ok()).collect();
        match numbers {
            Some(numbers) if in_table && !numbers.is_empty() => rows.push(numbers),
            _ => in_table = false,
        }
    }
    rows
}

/// Two balls stacked on a plate, settled for 0.1 s, then 200 steps printed: the plate carries
/// both (its stored wall force) and the upper ball, resting on the lower, feels no net force,
/// each step within 1e-3 of the weight, for `model paper` and `model paper/linear` at η = 0.3
/// and 0.6 (sphere–wall and sphere–sphere contacts at rest).
#[test]
#[ignore = "live: runs liggghts-paper (bash scripts/test.sh)"]
fn live_balls_at_rest_carry_their_weight_without_alternating() {
    let weight = ball_mass() * GRAVITY;
    for model in ["paper", "paper/linear"] {
        for eta in [0.3, 0.6] {
            let deck = format!(
                "{}fix             plate all wall/gran model {model} tangential history primitive type 2 zplane 0.0 store_force yes
create_atoms    1 single 0.0 0.0 0.0051 units box
create_atoms    1 single 0.0 0.0 0.0153 units box
set             atom * diameter {} density {DENSITY}
fix             integr all nve/sphere
compute         floor all reduce sum f_force_plate[3]
variable        upper equal fz[2]
thermo_style    custom step c_floor v_upper
thermo          50000
run             100000
thermo          1
run             200
",
                head(model, eta, "-0.01 0.01 -0.01 0.01 -0.001 0.03", [0.0, 0.0, -1.0]),
                2.0 * RADIUS
            );
            let rows = run_deck(&deck);
            let last: Vec<&Vec<f64>> = rows.iter().filter(|r| r[0] > 100_000.0).collect();
            assert_eq!(last.len(), 200, "{model} η={eta}: {rows:?}");
            let worst = |column: usize, reference: f64, load: f64| {
                last.iter()
                    .map(|r| (r[column] - reference).abs() / load)
                    .fold(0.0, f64::max)
            };
            println!(
                "{model} η={eta}: plate force off 2 m g by at most {:.1e} of it, upper ball's net force at most {:.1e} of m g",
                worst(1, 2.0 * weight, 2.0 * weight),
                worst(2, 0.0, weight)
            );
            for row in last {
                let (floor, upper) = (row[1], row[2]);
                assert!(
                    (floor - 2.0 * weight).abs() < 1e-3 * 2.0 * weight,
                    "{model} η={eta} step {}: the plate carries {floor} N, the balls weigh {} N",
                    row[0],
                    2.0 * weight
                );
                assert!(
                    upper.abs() < 1e-3 * weight,
                    "{model} η={eta} step {}: net force {upper} N on the upper ball (weight {weight} N)",
                    row[0]
                );
            }
        }
    }
}

/// Where a non-rotating ball placed on a plate tilted by `angle_degrees` (gravity tilted) is
/// after 0.2 s, m along the slope (from its start).
fn incline_travel(eta: f64, angle_degrees: f64) -> f64 {
    let angle = angle_degrees.to_radians();
    let deck = format!(
        "{}fix             plate all wall/gran model paper tangential history primitive type 2 zplane 0.0
create_atoms    1 single 0.0 0.0 {RADIUS} units box
set             atom 1 diameter {} density {DENSITY}
fix             integr all nve
variable        x equal x[1]
thermo_style    custom step v_x
thermo          200000
run             200000
",
        head(
            "paper",
            eta,
            "-0.5 0.5 -0.01 0.01 -0.001 0.02",
            [angle.sin(), 0.0, -angle.cos()]
        ),
        2.0 * RADIUS
    );
    let rows = run_deck(&deck);
    let end = rows.last().unwrap_or_else(|| panic!("no thermo rows"));
    assert!((end[0] - 200_000.0).abs() < 0.5, "{rows:?}");
    end[1]
}

/// A ball that cannot rotate (`fix nve`) with μ = 0.5 on the paper's contact: at 25° (below
/// atan μ = 26.57°) it stays put to the tangential spring's stretch (under 1 µm in 0.2 s); at
/// 28° it slides as Coulomb friction μ m g cos θ lets it, ½ g (sin θ − μ cos θ) t² to 2 %.
/// Before, the Coulomb limit flipped with the normal force and the ball slid from 20°.
#[test]
#[ignore = "live: runs liggghts-paper (bash scripts/test.sh)"]
fn live_a_ball_on_an_incline_holds_below_the_friction_angle() {
    for eta in [0.3, 0.6] {
        let held = incline_travel(eta, 25.0);
        println!("η={eta}, 25°: moved {held:.3e} m in 0.2 s");
        assert!(held.abs() < 1e-6, "η={eta}, 25°: moved {held} m");
        let angle = 28.0_f64.to_radians();
        let expected = 0.5 * GRAVITY * (angle.sin() - FRICTION * angle.cos()) * 0.2 * 0.2;
        let slid = incline_travel(eta, 28.0);
        println!("η={eta}, 28°: slid {slid:.4e} m in 0.2 s (Coulomb friction: {expected:.4e} m)");
        assert!(
            (slid - expected).abs() < 0.02 * expected,
            "η={eta}, 28°: slid {slid} m, Coulomb friction gives {expected} m"
        );
    }
}

/// 128 steel balls (R 5 mm, `insert/pack`) poured into a 6 × 6 cm box, 1 s; the kinetic energy
/// (translation and rotation) at the end, J, and the floor's force (`store_force`) over the
/// last six steps, N.
fn bed(model: &str, eta: f64) -> (f64, Vec<f64>) {
    let settings = if model == "hertz" {
        " tangential_damping off"
    } else {
        ""
    };
    let walls: String = [
        ("floor", "zplane 0.0", " store_force yes"),
        ("left", "xplane -0.03", ""),
        ("right", "xplane 0.03", ""),
        ("front", "yplane -0.03", ""),
        ("back", "yplane 0.03", ""),
    ]
    .iter()
    .map(|(id, plane, store)| {
        format!(
            "fix             {id} all wall/gran model {model} tangential history primitive type 2 {plane}{store}{settings}\n"
        )
    })
    .collect();
    let deck = format!(
        "{}{walls}region          fill block -0.025 0.025 -0.025 0.025 0.006 0.11 units box
fix             pts all particletemplate/sphere 15485863 atom_type 1 density constant {DENSITY} radius constant {RADIUS}
fix             pdd all particledistribution/discrete 32452843 1 pts 1.0
fix             ins all insert/pack seed 32452867 distributiontemplate pdd insert_every once overlapcheck yes all_in yes particles_in_region 150 region fill
fix             integr all nve/sphere
compute         rotation all erotate/sphere
compute         floor all reduce sum f_force_floor[3]
thermo_style    custom step atoms ke c_rotation c_floor
thermo_modify   norm no
thermo          100000
run             1000000
thermo          1
run             5
",
        head(model, eta, "-0.03 0.03 -0.03 0.03 0.0 0.12", [0.0, 0.0, -1.0])
    );
    let rows = run_deck(&deck);
    let last: Vec<&Vec<f64>> = rows.iter().filter(|r| r[0] >= 1_000_000.0).collect();
    assert!(last.len() >= 6, "{model}: {rows:?}");
    assert!(
        last.iter().all(|r| (r[1] - 128.0).abs() < 0.5),
        "{model}: {rows:?}"
    );
    let end = last[last.len() - 1];
    (end[2] + end[3], last.iter().map(|r| r[4]).collect())
}

/// A poured bed comes to rest: after 1 s its kinetic energy is below 1e-6 J (from 0.06 J while
/// falling; 1e-6 J is a speed of 1.4e-4 m/s per ball) for `model paper` at η = 0.3 as for
/// `model hertz` at the same COR with the same tangential model (a Coulomb spring without
/// dashpot: `tangential_damping off`, since the paper's law has no tangential damping); and the
/// floor carries the paper's bed with a force that varies by less than 1e-3 of the bed's
/// weight from step to step (before: ±12 %).
#[test]
#[ignore = "live: runs liggghts-paper (bash scripts/test.sh)"]
fn live_a_poured_bed_comes_to_rest_as_hertz_does() {
    let weight = 128.0 * ball_mass() * GRAVITY;
    let (hertz_energy, hertz_floor) = bed("hertz", 0.3);
    println!("hertz: kinetic energy {hertz_energy:.2e} J after 1 s, floor {hertz_floor:?} N");
    assert!(hertz_energy < 1e-6, "hertz: {hertz_energy} J after 1 s");
    let (paper_energy, floor) = bed("paper", 0.3);
    println!(
        "paper: kinetic energy {paper_energy:.2e} J after 1 s, floor {floor:?} N (weight {weight} N)"
    );
    assert!(paper_energy < 1e-6, "paper: {paper_energy} J after 1 s");
    for pair in floor.windows(2) {
        assert!(
            (pair[1] - pair[0]).abs() < 1e-3 * weight,
            "the floor's force {floor:?} N alternates (the bed weighs {weight} N)"
        );
    }
    assert!(
        floor.iter().all(|f| (f - weight).abs() < 0.1 * weight),
        "the floor carries {floor:?} N of a {weight} N bed"
    );
}
