//! Kratos' deck reader on its typed `MaterialsDEM.json` and `ProjectParametersDEM.json`: the
//! example mill with one field changed, and the exact one-line refusal that names the file, the
//! field's path, the value found and what is allowed; fields Kratos lets through are let
//! through; a relation no checked pair uses is reported, whatever its law. No code is run.

mod common;

use std::path::PathBuf;

use common::{millimpact, root};
use millimpact::analysis::deck::read_deck;
use millimpact::codes::deck::{DeckOptions, UserDeck};
use serde_json::{Value, json};

const EXAMPLE: &str = "examples/decks/kratos-mill";

/// The example mill in a fresh folder, its materials and project edited; the folder and the
/// path of the materials file.
fn mill(
    materials: impl Fn(&mut Value),
    project: impl Fn(&mut Value),
) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let example = root().join(EXAMPLE);
    for (name, edit) in [
        ("MaterialsDEM.json", &materials as &dyn Fn(&mut Value)),
        ("ProjectParametersDEM.json", &project),
    ] {
        let text = std::fs::read_to_string(example.join(name)).unwrap();
        let mut value: Value = serde_json::from_str(&text).unwrap();
        edit(&mut value);
        let text = serde_json::to_string_pretty(&value).unwrap();
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    std::fs::copy(
        example.join("millDEM.mdpa"),
        dir.path().join("millDEM.mdpa"),
    )
    .unwrap();
    let path = dir.path().join("MaterialsDEM.json");
    (dir, path)
}

fn read(path: &std::path::Path) -> Result<UserDeck, String> {
    read_deck(path, None, &DeckOptions::default())
        .map(|(_, deck)| deck)
        .map_err(|e| e.to_string())
}

type Edit = Box<dyn Fn(&mut Value)>;

fn none() -> Edit {
    Box::new(|_| {})
}

/// Each bad field, and the whole line the reader refuses it with after the folder.
#[test]
fn each_bad_field_is_refused_in_one_exact_line_with_its_path() {
    let cases: Vec<(&str, Edit, Edit, &str)> = vec![
        (
            "a modulus as text",
            Box::new(|m| m["materials"][1]["Variables"]["YOUNG_MODULUS"] = "abc".into()),
            none(),
            "MaterialsDEM.json: materials[1].Variables.YOUNG_MODULUS: found \"abc\"; supported: a number",
        ),
        (
            "a negative material id",
            Box::new(|m| m["materials"][0]["material_id"] = (-1).into()),
            none(),
            "MaterialsDEM.json: materials[0].material_id: found -1; supported: a material id (a whole number from 0)",
        ),
        (
            "a relation without its materials",
            Box::new(|m| {
                m["material_relations"][2]
                    .as_object_mut()
                    .unwrap()
                    .remove("material_ids_list");
            }),
            none(),
            "MaterialsDEM.json: material_relations[2].material_ids_list: no material_ids_list; supported: material_ids_list, which Kratos requires there",
        ),
        (
            "three materials in a relation",
            Box::new(|m| m["material_relations"][1]["material_ids_list"] = json!([1, 2, 3])),
            none(),
            "MaterialsDEM.json: material_relations[1].material_ids_list: found [1,2,3]; supported: two material ids [ID, ID]",
        ),
        (
            "a material id as text in a relation",
            Box::new(|m| m["material_relations"][1]["material_ids_list"][1] = "2".into()),
            none(),
            "MaterialsDEM.json: material_relations[1].material_ids_list[1]: found \"2\"; supported: a material id (a whole number from 0)",
        ),
        (
            "a law that is not a name",
            Box::new(|m| {
                m["material_relations"][3]["Variables"]["DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME"] =
                    json!(["DEM_D_Hertz_viscous_Coulomb"])
            }),
            none(),
            "MaterialsDEM.json: material_relations[3].Variables.DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME: found [\"DEM_D_Hertz_viscous_Coulomb\"]; supported: a constitutive law's name",
        ),
        (
            "an unknown law",
            Box::new(|m| {
                m["material_relations"][0]["Variables"]["DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME"] =
                    "DEM_D_Conical_damage".into()
            }),
            none(),
            "MaterialsDEM.json: material_relations[0].Variables.DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME: DEM_D_Conical_damage, a law whose force the harness does not step; supported: DEM_D_Hertz_viscous_Coulomb, DEM_D_Linear_viscous_Coulomb, DEM_D_Linear_Custom_Constants",
        ),
        (
            "a missing law",
            Box::new(|m| {
                m["material_relations"][4]["Variables"]
                    .as_object_mut()
                    .unwrap()
                    .remove("DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME");
            }),
            none(),
            "MaterialsDEM.json: material_relations[4].Variables.DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME: no DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME; supported: a constitutive law: DEM_D_Hertz_viscous_Coulomb, DEM_D_Linear_viscous_Coulomb, DEM_D_Linear_Custom_Constants",
        ),
        (
            "a friction as text",
            Box::new(|m| {
                m["material_relations"][0]["Variables"]["STATIC_FRICTION"] = "high".into()
            }),
            none(),
            "MaterialsDEM.json: material_relations[0].Variables.STATIC_FRICTION: found \"high\"; supported: a number",
        ),
        (
            "a model part that is not a name",
            Box::new(|m| m["material_assignation_table"][1][0] = 7.into()),
            none(),
            "MaterialsDEM.json: material_assignation_table[1][0]: found 7; supported: a string",
        ),
        (
            "an assignation of one item",
            Box::new(|m| m["material_assignation_table"][2] = json!(["RigidFacePart.Liner"])),
            none(),
            "MaterialsDEM.json: material_assignation_table[2]: found [\"RigidFacePart.Liner\"]; supported: a [MODEL PART, MATERIAL] pair",
        ),
        (
            "no assignation table",
            Box::new(|m| {
                m.as_object_mut()
                    .unwrap()
                    .remove("material_assignation_table");
            }),
            none(),
            "MaterialsDEM.json: material_assignation_table: no material_assignation_table; supported: material_assignation_table, which Kratos requires there",
        ),
        (
            "two materials of one id",
            Box::new(|m| m["materials"][2]["material_id"] = 1.into()),
            none(),
            "MaterialsDEM.json: materials[2].material_id: 1, which materials[0] has already; supported: one material per material_id",
        ),
        (
            "a time step as text",
            none(),
            Box::new(|p| p["MaxTimeStep"] = "2e-6".into()),
            "ProjectParametersDEM.json: MaxTimeStep: found \"2e-6\"; supported: a number",
        ),
        (
            "a materials file named by a number",
            none(),
            Box::new(|p| {
                p["solver_settings"]["material_import_settings"]["materials_filename"] = 5.into()
            }),
            "ProjectParametersDEM.json: solver_settings.material_import_settings.materials_filename: found 5; supported: a string",
        ),
        (
            "an automatic time step as text",
            none(),
            Box::new(|p| p["AutomaticTimestep"] = "yes".into()),
            "ProjectParametersDEM.json: AutomaticTimestep: found \"yes\"; supported: a boolean",
        ),
        (
            "a search tolerance as text",
            none(),
            Box::new(|p| p["SearchTolerance"] = "1e-4".into()),
            "ProjectParametersDEM.json: SearchTolerance: found \"1e-4\"; supported: a number",
        ),
    ];
    for (what, materials, project, says) in cases {
        let (dir, path) = mill(materials, project);
        let folder = dir.path().display().to_string();
        let error = read(&path).expect_err(what);
        let expected = format!("{folder}/{says}");
        assert_eq!(error, expected, "{what}");
        assert_eq!(error.lines().count(), 1, "{what}");
    }
}

/// Materials that are not a list, read through the project that names their file: the file
/// is not taken for some other file, the field is named.
#[test]
fn materials_that_are_not_a_list_are_named_through_the_project() {
    let (dir, _) = mill(|m| m["materials"] = json!({"material_id": 1}), |_| {});
    let error = read(&dir.path().join("ProjectParametersDEM.json")).unwrap_err();
    assert_eq!(
        error,
        format!(
            "{}/MaterialsDEM.json: materials: found {{\"material_id\":1}}; supported: a list",
            dir.path().display()
        )
    );
}

/// The command refuses a bad field with exit 2, its one line on stderr and nothing on stdout.
#[test]
fn a_bad_field_exits_2_with_its_line_and_runs_nothing() {
    let (dir, path) = mill(
        |m| m["materials"][1]["Variables"]["YOUNG_MODULUS"] = "abc".into(),
        |_| {},
    );
    let out = millimpact()
        .args(["deck", path.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    assert_eq!(
        String::from_utf8(out.stderr).unwrap(),
        format!(
            "error: {}/MaterialsDEM.json: materials[1].Variables.YOUNG_MODULUS: found \"abc\"; supported: a number\n",
            dir.path().display()
        )
    );
}

/// Fields the check does not read, anywhere, change nothing: Kratos lets them through.
#[test]
fn fields_the_check_does_not_read_are_let_through() {
    let (plain_dir, plain) = mill(|_| {}, |_| {});
    let (dir, extra) = mill(
        |m| {
            m["author"] = "the mill's modeller".into();
            m["materials"][0]["Variables"]["COMPUTE_WEAR"] = true.into();
            m["materials"][0]["notes"] = json!({"batch": 7});
            m["material_relations"][0]["Variables"]["SOME_FUTURE_VARIABLE"] = json!([1, 2]);
        },
        |p| {
            p["NewSetting"] = json!({"deep": [1, 2, 3]});
            p["solver_settings"]["material_import_settings"]["other"] = 1.into();
        },
    );
    // The same deck but for the folder each was written to.
    let shown = |path: &std::path::Path, folder: &std::path::Path| {
        let deck = read(path).unwrap();
        let text = format!("{:?}", (&deck.bodies, &deck.contacts, deck.timestep));
        (deck, text.replace(&folder.display().to_string(), "FOLDER"))
    };
    let (plain, plain_text) = shown(&plain, plain_dir.path());
    let (_, extra_text) = shown(&extra, dir.path());
    assert_eq!(plain_text, extra_text);
    assert_eq!(plain.contacts.len(), 5);
}

/// A relation between materials no checked pair meets is not refused for its law: it is named
/// among what is left out, with the law it has.
#[test]
fn a_relation_no_pair_uses_is_reported_with_its_law() {
    let (_dir, path) = mill(
        |m| {
            m["materials"].as_array_mut().unwrap().push(json!({
                "material_name": "ceramic",
                "material_id": 4,
                "Variables": {"PARTICLE_DENSITY": 3900.0, "YOUNG_MODULUS": 3.7e11, "POISSON_RATIO": 0.22}
            }));
            m["material_relations"].as_array_mut().unwrap().push(json!({
                "material_ids_list": [1, 4],
                "Variables": {"DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME": "DEM_D_Conical_damage"}
            }));
        },
        |_| {},
    );
    let deck = read(&path).unwrap();
    let line = deck
        .left_out
        .iter()
        .find(|l| l.starts_with("relations no checked pair uses"))
        .expect("the unused relation is reported");
    assert!(
        line.ends_with("MaterialsDEM.json: material_relations[5] (DEM_D_Conical_damage))"),
        "{line}"
    );
    // The unassigned material is not carried into the impacts.
    let carried: Value = serde_json::from_str(&deck.transplant.common.join("\n")).unwrap();
    assert_eq!(carried["materials"].as_array().unwrap().len(), 3);
}

/// The material a pair needs a relation for, and has none: refused, naming both.
#[test]
fn a_pair_without_a_relation_is_refused() {
    let (_dir, path) = mill(
        |m| {
            m["material_relations"].as_array_mut().unwrap().remove(4);
        },
        |_| {},
    );
    let error = read(&path).unwrap_err();
    assert!(
        error.ends_with("MaterialsDEM.json: no material_relations entry for the materials 2 (high_chrome_iron) and 3 (rubber_liner); a relation (law, COEFFICIENT_OF_RESTITUTION) for every pair of materials that meet, as Kratos needs"),
        "{error}"
    );
}
