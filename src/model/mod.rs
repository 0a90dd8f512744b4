//! The physics: case files, scenes, the paper's law and the codes' laws, the closed forms, and
//! the trajectories and figures every source is read into. No I/O but reading a case.

pub mod case;
pub mod count;
pub mod exact;
pub mod figures;
pub mod law;
pub mod scene;
pub(crate) mod shipped;
pub mod tangential;
pub mod trajectory;
