//! The command line offers exactly what the registries hold: the choices `--help` prints for
//! `--method`/`--methods`, `--code`/`--codes` and `--format` are the method registry's, the
//! code registry's and the exporters' names, in their order.

mod common;

use common::{millimpact, stdout};
use millimpact::codes::CodeName;
use millimpact::output::Format;
use millimpact::solve::Method;

/// The `[possible values: …]` that `--help` of `command` prints for `option`.
fn choices(command: &str, option: &str) -> Vec<String> {
    let help = stdout(millimpact().args([command, "--help"]));
    // Help text wraps; read it as one line.
    let text = help.split_whitespace().collect::<Vec<_>>().join(" ");
    // The option's own entry, under "Options:" (the usage line names required options too).
    let options = text.find("Options:").expect("an Options section");
    let text = &text[options..];
    let at = text
        .find(&format!("{option} <"))
        .unwrap_or_else(|| panic!("`{command} --help` documents {option}:\n{help}"));
    let rest = &text[at..];
    let next_option = rest[2..].find(" --").map_or(rest.len(), |i| i + 2);
    let own = &rest[..next_option];
    let start = own
        .find("[possible values: ")
        .unwrap_or_else(|| panic!("`{command} --help` lists the choices of {option}: {own}"))
        + "[possible values: ".len();
    let end = start + own[start..].find(']').unwrap();
    own[start..end].split(", ").map(str::to_string).collect()
}

fn names(list: impl IntoIterator<Item = &'static str>) -> Vec<String> {
    list.into_iter().map(str::to_string).collect()
}

#[test]
fn method_choices_are_the_method_registry() {
    let registry = names(Method::ALL.iter().map(|m| m.name()));
    assert_eq!(registry, names(Method::names()));
    assert!(registry.len() >= 5, "{registry:?}");
    for command in ["run", "sweep"] {
        assert_eq!(choices(command, "--method"), registry, "{command} --method");
    }
    assert_eq!(
        choices("precision", "--methods"),
        registry,
        "precision --methods"
    );
}

#[test]
fn code_choices_are_the_code_registry() {
    let registry = names(CodeName::ALL.iter().map(|c| c.name()));
    assert_eq!(registry, names(CodeName::names()));
    assert_eq!(
        registry,
        [
            "liggghts",
            "liggghts-paper",
            "yade",
            "yade-paper",
            "lammps",
            "lammps-2025",
            "lammps-paper",
            "kratos",
            "kratos-paper"
        ]
    );
    assert_eq!(choices("reference", "--code"), registry, "reference --code");
    // probe offers every code and refuses those it does not cover, in one line.
    assert_eq!(choices("probe", "--code"), registry, "probe --code");
    assert_eq!(
        choices("precision", "--codes"),
        registry,
        "precision --codes"
    );
}

#[test]
fn format_choices_are_the_exporters() {
    let registry = names(Format::ALL.map(Format::name));
    assert_eq!(registry, ["table", "json", "csv", "markdown"]);
    for command in [
        "run",
        "verify",
        "reference",
        "compare",
        "precision",
        "stability",
        "calibrate",
        "probe",
    ] {
        assert_eq!(choices(command, "--format"), registry, "{command} --format");
    }
    // A sweep file's rows are streamed as they finish: JSON lines besides the exporters.
    let mut streamed = registry.clone();
    streamed.push("jsonl".to_string());
    assert_eq!(choices("sweep", "--format"), streamed, "sweep --format");
}
