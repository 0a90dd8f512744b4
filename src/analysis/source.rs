//! What produced a figure: one of our methods, or a DEM code (run now or stored).

use serde::{Serialize, Serializer};

use crate::codes::CodeName;
use crate::solve::Method;

/// A source of impact figures.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Source {
    /// One of the harness's methods.
    Method(Method),
    /// A DEM code.
    Code(CodeName),
}

impl Source {
    /// Its name: the method's or the code's.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Source::Method(m) => m.name(),
            Source::Code(c) => c.name(),
        }
    }

    /// `method` or `code`.
    pub(crate) fn kind(self) -> &'static str {
        match self {
            Source::Method(_) => "method",
            Source::Code(_) => "code",
        }
    }
}

impl std::fmt::Display for Source {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Serialised as its name: method and code names are distinct.
impl Serialize for Source {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

/// The resolution a source runs at: the value of its precision knob.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Resolution {
    /// Steps per undamped period (fixed-step methods).
    StepsPerPeriod(u32),
    /// Relative tolerance (adaptive methods).
    Rtol(f64),
    /// Steps per elastic contact time (DEM codes).
    StepsPerContact(u32),
}

impl Resolution {
    /// Steps per period, if that is the knob.
    pub fn steps_per_period(resolution: Option<Resolution>) -> Option<u32> {
        match resolution {
            Some(Resolution::StepsPerPeriod(n)) => Some(n),
            _ => None,
        }
    }

    /// The relative tolerance, if that is the knob.
    pub fn rtol(resolution: Option<Resolution>) -> Option<f64> {
        match resolution {
            Some(Resolution::Rtol(r)) => Some(r),
            _ => None,
        }
    }

    /// Steps per contact, if that is the knob.
    pub(crate) fn steps_per_contact(resolution: Option<Resolution>) -> Option<u32> {
        match resolution {
            Some(Resolution::StepsPerContact(n)) => Some(n),
            _ => None,
        }
    }
}
