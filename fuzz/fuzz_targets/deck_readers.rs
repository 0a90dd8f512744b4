//! The four deck readers on arbitrary text: a deck read or refused, never a panic, and a
//! refusal says something. The first byte picks the reader (LIGGGHTS, LAMMPS, a Kratos
//! materials file, a YADE dump); the rest is the deck. No code starts: the LAMMPS reader
//! falls back to its build's conventions where no binary is found (run with the
//! `MILLIMPACT_<CODE>_BINARY` variables naming no file), and YADE's part is its dump's reading.
//! Seeds: `tests/data/deck/shapes/` and `tests/data/deck/yade/*.dump.json` (the proptest
//! `tests/deck_fuzz.rs` runs the same readers in the fast tier).
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use millimpact::analysis::deck::read_deck;
use millimpact::codes::CodeName;
use millimpact::codes::deck::DeckOptions;
use millimpact::codes::yade::deck::YadeDeck;

fuzz_target!(|data: &[u8]| {
    let Some((&pick, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let options = DeckOptions::default();
    if pick % 4 == 3 {
        if let Err(e) = YadeDeck::read_dump(Path::new("script.py"), text, &options) {
            assert!(!e.to_string().trim().is_empty());
        }
        return;
    }
    let (code, name) = match pick % 4 {
        0 => (CodeName::Liggghts, "in.deck"),
        1 => (CodeName::Lammps, "in.deck"),
        _ => (CodeName::Kratos, "MaterialsDEM.json"),
    };
    let dir = std::env::temp_dir().join(format!("millimpact-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("the deck written");
    if let Err(e) = read_deck(&path, Some(code), &options) {
        assert!(!e.to_string().trim().is_empty());
    }
});
