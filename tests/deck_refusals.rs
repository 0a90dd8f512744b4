//! What `millimpact deck` refuses, in each reader: every line, field or set-up the check cannot
//! take, named by its file and line (or field) with what is supported; the command's refusal in
//! one line with exit 2 and nothing run (and `report --deck`'s, before any work); and each
//! reader taking its own files only.

// A value read from a deck is the number written in it, bit for bit: compared exactly.
#![allow(clippy::float_cmp)]

mod common;

use std::path::Path;

use common::deck::{
    GRANULAR, HEAD, KRATOS_MILL, KRATOS_PROJECT, MILL, deck_files, hide_codes, kratos_deck,
    read_with, two_types, yade_case, yade_read,
};
use common::{millimpact, root};
use millimpact::analysis::deck::read_deck;
use millimpact::codes::CodeName;
use millimpact::codes::deck::{DeckOptions, GivenParticle};
use millimpact::codes::yade::deck::YadeDeck;

/// Each deck with one bad line, and what its error must say besides its file and line.
#[test]
fn bad_lines_are_refused_with_their_file_line_and_what_is_supported() {
    let atoms = "pair_coeff * *\ncreate_atoms 1 single 0 0 0\nset atom 1 diameter 0.02 density 7800\ntimestep 1e-7\n";
    let cases: [(&str, String, usize, &str); 10] = [
        (
            "normal model",
            format!("{HEAD}pair_style gran model edinburgh\n{atoms}"),
            8,
            "supported: model hertz, hooke",
        ),
        (
            "cohesion",
            format!("{HEAD}pair_style gran model hertz cohesion sjkr\n{atoms}"),
            8,
            "supported: cohesion off",
        ),
        (
            "pair style",
            format!("{HEAD}pair_style lj/cut 2.5\n{atoms}"),
            8,
            "supported: pair_style gran",
        ),
        (
            "unknown variable",
            format!("{HEAD}pair_style gran model hertz\ntimestep ${{dt}}\n"),
            9,
            "`dt` is not defined",
        ),
        (
            "running value",
            format!(
                "{HEAD}variable t equal step*2\npair_style gran model hertz\ntimestep ${{t}}\n"
            ),
            10,
            "thermo keyword",
        ),
        (
            "units",
            format!(
                "units cgs\n{}pair_style gran model hertz\n{atoms}",
                &HEAD[9..]
            ),
            1,
            "supported: units si",
        ),
        (
            "soft limit",
            format!(
                "{}pair_style gran model hertz\n{atoms}",
                HEAD.replace("hard_particles yes\n", "")
            ),
            4,
            "hard_particles yes",
        ),
        (
            "integrator",
            format!("{HEAD}pair_style gran model hertz\nfix i all nve/limit 0.1\n{atoms}"),
            9,
            "supported: fix nve/sphere",
        ),
        (
            "template",
            format!(
                "{HEAD}pair_style gran model hertz\nfix p all particletemplate/sphere 1 atom_type 1 density constant 7800 radius gaussian 0.01 0.001\ntimestep 1e-7\n"
            ),
            9,
            "--particle 1:RADIUS:DENSITY",
        ),
        (
            "multisphere",
            format!(
                "{HEAD}pair_style gran model hertz\nfix p all particletemplate/multisphere 1 atom_type 1\n"
            ),
            9,
            "supported: particletemplate/sphere",
        ),
    ];
    for (what, text, line, says) in cases {
        let (_d, path) = deck_files(&[("in.bad", &text)]);
        let e = read_deck(&path, None, &DeckOptions::default())
            .unwrap_err()
            .to_string();
        let at = format!("{}:{line}: ", path.display());
        assert!(e.starts_with(&at) && e.contains(says), "{what}: {e}");
    }
}

#[test]
fn an_included_file_names_its_own_lines_and_a_missing_one_is_named() {
    let (_d, path) = deck_files(&[
        ("in.main", &format!("{HEAD}include more.in\n")),
        (
            "more.in",
            "# the pair line\n\npair_style gran model luding\n",
        ),
    ]);
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("more.in:3: normal model `luding`"), "{e}");
    let (_d, path) = deck_files(&[("in.main", &format!("{HEAD}include nowhere.in\n"))]);
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("in.main:8: include ") && e.contains("`nowhere.in` does not exist"),
        "{e}"
    );
}

#[test]
fn the_command_refuses_a_bad_deck_in_one_line_with_exit_2_and_runs_nothing() {
    let (_d, path) = deck_files(&[(
        "in.bad",
        &format!("{HEAD}pair_style gran model hertz cohesion sjkr\n"),
    )]);
    let out = millimpact()
        .args(["deck", path.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("error: ") && err.contains("in.bad:8: cohesion sjkr"),
        "{err}"
    );
    // A file no reader takes.
    let (_d, path) = deck_files(&[("notes.txt", "a list of groceries\n")]);
    let out = millimpact()
        .args(["deck", path.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("not a deck of any code this build reads; supported: liggghts:"),
        "{err}"
    );
}

/// `report --deck` reads its decks before any work: a bad one is the same one line, exit 2,
/// and no report folder.
#[test]
fn the_report_refuses_a_bad_deck_before_any_work() {
    let (dir, path) = deck_files(&[(
        "in.bad",
        &format!("{HEAD}pair_style gran model hertz cohesion sjkr\n"),
    )]);
    let out_dir = dir.path().join("report");
    let out = millimpact()
        .current_dir(root())
        .args(["report", "--deck", path.to_str().unwrap(), "--out"])
        .arg(&out_dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("error: ") && err.contains("in.bad:8: cohesion sjkr"),
        "{err}"
    );
    assert!(!out_dir.exists(), "no report written");
}

#[test]
fn a_lammps_line_the_build_lacks_or_a_pair_without_coefficients_is_refused() {
    hide_codes();
    let head = "units si\natom_style sphere\ncreate_box 2 box\ncreate_atoms 1 single 0 0 0\ncreate_atoms 2 single 1 0 0\nset type 1 diameter 0.01 density 2500\nset type 2 diameter 0.01 density 2500\ntimestep 1e-6\npair_style granular\n";
    let (_d, path) = deck_files(&[(
        "in.cr",
        &format!(
            "{head}pair_coeff * * hertz/material 1e9 0.5 0.3 damping coeff_restitution tangential linear_nohistory 0 0\n"
        ),
    )]);
    let e = read_deck(&path, Some(CodeName::Lammps), &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("in.cr:10: damping coeff_restitution: this build (probed) has none")
            && e.contains("--code lammps-2025"),
        "{e}"
    );
    // A pair_coeff without its tangential model, which both builds refuse.
    let (_d, path) = deck_files(&[(
        "in.tangential",
        &format!("{head}pair_coeff * * hertz/material 1e9 0.5 0.3 damping tsuji\n"),
    )]);
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("in.tangential:10: a pair_coeff without a tangential model"),
        "{e}"
    );
    let (_d, path) = deck_files(&[(
        "in.dmt",
        &format!("{head}pair_coeff * * dmt 1e9 0.5 0.3 0.1\n"),
    )]);
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains(
            "in.dmt:10: normal model `dmt`: an adhesive force the impact check does not model; supported: hooke k d, hertz k d, hertz/material E d nu"
        ),
        "{e}"
    );
}

/// Each Kratos setup with one bad field, and what its error must say after its file and field.
#[test]
fn bad_kratos_fields_are_refused_with_their_path_and_what_is_supported() {
    type Edit = Box<dyn Fn(&mut serde_json::Value)>;
    let none = || -> Edit { Box::new(|_| {}) };
    let cases: Vec<(&str, Edit, Edit, &str, &str)> = vec![
        (
            "law",
            Box::new(|m| {
                m["material_relations"][3]["Variables"]["DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME"] =
                    "DEM_D_Linear_classic".into()
            }),
            none(),
            "MaterialsDEM.json: material_relations[3].Variables.DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME: ",
            "supported: DEM_D_Hertz_viscous_Coulomb, DEM_D_Linear_viscous_Coulomb, DEM_D_Linear_Custom_Constants",
        ),
        (
            "restitution as text",
            Box::new(|m| {
                m["material_relations"][0]["Variables"]["COEFFICIENT_OF_RESTITUTION"] = "0.7".into()
            }),
            none(),
            "MaterialsDEM.json: material_relations[0].Variables.COEFFICIENT_OF_RESTITUTION: ",
            "found \"0.7\"; supported: a number",
        ),
        (
            "restitution above 1",
            Box::new(|m| {
                m["material_relations"][1]["Variables"]["COEFFICIENT_OF_RESTITUTION"] = 1.5.into()
            }),
            none(),
            "MaterialsDEM.json: material_relations[1].Variables.COEFFICIENT_OF_RESTITUTION: ",
            "supported: a restitution in (0, 1]",
        ),
        (
            "K_NORMAL missing",
            Box::new(|m| {
                m["material_relations"][4]["Variables"]["DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME"] =
                    "DEM_D_Linear_Custom_Constants".into()
            }),
            none(),
            "MaterialsDEM.json: material_relations[4].Variables.K_NORMAL: ",
            "no K_NORMAL",
        ),
        (
            "density missing",
            Box::new(|m| {
                m["materials"][0]["Variables"]
                    .as_object_mut()
                    .unwrap()
                    .remove("PARTICLE_DENSITY");
            }),
            none(),
            "MaterialsDEM.json: materials[0].Variables.PARTICLE_DENSITY: ",
            "no PARTICLE_DENSITY",
        ),
        (
            "material name",
            Box::new(|m| m["material_assignation_table"][0][1] = "steel".into()),
            none(),
            "MaterialsDEM.json: material_assignation_table[0][1]: ",
            "material `steel` is in no material_name",
        ),
        (
            "model part",
            Box::new(|m| m["material_assignation_table"][2][0] = "FEMPart.Liner".into()),
            none(),
            "MaterialsDEM.json: material_assignation_table[2][0]: ",
            "supported: SpheresPart, DEMInletPart and RigidFacePart",
        ),
        (
            "scheme",
            none(),
            Box::new(|p| p["TranslationalIntegrationScheme"] = "Forward_Euler".into()),
            "ProjectParametersDEM.json: TranslationalIntegrationScheme: ",
            "supported: Symplectic_Euler",
        ),
        (
            "virtual mass",
            none(),
            Box::new(|p| p["VirtualMassCoefficient"] = 0.9.into()),
            "ProjectParametersDEM.json: VirtualMassCoefficient: ",
            "supported: 1.0",
        ),
        (
            "continuum",
            none(),
            Box::new(|p| p["ElementType"] = "SphericContPartDEMElement3D".into()),
            "ProjectParametersDEM.json: ElementType: ",
            "supported: SphericPartDEMElement3D",
        ),
    ];
    for (what, materials, project, at, says) in cases {
        let (dir, path) = kratos_deck(materials, project);
        let e = read_deck(&path, None, &DeckOptions::default())
            .unwrap_err()
            .to_string();
        let at = format!("{}{at}", dir.path().display().to_string() + "/");
        assert!(e.starts_with(&at) && e.contains(says), "{what}: {e}");
    }
}

#[test]
fn a_kratos_setup_lacking_a_part_says_what_and_how_to_give_it() {
    let (_d, path) = kratos_deck(
        |m| {
            m["material_relations"].as_array_mut().unwrap().remove(2);
        },
        |_| {},
    );
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("no material_relations entry for the materials 2 (high_chrome_iron) and 2 (high_chrome_iron)"), "{e}");
    // No .mdpa of the problem's name: Kratos stops at it, and so does the check.
    let (d, path) = kratos_deck(|_| {}, |p| p["problem_name"] = "elsewhere".into());
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("problem_name: ") && e.contains("`elsewhereDEM.mdpa` does not exist"),
        "{e}"
    );
    // An .mdpa with no sphere to take the radii from: named, with the flag that gives them.
    std::fs::write(d.path().join("elsewhereDEM.mdpa"), "").unwrap();
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("no radius for material 1 (forged_steel)")
            && e.contains("elsewhereDEM.mdpa")
            && e.ends_with("--particle 1:RADIUS:7800"),
        "{e}"
    );
    // A distribution in the .mdpa: more radii than are checked one by one.
    let (dir, path) = kratos_deck(|_| {}, |_| {});
    let mdpa = std::fs::read_to_string(dir.path().join("millDEM.mdpa")).unwrap();
    let mdpa = mdpa
        .replace("    2   0   0.03\n", "    2   0   0.031\n")
        .replace("    3   0   0.03\n", "    3   0   0.032\n")
        .replace("    1   0   0.03\n", "    1   0   0.029\n");
    let mdpa = mdpa.replace("    4   0   0.02\n", "    4   0   0.021\n");
    let mdpa = mdpa.replace(
        "Begin SubModelPartElements\n        1\n",
        "Begin SubModelPartElements\n        1\n        4\n",
    );
    std::fs::write(dir.path().join("millDEM.mdpa"), mdpa).unwrap();
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("SpheresPart.DEMParts_SteelBalls (material 1 (forged_steel)) has 4 radii from 0.021 to 0.032 m") && e.contains("--particle 1:RADIUS:DENSITY"),
        "{e}"
    );
    // A project beside it that names another materials file.
    let (_d, path) = kratos_deck(
        |_| {},
        |p| {
            p["solver_settings"]["material_import_settings"]["materials_filename"] =
                "Other.json".into()
        },
    );
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("names the materials file")
            && e.contains("Other.json")
            && e.contains("name ")
            && e.contains("ProjectParametersDEM.json instead"),
        "{e}"
    );
    // A materials file alone: the project with the time step is missing.
    let (dir, path) = kratos_deck(|_| {}, |_| {});
    std::fs::remove_file(dir.path().join("ProjectParametersDEM.json")).unwrap();
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("no ProjectParametersDEM.json beside it") && e.contains("MaxTimeStep"),
        "{e}"
    );
}

#[test]
fn a_kratos_setup_with_an_unsupported_law_exits_2_naming_the_field_and_runs_nothing() {
    let (_d, path) = kratos_deck(
        |m| {
            m["material_relations"][0]["Variables"]["DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME"] =
                "DEM_D_Conical_damage".into()
        },
        |_| {},
    );
    let out = millimpact()
        .args(["deck", path.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("error: ")
            && err.contains("MaterialsDEM.json: material_relations[0].Variables.DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME: DEM_D_Conical_damage")
            && err.contains("supported: DEM_D_Hertz_viscous_Coulomb"),
        "{err}"
    );
}

#[test]
fn each_reader_recognises_its_own_files_only() {
    let text = |p: &str| std::fs::read_to_string(root().join(p)).unwrap();
    let kratos = CodeName::Kratos.driver().deck().unwrap();
    let liggghts = CodeName::Liggghts.driver().deck().unwrap();
    let lammps = CodeName::Lammps.driver().deck().unwrap();
    for json in [KRATOS_MILL, KRATOS_PROJECT] {
        assert!(kratos.recognises(Path::new(json), &text(json)), "{json}");
        assert!(!liggghts.recognises(Path::new(json), &text(json)), "{json}");
        assert!(!lammps.recognises(Path::new(json), &text(json)), "{json}");
    }
    for script in [MILL, GRANULAR] {
        assert!(
            !kratos.recognises(Path::new(script), &text(script)),
            "{script}"
        );
    }
    // JSON of something else is no Kratos setup.
    let (_d, path) = deck_files(&[("settings.json", "{\"theme\": \"dark\"}\n")]);
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("not a deck of any code this build reads")
            && e.contains("kratos: Kratos DEM MaterialsDEM.json or ProjectParametersDEM.json"),
        "{e}"
    );
}

/// Each script of `tests/data/deck/yade/` that YADE sets up but the check cannot take: its
/// line (0: the file alone) and what its error must say.
#[test]
fn yade_set_ups_the_check_cannot_take_are_refused_with_their_line_and_what_is_supported() {
    let cases: [(&str, usize, &str); 10] = [
        (
            "refuse-law",
            9,
            "functor Law2_ScGeom_MindlinPhys_HertzWithLinearShear; supported: Ig2_Sphere_Sphere_ScGeom",
        ),
        (
            "refuse-no-law",
            8,
            "without Law2_ScGeom_FrictPhys_CundallStrack",
        ),
        ("refuse-local-damping", 10, "damping = 0.2 (its default)"),
        (
            "refuse-time-stepper",
            6,
            "GlobalStiffnessTimeStepper: the time step is set while the script runs",
        ),
        (
            "refuse-material-class",
            2,
            "material class `CohFrictMat` (O.materials[0]); supported: FrictMat, ViscElMat",
        ),
        (
            "refuse-free-box",
            4,
            "supported: box(…, fixed=True) as a wall",
        ),
        (
            "refuse-match-maker",
            8,
            "its MatchMaker gives YADE no number for the materials 0 and 0",
        ),
        (
            "refuse-no-geometry",
            4,
            "no Ig2_Wall_Sphere_ScGeom in the InteractionLoop",
        ),
        (
            "refuse-not-appended",
            3,
            "a Sphere whose material is not in O.materials (its id is -1",
        ),
        ("refuse-no-step", 0, "the script sets no O.dt"),
    ];
    for (name, line, says) in cases {
        let e = yade_case(name).unwrap_err();
        let at = match line {
            0 => format!("tests/data/deck/yade/{name}.py: "),
            _ => format!("tests/data/deck/yade/{name}.py:{line}: "),
        };
        assert!(e.starts_with(&at) && e.contains(says), "{name}: {e}");
    }
    // The radius given on the command line replaces the type's, by its O.materials id.
    let options = DeckOptions {
        particles: vec![GivenParticle {
            type_id: 0,
            radius: 0.02,
            density: 7800.0,
        }],
        ..DeckOptions::default()
    };
    let deck = yade_read("tests/data/deck/yade/base.py", "base.dump.json", &options).unwrap();
    let radii: Vec<f64> = deck.bodies.iter().map(|b| b.radius).collect();
    assert_eq!(radii, [0.02]);
    // A LIGGGHTS deck takes no type 0.
    let e = read_deck(&root().join(MILL), None, &options)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("--particle 0:0.02:7800: atom types count from 1"),
        "{e}"
    );
    // --var names nothing in a YADE script.
    let options = DeckOptions {
        variables: vec![("E".into(), "1e7".into())],
        ..DeckOptions::default()
    };
    let e = yade_read("tests/data/deck/yade/base.py", "base.dump.json", &options).unwrap_err();
    assert!(
        e.contains("--var E: a YADE script's names are its own"),
        "{e}"
    );
}

#[test]
fn a_yade_script_that_runs_before_its_engines_are_set_is_refused_naming_that_line() {
    let e = yade_case("runs-early").unwrap_err();
    assert_eq!(
        e,
        "tests/data/deck/yade/runs-early.py: the script sets no O.engines before the reading stopped at its first step (O.run, line 7): YADE's default engines are no contact law of the script's; O.engines = [..., InteractionLoop([Ig2…], [Ip2…], [Law2…]), NewtonIntegrator(damping=0)] before the first O.run"
    );
}

#[test]
fn a_yade_dump_that_does_not_read_names_its_field() {
    let e = YadeDeck::read_dump(
        Path::new("s.py"),
        "{\"version\": 1}",
        &DeckOptions::default(),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("s.py: the dump: YADE's dump of the set-up does not read: "),
        "{e}"
    );
}

#[test]
fn a_yade_script_with_an_unsupported_functor_is_refused_naming_its_line() {
    std::env::set_current_dir(root()).unwrap();
    let e = yade_read(
        "tests/data/deck/yade-capillary.py",
        "capillary.dump.json",
        &DeckOptions::default(),
    )
    .unwrap_err();
    assert!(
        e.starts_with("tests/data/deck/yade-capillary.py:14: functor Ip2_FrictMat_FrictMat_CapillaryPhys; supported: "),
        "{e}"
    );
}

/// What LAMMPS refuses, refused with the lines: two own lines of different forms to mix, a
/// type without its own line, and (in the 2021 build) `pair_coeff J I` with `J > I`.
#[test]
fn a_pair_lammps_cannot_mix_is_refused_with_both_lines() {
    let forms = two_types(
        "pair_coeff 1 1 hertz/material 6.3e10 0.9 0.22 damping tsuji tangential linear_nohistory 0 0\n\
pair_coeff 2 2 hooke 1e6 0.5 damping velocity tangential linear_nohistory 0 0\n",
    );
    let (_d, path) = deck_files(&[("in.forms", &forms)]);
    let at = |line: usize| format!("{}:{line}", path.display());
    for code in [CodeName::Lammps, CodeName::Lammps2025] {
        hide_codes();
        let e = read_deck(&path, Some(code), &DeckOptions::default())
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with(&format!("{}: no pair_coeff sets the types 1 and 2, and LAMMPS refuses to mix them from pair_coeff 1 1 ({}: hertz/material damping tsuji tangential linear_nohistory) and 2 2 (here: hooke damping velocity tangential linear_nohistory)", at(11), at(10)))
                && e.contains("supported: a pair_coeff 1 2 of its own"),
            "{code}: {e}"
        );
    }
    // A tangential model of another name is another form too.
    let tangential = two_types(
        "pair_coeff 1 1 hertz/material 6.3e10 0.9 0.22 damping tsuji tangential mindlin NULL 1.0 0.3\n\
pair_coeff 2 2 hertz/material 2e11 0.6 0.3 damping tsuji tangential linear_nohistory 0 0\n",
    );
    let (_d, path) = deck_files(&[("in.tangential", &tangential)]);
    hide_codes();
    let e = read_deck(&path, Some(CodeName::Lammps2025), &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("in.tangential:11: no pair_coeff sets the types 1 and 2")
            && e.contains("tangential mindlin"),
        "{e}"
    );
    // Its own line for every type of the box, in use or not.
    let three = two_types(
        "pair_coeff 1 1 hertz/material 6.3e10 0.9 0.22 damping tsuji tangential linear_nohistory 0 0\n\
pair_coeff 2 2 hertz/material 2e11 0.6 0.3 damping tsuji tangential linear_nohistory 0 0\n",
    )
    .replace("create_box 2 box", "create_box 3 box");
    let (_d, path) = deck_files(&[("in.three", &three)]);
    hide_codes();
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("in.three: no pair_coeff sets the type 3 with itself")
            && e.contains("All pair coeffs are not set"),
        "{e}"
    );
    // pair_coeff 2 1: the 2021 build sets nothing and refuses it; the 2025 build reads 1 2.
    let swapped = two_types(
        "pair_coeff 1 1 hooke 1e6 0.5 damping velocity tangential linear_nohistory 0 0\n\
pair_coeff 2 2 hooke 4e6 2.0 damping velocity tangential linear_nohistory 0 0\n\
pair_coeff 2 1 hooke 9e6 0.1 damping velocity tangential linear_nohistory 0 0\n",
    );
    let (_d, path) = deck_files(&[("in.swapped", &swapped)]);
    hide_codes();
    let e = read_deck(&path, Some(CodeName::Lammps), &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("in.swapped:12: pair_coeff 2 1: this build sets no pair for J < I")
            && e.contains("supported: pair_coeff 1 2"),
        "{e}"
    );
    let law = read_with(CodeName::Lammps2025, &path).contacts[1]
        .law
        .dashpot()
        .copied()
        .expect("a spring–dashpot law");
    assert_eq!((law.stiffness, law.damping), (9e6, 0.1));
}

/// The command refuses the unmixable deck in one line naming it, exit 2, and runs nothing.
#[test]
fn the_command_refuses_a_pair_lammps_cannot_mix_with_exit_2() {
    hide_codes();
    let forms = two_types(
        "pair_coeff 1 1 hertz/material 6.3e10 0.9 0.22 damping tsuji tangential linear_nohistory 0 0\n\
pair_coeff 2 2 hertz 1e9 0.5 damping tsuji tangential linear_nohistory 0 0\n",
    );
    let (_d, path) = deck_files(&[("in.forms", &forms)]);
    for code in ["lammps", "lammps-2025"] {
        let out = millimpact()
            .args(["deck", path.to_str().unwrap(), "--code", code])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2));
        assert!(out.stdout.is_empty());
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.starts_with("error: ")
                && err.contains("in.forms:11: no pair_coeff sets the types 1 and 2")
                && err.contains("in.forms:10: hertz/material"),
            "{err}"
        );
    }
}

/// One pass names every line the check cannot honour, in the order the code reads them, the
/// units first: a user fixes them all at once, not one per attempt.
#[test]
fn every_line_the_check_cannot_honour_is_named_in_one_pass_units_first() {
    let text = format!(
        "{}pair_style gran model hertz tangential histroy\nfix p all particletemplate/multisphere 1 atom_type 1\n\
timestep ${{dt}}\nunits lj\nfix w all wall/gran model hertz primitive type 3 zplane 0.0 limitforce on\n",
        HEAD.replace("units si\n", "")
    );
    let (_d, path) = deck_files(&[("in.many", &text)]);
    let e = read_deck(&path, None, &DeckOptions::default())
        .unwrap_err()
        .to_string();
    let lines: Vec<&str> = e.lines().collect();
    let at = |n: usize| format!("{}:{n}: ", path.display());
    assert_eq!(lines.len(), 5, "{e}");
    assert!(
        lines[0].starts_with(&at(10)) && lines[0].contains("units lj"),
        "{e}"
    );
    assert!(
        lines[1].starts_with(&at(7))
            && lines[1].contains("tangential `histroy`: LIGGGHTS 3.8 has no such model")
            && lines[1].contains("supported: tangential no_history, history, tan_luding"),
        "{e}"
    );
    assert!(
        lines[2].starts_with(&at(8)) && lines[2].contains("non-spherical"),
        "{e}"
    );
    assert!(
        lines[3].starts_with(&at(9)) && lines[3].contains("`dt` is not defined"),
        "{e}"
    );
    assert!(
        lines[4].starts_with(&at(11))
            && lines[4].contains("`limitforce on`")
            && lines[4].contains("limitForce"),
        "{e}"
    );
}

/// A keyword LAMMPS does not know in a granular model is refused with the words it accepts.
#[test]
fn a_lammps_model_keyword_typo_names_the_words_lammps_accepts() {
    hide_codes();
    let head = two_types("");
    let (_d, path) = deck_files(&[(
        "in.typo",
        &format!(
            "{head}pair_coeff * * hertz/material 1e9 0.5 0.3 tangential linear_histroy 1 1 0.5\n"
        ),
    )]);
    let e = read_deck(&path, Some(CodeName::Lammps), &DeckOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("in.typo:10: tangential `linear_histroy`: LAMMPS has no such tangential model")
            && e.contains("supported: tangential linear_nohistory, linear_history"),
        "{e}"
    );
}
