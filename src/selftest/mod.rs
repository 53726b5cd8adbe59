//! Kernel tests: every kernel of `kernel` against its portable twin on pseudo-random inputs.
//!
//! The benchmark firmware (`mcu-bench`) runs them on every Cortex-M core before it measures,
//! and the Pico firmware runs the RP2040's own row routine at start-up; each returns the first
//! input on which a kernel and its twin differ, or `None`. The generators and the oracles are
//! plain portable code and compile on every target: on the host, where every kernel is its
//! portable implementation, the unit tests run them too (the kernels decline there, so the
//! comparisons pass; what the host run checks is that the generators and the oracles work).

mod geometry;
mod raster;

pub use geometry::{
    cull_self_test, light_self_test, projection_self_test, transform_self_test, vertex_self_test,
};
pub use raster::{
    dither_fits_self_test, dither_rows_self_test, dither_span_self_test, edge_setup_self_test,
    gouraud_setup_self_test, rows_self_test, span_self_test, triangle_setup_self_test,
};

use crate::geometry::project::{pack_channels, Viewport};
use crate::geometry::vertex_record;
use crate::kernel;
use crate::kernel::records::{
    first_pixel, ActiveList, ActiveTri, Bins, CullCounts, ScreenVertex, Sorted, TriRecord,
    DITHER_OK, FAST, FLAT, LAST_IN_ROUTINE, LIT, NEEDS_LIGHT, SWITCH_IN_ROUTINE,
};
use crate::kernel::records::{CullStop, Edge};
use crate::num::math::Mat4;
use crate::num::scalar::Scalar;
use crate::raster::setup::attribute_words;
use crate::raster::span::{
    span_flat_portable, span_packed_dither_portable, span_packed_portable, LESS,
};
use crate::raster::{DepthTest, SpanMode};
use crate::scene::color::{rgb565_words_mut, TargetColor};
use crate::scene::shade::lit_diffuse;
use crate::scene::shade::PreparedLight;
use heapless::Vec;

/// A signed value of 1 to `max_bits`
/// bits (the count from `next`'s top bits, the sign from its lowest) from the generator `next`.
pub fn signed_bits(next: &mut impl FnMut() -> u32, max_bits: u32) -> i32 {
    let r = next();
    let bits = (r >> 27) % max_bits + 1;
    let v = (next() >> (32 - bits)) as i32;
    if r & 1 == 0 {
        -v
    } else {
        v
    }
}

/// For the benchmark firmware's self-tests (Cortex-M) and the unit tests: a xorshift32
/// generator from `seed` (nonzero), the same sequence on every core.
pub fn xorshift32(seed: u32) -> impl FnMut() -> u32 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state
    }
}

/// For the self-tests: any depth and any 10-bit colour channels for `p`.
fn random_depth_and_colour(p: &mut ScreenVertex, next: &mut impl FnMut() -> u32) {
    let d = next();
    p.z = d as u16;
    p.zf = (d >> 16) as u8;
    let c = next();
    p.set_color([
        (c & 1023) as u16,
        (c >> 10 & 1023) as u16,
        (c >> 20 & 1023) as u16,
    ]);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On the host every kernel is its portable implementation (or declines), so every
    /// comparison must pass; this runs the generators and the oracles the firmware runs.
    #[test]
    fn every_kernel_comparison_runs_and_passes_on_the_host() {
        assert_eq!(edge_setup_self_test(500), None);
        assert_eq!(projection_self_test(500), None);
        assert_eq!(gouraud_setup_self_test(500), None);
        assert_eq!(triangle_setup_self_test(500), None);
        assert_eq!(dither_fits_self_test(500), None);
        assert_eq!(dither_span_self_test(500), None);
        assert_eq!(span_self_test(500), None);
        assert_eq!(dither_rows_self_test(50), None);
        assert_eq!(rows_self_test(50), None);
        assert_eq!(cull_self_test(200), None);
        assert_eq!(vertex_self_test(200), None);
        assert_eq!(light_self_test(200), None);
        assert_eq!(transform_self_test(500), None);
    }

    /// The generator is the same xorshift32 sequence everywhere (the firmware's cases are the
    /// host's).
    #[test]
    fn the_generator_is_xorshift32() {
        let mut g = xorshift32(1);
        assert_eq!([g(), g(), g()], [270_369, 67_634_689, 2_647_435_461]);
    }
}
