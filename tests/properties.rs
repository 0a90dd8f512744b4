//! Properties over the whole valid range: every method, at every setting the command line
//! admits, returns finite figures with the COR in [0, 1] and a non-negative absorbed energy, or
//! refuses the setting with a reason; the case reader never panics, whatever bytes it is given.

mod common;

use std::io::Write;

use common::{case, scenes};
use millimpact::analysis::run::{IntegrationOptions, warnings};
use millimpact::model::case::Case;
use millimpact::solve::Method;
use millimpact::solve::paper;
use proptest::prelude::*;

/// Integrate `c` as `run` would with `options`: the same validation, then the solver.
fn run(c: &Case, options: &IntegrationOptions) -> Option<millimpact::Outcome> {
    let settings = options.settings(c, false).ok()?;
    paper::solve(&c.law(), c.impact_velocity, &settings).ok()
}

/// Any double, or a positive one log-uniform over the whole range of doubles, or one in [0, 1).
fn number() -> impl Strategy<Value = f64> {
    prop_oneof![
        any::<f64>(),
        (-320.0f64..308.0).prop_map(|e| 10f64.powf(e)),
        0.0f64..1.0,
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Cases drawn log-uniformly over moduli, sizes and speeds, η over [0, 1), every method at
    /// a resolution anywhere in its admitted range: finite figures, COR in [0, 1], no energy
    /// created, or a refusal.
    #[test]
    fn every_method_gives_a_physical_answer_or_refuses(
        log_e in 5.0f64..15.0,
        log_r in -6.0f64..0.0,
        log_v in -8.0f64..3.0,
        eta in 0.0f64..0.999_999,
        scene_index in 0usize..3,
        method_index in 0usize..Method::ALL.len(),
        log_steps in 0.0f64..4.5,
        log_rtol in -14.0f64..-2.0,
        by_timestep in any::<bool>(),
    ) {
        let (name, scene) = scenes(10f64.powf(log_r), 10f64.powf(log_e)).swap_remove(scene_index);
        let c = case(name, scene, 10f64.powf(log_v), eta);
        let method = Method::ALL[method_index];
        let mut options = IntegrationOptions { method, ..IntegrationOptions::default() };
        let steps = 10f64.powf(log_steps).round().max(1.0);
        if method.is_fixed_step() {
            if by_timestep {
                // A step in seconds: the undamped period over `steps`, as a user might give it.
                let law = c.law();
                let y0 = law.elastic_peak(c.impact_velocity);
                let period = 4.0 * millimpact::model::exact::j_integral(law.exponent)
                    * y0 / c.impact_velocity;
                options.timestep = Some(period / steps);
            } else {
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                let n = steps as u32;
                options.steps_per_period = Some(n);
            }
        } else if method == Method::Dopri5 {
            options.rtol = Some(10f64.powf(log_rtol));
        }
        if let Some(outcome) = run(&c, &options) {
            let f = outcome.figures;
            let what = format!(
                "{name} E=1e{log_e:.2} R=1e{log_r:.2} v0=1e{log_v:.2} η={eta} {method} \
                 steps={steps} by_timestep={by_timestep}"
            );
            for (label, x) in [
                ("cor", f.cor),
                ("peak", f.peak_deformation),
                ("peak force", f.peak_force),
                ("contact time", f.contact_time),
                ("absorbed energy", f.absorbed_energy),
            ] {
                prop_assert!(x.is_finite(), "{what}: {label} = {x}");
            }
            // Outside [0, 1] is a fixed-step method's step error at a coarse step, and then the
            // run says so.
            let physical = (0.0..=1.0).contains(&f.cor) && f.absorbed_energy >= 0.0;
            let warned = warnings(&c, method, &f).iter().any(|w| w.contains("outside [0, 1]"));
            prop_assert!(physical != warned, "{what}: COR {}, absorbed {}, warned {warned}",
                f.cor, f.absorbed_energy);
            prop_assert!(physical || method.is_fixed_step(), "{what}: COR {}", f.cor);
            prop_assert!(f.peak_deformation > 0.0 && f.contact_time > 0.0, "{what}");
        }
    }

    /// Arbitrary bytes as a case file: an error or a case, never a panic, and an error is one
    /// line.
    #[test]
    fn the_case_reader_never_panics(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
        let mut file = tempfile::NamedTempFile::new().unwrap();
        file.write_all(&bytes).unwrap();
        if let Err(e) = Case::load(file.path()) {
            prop_assert!(!e.to_string().contains('\n'), "{e}");
        }
    }

    /// Arbitrary text, and text made of a case file's own pieces in any order: the reader
    /// answers with a case or one line, never a panic (multi-byte characters included, where an
    /// error's line and column are counted).
    #[test]
    fn the_case_reader_never_panics_on_any_text(
        text in prop_oneof![
            any::<String>(),
            proptest::collection::vec(
                prop_oneof![
                    Just("scene = \"ball_plate\"\n".to_string()),
                    Just("[ball]\n".to_string()),
                    Just("[plate]\n".to_string()),
                    Just("radius = ".to_string()),
                    Just("rigid = true\n".to_string()),
                    Just("impact_velocity = 2.0\n".to_string()),
                    Just("loss_coefficient = 0.35\n".to_string()),
                    Just("δ = \"é\"\n".to_string()),
                    "[0-9.e+-]{1,12}\n",
                    "[a-z_\\[\\]=\" ]{1,12}",
                ],
                0..20,
            )
            .prop_map(|pieces| pieces.concat()),
        ]
    ) {
        if let Err(e) = Case::parse(&text, std::path::Path::new("any.toml")) {
            prop_assert!(!e.to_string().contains('\n'), "{e}");
        }
    }

    /// Case-shaped text with arbitrary numbers in every field: the reader accepts only what it
    /// can represent, and what it accepts integrates to a physical answer.
    #[test]
    fn case_shaped_text_with_any_numbers(
        radius in number(),
        density in number(),
        modulus in number(),
        poisson in number(),
        speed in number(),
        eta in number(),
    ) {
        let text = format!(
            "scene = \"ball_plate\"\nimpact_velocity = {speed:e}\nloss_coefficient = {eta:e}\n\
             [ball]\nradius = {radius:e}\ndensity = {density:e}\nyoungs_modulus = {modulus:e}\n\
             poisson_ratio = {poisson:e}\n[plate]\nrigid = true\n"
        );
        let mut file = tempfile::NamedTempFile::new().unwrap();
        file.write_all(text.as_bytes()).unwrap();
        if let Ok(c) = Case::load(file.path()) {
            let outcome = run(&c, &IntegrationOptions::default());
            prop_assert!(outcome.is_some(), "{text}");
            let cor = outcome.unwrap().figures.cor;
            prop_assert!((0.0..=1.0).contains(&cor), "{text}: COR {cor}");
        }
    }
}
