//! The span seam: each active triangle's **span kind**, decided once when the triangle becomes
//! active ([`enter`], the one setup-and-attach path of every strip pass, layered pass and
//! seek), and the one place where a row of a triangle is drawn by its kind ([`draw_row`],
//! called once per triangle and row by every row loop). A new way of filling spans is a new
//! kind: a constant here, its arm in [`draw_row`] and its choice in [`kind_of_mode`] — no flag
//! in the row loops, no depth-test `match` of its own (its span loop takes the test as a const
//! parameter through [`by_depth_test`](crate::raster::span::by_depth_test)).
//!
//! A kind is a value of the bits of [`ActiveTri::flags`] that are not row state. The setup
//! writes the attribute layout's bits ([`FLAT`]: one attribute, [`FAST`]: packed, with
//! [`DITHER_OK`] for a dithered fast Gouraud triangle; the Thumb setup kernel writes the same
//! constants); a triangle with a pool entry (its index in [`ActiveTri::spare`]) gets
//! [`POOL`] and its code at [`enter`]. Row state: [`MID_LEFT`] always, and
//! [`LAST_IN_ROUTINE`] and [`SWITCH_IN_ROUTINE`] for the [`FAST`] kinds only, which the Cortex-M
//! row routine draws (and, with its row count used up, tests on any triangle, then draws only a
//! [`FAST`] one); a pool kind (never fast) has those two bits, [`DITHER_OK`]'s bit and bit 7
//! for its code: 16 codes, each with and without [`FLAT`], of which 4 are used (textured,
//! Phong, fast Phong, toon).

use crate::geometry::pool::{ActiveExtra, FREE, MODE_FAST_PHONG, MODE_PHONG, MODE_TOON};
use crate::geometry::project::ScreenVertex;
use crate::geometry::vertex_extra::VertexExtra;
use crate::raster::shadow_span::{attach_shadow, Attach};
use crate::raster::span::{LESS, NONE};
use crate::raster::span_map::{NoMap, SpanMap};
use crate::raster::textured::attach_textured;
use crate::raster::*;
use crate::scene::color::TargetColor;

/// Bit of a pool kind: the triangle has an entry in the attribute pool, [`ActiveTri::spare`].
pub(crate) const POOL: u8 = 64;
/// The bits of a pool kind's code (besides [`POOL`] and [`FLAT`]): [`DITHER_OK`]'s, bit 7,
/// [`LAST_IN_ROUTINE`]'s and [`SWITCH_IN_ROUTINE`]'s, all free in a triangle that is not
/// [`FAST`]. (The Cortex-M row routine reads the last two on any triangle whose routine rows
/// are used up, and leaves it to the portable path unless it is [`FAST`]: the test costs a
/// fast triangle two instructions at its last row and at its switch, and no other triangle
/// anything.)
const CODE_BITS: u8 = DITHER_OK | 128 | LAST_IN_ROUTINE | SWITCH_IN_ROUTINE;
/// A pool kind's code `n` (0..16) as flag bits (codes 0..4 in the first two bits, as they
/// were before the routine's bits were freed).
const fn code(n: u8) -> u8 {
    POOL | ((n & 1) << 5) | ((n & 2) << 6) | ((n & 4) << 1) | ((n & 8) << 1)
}
const _: () = assert!(
    code(15) & !POOL == CODE_BITS
        && DITHER_OK == 32
        && FAST == 4
        && LAST_IN_ROUTINE == 8
        && SWITCH_IN_ROUTINE == 16
        && code(3) == POOL | DITHER_OK | 128
);

// The kinds. Without a pool entry (the setup decides among these):
/// Gouraud, 20-bit attribute rows, any depth test and colour type (`Span::fill_gouraud`).
pub(crate) const GOURAUD: u8 = 0;
/// Flat, any depth test and colour type (`Span::fill_flat`).
pub(crate) const FLAT_KIND: u8 = FLAT;
/// Fast Gouraud: packed rows, `Less`, channels of at most 6 bits (`span_packed`, or dithered
/// by `span_packed_dither_clamped`), and the Cortex-M row routine.
pub(crate) const FAST_GOURAUD: u8 = FAST;
/// Fast Gouraud that may be dithered without clamping (`span_packed_dither`).
pub(crate) const FAST_GOURAUD_DITHER: u8 = FAST | DITHER_OK;
/// Fast flat: `Less` (`span_flat`).
pub(crate) const FAST_FLAT: u8 = FAST | FLAT;
// [`draw_row`] tells the plain kinds apart by the FAST bit.
const _: () = assert!(FAST_GOURAUD & FAST_GOURAUD_DITHER & FAST_FLAT & FAST != 0);
const _: () = assert!((GOURAUD | FLAT_KIND) & FAST == 0);
// With a pool entry (chosen at [`enter`] from the first vertex's attribute mode):
/// Textured, the texture modulated by the Gouraud rows (with [`FLAT`]: by the face colour).
pub(crate) const TEXTURED: u8 = code(0);
/// Textured, modulated by the face colour.
pub(crate) const TEXTURED_FLAT: u8 = TEXTURED | FLAT;
/// Phong: lit per pixel from the interpolated normal.
pub(crate) const PHONG: u8 = code(1);
/// Fast Phong: lit every 8th pixel, linear in between.
pub(crate) const FAST_PHONG: u8 = code(2);
/// Toon: lit per pixel from the interpolated normal, the diffuse term in bands.
pub(crate) const TOON: u8 = code(3);
/// A shadow map's receiver (Gouraud): darkened where the map holds a caster nearer the light
/// (`shadow_span`; chosen at [`enter`] in a mapped frame, not from the vertices' mode).
pub(crate) const SHADOW: u8 = code(4);
/// A shadow map's receiver, flat.
pub(crate) const SHADOW_FLAT: u8 = SHADOW | FLAT;

impl ActiveTri {
    /// The span kind: the flag bits without the row state.
    #[inline(always)]
    pub(crate) fn kind(&self) -> u8 {
        // (FAST = 4: times 6 is LAST_IN_ROUTINE | SWITCH_IN_ROUTINE for a fast triangle.)
        self.flags & !(MID_LEFT | ((self.flags & FAST) * 6))
    }

    /// Whether the triangle has an entry in the attribute pool ([`ActiveTri::spare`]).
    #[inline(always)]
    pub(crate) fn has_pool_entry(&self) -> bool {
        self.flags & POOL != 0
    }
}

/// The pool kind of a triangle whose first vertex has attribute mode `mode` (a texture mode's
/// index, or a lighting mode), without [`FLAT`].
fn kind_of_mode(mode: u8) -> u8 {
    match mode {
        MODE_PHONG => PHONG,
        MODE_FAST_PHONG => FAST_PHONG,
        MODE_TOON => TOON,
        _ => TEXTURED,
    }
}

/// Whether triangle `t` needs a pool entry: its first vertex has attributes (a texture or a
/// per-pixel lighting mode; a flat triangle's colour vertex has the attributes of the vertex
/// it copies).
#[inline(always)]
pub(crate) fn needs_pool(t: &TriRecord, xverts: &[VertexExtra]) -> bool {
    let i = (t.v[0] & !FLAT_BIT) as usize;
    xverts
        .get(i)
        .is_some_and(|x| x.texture.is_some() || x.mode >= MODE_PHONG)
}

/// Makes triangle `t` active at `row` in `active`: set up for the strip's `mode` (its kind
/// decided), and, when it needs one (`pooled`: the renderer has attribute stores, a constant
/// where it is called, else never),
/// given its planes in a free entry of `pool` and its pool kind. `then` runs on the record
/// once it is kept (a seek moves it to its row there). `map`: the frame's shadow map context
/// ([`SpanMap`]): in a mapped frame a receiver's triangle without a pool kind of its own gets
/// a shadow kind. Returns false when it was left out (the
/// list or the pool full: the caller counts it); true also when it covers no row and was not
/// added (the list's length tells).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn enter<C: TargetColor, const N: usize, M: SpanMap>(
    pooled: bool,
    active: &mut ActiveList<N>,
    pool: &mut [ActiveExtra],
    t: &TriRecord,
    verts: &[ScreenVertex],
    xverts: &[VertexExtra],
    row: i32,
    height: i32,
    mode: SpanMode,
    map: M,
    then: impl FnOnce(&mut ActiveTri),
) -> bool {
    let pooled = pooled && needs_pool(t, xverts);
    let shadow = M::ON && !pooled && map.view().is_some_and(|v| v.receives(t));
    // A pool kind is set up as an ordinary triangle (no fast path).
    let m = if pooled || shadow {
        SpanMode::default()
    } else {
        mode
    };
    let before = active.len();
    if !active.push_with(|a| a.setup::<C>(t, verts, row, height, m)) {
        return false;
    }
    if active.len() == before {
        return true; // nothing to draw from this row on
    }
    let a = active.get_mut(before);
    if pooled {
        let x0 = xverts[(t.v[0] & !FLAT_BIT) as usize];
        match attach_textured::<C>(a, pool, t, verts, xverts) {
            Some(slot) => {
                a.flags |= kind_of_mode(x0.mode);
                a.spare = slot as i16;
            }
            None => {
                active.swap_remove(before);
                return false;
            }
        }
    }
    if let (true, Some(view)) = (shadow, map.view()) {
        match attach_shadow(pool, t, verts, view.look) {
            Attach::Slot(slot) => {
                let a = active.get_mut(before);
                a.flags |= SHADOW;
                a.spare = slot as i16;
            }
            Attach::Plain => {}
            Attach::Full => {
                active.swap_remove(before);
                return false;
            }
        }
    }
    then(active.get_mut(before));
    true
}

/// Draws row `row` of triangle `a` by its kind into one line of the strip (`colors`, and
/// `depth` unless `Z` is [`NONE`]: a renderer without depth lines) and moves it to the next
/// row; frees its pool entry when this was its last row. `POOLED`: the renderer has attribute
/// stores (without them, the pool kinds' arms are compiled out); `map`: the frame's shadow
/// map context ([`SpanMap`]). Returns `(fragments tested,
/// pixels written, finished)`. The one dispatch on the kind: the pool kinds in
/// [`pool_row`], the others in [`plain_row`], each out of line (in one function, the pool
/// kinds' code made the plain kinds' rows of a renderer with a pool 50 instructions dearer on
/// RISC-V: the icosphere's Gouraud frame +7 %).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn draw_row<C: TargetColor, const Z: u8, const POOLED: bool, M: SpanMap>(
    a: &mut ActiveTri,
    pool: &mut [ActiveExtra],
    row: i32,
    colors: &mut [C],
    depth: &mut [u16],
    test: DepthTest,
    dither: bool,
    map: M,
) -> (u32, u32, bool) {
    if Z == NONE {
        plain_row_no_depth::<C>(a, row, colors, dither)
    } else if POOLED && a.has_pool_entry() {
        pool_row::<C, M>(a, pool, row, colors, depth, test, dither, map)
    } else {
        plain_row::<C>(a, row, colors, depth, test, dither)
    }
}

/// The columns of `a`'s span on a line of `width` pixels, and its left edge's column.
#[inline(always)]
fn columns(a: &ActiveTri, width: usize) -> (i32, i32, i32) {
    let lc = a.edges[0].c();
    (lc, lc.max(0), a.edges[1].c().min(width as i32))
}

/// [`draw_row`] for the kinds without a pool entry, with depth lines ([`plain_row_in`]).
#[inline(never)]
fn plain_row<C: TargetColor>(
    a: &mut ActiveTri,
    row: i32,
    colors: &mut [C],
    depth: &mut [u16],
    test: DepthTest,
    dither: bool,
) -> (u32, u32, bool) {
    plain_row_in::<C, LESS>(a, row, colors, depth, test, dither)
}

/// [`draw_row`] for a renderer without depth lines ([`plain_row_in`]): a function of its own
/// with only the arguments it reads (on a Cortex-M0 the depth line's and test's arguments went
/// through the stack, 1–2 % of the painter's cube frame).
#[inline(never)]
fn plain_row_no_depth<C: TargetColor>(
    a: &mut ActiveTri,
    row: i32,
    colors: &mut [C],
    dither: bool,
) -> (u32, u32, bool) {
    plain_row_in::<C, NONE>(a, row, colors, &mut [], DepthTest::Always, dither)
}

/// The row of the kinds without a pool entry: [`FAST_GOURAUD`], [`FAST_GOURAUD_DITHER`],
/// [`FAST_FLAT`], [`GOURAUD`] and [`FLAT_KIND`].
#[inline(always)]
fn plain_row_in<C: TargetColor, const Z: u8>(
    a: &mut ActiveTri,
    row: i32,
    colors: &mut [C],
    depth: &mut [u16],
    test: DepthTest,
    dither: bool,
) -> (u32, u32, bool) {
    let width = if Z == NONE {
        colors.len()
    } else {
        colors.len().min(depth.len())
    };
    let (lc, xs, xe) = columns(a, width);
    let dither = dither && C::can_dither();
    let mut counts = (0, 0);
    if xs < xe {
        // By the FAST bit alone (FAST_GOURAUD, FAST_GOURAUD_DITHER, FAST_FLAT, or GOURAUD and
        // FLAT_KIND, which `span` tells apart): a match on the whole kind cost 5 instructions
        // a row, 1-2 % of the painter's cube on every Cortex-M core.
        let written = if a.flags & FAST != 0 {
            a.fast_span::<C, Z>(lc, xs, xe, row, colors, depth, dither)
        } else {
            a.span::<C, Z>(lc, xs, xe, row, colors, depth, test, dither)
        };
        counts = ((xe - xs) as u32, written);
    }
    let done = next_row(a, row, dither);
    (counts.0, counts.1, done)
}

/// [`draw_row`] for the kinds with a pool entry: [`TEXTURED`], [`TEXTURED_FLAT`], [`PHONG`],
/// [`FAST_PHONG`] and [`TOON`], or in a mapped frame [`SHADOW`] and [`SHADOW_FLAT`] (drawn
/// with depth lines only).
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn pool_row<C: TargetColor, M: SpanMap>(
    a: &mut ActiveTri,
    pool: &mut [ActiveExtra],
    row: i32,
    colors: &mut [C],
    depth: &mut [u16],
    test: DepthTest,
    dither: bool,
    map: M,
) -> (u32, u32, bool) {
    let (lc, xs, xe) = columns(a, colors.len().min(depth.len()));
    let mut counts = (0, 0);
    if xs < xe {
        let k = a.kind();
        let (zs, cs) = (
            &mut depth[xs as usize..xe as usize],
            &mut colors[xs as usize..xe as usize],
        );
        // A mapped frame's pool kinds are the shadow kinds only (it refuses textured and per-pixel
        // lit objects): with the other spans called from its row too, the compiler stopped
        // inlining the textured span's loop into the plain frames' row (rv32imac textured
        // +3-4 %).
        let written = if M::ON {
            match (k, map.view()) {
                (SHADOW | SHADOW_FLAT, Some(view)) => {
                    crate::raster::shadow_span::span::<C>(a, pool, lc, xs, row, zs, cs, test, view)
                }
                _ => 0,
            }
        } else {
            match k {
                TEXTURED | TEXTURED_FLAT if crate::kernel::TEXTURED_SPAN_OUT_OF_LINE => {
                    crate::raster::textured::span_out_of_line::<C>(
                        a, pool, lc, xs, row, zs, cs, test,
                    )
                }
                TEXTURED | TEXTURED_FLAT => {
                    crate::raster::textured::span::<C>(a, pool, lc, xs, row, zs, cs, test)
                }
                PHONG | FAST_PHONG | TOON => {
                    let span = crate::raster::phong::span::<C, FAST_PHONG, TOON>;
                    span(a, k, pool, lc, xs, row, zs, cs, test, dither)
                }
                _ => 0,
            }
        };
        counts = ((xe - xs) as u32, written);
    }
    // The edges and the depth and colour rows move on in the plain row, for no pixel: its call
    // sites stay the only ones of `ActiveTri::advance` besides the seek's (with one more, the
    // compiler stopped inlining it into the portable row loop: RISC-V torus +4.7 %).
    let (_, _, done) = plain_row::<C>(a, row, &mut [], &mut [], test, false);
    if done {
        if let Some(e) = pool.get_mut(a.spare as usize) {
            e.kind = FREE;
        }
    }
    (counts.0, counts.1, done)
}

/// Moves `a` from `row`, just drawn, to the next row; true when `row` was its last.
#[inline(always)]
fn next_row(a: &mut ActiveTri, row: i32, dither: bool) -> bool {
    let next = row + 1;
    if next >= a.row_end as i32 {
        return true;
    }
    a.advance_inlined(next);
    a.set_routine_rows(next, dither);
    false
}

impl ActiveTri {
    /// Row `row` of a triangle without a pool entry, with depth test `Less` (the self-tests'
    /// and unit tests' entry; the strip passes call [`draw_row`]).
    pub(crate) fn draw_row<C: TargetColor>(
        &mut self,
        row: i32,
        colors: &mut [C],
        depth: &mut [u16],
        test: DepthTest,
        dither: bool,
    ) -> (u32, u32, bool) {
        draw_row::<C, LESS, false, NoMap>(self, &mut [], row, colors, depth, test, dither, NoMap)
    }
}
