//! The four deck readers on decks no user meant: each deck of the corpus
//! (`tests/data/deck/shapes/`) and each recorded YADE dump, cut, repeated, reordered and with
//! words replaced, is read or refused, never a panic, and a refusal says something. No code
//! starts (the codes are hidden; YADE's part here is the reading of its dump). The cargo-fuzz
//! target `fuzz/fuzz_targets/deck_readers.rs` runs the same readers without end where
//! cargo-fuzz is installed.

mod common;

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

use common::deck::hide_codes;
use common::root;
use millimpact::analysis::deck::read_deck;
use millimpact::codes::CodeName;
use millimpact::codes::deck::DeckOptions;
use millimpact::codes::yade::deck::YadeDeck;
use proptest::prelude::*;

/// Words a mutation may put in a deck: the commands, keywords and numbers the readers
/// branch on, and some they must refuse.
const WORDS: [&str; 40] = [
    "units",
    "si",
    "lj",
    "include",
    "variable",
    "equal",
    "atom",
    "${x}",
    "$(zlo)",
    "$(",
    "v_x",
    "pair_style",
    "gran",
    "granular",
    "gran/hooke",
    "model",
    "hertz",
    "tangential",
    "history",
    "pair_coeff",
    "*",
    "fix",
    "wall/gran",
    "mesh/surface",
    "file",
    "read_data",
    "set",
    "group",
    "all",
    "type",
    "diameter",
    "density",
    "create_box",
    "0",
    "-1",
    "1e300",
    "NaN",
    "&",
    "#",
    "\"",
];

/// The scripts and Kratos materials files of the corpus, with the code that reads each.
fn seeds() -> Vec<(PathBuf, CodeName)> {
    let dir = root().join("tests/data/deck/shapes");
    let text = std::fs::read_to_string(dir.join("manifest.csv")).unwrap();
    text.lines()
        .skip(1)
        .filter_map(|l| {
            let mut f = l.split(',');
            let (deck, code) = (f.next()?, f.next()?);
            let code = CodeName::ALL.iter().copied().find(|c| c.name() == code)?;
            (code != CodeName::Yade).then(|| (dir.join(deck), code))
        })
        .collect()
}

/// One change to a deck's lines.
#[derive(Clone, Debug)]
enum Mutation {
    /// Remove line k.
    Drop(usize),
    /// Repeat line k.
    Repeat(usize),
    /// Swap lines k and k + 1.
    Swap(usize),
    /// Replace word w of line k.
    Word(usize, usize, usize),
    /// Cut the text at character c.
    Cut(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        any::<usize>().prop_map(Mutation::Drop),
        any::<usize>().prop_map(Mutation::Repeat),
        any::<usize>().prop_map(Mutation::Swap),
        (any::<usize>(), any::<usize>(), 0..WORDS.len())
            .prop_map(|(k, w, x)| Mutation::Word(k, w, x)),
        any::<usize>().prop_map(Mutation::Cut),
    ]
}

fn mutate(text: &str, mutations: &[Mutation]) -> String {
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    for m in mutations {
        if lines.is_empty() {
            break;
        }
        let n = lines.len();
        match *m {
            Mutation::Drop(k) => {
                lines.remove(k % n);
            }
            Mutation::Repeat(k) => lines.insert(k % n, lines[k % n].clone()),
            Mutation::Swap(k) => lines.swap(k % n, (k + 1) % n),
            Mutation::Word(k, w, x) => {
                let mut words: Vec<&str> = lines[k % n].split(' ').collect();
                let at = w % words.len();
                words[at] = WORDS[x];
                lines[k % n] = words.join(" ");
            }
            Mutation::Cut(c) => {
                let all = lines.join("\n");
                let cut: String = all.chars().take(c % (all.chars().count() + 1)).collect();
                lines = cut.lines().map(String::from).collect();
            }
        }
    }
    lines.join("\n") + "\n"
}

/// Read the deck at `path` (a copy beside the seed's own files) and require an answer, not
/// a panic; a refusal says something.
fn read_without_panic(path: &Path, code: CodeName) -> Result<(), TestCaseError> {
    let read = catch_unwind(AssertUnwindSafe(|| {
        read_deck(path, Some(code), &DeckOptions::default())
    }));
    match read {
        Err(_) => Err(TestCaseError::fail(format!("{} panicked", path.display()))),
        Ok(Err(e)) => {
            prop_assert!(!e.to_string().trim().is_empty());
            Ok(())
        }
        Ok(Ok(_)) => Ok(()),
    }
}

/// The seed's folder copied, so that its includes, data files, meshes and `.mdpa` files are
/// found beside the mutated deck.
fn copy_folder(from: &Path, to: &Path) {
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        if entry.file_type().unwrap().is_file() {
            std::fs::copy(entry.path(), to.join(entry.file_name())).unwrap();
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn the_script_and_kratos_readers_never_panic_on_a_mutated_corpus_deck(
        seed in any::<prop::sample::Index>(),
        mutations in prop::collection::vec(mutation(), 1..6),
    ) {
        hide_codes();
        let seeds = seeds();
        let (path, code) = &seeds[seed.index(seeds.len())];
        let dir = tempfile::tempdir().unwrap();
        copy_folder(path.parent().unwrap(), dir.path());
        let name = path.file_name().unwrap();
        let text = std::fs::read_to_string(path).unwrap();
        let deck = dir.path().join(name);
        std::fs::write(&deck, mutate(&text, &mutations)).unwrap();
        read_without_panic(&deck, *code)?;
    }

    #[test]
    fn the_yade_reader_never_panics_on_a_mutated_dump(
        seed in any::<prop::sample::Index>(),
        mutations in prop::collection::vec(mutation(), 1..6),
    ) {
        let dir = root().join("tests/data/deck/yade");
        let mut dumps: Vec<PathBuf> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.to_string_lossy().ends_with(".dump.json"))
            .collect();
        dumps.sort();
        let dump = &dumps[seed.index(dumps.len())];
        // A dump is one JSON document: its lines are cut where its pretty-printing breaks.
        let text = std::fs::read_to_string(dump).unwrap();
        let mutated = mutate(&text, &mutations);
        let read = catch_unwind(AssertUnwindSafe(|| {
            YadeDeck::read_dump(Path::new("script.py"), &mutated, &DeckOptions::default())
        }));
        prop_assert!(read.is_ok(), "{} panicked", dump.display());
    }
}

/// A dump that names a material's attribute as set but gives it no value (found by the
/// `deck_readers` fuzz target) is refused in one line naming the attribute, not a panic.
#[test]
fn a_set_attribute_without_a_value_is_refused() {
    let path = root().join("tests/data/deck/yade/base.dump.json");
    let mut dump: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let material = &mut dump["materials"][0];
    let key = material["changed"]
        .as_array()
        .unwrap()
        .iter()
        .map(|k| k.as_str().unwrap().to_string())
        .find(|k| k != "id")
        .expect("the seed's material sets an attribute");
    material["attributes"]
        .as_object_mut()
        .unwrap()
        .remove(&key)
        .expect("the attribute has a value in the seed");
    let read = catch_unwind(AssertUnwindSafe(|| {
        YadeDeck::read_dump(
            Path::new("script.py"),
            &dump.to_string(),
            &DeckOptions::default(),
        )
    }))
    .expect("no panic");
    let error = read.expect_err("refused").to_string();
    assert!(
        error.contains(&format!("{key}: set in the dump but given no value")),
        "{error}"
    );
    assert!(!error.contains('\n'), "{error}");
}
