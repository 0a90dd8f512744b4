//! What `tangential mindlin NULL` gives a `fix wall/gran granular hertz/material` wall in each
//! stock LAMMPS build, measured: the same sliding impact run with `NULL` and with each
//! candidate stiffness written out. A run is deterministic, so the `NULL` run equals, to every
//! printed digit, the run given the stiffness the build really forms.
//!
//! The 2021 build's `fix_wall_gran.cpp` forms `E (2−ν)(1+ν)/4` (the compliance's factors
//! multiplied where they divide), 0.61 of Mindlin's `8 G* = 2E/((2−ν)(1+ν))` for ν = 0.3, which
//! its `pair_granular.cpp` and the 2025 build form; with a tangential dashpot the difference
//! decides how much of Coulomb's impulse a wall delivers (the book's tangential page).

use std::path::Path;

use millimpact::codes::CodeName;

const YOUNG: f64 = 2.0e11;
const POISSON: f64 = 0.3;

/// A 6 mm steel ball at 1 m/s onto the wall and 5 m/s along it, 10,000 steps of 2e-8 s, the
/// wall's tangential damping `XT = 1`, μ 0.3; prints the ball's velocity along the wall and
/// off it after.
fn input(young: f64, tangential_stiffness: &str) -> String {
    format!(
        "units si\natom_style sphere\ndimension 3\nboundary p p f\natom_modify map array\n\
         region box block -0.05 0.05 -0.05 0.05 0.0 0.02\ncreate_box 1 box\n\
         create_atoms 1 single 0.0 0.0 0.0031 units box\n\
         set atom 1 diameter 0.006 density 7800.0\nvelocity all set 5.0 0.0 -1.0 units box\n\
         comm_modify vel yes\nneighbor 0.001 bin\npair_style none\ntimestep 2e-8\n\
         fix integrate all nve/sphere\n\
         fix wall all wall/gran granular hertz/material {young:e} 0.6 {POISSON} damping tsuji \
         tangential mindlin {tangential_stiffness} 1.0 0.3 zplane 0.0 NULL\n\
         thermo 10000\nrun 10000\nvariable vx equal vx[1]\nvariable vz equal vz[1]\n\
         print \"AFTER ${{vx}} ${{vz}}\"\n"
    )
}

/// The ball's `(v_t, v_n)` after the impact in `code`'s wall of modulus `young` and
/// tangential stiffness `tangential_stiffness` as written, as the build prints them.
fn after(code: CodeName, young: f64, tangential_stiffness: &str, dir: &Path) -> (String, String) {
    let path = dir.join("in.wall");
    std::fs::write(&path, input(young, tangential_stiffness)).unwrap();
    let out = code
        .driver()
        .locate()
        .unwrap_or_else(|e| panic!("{code} is installed: {e}"))
        .command()
        .current_dir(dir)
        .args(["-log", "none", "-echo", "none", "-in"])
        .arg(&path)
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{log}");
    let line = log
        .lines()
        .find_map(|l| l.strip_prefix("AFTER "))
        .unwrap_or_else(|| panic!("no AFTER line in\n{log}"));
    let mut words = line.split_whitespace().map(String::from);
    (words.next().unwrap(), words.next().unwrap())
}

/// The share of Coulomb's impulse `μ (1+e) m v_n` the wall delivered, e the run's own COR.
fn delivered((v_t, v_n): &(String, String)) -> f64 {
    let (v_t, e): (f64, f64) = (v_t.parse().unwrap(), v_n.parse().unwrap());
    (5.0 - v_t) / (0.3 * (1.0 + e))
}

#[test]
#[ignore = "live: runs both stock LAMMPS builds"]
fn live_a_wall_mindlin_null_is_the_builds_own_stiffness() {
    let dir = tempfile::tempdir().unwrap();
    let (e, nu) = (YOUNG, POISSON);
    // Written in the order each build writes it, so that the numbers are the same to the bit.
    let inverted = format!("{:e}", e / 4.0 * (2.0 - nu) * (1.0 + nu));
    let mindlin = format!("{:e}", 8.0 * (e / (4.0 * (2.0 - nu) * (1.0 + nu))));
    let mut null = Vec::new();
    for (code, own, other) in [
        (CodeName::Lammps, &inverted, &mindlin),
        (CodeName::Lammps2025, &mindlin, &inverted),
    ] {
        let with_null = after(code, e, "NULL", dir.path());
        assert_eq!(with_null, after(code, e, own, dir.path()), "{code}");
        assert_ne!(with_null, after(code, e, other, dir.path()), "{code}");
        null.push(delivered(&with_null));
    }
    eprintln!(
        "Coulomb's impulse delivered with `mindlin NULL 1.0`: lammps {:.2} %, lammps-2025 {:.2} %",
        100.0 * null[0],
        100.0 * null[1]
    );
    assert!(null[0] < 0.95 && null[1] > 0.985, "{null:?}");
    // The 2021 build given the 2025 build's E* (its wall reads E/(2(1−ν)), the 2025 one
    // E/(2(1−ν²))) and Mindlin's k_t runs the 2025 wall.
    let as_2025 = after(CodeName::Lammps, e / (1.0 + nu), &mindlin, dir.path());
    assert!((delivered(&as_2025) - null[1]).abs() < 1e-9, "{as_2025:?}");
}
