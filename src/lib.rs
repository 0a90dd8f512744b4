//! millimpact: a validation harness for the contact law of grinding bodies
//! (dissipative force = η × gradient of the elastic energy), against exact closed forms and
//! the DEM codes LIGGGHTS, YADE and LAMMPS.

#![warn(missing_docs)]

pub mod app;
pub mod case;
pub mod cli;
pub mod codes;
pub mod compare;
pub mod exact;
pub mod figures;
pub mod law;
pub mod precision;
pub mod references;
pub mod report;
pub mod scene;
pub mod solve;
pub mod stability;
