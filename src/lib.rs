//! millimpact: a validation harness for the contact law of grinding bodies
//! (dissipative force = η × gradient of the elastic energy), against exact closed forms and
//! the DEM codes LIGGGHTS, YADE and LAMMPS.

pub mod codes;
pub mod law;
pub mod scene;
pub mod exact;
pub mod solve;
