//! The Yade driver (being written).

use std::path::Path;

use super::{CodeDriver, CodeError, CodeSetup, ParsedRun, RenderedInput};
use crate::law::DashpotLaw;

/// The Yade driver.
pub struct Yade;

impl CodeDriver for Yade {
    fn name(&self) -> &'static str {
        "yade"
    }
    fn binary(&self) -> &'static str {
        "yade"
    }
    fn render(&self, setup: &CodeSetup) -> Result<RenderedInput, CodeError> {
        Err(CodeError::Unsupported {
            code: self.name().into(),
            case: setup.case_name.clone(),
            reason: "driver not written yet".into(),
        })
    }
    fn parse(&self, _setup: &CodeSetup, _workdir: &Path, _log: &str) -> Result<ParsedRun, String> {
        Err("driver not written yet".into())
    }
    fn law(&self, setup: &CodeSetup) -> DashpotLaw {
        DashpotLaw::damped_hertz(setup.reduced_mass, setup.stiffness, setup.target_restitution)
    }
}
