//! The integration tests' helpers: the support crate's host module (a simulated display buffer
//! that counts writes, PNG goldens, fixed point against float, the texture test scenes).
#![allow(unused_imports)]

pub use scanline3d_support::host::*;
