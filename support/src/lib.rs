//! # scanline3d-support
//!
//! What the firmware, the QEMU benchmark and the host tools of the
//! [scanline3d](https://crates.io/crates/scanline3d) repository share, built only on the
//! renderer's public API and `no_std` like it:
//!
//! - [`demo`]: the built-in scenes (the benchmark torus, the benchmark frames, the shadow and
//!   CSG scenes, the Pico board's scene and its strip pass);
//! - [`hash`]: draw targets that keep no pixels, only a hash of them (a frame drawn on a
//!   microcontroller compared with the host's) or nothing at all;
//! - [`metrics`]: error metrics between two renderings, line by line in O(width) memory;
//! - [`overlay`]: text rasterized once and composed into the strips a label crosses;
//! - `host` (the `host` feature, with `std`): the tests' and tools' simulated display, PNG
//!   goldens and comparisons.
//!
//! Not published: the repository's tools and firmware use it by path.

#![cfg_attr(not(feature = "host"), no_std)]
#![deny(missing_docs)]
#![deny(rustdoc::broken_intra_doc_links)]
#![allow(clippy::needless_range_loop)]

pub mod demo;
mod demo_assets;
mod demo_csg;
// Written by `bake` (the tools' tests check that re-baking reproduces it byte for byte):
// neither formatted nor linted here.
#[rustfmt::skip]
#[allow(dead_code, clippy::all)]
mod demo_csg_mesh;
mod demo_shadow;
pub mod hash;
#[cfg(feature = "host")]
pub mod host;
pub mod metrics;
pub mod overlay;
