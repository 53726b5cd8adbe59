//! The library's integration tests, compiled as one test binary: each file in `tests/` is a
//! module of it (one link and one set of monomorphized renderers instead of one per file; the
//! test names keep the file as their first path component, e.g. `hard_cases::`).

mod common;

/// The fuzz target's input decoding, which `fuzz_regressions` and `properties` both use.
#[path = "../fuzz/fuzz_targets/render_input.rs"]
#[allow(dead_code)]
mod render_input;

mod accuracy;
mod bad_input;
mod bench_scenes;
mod capacities_api;
mod depth_modes;
mod dither_fast;
mod edges;
mod effects;
mod external_user;
mod frame_api;
mod fuzz_regressions;
mod hard_cases;
mod hostile_features;
mod hostile_numbers;
mod hostile_shapes;
mod hostile_targets;
mod named_capacities;
mod passes;
mod phong;
mod pixels;
mod properties;
mod reference_raster;
mod scenes;
mod seek;
mod shadow_map;
mod shadows;
mod strip_output;
mod targets;
mod textures;
mod volumes;
