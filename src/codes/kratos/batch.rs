//! Kratos batches: many impacts side by side in one DEM stage, in any scene. Each impact is
//! built as the single script builds it (its own properties and sub-properties, spheres, the
//! same start state); the stage runs the single script's step loop once for all, and each impact
//! records its single run's rows (its own steps, then its state after them). Where the bodies
//! sit is chosen so that every number its contact reads is its single run's to the last bit
//! (tested for every scene):
//!
//! - Two balls: each pair on its own line across the others, both balls at the same coordinate
//!   across, so their difference of positions is the single run's.
//! - A plate or a rod end: one wall for all, the single run's two triangles scaled by a power of
//!   two, each sphere over its own point of one triangle. Kratos' `FacetCheck` forms the normal
//!   from the edges and scales it by the reciprocal of its length: scaled by a power of two, the
//!   edges give the single run's normal to the bit, whose in-plane components are exact zeros, so
//!   the distance is the single run's whatever the sphere's place in the plane. (A wall per
//!   impact, moved in the plane, is not: its moved corners round, its edges come out an ulp
//!   longer or shorter, and so, for some offsets, does the distance: measured, 3e-14 of the
//!   force.) One wall means one wall material and one ball radius per batch.
//!
//! Side by side rather than one after another: importing Kratos and initialising a stage cost
//! far more than an impact's steps, and the loop's Python calls a step are shared.

use crate::codes::batch::parse_marked_batch;
use crate::codes::batch_fns::{BatchFns, check_batch_size};
use crate::codes::kratos::Kratos;
use crate::codes::script_values::python_dict;
use crate::codes::template::exact_number;
use crate::codes::{BatchError, CodeSetup, RenderedInput};
use crate::model::scene::SceneKind;

/// Most impacts in one batch.
pub(crate) const MAX_BATCH: usize = 256;

/// Impacts whose steps cost what one start of Kratos does: importing Kratos and initialising
/// the stage take about 0.27 s of CPU, an impact at 200 steps per contact about 1.8 ms of its
/// batch (its steps and rows), measured on Kratos 10.4.
pub(crate) const IMPACTS_PER_START: usize = 150;

/// The batch script.
pub(crate) const BATCH_SCRIPT: &str = "batch.py";

/// The part of the batch script after its list of impacts.
pub(super) const SCRIPT: &str = include_str!("batch.py");

/// The batch script for `setups`, or why they cannot run as one.
pub(crate) fn render_batch(setups: &[CodeSetup]) -> Result<RenderedInput, BatchError> {
    check_batch_size(setups, MAX_BATCH, "the batch script's size")?;
    let first = &setups[0];
    let mut impacts = String::new();
    let shared = |values: &[(&'static str, String)]| -> Vec<String> {
        values
            .iter()
            .filter(|(key, _)| ["scene", "radius", "wall_young", "wall_poisson"].contains(key))
            .map(|(_, value)| value.clone())
            .collect()
    };
    let first_values = Kratos.script_values(first)?;
    let wall = first.scene != SceneKind::BallBall;
    for s in setups {
        if s.timestep.to_bits() != first.timestep.to_bits() {
            return Err(BatchError::Differ { what: "time step" });
        }
        let values = Kratos.script_values(s)?;
        if s.scene != first.scene || (wall && shared(&values) != shared(&first_values)) {
            return Err(BatchError::Differ {
                what: "scene, or the wall's material or ball radius (one wall per batch)",
            });
        }
        // The single script's values, as Python literals.
        impacts += &format!("    {},\n", python_dict(&values));
    }
    // Far enough apart that no two impacts' bodies or walls (squares of side 8 R) ever meet.
    let reach = setups
        .iter()
        .map(|s| (8.0 * s.sphere.radius).max(2.0 * s.other_sphere.map_or(0.0, |o| o.radius)))
        .fold(0.0f64, f64::max);
    let text = format!(
        "# millimpact: {} impacts side by side in one Kratos DEM stage (src/codes/kratos/batch.rs).\n\
         # Each impact's values, as the single script is filled with them.\nIMPACTS = [\n{impacts}]\nSPACING = {}\n{}",
        setups.len(),
        exact_number(2.0 * reach),
        super::with_common(SCRIPT),
    );
    Ok(super::script_input(BATCH_SCRIPT, text))
}

/// Kratos' batches: many impacts side by side in one stage.
pub(crate) static KRATOS_BATCH: BatchFns =
    BatchFns::new(MAX_BATCH, render_batch, parse_marked_batch).costing(IMPACTS_PER_START);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codes::CodeName;
    use crate::codes::kratos::RUN_FILES;
    use crate::codes::setup::shipped_setup;

    #[test]
    fn the_script_lists_each_impact_with_its_single_scripts_values() {
        let setups = [
            shipped_setup(CodeName::Kratos, "rod_end", 0.1),
            shipped_setup(CodeName::Kratos, "rod_end", 0.6),
        ];
        let text = render_batch(&setups).unwrap().text;
        for s in &setups {
            let impact = python_dict(&Kratos.script_values(s).unwrap());
            assert!(text.contains(&impact), "{impact}");
        }
        // A batch writes its own files, not a single run's.
        assert!(!text.contains(&format!("\"{}\"", RUN_FILES[1])));
        let mut finer = shipped_setup(CodeName::Kratos, "rod_end", 0.6);
        finer.timestep /= 2.0;
        assert!(matches!(
            render_batch(&[setups[0].clone(), finer]),
            Err(BatchError::Differ { .. })
        ));
    }
}
