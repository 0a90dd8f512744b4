//! The cases shipped in `cases/`, built into the binary, so that a command that draws on them
//! (the report's figures, `compare` and `calibrate` with no case given) reads the same cases
//! from whatever folder it runs in.

use std::path::Path;

use super::case::{Case, CaseError};

/// Each shipped case's name and the text of `cases/<name>.toml` as this build was made from.
const SHIPPED: [(&str, &str); 7] = [
    ("ball_ball", include_str!("../../cases/ball_ball.toml")),
    (
        "ball_ball_paper",
        include_str!("../../cases/ball_ball_paper.toml"),
    ),
    (
        "ball_ball_unequal",
        include_str!("../../cases/ball_ball_unequal.toml"),
    ),
    ("ball_plate", include_str!("../../cases/ball_plate.toml")),
    (
        "ball_plate_rigid",
        include_str!("../../cases/ball_plate_rigid.toml"),
    ),
    ("rod_end", include_str!("../../cases/rod_end.toml")),
    (
        "rod_end_bilateral",
        include_str!("../../cases/rod_end_bilateral.toml"),
    ),
];

/// The three canonical impacts (ball on plate, ball on ball, a rod's end), in report order.
pub(crate) const CANONICAL: [&str; 3] = ["ball_plate", "ball_ball", "rod_end"];

/// A case shipped as `cases/<name>.toml`, read from this build (its path says
/// `cases/<name>.toml`, as the commands that reproduce it name it).
pub fn shipped_case(name: &str) -> Result<Case, CaseError> {
    let path = Path::new("cases").join(format!("{name}.toml"));
    let Some((_, text)) = SHIPPED.iter().find(|(n, _)| *n == name) else {
        let known: Vec<&str> = SHIPPED.iter().map(|(n, _)| *n).collect();
        return Err(CaseError::new(
            &path.display().to_string(),
            "(file)",
            name,
            &format!("a shipped case: {}", known.join(", ")),
        ));
    };
    Case::parse(text, &path)
}

/// The canonical cases, from this build.
pub fn canonical_cases() -> Result<Vec<Case>, CaseError> {
    CANONICAL.iter().map(|n| shipped_case(n)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every file in `cases/` is built in, and each reads back as its file does.
    #[test]
    fn every_case_file_is_shipped_and_reads_as_its_file() {
        let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases");
        let mut on_disk: Vec<String> = std::fs::read_dir(&folder)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|x| x == "toml"))
            .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
            .collect();
        on_disk.sort();
        let built: Vec<String> = SHIPPED.iter().map(|(n, _)| n.to_string()).collect();
        assert_eq!(built, on_disk);
        for name in &built {
            let shipped = shipped_case(name).unwrap();
            let file = Case::load(&folder.join(format!("{name}.toml"))).unwrap();
            assert_eq!(shipped.law(), file.law(), "{name}");
            assert_eq!(shipped.name, file.name);
        }
        assert!(shipped_case("no_such_case").is_err());
    }
}
