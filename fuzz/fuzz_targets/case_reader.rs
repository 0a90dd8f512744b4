//! The case reader on arbitrary text: an error or a case, never a panic; an error is one line,
//! and a case it accepts integrates to a COR in [0, 1].
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use millimpact::analysis::run::IntegrationOptions;
use millimpact::model::case::Case;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match Case::parse(text, Path::new("fuzz.toml")) {
        Err(e) => assert!(!e.to_string().contains('\n'), "{e}"),
        Ok(case) => {
            let settings = IntegrationOptions::default()
                .settings(&case, false)
                .expect("the default settings suit every case");
            let outcome = millimpact::solve(&case.law(), case.impact_velocity, &settings)
                .expect("an accepted case integrates");
            assert!((0.0..=1.0).contains(&outcome.figures.cor), "{text}");
        }
    }
});
