//! The kernel interface: every architecture-specific routine of the renderer, behind one set of
//! entry points that work on the plain records of [`records`].
//!
//! Each entry point does **a prefix of its work and says how far it got** (a count, an index,
//! an `Option` or a `bool`); the caller finishes the rest with portable code. Which
//! implementation runs is chosen here and nowhere else, by the cfg aliases that `build.rs`
//! sets (a third, `scanline3d_thumb2`, picks Thumb-2 forms inside [`thumb`]):
//!
//! - `scanline3d_thumb`: a Cortex-M target (`target_arch = "arm"`, `target_os = "none"`) and
//!   the `portable` feature off. The Thumb kernels of [`thumb`] that pay off on every Cortex-M
//!   core run: the RGB565 span loops, the row routine, the line clear, the cull loop, the
//!   triangle setup, the Gouraud attribute setup and the dither check (the two setups in
//!   Thumb-2 forms, `thumb::setup_t2`, where `scanline3d_thumb2`).
//! - `scanline3d_thumb_v6m`: the same on ARMv6-M (Cortex-M0/M0+: no 32 × 32 → 64-bit multiply,
//!   no divide instruction). The kernels that only pay off there run too: the Q16.16
//!   transforms, the vertex run, the lighting run, the projection, the edge setup and the flat
//!   span.
//! - `scanline3d_thumb2`: a Cortex-M core with Thumb-2 (ARMv7-M, ARMv7E-M, ARMv8-M Mainline).
//!   Besides the kernels of every Cortex-M core (the two setups and the row routine in Thumb-2
//!   forms), the vertex run, the projection and the lighting run run there, with Thumb-2
//!   forms of the transform, the projection and the lighting's products (`thumb::xform_t2`,
//!   `thumb::project_t2`, the Thumb-2 macros of `thumb::light`: `smlal`, `smull`, `umull`,
//!   `clz`). The edge kernel and the single transforms stay on ARMv6-M (on Thumb-2 the
//!   portable forms, with the long multiply and the divide, are as fast or faster).
//! - `scanline3d_thumb_geometry`: either of the last two, where the vertex run, the projection
//!   and the lighting run have a kernel (the one alias their entry points and modules test).
//!
//! With neither (the host, and any target with the `portable` feature) every entry point runs
//! its portable implementation. A triangle or a colour type the fast kernels do not handle (a
//! new shading mode, a texture, a colour type other than RGB565) is declined by them and takes
//! the portable path: adding one needs no assembly.
//!
//! | entry point | Thumb kernel | portable implementation (the twin it is compared with) |
//! |---|---|---|
//! | [`cull_push`] | `thumb::cull` (all Cortex-M; a Thumb-2 routine where `scanline3d_thumb2`) | `portable::cull_push` |
//! | [`edge_new`] | `thumb::edge` (ARMv6-M) | `Edge::new_portable` |
//! | [`clear_line565`] | `thumb::fill` (all Cortex-M) | `portable::clear_line` |
//! | [`transform_q16`], [`transform_dir_q16`] | `thumb::xform` (ARMv6-M; elsewhere the native 64-bit multiply-accumulate is faster) | declines; `Scalar::dot3_add` rows |
//! | [`project_q16`] | `thumb::project` (ARMv6-M; `thumb::project_t2` where `scanline3d_thumb2`) | declines; `Viewport::project` |
//! | [`project_run`] | `thumb::vertex` (ARMv6-M and `scanline3d_thumb2`, calling `thumb::xform_t2` and `thumb::project_t2` there) | declines; the geometry stage's vertex loop |
//! | [`light_run`] | `thumb::light` (ARMv6-M; Thumb-2 forms of its products where `scanline3d_thumb2`) | declines; the lighting stage's vertex loop |
//! | [`setup565`] | `thumb::setup` (all Cortex-M; Thumb-2 form in `thumb::setup_t2` where `scanline3d_thumb2`) | declines; `ActiveTri::setup` |
//! | [`gouraud_setup`] | `thumb::gouraud` (all Cortex-M; Thumb-2 form in `thumb::setup_t2` where `scanline3d_thumb2`) | declines; `raster::attribute_words` |
//! | [`dither_fits565`] | `thumb::dither_fits` (all Cortex-M) | declines; `ActiveTri::dither_fits` |
//! | [`span565_less`], [`span565_less_dither`] | `thumb::span` (all Cortex-M; Thumb-2 pixel loop where `scanline3d_thumb2`) | declines; the span stage's packed loops |
//! | [`span565_flat_less`] | `thumb::span` (ARMv6-M) | declines; the span stage's flat loop |
//! | [`rows565`] | `thumb::rows`, `thumb::rows_dither` (all Cortex-M; hot path in Thumb-2, `thumb::rows_t2`, where `scanline3d_thumb2`) | declines; `ActiveTri::draw_row` |
//!
//! Every Thumb kernel computes exactly what its twin computes (the same roundings, the same
//! wrapping), so the image is bit-identical on every target: the benchmark firmware compares
//! each kernel with its twin on random inputs before it measures (`selftest`), and
//! `scripts/mcu-bench` compares the frames' hashes with the host's. The kernels depend on the
//! records and on `wide`'s integer helpers, never on the renderer.

pub(crate) mod portable;
pub(crate) mod records;
#[cfg(scanline3d_thumb)]
mod thumb;
pub(crate) mod wide;

use heapless::Vec;

use records::TriRecord;
use records::{ActiveList, ActiveTri, Bins, CullCounts, CullStop, Edge, ScreenVertex, Sorted};

/// What [`setup565`] did.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[cfg_attr(not(scanline3d_thumb), allow(dead_code))]
pub(crate) enum Setup565 {
    /// Set up and kept (while dithering: with `DITHER_OK`).
    Kept,
    /// No row to draw from the given row on.
    Empty,
    /// Set up, but while dithering its packed fields failed `ActiveTri::dither_fits`: the
    /// triangle must be set up again without the fast path.
    NotDitherable,
}

/// `(n / d, n % d)` for `d > 0`. Where the core has no divide instruction (ARMv6-M: the
/// library division costs over a hundred instructions whatever the quotient) by shift and
/// subtract, one step per quotient bit, which suits an edge's few-bit quotients; elsewhere the
/// division. (The `scanline3d_no_divide` cfg of `build.rs`; not affected by `portable`.)
#[inline]
pub(crate) fn udiv_small(n: u32, d: u32) -> (u32, u32) {
    #[cfg(scanline3d_no_divide)]
    return crate::kernel::wide::udiv_shift_subtract(n, d);
    #[cfg(not(scanline3d_no_divide))]
    (n / d, n % d)
}

/// `n / len` (toward zero) for `len ≥ 1`: a span segment's step. Where the core has no divide
/// instruction (ARMv6-M) by shifts, adds and 32-bit products for `len` up to 15 (a fast-Phong
/// segment's or a short perspective-textured segment's length), the division above that;
/// elsewhere the division. (The `scanline3d_no_divide` cfg of `build.rs`, as [`udiv_small`].)
#[inline(always)]
pub(crate) fn div_segment(n: i32, len: i32) -> i32 {
    #[cfg(scanline3d_no_divide)]
    return crate::kernel::wide::div_by_small_shift_add(n, len);
    // `/` as the spans had it (`wrapping_div` compiles to other code: fast Phong +0.5 % on
    // the M4F).
    #[cfg(not(scanline3d_no_divide))]
    {
        n / len
    }
}

impl Edge {
    /// The edge `a → b` (`a.y < b.y`) at pixel row `row` (on the screen, 0..=1024), for
    /// coordinates within ±[`records::COORD_LIMIT`]: every product is under 2³⁰ and the sum
    /// under 2³¹, so the setup is 32-bit (two small divisions). The edge kernel takes the rows
    /// the renderer sets edges up on; [`Edge::new_portable`] the rest.
    #[inline(always)]
    pub(crate) fn new(xa: i32, ya: i32, xb: i32, yb: i32, row: i32) -> Edge {
        if let Some(e) = edge_new(xa, ya, xb, yb, row) {
            return e;
        }
        Edge::new_portable(xa, ya, xb, yb, row)
    }
}

/// The edge kernel: [`Edge::new_portable`]'s edge for a row from the edge's first sample on
/// (`0 ≤ k ≤ dy + 16`), for coordinates that fit 16 bits; `None` where it declines.
#[inline(always)]
pub(crate) fn edge_new(xa: i32, ya: i32, xb: i32, yb: i32, row: i32) -> Option<Edge> {
    #[cfg(scanline3d_thumb_v6m)]
    return thumb::edge_new(xa, ya, xb, yb, row);
    #[cfg(not(scanline3d_thumb_v6m))]
    {
        let _ = (xa, ya, xb, yb, row);
        None
    }
}

/// Whether the triangle-setup kernels ([`setup565`], [`gouraud_setup`], [`dither_fits565`])
/// can do anything (the setup keeps its portable attribute words out of line only then).
pub(crate) const SETUP_KERNELS: bool = cfg!(scanline3d_thumb);

/// Whether the pooled kinds' row (`raster::kind::pool_row`) calls the textured span out of
/// line, in a function of its own, rather than where the compiler chooses. On the Thumb cores
/// the textured rows were then 0.3-2.7 % cheaper on Cortex-M4F and M33 (the Phong rows 0.1-0.5 %)
/// and unchanged on M0; on RISC-V (rv32imac) the textured rows were 1.1-4.3 % dearer, so the
/// compiler keeps the choice there (`scripts/mcu-bench`; CHANGELOG has the figures).
pub(crate) const TEXTURED_SPAN_OUT_OF_LINE: bool = cfg!(scanline3d_thumb);

/// Whether the textured span's pixel loop walks each segment as slices of the depth and colour
/// lines cut to the span (no index, no bounds check per pixel; on the Thumb cores textured
/// −4 % on the Cortex-M4F and M33, −5 % on the M0) or by index (elsewhere: on rv32imac the
/// sliced loop was 1.0–1.3 % dearer, textured_fog aside, and the indexed loop over the cut
/// lines 5–9 %). The same pixels either way.
pub(crate) const TEXTURED_PIXELS_SLICED: bool = cfg!(scanline3d_thumb);

/// Whether [`transform_q16`] and [`transform_dir_q16`] can do anything (a caller keeps its
/// fallback out of line only then).
pub(crate) const TRANSFORM: bool = cfg!(scanline3d_thumb_v6m);

/// `m · (p, 1)` in Q16.16 words, as four `Scalar::dot3_add` rows of `Fx<I16F16>` give it,
/// when every entry is in [−2³⁰, 2³⁰); `None` where it declines.
#[inline(always)]
pub(crate) fn transform_q16(m: &[[i32; 4]; 4], p: [i32; 3]) -> Option<[i32; 4]> {
    #[cfg(scanline3d_thumb_v6m)]
    return thumb::transform_q16(m, p);
    #[cfg(not(scanline3d_thumb_v6m))]
    {
        let _ = (m, p);
        None
    }
}

/// The upper 3 × 3 block of `m` times the direction `v` in Q16.16 words (see
/// [`transform_q16`]); `None` where it declines.
#[inline(always)]
pub(crate) fn transform_dir_q16(m: &[[i32; 4]; 4], v: [i32; 3]) -> Option<[i32; 3]> {
    #[cfg(scanline3d_thumb_v6m)]
    return thumb::transform_dir_q16(m, v);
    #[cfg(not(scanline3d_thumb_v6m))]
    {
        let _ = (m, v);
        None
    }
}

/// `Viewport::project`'s screen words (x, y in subpixels clamped to ±`COORD_LIMIT`, depth as
/// unsigned 16.8) of a Q16.16 clip-space point for the scales `sx`, `sy` (8 × the viewport
/// size); `None` where it declines (scales of 2¹⁶ or more, w ≤ 2⁻¹³, beyond the guard band).
#[inline(always)]
pub(crate) fn project_q16(p: &[i32; 4], sx: u32, sy: u32) -> Option<[i32; 3]> {
    #[cfg(scanline3d_thumb_geometry)]
    return thumb::project_q16(p, sx, sy);
    #[cfg(not(scanline3d_thumb_geometry))]
    {
        let _ = (p, sx, sy);
        None
    }
}

/// Whether [`project_run`] can store anything (the vertex loop asks it only then).
pub(crate) const PROJECT_RUN: bool = cfg!(scanline3d_thumb_geometry);

/// The vertex kernel: stores the vertex-store records of the longest run of Q16.16 positions
/// `ps` (at most the store's room) that it handles exactly as the geometry stage's vertex loop
/// would (transform by `m`, outcode with the guard band `g`, projection with the scales `sx`,
/// `sy`; records before the probe's snapping) and returns its length; 0 lets the loop take the
/// first position.
#[inline(always)]
pub(crate) fn project_run<const V: usize>(
    m: &[[i32; 4]; 4],
    ps: &[[i32; 3]],
    g: i32,
    sx: u32,
    sy: u32,
    out: &mut Vec<ScreenVertex, V>,
) -> usize {
    #[cfg(scanline3d_thumb_geometry)]
    return thumb::project_run(m, ps, g, sx, sy, out);
    #[cfg(not(scanline3d_thumb_geometry))]
    {
        let _ = (m, ps, g, sx, sy, out);
        0
    }
}

/// Whether [`light_run`] can light anything (the lighting stage asks it only then).
pub(crate) const LIGHT_RUN: bool = cfg!(scanline3d_thumb_geometry);

/// The lighting kernel, for RGB565 targets: lights the vertices of `verts` that the cull loop
/// marked, as the lighting stage would with one grey light of direction `dir` (object space)
/// and colour fraction `frac` and a material without specular term (all Q16.16 words), until
/// the first marked vertex it does not handle; returns how many vertices it passed, or `None`
/// when it handles none for these constants.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn light_run(
    verts: &mut [ScreenVertex],
    normals: &[[i32; 3]],
    dir: [i32; 3],
    frac: i32,
    ambient: i32,
    diffuse: i32,
    color: [u8; 3],
) -> Option<usize> {
    #[cfg(scanline3d_thumb_geometry)]
    return thumb::light_run(verts, normals, dir, frac, ambient, diffuse, color);
    #[cfg(not(scanline3d_thumb_geometry))]
    {
        let _ = (verts, normals, dir, frac, ambient, diffuse, color);
        None
    }
}

/// The cull loop: the common cases of an object's triangle loop for Gouraud triangles of real
/// colours, from triangle `*k` on. Each triangle whose vertices are valid and need no clipping
/// is counted as outside, degenerate or culled, or (a front face) stored by [`Bins::push`],
/// exactly as the full path does, and when stored its unlit vertices are marked
/// `NEEDS_LIGHT`; `*k` moves past it. Stops at a triangle that needs the full path. `verts`
/// are the object's vertices, `base` the store index of the first.
#[inline(always)]
pub(crate) fn cull_push<const T: usize>(
    tris: &[[u16; 3]],
    k: &mut usize,
    verts: &mut [ScreenVertex],
    base: u16,
    bins: Bins<'_, T>,
    counts: &mut CullCounts,
    needed: &mut usize,
) -> CullStop {
    #[cfg(scanline3d_thumb)]
    return thumb::cull_push(tris, k, verts, base, bins, counts, needed);
    #[cfg(not(scanline3d_thumb))]
    return portable::cull_push(tris, k, verts, base, bins, counts, needed);
}

/// The triangle-setup kernel: `ActiveTri::setup` of a Gouraud triangle on a strip whose mode
/// is fast Gouraud (`DepthTest::Less`) with RGB565 channels, and with `dither` the dither
/// check too: what it did, or `None` (the record unspecified) where it declines.
#[inline(always)]
pub(crate) fn setup565(
    rec: &mut ActiveTri,
    t: &TriRecord,
    verts: &[ScreenVertex],
    row: i32,
    height: i32,
    dither: bool,
) -> Option<Setup565> {
    #[cfg(scanline3d_thumb)]
    return thumb::setup565(rec, t, verts, row, height, dither);
    #[cfg(not(scanline3d_thumb))]
    {
        let _ = (rec, t, verts, row, height, dither);
        None
    }
}

/// The attribute-setup kernel: `raster::attribute_words` of a fast Gouraud triangle with
/// RGB565 channels, written into `rec`'s `gx`, `row` and `inc`; false where it declines (then
/// those words are unspecified: the Thumb-2 form may have written some before a late decline,
/// and the caller's portable code writes all of them).
#[inline(always)]
pub(crate) fn gouraud_setup(rec: &mut ActiveTri, tri: &Sorted<'_>) -> bool {
    #[cfg(scanline3d_thumb)]
    return thumb::gouraud_setup(rec, tri);
    #[cfg(not(scanline3d_thumb))]
    {
        let _ = (rec, tri);
        false
    }
}

/// The dither-check kernel: `ActiveTri::dither_fits` of a fast RGB565 Gouraud record with
/// vertices `p` set up on `row`; `None` where it declines.
#[inline(always)]
pub(crate) fn dither_fits565(rec: &ActiveTri, p: [&ScreenVertex; 3], row: i32) -> Option<bool> {
    #[cfg(scanline3d_thumb)]
    return Some(thumb::dither_fits565(rec, p, row));
    #[cfg(not(scanline3d_thumb))]
    {
        let _ = (rec, p, row);
        None
    }
}

/// The `DepthTest::Less` Gouraud span into RGB565 words, from the packed start values and
/// steps (`z`, `rb`, `g`: value and per-pixel step of each) over `zs` and `cs` (the same
/// length); the pixels written, or `None` where it declines.
#[inline(always)]
pub(crate) fn span565_less(
    zs: &mut [u16],
    cs: &mut [u16],
    z: [i32; 2],
    rb: [u32; 2],
    g: [i32; 2],
) -> Option<u32> {
    #[cfg(scanline3d_thumb)]
    return Some(thumb::span565_less(zs, cs, z, rb, g));
    #[cfg(not(scanline3d_thumb))]
    {
        let _ = (zs, cs, z, rb, g);
        None
    }
}

/// [`span565_less`] with 4×4 ordered dithering, `x0` the first pixel's column and `row` the
/// pixel row; the pixels written, or `None` where it declines.
#[inline(always)]
pub(crate) fn span565_less_dither(
    zs: &mut [u16],
    cs: &mut [u16],
    z: [i32; 2],
    rb: [u32; 2],
    g: [i32; 2],
    x0: usize,
    row: i32,
) -> Option<u32> {
    #[cfg(scanline3d_thumb)]
    return Some(thumb::span565_less_dither(zs, cs, z, rb, g, x0, row));
    #[cfg(not(scanline3d_thumb))]
    {
        let _ = (zs, cs, z, rb, g, x0, row);
        None
    }
}

/// The `DepthTest::Less` flat span into RGB565 words (`z` 16.12 with its rounding bias, `gz`
/// its step, `color` the word); the pixels written, or `None` where it declines (on Thumb-2
/// cores LLVM's loop, with post-indexed loads and conditional stores, measured faster).
#[inline(always)]
pub(crate) fn span565_flat_less(
    zs: &mut [u16],
    cs: &mut [u16],
    z: i32,
    gz: i32,
    color: u16,
) -> Option<u32> {
    #[cfg(scanline3d_thumb_v6m)]
    return Some(thumb::span565_flat_less(zs, cs, z, gz, color));
    #[cfg(not(scanline3d_thumb_v6m))]
    {
        let _ = (zs, cs, z, gz, color);
        None
    }
}

/// The row kernel: draws one row of the active triangles from `start` on for as long as they
/// are fast Gouraud triangles it handles, each exactly as `ActiveTri::draw_row` would (RGB565
/// words; dithered for pixel row `row` when `dither`). Returns `(index reached, fragments,
/// written)`, or `None` where it draws nothing.
#[inline(always)]
pub(crate) fn rows565<const N: usize>(
    active: &mut ActiveList<N>,
    start: usize,
    colors: &mut [u16],
    depth: &mut [u16],
    row: usize,
    dither: bool,
) -> Option<(usize, u32, u32)> {
    #[cfg(scanline3d_thumb)]
    return thumb::rows565(active, start, colors, depth, row, dither);
    #[cfg(not(scanline3d_thumb))]
    {
        let _ = (active, start, colors, depth, row, dither);
        None
    }
}

/// Clears a strip line of RGB565 words: colour `background`, depth 65535.
#[inline(always)]
pub(crate) fn clear_line565(colors: &mut [u16], depth: &mut [u16], background: u16) {
    #[cfg(scanline3d_thumb)]
    thumb::clear_line(colors, depth, background);
    #[cfg(not(scanline3d_thumb))]
    portable::clear_line(colors, depth, background);
}
