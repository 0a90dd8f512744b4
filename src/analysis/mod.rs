//! What the harness concludes: runs against the closed forms, the reference store and its
//! verification, the attribution of each code's difference, and the comparison, precision,
//! stability and sweep studies. Typed options in, typed summaries out; nothing here prints.

pub mod benchmark;
pub mod calibrate;
pub mod compare;
pub mod deck;
pub mod mill;
pub mod precision;
pub mod probe;
pub mod report;
pub mod run;
pub mod source;
pub(crate) mod stability;
pub mod store;
pub mod sweep;
pub(crate) mod tolerance;
