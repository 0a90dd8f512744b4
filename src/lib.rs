//! millimpact: a validation harness for the contact law of grinding bodies (dissipative force
//! = η × gradient of the elastic energy), against exact closed forms and the DEM codes
//! LIGGGHTS, YADE and LAMMPS.
//!
//! Layers point one way: [`model`] ← [`solve`] ← [`codes`] ← [`analysis`] ← commands;
//! [`output`] and [`error`] know nothing of the commands, and clap lives in [`cli`] alone.

#![warn(missing_docs)]

pub mod analysis;
pub mod cli;
pub mod codes;
pub mod commands;
pub mod error;
pub mod model;
pub mod output;
pub mod solve;
