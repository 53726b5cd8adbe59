//! # scanline3d-tools
//!
//! The host tools' shared code (the binaries are in `src/bin`): OBJ import and baking
//! ([`obj`]), CSG trees meshed into closed triangle meshes ([`csg`]), PNG textures to flash
//! arrays ([`texture_io`]), the QEMU benchmark's ratchet ([`ratchet`]) and atomic output files
//! ([`atomic`]), with the support
//! crate's host helpers (the simulated display, PNG goldens, fixed point against float)
//! re-exported, so that the tools and their tests name one module.

pub use scanline3d_support::host::*;

pub mod atomic;
pub mod csg;
pub mod obj;
pub mod ratchet;
#[cfg(feature = "simplify")]
mod simplify;
pub mod texture_io;
