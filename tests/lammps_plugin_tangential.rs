//! The paper plugin's tangential force (`tangential mindlin MU`, `tangential linear KT MU` after
//! the normal coefficients of `pair_style paper` and `fix wall/paper`), run live by LAMMPS 2025
//! with the plugin (`lammps-paper`) and checked against the closed form of Coulomb sliding
//! throughout: in one and two MPI processes (the bodies on different processes, one ball
//! changing process in the middle of its contact), newton_pair on and off.
//!
//! In gross sliding the spring is at its Coulomb bound at every step of the contact, so each
//! step's tangential force is μ times the normal force of the same step: the tangential impulse
//! is μ times the normal impulse whatever the step, and the closed form
//! `|Δv_t| = μ (1+e) v_n`, `|Δω| = 5 μ (1+e) v_n / (2R)` holds to rounding once `e` is the COR
//! the run realised. The ball on the wall meets it to 1e-12 at 50 steps per contact. Two balls
//! add geometry: their centres move apart along the contact plane as friction acts, so the
//! normal turns by up to `(1+e) μ v_n t_c / (4R)` over the contact and the fixed-axis closed
//! form holds to about `(1+e) v_n t_c / (4R)`, the bound the pair is held to (7.4e-5 here).
//!
//! The live tests FAIL (not skip) when the build is not installed.

mod common;

use std::collections::HashMap;
use std::path::Path;

use common::paper_build::run_lammps_paper;
use millimpact::codes::CodeDriver;
use millimpact::codes::lammps::paper::LammpsPaper;
use millimpact::codes::lammps::paper_plugin_modulus;
use millimpact::model::exact;
use millimpact::model::law::PaperLaw;
use millimpact::model::tangential::{
    PlaneMotion, TangentialBodies, TangentialLaw, gross_sliding_holds, gross_sliding_impulse,
};

/// The balls: 4 mm steel, E 200 GPa, ν 0.3, density 7800 kg/m³; the wall the same steel.
const RADIUS: f64 = 0.002;
const DENSITY: f64 = 7800.0;
const YOUNG: f64 = 2e11;
const POISSON: f64 = 0.3;
/// η = 0.1 (e = 0.9045).
const ETA: f64 = 0.1;
const FRICTION: f64 = 0.4;

fn mass() -> f64 {
    4.0 / 3.0 * std::f64::consts::PI * RADIUS.powi(3) * DENSITY
}

/// `G*` of two bodies of this steel: `1/G* = 2 × 2 (2 − ν)(1 + ν)/E`.
fn shear_modulus() -> f64 {
    1.0 / (2.0 * 2.0 * (2.0 - POISSON) * (1.0 + POISSON) / YOUNG)
}

/// The paper's law of a contact of reduced radius `r_star` and reduced mass `m`.
fn law(r_star: f64, m: f64) -> PaperLaw {
    PaperLaw {
        mass: m,
        stiffness: 4.0 / 3.0 * paper_plugin_modulus(YOUNG, POISSON, YOUNG, POISSON) * r_star.sqrt(),
        exponent: 1.5,
        loss_coefficient: ETA,
    }
}

/// One ball after a run: process, centre x, velocity and spin vectors.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Ball {
    proc: u32,
    x: f64,
    v: [f64; 3],
    w: [f64; 3],
}

impl Ball {
    /// Everything but the process, bit for bit: x, the velocity, the spin.
    fn state(&self) -> Vec<u64> {
        std::iter::once(self.x)
            .chain(self.v)
            .chain(self.w)
            .map(f64::to_bits)
            .collect()
    }
}

/// The balls' states by atom ID, processes left out.
fn states(balls: &HashMap<u32, Ball>) -> Vec<(u32, Vec<u64>)> {
    let mut all: Vec<_> = balls.iter().map(|(&id, b)| (id, b.state())).collect();
    all.sort_by_key(|&(id, _)| id);
    all
}

/// The build, or a failure naming how to make it.
fn require_build() {
    if let Err(e) = LammpsPaper.locate() {
        panic!(
            "lammps-paper is not installed ({e}): this live test needs the LAMMPS 2025 venv and \
             its paper plugin (bash scripts/install-dem-codes.sh, which runs \
             scripts/build-lammps-paper.sh); it fails rather than skips without it"
        );
    }
}

/// Run `deck` with `newton` in `processes` MPI processes (the venv's MPICH `mpiexec` for two)
/// and read the balls of its final `write_dump`, by atom ID.
fn run(deck: &str, newton: &str, processes: u32) -> HashMap<u32, Ball> {
    let dir = tempfile::TempDir::new().unwrap();
    std::fs::write(dir.path().join("impact.in"), deck).unwrap();
    let text = run_lammps_paper("impact.in", dir.path(), newton, processes, "impact");
    let grid = format!("{processes} by 1 by 1 MPI processor grid");
    assert!(text.contains(&grid), "not {grid}: {text}");
    read_dump(&dir.path().join("final.txt"))
}

/// The rows of `write_dump … id proc x vx vy vz omegax omegay omegaz`.
fn read_dump(path: &Path) -> HashMap<u32, Ball> {
    let text = std::fs::read_to_string(path).unwrap();
    let rows = text
        .lines()
        .skip_while(|l| !l.starts_with("ITEM: ATOMS"))
        .skip(1);
    rows.map(|row| {
        let w: Vec<f64> = row.split_whitespace().map(|x| x.parse().unwrap()).collect();
        assert_eq!(w.len(), 9, "{row}");
        let id = u32::try_from(
            row.split_whitespace()
                .next()
                .unwrap()
                .parse::<u64>()
                .unwrap(),
        )
        .unwrap();
        let proc = u32::try_from(
            row.split_whitespace()
                .nth(1)
                .unwrap()
                .parse::<u64>()
                .unwrap(),
        )
        .unwrap();
        (
            id,
            Ball {
                proc,
                x: w[2],
                v: [w[3], w[4], w[5]],
                w: [w[6], w[7], w[8]],
            },
        )
    })
    .collect()
}

/// The deck's head: the plugin, SI units, spheres, the processes side by side along x (so two
/// processes split the box at x = 0), re-neighbouring (and so exchange between processes and
/// the neighbour history's round trip) every step, two atoms of type 1 with this steel.
fn head(box_half: f64, atoms: [(f64, f64); 2]) -> String {
    let mut deck = format!(
        "plugin          load paperplugin.so\n\
         units           si\n\
         atom_style      sphere\n\
         atom_modify     map array\n\
         boundary        f f f\n\
         newton          ${{newton}}\n\
         processors      * 1 1\n\
         comm_modify     vel yes\n\
         region          box block -{box_half} {box_half} -{box_half} {box_half} -{box_half} {box_half} units box\n\
         create_box      1 box\n\
         neighbor        {skin:e} bin\n\
         neigh_modify    every 1 delay 0 check no\n",
        skin = RADIUS / 4.0,
    );
    for (x, z) in atoms {
        deck += &format!("create_atoms    1 single {x:e} 0 {z:e} units box\n");
    }
    deck += &format!(
        "set             type 1 diameter {:e}\nset             type 1 density {DENSITY:e}\n",
        2.0 * RADIUS
    );
    deck
}

/// The deck's tail: NVE with rotation, the step, the run, the final state at full precision.
fn tail(dt: f64, steps: u64) -> String {
    format!(
        "fix             integrate all nve/sphere\n\
         timestep        {dt:e}\n\
         run             {steps}\n\
         write_dump      all custom final.txt id proc x vx vy vz omegax omegay omegaz modify format float %.17g\n"
    )
}

/// Ball on the wall z = 0: `v_n` 1.2 m/s. Ball 1 arrives at `v_t` 6.0 m/s along x without
/// spin, its centre crossing x = 0 (the processes' border) at mid-contact; ball 2, at
/// x = −5 mm, arrives spinning at 3000 rad/s about y with no tangential velocity (slip
/// −6 m/s, the rigid-body threshold (7/2) μ (1+e) v_n being 3.2 m/s). Steps of
/// `t_c / steps_per_contact`, `t_c` the contact time of the paper's law.
struct WallRun {
    v_n: f64,
    v_t: f64,
    spin: f64,
    contact_time: f64,
}

fn wall_run() -> WallRun {
    let v_n = 1.2;
    WallRun {
        v_n,
        v_t: 6.0,
        spin: 3000.0,
        contact_time: exact::paper_impact(&law(RADIUS, mass()), v_n)
            .figures
            .contact_time,
    }
}

fn wall_deck(tangential: &str, steps_per_contact: f64) -> String {
    let WallRun {
        v_n,
        v_t,
        spin,
        contact_time,
    } = wall_run();
    let dt = contact_time / steps_per_contact;
    // Ten steps to contact; the run lasts two contacts.
    let gap = 10.0 * dt * v_n;
    let z = RADIUS + gap;
    let x1 = -v_t * (10.0 * dt + contact_time / 2.0);
    let mut deck = head(0.01, [(x1, z), (-0.005, z)]);
    deck += &format!(
        "set             atom 1 vx {v_t:e} vz -{v_n:e}\n\
         set             atom 2 vz -{v_n:e} omega 0 {spin:e} 0\n\
         fix             wall all wall/paper hertz {ETA:e} {YOUNG:e} {POISSON:e} {YOUNG:e} {POISSON:e} {tangential} zplane 0 NULL\n"
    );
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let steps = (2.0 * steps_per_contact) as u64 + 10;
    deck + &tail(dt, steps)
}

/// How far a ball's `(v_t', ω')` about the axis y is from the closed form of Coulomb sliding
/// throughout at the COR `e` its own normal rebound realised, relative to the closed form's
/// change: (v_t error, ω error, e).
fn wall_miss(ball: &Ball, v_n: f64, v_t: f64, spin: f64) -> (f64, f64, f64) {
    let e = ball.v[2] / v_n;
    let before = PlaneMotion {
        tangential_velocity: v_t,
        angular_velocity: spin,
    };
    let bodies = TangentialBodies {
        ball: (mass(), RADIUS, before),
        other: None,
    };
    let slip = bodies.slip();
    assert_eq!(
        gross_sliding_holds(
            &TangentialLaw::default(),
            FRICTION,
            slip,
            v_n,
            e,
            ETA,
            law(RADIUS, mass()).stiffness,
            shear_modulus(),
            RADIUS,
            1.5
        ),
        Some(true),
        "the case slides throughout"
    );
    let impulse = gross_sliding_impulse(mass(), v_n, e, FRICTION, slip);
    let (after, _) = bodies.after(impulse);
    let dv = (after.tangential_velocity - v_t).abs();
    let dw = (after.angular_velocity - spin).abs();
    (
        (ball.v[0] - after.tangential_velocity).abs() / dv,
        (ball.w[1] - after.angular_velocity).abs() / dw,
        e,
    )
}

/// The wall: Mindlin spring, μ 0.4, at 50 and 500 steps per contact (at 500 one step's slip
/// loads the spring to about a tenth of the bound at peak overlap: the force rests on the
/// history), in one and two processes, newton on and off: `v_t'` and `ω'` of the sliding ball and of the spinning one meet the
/// closed form within 1e-12 of its change (the impulses are μ times each other step by step),
/// the two-process runs hold the balls on different processes (ball 1 changed process in its
/// contact, carrying its shear history), and every run is the one-process newton-on run to the
/// bit. Nothing moves out of the plane of the impact.
#[test]
#[ignore = "live: runs LAMMPS 2025 with the paper plugin (bash scripts/test.sh)"]
fn live_the_walls_mindlin_spring_slides_as_the_closed_form() {
    require_build();
    let WallRun { v_n, v_t, spin, .. } = wall_run();
    for steps in [50.0, 500.0] {
        let deck = wall_deck(&format!("tangential mindlin {FRICTION}"), steps);
        let first = run(&deck, "on", 1);
        for (newton, processes) in [("on", 1), ("off", 1), ("on", 2), ("off", 2)] {
            let balls = run(&deck, newton, processes);
            let label =
                format!("{steps} steps per contact, newton {newton}, {processes} processes");
            assert_eq!(states(&balls), states(&first), "{label}");
            let (sliding, spinning) = (balls[&1], balls[&2]);
            if processes == 2 {
                assert!(sliding.x > 0.0 && sliding.proc == 1, "{label}: {sliding:?}");
                assert!(
                    spinning.x < 0.0 && spinning.proc == 0,
                    "{label}: {spinning:?}"
                );
            }
            let (dv, dw, e) = wall_miss(&sliding, v_n, v_t, 0.0);
            eprintln!(
                "wall, sliding, {label}: e {e:.12} v_t' {:.15} ω' {:.12} misses {dv:.1e} {dw:.1e}",
                sliding.v[0], sliding.w[1]
            );
            assert!(dv < 1e-12 && dw < 1e-12, "{label}: {dv:e} {dw:e}");
            let (dv, dw, e) = wall_miss(&spinning, v_n, 0.0, spin);
            eprintln!(
                "wall, spinning, {label}: e {e:.12} v_t' {:.15} ω' {:.12} misses {dv:.1e} {dw:.1e}",
                spinning.v[0], spinning.w[1]
            );
            assert!(dv < 1e-12 && dw < 1e-12, "{label}: {dv:e} {dw:e}");
            for ball in [sliding, spinning] {
                assert_eq!(ball.v[1].to_bits(), 0f64.to_bits(), "{label}: {ball:?}");
                assert_eq!(ball.w[0].to_bits(), 0f64.to_bits(), "{label}: {ball:?}");
                assert_eq!(ball.w[2].to_bits(), 0f64.to_bits(), "{label}: {ball:?}");
            }
        }
    }
}

/// The wall with a linear spring stiff enough to stay at the bound (k_t 5e7 N/m, twice
/// Mindlin's at this impact's peak overlap) slides as the closed form too; without the
/// tangential words the impact is frictionless: `v_t` leaves as it came and nothing spins, and
/// the normal rebound is the Mindlin run's to the bit (the normal force does not see the
/// tangential one on a flat wall).
#[test]
#[ignore = "live: runs LAMMPS 2025 with the paper plugin (bash scripts/test.sh)"]
fn live_the_walls_linear_spring_slides_and_no_keyword_is_frictionless() {
    require_build();
    let WallRun { v_n, v_t, spin, .. } = wall_run();
    let linear = run(
        &wall_deck(&format!("tangential linear 5e7 {FRICTION}"), 100.0),
        "on",
        2,
    );
    for (id, v_t, spin) in [(1, v_t, 0.0), (2, 0.0, spin)] {
        let (dv, dw, e) = wall_miss(&linear[&id], v_n, v_t, spin);
        eprintln!("wall, linear spring, ball {id}: e {e:.12} misses {dv:.1e} {dw:.1e}");
        assert!(dv < 1e-12 && dw < 1e-12, "ball {id}: {dv:e} {dw:e}");
    }
    let none = run(&wall_deck("", 100.0), "on", 2);
    let mindlin = run(
        &wall_deck(&format!("tangential mindlin {FRICTION}"), 100.0),
        "on",
        2,
    );
    assert_eq!(none[&1].v[0].to_bits(), v_t.to_bits());
    assert_eq!(none[&1].w.map(f64::to_bits), [0f64.to_bits(); 3]);
    assert_eq!(none[&2].v[0].to_bits(), 0f64.to_bits());
    assert_eq!(
        none[&2].w.map(f64::to_bits),
        [0.0, spin, 0.0].map(f64::to_bits)
    );
    for id in [1, 2] {
        assert_eq!(
            none[&id].v[2].to_bits(),
            mindlin[&id].v[2].to_bits(),
            "ball {id}"
        );
        assert!((none[&id].v[2] / v_n - exact::restitution(ETA)).abs() < 1e-3);
    }
}

/// Two balls meeting head on along x at `v_n` (each at `v_n/2`), ball 1 at x > 0 and ball 2 at
/// x < 0 (so on different processes in two), both spinning at `spin` about z: the contact slips
/// at `−2 R spin` along y while the centres have no tangential velocity.
fn pair_deck(v_n: f64, spin: f64, steps_per_contact: f64) -> (String, f64) {
    let m = mass();
    let contact_time = exact::paper_impact(&law(RADIUS / 2.0, m / 2.0), v_n)
        .figures
        .contact_time;
    let dt = contact_time / steps_per_contact;
    let gap = 10.0 * dt * v_n;
    let x = RADIUS + gap / 2.0;
    let mut deck = head(0.01, [(x, 0.0), (-x, 0.0)]);
    deck += &format!(
        "set             atom 1 vx -{half:e} omega 0 0 {spin:e}\n\
         set             atom 2 vx {half:e} omega 0 0 {spin:e}\n\
         pair_style      paper\n\
         pair_coeff      * * {ETA:e} {YOUNG:e} {POISSON:e} tangential mindlin {FRICTION}\n",
        half = v_n / 2.0
    );
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let steps = (2.0 * steps_per_contact) as u64 + 10;
    (deck + &tail(dt, steps), contact_time)
}

/// The pair: Mindlin spring, μ 0.4, 4 mm steel balls meeting at 0.01 m/s spinning at 20 rad/s
/// (slip 0.08 m/s, 3 times the rigid-body threshold), 1000 steps per contact (one step's slip
/// loads the spring to under a tenth of the bound at peak overlap: the force rests on the
/// history kept in LAMMPS' neighbour history, re-neighboured every step), in one and two
/// processes (one ball on each), newton_pair on and off, every run the first to the bit: each
/// ball's `v_t'` and `ω'` against `TangentialBodies::after` with the gross-sliding impulse at
/// the realised COR, within the geometric bound `(1+e) v_n t_c / (4R)` of the change (the
/// normal turns as the centres part along y).
#[test]
#[ignore = "live: runs LAMMPS 2025 with the paper plugin (bash scripts/test.sh)"]
fn live_a_spinning_pair_slides_as_the_closed_form_on_one_and_two_processes() {
    require_build();
    let (v_n, spin) = (0.01, 20.0);
    let (deck, contact_time) = pair_deck(v_n, spin, 1000.0);
    let first = run(&deck, "on", 1);
    let m = mass();
    for (newton, processes) in [("on", 1), ("off", 1), ("on", 2), ("off", 2)] {
        let balls = run(&deck, newton, processes);
        let label = format!("newton {newton}, {processes} processes");
        assert_eq!(states(&balls), states(&first), "{label}");
        let (one, two) = (balls[&1], balls[&2]);
        if processes == 2 {
            assert!(one.proc == 1 && two.proc == 0, "{label}: {one:?} {two:?}");
        }
        let e = (one.v[0] - two.v[0]) / v_n;
        let motion = PlaneMotion {
            tangential_velocity: 0.0,
            angular_velocity: spin,
        };
        let bodies = TangentialBodies {
            ball: (m, RADIUS, motion),
            other: Some((m, RADIUS, motion)),
        };
        let slip = bodies.slip();
        assert!((slip + 2.0 * RADIUS * spin).abs() < 1e-15);
        assert_eq!(
            gross_sliding_holds(
                &TangentialLaw::default(),
                FRICTION,
                slip,
                v_n,
                e,
                ETA,
                law(RADIUS / 2.0, m / 2.0).stiffness,
                shear_modulus(),
                RADIUS / 2.0,
                1.5
            ),
            Some(true)
        );
        let (a, b) = bodies.after(gross_sliding_impulse(m / 2.0, v_n, e, FRICTION, slip));
        let b = b.unwrap();
        let change = (a.tangential_velocity).abs();
        let spin_change = (a.angular_velocity - spin).abs();
        let bound = (1.0 + e) * v_n * contact_time / (4.0 * RADIUS);
        let misses = [
            (one.v[1] - a.tangential_velocity).abs() / change,
            (two.v[1] - b.tangential_velocity).abs() / change,
            (one.w[2] - a.angular_velocity).abs() / spin_change,
            (two.w[2] - b.angular_velocity).abs() / spin_change,
        ];
        eprintln!(
            "pair, {label}: e {e:.12} v_t' {:.15} {:.15} ω' {:.12} {:.12} misses {} (bound {bound:.1e})",
            one.v[1],
            two.v[1],
            one.w[2],
            two.w[2],
            misses.map(|x| format!("{x:.1e}")).join(" ")
        );
        assert!(misses.iter().all(|&x| x < bound), "{label}: {misses:?}");
    }
}

// ---------------------------------------------------------------------------------------------
// The deck reader (no binary needed).

/// The shipped plugin deck with `edit` applied, written to a scratch file named `in.paper`.
fn edited_mill(edit: impl Fn(String) -> String) -> (tempfile::TempDir, std::path::PathBuf) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text =
        std::fs::read_to_string(root.join("tests/data/deck/lammps-paper/in.paper_mill")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("in.paper");
    std::fs::write(&path, edit(text)).unwrap();
    (dir, path)
}

/// A deck whose plugin lines carry the tangential words is read, not refused: each pair keeps
/// the paper's law of its normal coefficients, says which tangential force its line gives,
/// and the impacts carry the lines as written.
#[test]
fn a_deck_with_the_plugins_tangential_words_is_read() {
    let (_dir, path) = edited_mill(|t| {
        t.replace(
            "pair_coeff      1 1 0.35 ${steel_E} 0.3\n",
            "pair_coeff      1 1 0.35 ${steel_E} 0.3 tangential mindlin 0.4\n",
        )
        .replace(
            "pair_coeff      2 2 0.30 ${steel_E} 0.3\n",
            "pair_coeff      2 2 0.30 ${steel_E} 0.3 tangential linear 2e6 0.3\n",
        )
        .replace(
            "wall/paper hertz 0.25 ${steel_E} 0.3 ${steel_E} 0.3 zplane",
            "wall/paper hertz 0.25 ${steel_E} 0.3 ${steel_E} 0.3 tangential mindlin 0.5 zplane",
        )
    });
    let (_, deck) = millimpact::analysis::deck::read_deck(
        &path,
        None,
        &millimpact::codes::deck::DeckOptions::default(),
    )
    .unwrap();
    use millimpact::codes::deck::TypeRef::{Type, Wall};
    let traps = |types: [millimpact::codes::deck::TypeRef; 2]| {
        let c = deck.contacts.iter().find(|c| c.types == types).unwrap();
        let millimpact::model::law::CodeLaw::Paper(law) = c.law else {
            panic!("{:?}", c.law)
        };
        (law.loss_coefficient, c.traps.join(" | "))
    };
    let (eta, t) = traps([Type(1), Type(1)]);
    assert!((eta - 0.35).abs() < 1e-15);
    assert!(
        t.contains("tangential mindlin 0.4: k_t = 8 G* sqrt(R* δ)"),
        "{t}"
    );
    let (eta, t) = traps([Type(2), Type(2)]);
    assert!((eta - 0.30).abs() < 1e-15);
    assert!(t.contains("tangential linear 2000000 0.3"), "{t}");
    let (_, t) = traps([Type(1), Wall]);
    assert!(t.contains("tangential mindlin 0.5"), "{t}");
    let (_, t) = traps([Type(1), Type(3)]);
    assert!(!t.contains("tangential"), "{t}");
    assert!(
        deck.transplant.walls[0].contains("tangential mindlin 0.5 zplane 0 NULL"),
        "{:?}",
        deck.transplant.walls
    );
}

/// Bad tangential words are refused before a run, in one line naming the file and line, the
/// word and its value, and what is allowed (exit 2).
#[test]
fn bad_tangential_words_are_refused_in_one_line() {
    let pair = "pair_coeff      2 3 0.50 ${steel_E} 0.3 ${alumina_E} 0.22";
    let cases: [(&str, String, &str); 5] = [
        (
            "a negative μ",
            format!("{pair} tangential mindlin -0.2"),
            "in.paper:22: tangential MU = -0.2; supported: a finite MU >= 0",
        ),
        (
            "a zero k_t",
            format!("{pair} tangential linear 0 0.3"),
            "in.paper:22: tangential KT = 0; supported: KT > 0",
        ),
        (
            "an unknown model",
            format!("{pair} tangential mindlin/rescale 0.3"),
            "in.paper:22: tangential model `mindlin/rescale`; supported: tangential mindlin MU, or tangential linear KT MU",
        ),
        (
            "a missing μ",
            format!("{pair} tangential linear 1e6"),
            "in.paper:22: `tangential linear 1e6` (3 words); supported: tangential mindlin MU, or tangential linear KT MU",
        ),
        (
            "μ not a number",
            format!("{pair} tangential mindlin rough"),
            "in.paper:22: tangential MU `rough` is not a number",
        ),
    ];
    for (what, line, expected) in cases {
        let (_dir, path) = edited_mill(|t| t.replace(pair, &line));
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_millimpact"))
            .args(["deck"])
            .arg(&path)
            .args(["--impact-velocity", "2"])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{what}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.lines().count(), 1, "{what}: {err}");
        assert!(err.contains(expected), "{what}: {err}");
    }
}

// ---------------------------------------------------------------------------------------------
// A poured bed with friction: many contacts per sphere, atoms changing process.

/// 245 glass-like spheres (r 5 mm, ρ 2500, E 100 MPa, ν 0.3, η 0.5) thrown sideways into a
/// box of wall/paper planes under gravity, `tangential` words on the pair and the walls (the
/// floor with a linear spring), the processes' border moved by `fix balance` (a fix that
/// migrates atoms in pre_exchange, which LAMMPS' neighbour history must precede); kinetic and
/// rotational energy at 0.1 s and 0.6 s.
fn bed_deck(tangential: bool) -> String {
    let (mindlin, linear) = if tangential {
        ("tangential mindlin 0.5", "tangential linear 2e4 0.5")
    } else {
        ("", "")
    };
    let wall = "wall/paper hertz 0.5 1e8 0.3 1e8 0.3";
    format!(
        "plugin          load paperplugin.so\n\
         units           si\n\
         atom_style      sphere\n\
         atom_modify     map array\n\
         boundary        f f f\n\
         newton          ${{newton}}\n\
         processors      * 1 1\n\
         comm_modify     vel yes\n\
         region          box block -0.05 0.05 -0.05 0.05 0 0.2 units box\n\
         create_box      1 box\n\
         lattice         sc 0.012\n\
         region          fill block -0.04 0.04 -0.04 0.04 0.012 0.07 units box\n\
         create_atoms    1 region fill\n\
         displace_atoms  all random 0.001 0.001 0.001 4821 units box\n\
         set             type 1 diameter 0.01\n\
         set             type 1 density 2500\n\
         velocity        all set 0.3 0 -0.5 units box\n\
         pair_style      paper\n\
         pair_coeff      * * 0.5 1e8 0.3 {mindlin}\n\
         fix             xwalls all {wall} {mindlin} xplane -0.05 0.05\n\
         fix             ywalls all {wall} {mindlin} yplane -0.05 0.05\n\
         fix             floor all {wall} {linear} zplane 0 NULL\n\
         fix             balance all balance 1000 1.1 shift x 10 1.1\n\
         fix             gravity all gravity 9.81 vector 0 0 -1\n\
         fix             integrate all nve/sphere\n\
         neighbor        0.002 bin\n\
         neigh_modify    delay 0\n\
         compute         rke all erotate/sphere\n\
         thermo_style    custom step atoms ke c_rke\n\
         timestep        2e-5\n\
         thermo          5000\n\
         run             5000\n\
         print           \"BED 0.1 $(ke:%.10g) $(c_rke:%.10g) $(count(all))\"\n\
         run             25000\n\
         print           \"BED 0.6 $(ke:%.10g) $(c_rke:%.10g) $(count(all))\"\n\
         write_dump      all custom final.txt id proc x vx vy vz omegax omegay omegaz modify format float %.17g\n"
    )
}

/// The bed's printed energies: `[(kinetic, rotational, atoms) at 0.1 s, at 0.6 s]`, J.
fn bed(tangential: bool, newton: &str, processes: u32) -> [(f64, f64, f64); 2] {
    let dir = tempfile::TempDir::new().unwrap();
    std::fs::write(dir.path().join("bed.in"), bed_deck(tangential)).unwrap();
    let text = run_lammps_paper("bed.in", dir.path(), newton, processes, "bed");
    let at = |time: &str| {
        let prefix = format!("BED {time} ");
        let line = text
            .lines()
            .find(|l| l.starts_with(&prefix))
            .unwrap_or_else(|| panic!("no `{prefix}` line: {text}"));
        let w: Vec<f64> = line[prefix.len()..]
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect();
        (w[0], w[1], w[2])
    };
    [at("0.1"), at("0.6")]
}

/// The bed with friction runs in one and two processes, newton_pair on and off (every sphere
/// kept, several history partners each, atoms crossing between processes): friction spins the
/// spheres (rotational energy above a tenth of the translational at 0.1 s) and the bed settles
/// (less than 1 % of the 0.1 s kinetic energy left at 0.6 s, spin included); without the words
/// nothing spins at all.
#[test]
#[ignore = "live: runs LAMMPS 2025 with the paper plugin (bash scripts/test.sh)"]
fn live_a_poured_bed_with_friction_spins_and_settles_on_one_and_two_processes() {
    require_build();
    for (newton, processes) in [("on", 1), ("off", 1), ("on", 2), ("off", 2)] {
        let [(k0, r0, n0), (k1, r1, n1)] = bed(true, newton, processes);
        let label = format!("newton {newton}, {processes} processes");
        eprintln!("bed, {label}: 0.1 s {k0:e} J + {r0:e} J spin; 0.6 s {k1:e} J + {r1:e} J spin");
        assert!(
            (n0 - 245.0).abs() < 0.5 && (n1 - 245.0).abs() < 0.5,
            "{label}: {n0} {n1} atoms"
        );
        assert!(r0 > 0.1 * k0, "{label}: {r0} J spin of {k0} J");
        assert!(k1 + r1 < 1e-2 * (k0 + r0), "{label}: {k1} + {r1} J left");
    }
    let [(_, r0, _), (_, r1, _)] = bed(false, "on", 1);
    assert_eq!((r0.to_bits(), r1.to_bits()), (0, 0), "frictionless");
}

/// The plugin's tangential refusals stop LAMMPS with its own ERROR line (exit status 1): Mindlin
/// on a linear normal law, KT <= 0, μ < 0, a word missing, an unknown model, on the pair and on
/// the wall.
#[test]
#[ignore = "live: runs LAMMPS 2025 with the paper plugin (bash scripts/test.sh)"]
fn live_the_plugins_tangential_refusals_are_lammps_errors() {
    require_build();
    let pair = |style: &str, coeff: &str| {
        head(0.01, [(0.003, 0.0), (-0.003, 0.0)])
            + &format!("pair_style      {style}\npair_coeff      * * {coeff}\n")
            + &tail(1e-7, 1)
    };
    let wall = |words: &str| {
        head(0.01, [(0.003, 0.003), (-0.003, 0.003)])
            + &format!("fix             w all wall/paper {words} zplane 0 NULL\n")
            + &tail(1e-7, 1)
    };
    let cases = [
        (
            pair("paper/linear", "0.1 1e6 tangential mindlin 0.4"),
            "ERROR: pair paper/linear: tangential mindlin needs the bodies' E and nu",
        ),
        (
            pair("paper", "0.1 2e11 0.3 tangential linear 0 0.4"),
            "ERROR: pair paper: tangential KT must be positive, got 0",
        ),
        (
            pair("paper", "0.1 2e11 0.3 tangential mindlin -0.4"),
            "ERROR: pair paper: tangential MU must be finite and >= 0, got -0.4",
        ),
        (
            pair("paper", "0.1 2e11 0.3 tangential linear 1e6"),
            "ERROR: pair paper: tangential linear KT MU (got 3 words)",
        ),
        (
            wall("hertz 0.1 2e11 0.3 2e11 0.3 tangential history 0.4"),
            "ERROR: fix wall/paper: unknown tangential model history",
        ),
        (
            wall("linear 0.1 1e6 tangential mindlin 0.4"),
            "ERROR: fix wall/paper: tangential mindlin needs the bodies' E and nu",
        ),
    ];
    let executable = LammpsPaper.locate().unwrap();
    for (deck, wanted) in cases {
        let dir = tempfile::TempDir::new().unwrap();
        std::fs::write(dir.path().join("impact.in"), &deck).unwrap();
        let out = executable
            .command()
            .args(["-in", "impact.in", "-var", "newton", "on"])
            .args(["-log", "none", "-echo", "none", "-nocite"])
            .current_dir(dir.path())
            .env("TMPDIR", dir.path())
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&out.stdout);
        assert_eq!(out.status.code(), Some(1), "{wanted}: {text}");
        assert!(
            text.lines().any(|l| l.starts_with(wanted)),
            "{wanted}: {text}"
        );
    }
}
