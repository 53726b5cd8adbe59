//! The kernels' records: the plain, fixed-layout data the kernel entry points (and the
//! stages around them) work on — a projected vertex, a stored triangle, an edge, an active
//! triangle, the bins a front face goes into — with the precision of every field.
//!
//! The layouts are `repr(C)` because the Thumb kernels address fields by offset
//! (`kernel::thumb` asserts every offset it uses). Nothing here depends on the renderer; the
//! renderer and the raster stages depend on these records.

use heapless::Vec;

/// Fraction bits of snapped screen positions: 4, i.e. 1/16 px.
pub const SUBPIXEL_BITS: u32 = 4;
/// Subpixels per pixel.
pub const SUBPIXELS: i32 = 1 << SUBPIXEL_BITS;
/// Fraction bits of interpolated depth (unsigned 16.12 fixed point in an `i32`; range
/// 0..=65535·2¹² plus a half-step bias; step 2⁻¹² depth units).
pub const DEPTH_FRAC_BITS: u32 = 12;
/// Largest stored depth (the far plane).
pub const DEPTH_MAX: i32 = 65535;
/// Largest magnitude of a snapped screen coordinate, in subpixels (16 383 = 1024 px − 1/16):
/// the guard band is chosen so that every projected vertex stays within it. Coordinates then
/// fit an `i16`, and every product and sum of the edge and area setup fits 32 bits
/// (|Δ| ≤ 32 766, and 2·32 766² < 2³¹).
pub const COORD_LIMIT: i32 = (1 << 14) - 1;
/// Largest supported screen width or height in pixels.
pub const MAX_SCREEN: usize = 1024;

/// A vertex after projection: snapped position, depth and colour.
///
/// Size: 12 bytes (the vertex store is the largest part of a renderer's RAM). `repr(C)`, aligned
/// to 4 bytes: the Cortex-M assembly reads x and y as one word (an unaligned word load faults
/// on a Cortex-M0).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
#[repr(C, align(4))]
pub struct ScreenVertex {
    /// x in subpixels (signed 12.4 fixed point; |x| ≤ [`COORD_LIMIT`]).
    pub x: i16,
    /// y in subpixels, downwards (signed 12.4; |y| ≤ [`COORD_LIMIT`]).
    pub y: i16,
    /// Depth, integer part (0 at the near plane, 65535 at the far plane); with [`Self::zf`]
    /// unsigned 16.8, step 2⁻⁸ of a depth step.
    pub z: u16,
    /// Depth, 8 fraction bits.
    pub zf: u8,
    /// Colour: the upper 8 of the 10-bit channels (see [`ScreenVertex::color`]).
    pub(crate) rgb_hi: [u8; 3],
    /// Renderer bookkeeping: outcode and state bits in bits 0..=9; bits 10..=15 hold the
    /// lowest 2 bits of each 10-bit colour channel.
    pub(crate) flags: u16,
}

/// Byte offsets of [`ScreenVertex::rgb_hi`] and [`ScreenVertex::flags`], for the Cortex-M
/// triangle setup (`kernel::thumb`).
#[cfg_attr(not(scanline3d_thumb), allow(dead_code))]
pub(crate) const RGB_HI_OFFSET: usize = core::mem::offset_of!(ScreenVertex, rgb_hi);
#[cfg_attr(not(scanline3d_thumb), allow(dead_code))]
pub(crate) const FLAGS_OFFSET: usize = core::mem::offset_of!(ScreenVertex, flags);

/// Mask of [`ScreenVertex::flags`] bits that belong to the renderer (the rest is colour).
pub(crate) const FLAG_MASK: u16 = (1 << 10) - 1;

impl ScreenVertex {
    /// Colour channels in the target's channel units with `10 − bits` fraction bits for a
    /// channel of `bits` bits (RGB565: red and blue 5.5, green 6.4; 8-bit channels 8.2;
    /// 0..=1023, step 1/32 LSB for RGB565; see [`pack_channels`](crate::geometry::project::pack_channels)).
    #[inline]
    #[must_use]
    pub fn color(&self) -> [u16; 3] {
        let lo = self.flags >> 10;
        [
            (self.rgb_hi[0] as u16) << 2 | (lo & 3),
            (self.rgb_hi[1] as u16) << 2 | (lo >> 2 & 3),
            (self.rgb_hi[2] as u16) << 2 | (lo >> 4 & 3),
        ]
    }

    /// Sets the colour (10-bit channels, see [`ScreenVertex::color`]).
    #[inline]
    pub fn set_color(&mut self, c: [u16; 3]) {
        self.rgb_hi = c.map(|v| (v >> 2) as u8);
        let lo = (c[0] & 3) | (c[1] & 3) << 2 | (c[2] & 3) << 4;
        self.flags = (self.flags & FLAG_MASK) | lo << 10;
    }

    /// Depth as unsigned 16.12 in an `i32` (0..=65535·2¹², the rasterizer's depth format).
    #[inline]
    #[must_use]
    pub fn depth(&self) -> i32 {
        ((self.z as i32) << DEPTH_FRAC_BITS) | ((self.zf as i32) << (DEPTH_FRAC_BITS - 8))
    }
}

/// Outcode bit: `x < −w`.
pub const LEFT: u8 = 1;
/// Outcode bit: `x > w`.
pub const RIGHT: u8 = 2;
/// Outcode bit: `y < −w`.
pub const BOTTOM: u8 = 4;
/// Outcode bit: `y > w`.
pub const TOP: u8 = 8;
/// Outcode bit: `z < 0` (in front of the near plane, including everything behind the eye).
pub const NEAR: u8 = 16;
/// Outcode bit: `z > w` (beyond the far plane).
pub const FAR: u8 = 32;
/// Extra bit (not part of the 6-bit outcode): outside the x/y guard band.
pub const GUARD: u8 = 64;
/// The bits that require geometric clipping.
pub const NEEDS_CLIP: u8 = NEAR | FAR | GUARD;
/// [`ScreenVertex`] flag bits of the renderer (bits 0..=5 are the outcode above): a NaN,
/// infinite or overflowed position; projected; lit (its colour is set).
pub(crate) const INVALID: u16 = 1 << 7;
pub(crate) const PROJECTED: u16 = 1 << 8;
pub(crate) const LIT: u16 = 1 << 9;
/// Set by the cull kernel (`kernel::cull_push`) on an unlit vertex of a stored front face: it needs lighting (the
/// object's loop lights those after its triangles). A colour bit, free until the vertex is lit
/// ([`ScreenVertex::set_color`] overwrites it).
pub(crate) const NEEDS_LIGHT: u16 = 1 << 15;

/// What culling decided for a snapped triangle.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Facing {
    /// Counter-clockwise as the viewer sees it: drawn.
    Front,
    /// Clockwise as the viewer sees it: culled.
    Back,
    /// Zero snapped area: skipped.
    Degenerate,
}

/// Twice the signed area of a snapped triangle in subpixels², positive for front faces
/// (counter-clockwise as the viewer sees them, which is clockwise in y-down screen space).
#[must_use]
pub fn signed_area2(a: &ScreenVertex, b: &ScreenVertex, c: &ScreenVertex) -> i64 {
    // Coordinates within ±COORD_LIMIT (2¹⁴ − 1): differences ≤ 32 766 and 2·32 766² < 2³¹,
    // so 32-bit arithmetic is exact (two single-instruction multiplies on a Cortex-M0).
    let (x0, y0) = (a.x as i32, a.y as i32);
    let area = (c.x as i32 - x0) * (b.y as i32 - y0) - (b.x as i32 - x0) * (c.y as i32 - y0);
    area as i64
}

/// Classifies a snapped triangle.
#[must_use]
pub fn facing(a: &ScreenVertex, b: &ScreenVertex, c: &ScreenVertex) -> Facing {
    match signed_area2(a, b, c) {
        0 => Facing::Degenerate,
        x if x > 0 => Facing::Front,
        _ => Facing::Back,
    }
}

/// One edge from its upper vertex `a` to its lower vertex `b`, positioned on a pixel row:
/// `c` is the first pixel whose centre is at or right of the edge; the exact crossing is
/// `c − (16·e + k)/(16·dy)` pixels (relative to centres) with `0 ≤ e < dy` and a constant
/// `0 ≤ k < 16`. Every row step changes the numerator by a multiple of 16, so the DDA keeps
/// `e = floor(numerator / 16)` exactly and the test `numerator < 0` is `e < 0`: all five
/// fields fit 16 bits. Rows step it in the packed form [`EdgeDda`] ([`Edge::dda`]).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
#[repr(C)] // field offsets are used by the Cortex-M edge setup (`kernel::thumb`)
pub(crate) struct Edge {
    /// Current pixel boundary (column index; |c| ≤ 1025 on every row the edge is used).
    pub c: i16,
    /// Whole pixels the boundary moves per row (floor; |sq| ≤ 32 766).
    pub sq: i16,
    /// Remainder in sixteenths, `0 ≤ e < dy`.
    pub(crate) e: i16,
    /// Remainder of the move per row in sixteenths, `0 ≤ sr < dy`.
    pub(crate) sr: u16,
    /// `max(1, yb − ya)` in subpixels (≤ 32 766).
    pub(crate) dy: u16,
}

/// Bias of the column in [`EdgeDda::w`]: every column an edge takes on a row where it is used
/// (|c| ≤ 1025), and every sum `c + sq` on the way to the next such row, is in
/// `−2¹⁵..2¹⁵`, so the biased column is a 16-bit unsigned half that never carries into `e`.
pub(crate) const C_BIAS: i32 = 1 << 15;

/// An edge as the row loops step it: [`Edge`]'s fields in two words, so that one addition
/// steps both the column and the remainder and its sign is the carry test.
///
/// - `w = e·2¹⁶ + (c + 2¹⁵)`: remainder `0 ≤ e < dy` (< 2¹⁵) in the high half, the biased
///   column (0..2¹⁶) in the low half.
/// - `s = sq − sr·2¹⁶` (modulo 2³²): the low half is `sq` (as an `i16`), the high half is
///   the remainder's step.
///
/// `w + s = (e − sr)·2¹⁶ + (c + sq + 2¹⁵)` exactly, whose sign is that of `e − sr`; when it is
/// negative, adding `dy·2¹⁶ + 1` gives `e − sr + dy` and `c + sq + 1`, as [`Edge`]'s step.
/// `dy` (≤ 32 766) is kept beside the words ([`ActiveTri::dy`]). Size: 8 bytes.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
#[repr(C)] // field offsets are used by the Cortex-M row loop (`kernel::thumb`)
pub(crate) struct EdgeDda {
    pub(crate) w: u32,
    pub(crate) s: u32,
}

impl EdgeDda {
    /// The current pixel boundary.
    #[inline(always)]
    pub(crate) fn c(&self) -> i32 {
        (self.w & 0xffff) as i32 - C_BIAS
    }

    /// Whole pixels the boundary moves per row (floor).
    #[inline(always)]
    pub(crate) fn sq(&self) -> i32 {
        self.s as i16 as i32
    }

    /// Moves to the next row (`dy` is this edge's); returns true when the boundary moved by
    /// `sq + 1` instead of `sq`.
    #[inline(always)]
    pub(crate) fn step(&mut self, dy: u16) -> bool {
        let w = self.w.wrapping_add(self.s);
        if (w as i32) < 0 {
            self.w = w.wrapping_add((dy as u32) << 16 | 1);
            true
        } else {
            self.w = w;
            false
        }
    }

    /// Moves `n` rows at once, exactly as `n` calls of [`EdgeDda::step`] would (`dy` is this
    /// edge's; `n·sr` < 2³¹, true for any `n` below 2¹⁶), and returns how many of those steps
    /// carried (moved by `sq + 1`). One multiply and one divide instead of `n` additions: for a
    /// seek, not for the row loop. The column must stay in range as [`C_BIAS`] says, which it
    /// does on every row the edge is used.
    pub(crate) fn jump(&mut self, n: u32, dy: u16) -> u32 {
        let e = (self.w >> 16) as i32;
        let sr = ((self.sq() as u32).wrapping_sub(self.s) >> 16) as i32;
        let dy = i32::from(dy);
        // Each step takes sr from the remainder and adds dy (one carry) when it goes below 0:
        // after n steps the remainder is e − n·sr + k·dy in 0..dy, k the carries.
        let t = e - n as i32 * sr;
        let k = if t >= 0 { 0 } else { (dy - 1 - t) / dy };
        let e = t + k * dy;
        let c = self.c() + n as i32 * self.sq() + k;
        self.w = ((e as u32) << 16) | ((c + C_BIAS) as u32 & 0xffff);
        k as u32
    }

    /// The column and carry [`EdgeDda::step`] would give, in 32 bits, without moving (one row
    /// past the edge's end the column may leave the range of the packed half).
    #[inline(always)]
    pub(crate) fn peek(&self) -> (i32, bool) {
        let e = self.w >> 16;
        let sr = (self.sq() as u32).wrapping_sub(self.s) >> 16;
        let carry = e < sr;
        (self.c() + self.sq() + carry as i32, carry)
    }
}

/// Bit of [`TriRecord::v`]`[0]` that marks a flat-shaded triangle: its colour is the colour of
/// vertex `v[0] & !FLAT_BIT` (the renderer stores a copy of a vertex with the face colour).
pub(crate) const FLAT_BIT: u16 = 1 << 15;

/// A triangle as stored between geometry and rasterization (6 bytes): three indices into the
/// vertex store, the first one carrying [`FLAT_BIT`]. Records are sorted by first covered row
/// after the geometry stage, so no list link is stored.
#[derive(Copy, Clone, Debug)]
#[repr(C)]
pub(crate) struct TriRecord {
    /// Indices into the renderer's vertex store (below 2¹⁵); [`FLAT_BIT`] in `v[0]`.
    pub v: [u16; 3],
}

impl TriRecord {
    /// The three vertex indices without the flag.
    #[inline(always)]
    pub(crate) fn indices(&self) -> [usize; 3] {
        [
            (self.v[0] & !FLAT_BIT) as usize,
            self.v[1] as usize,
            self.v[2] as usize,
        ]
    }
}

/// [`ActiveTri::flags`]: the middle vertex is left of the long edge.
pub(crate) const MID_LEFT: u8 = 1;
/// [`ActiveTri::flags`]: flat shaded (one attribute; `gx[1]` holds the colour).
pub(crate) const FLAT: u8 = 2;
/// [`ActiveTri::flags`]: drawn by the fast span loops. The width + height of the bounding box
/// is ≤ 1024 px, so the rounding drift of the attribute rows (≤ ½ unit per pixel of distance
/// from the anchor) stays far inside the depth bias and the colour fields' headroom and span
/// starts need no clamping; the depth test is [`DepthTest::Less`] and, for Gouraud triangles,
/// the colour has channels of at most 6 bits. A fast Gouraud triangle keeps its rows *packed*
/// (see [`ActiveTri::row`]), ready for [`span_packed`] (or, dithered, [`span_packed_dither`]
/// when it has [`DITHER_OK`]).
pub(crate) const FAST: u8 = 4;
/// [`ActiveTri::flags`]: the row where [`ActiveTri::routine_rows`] runs out is the triangle's
/// last, which the Cortex-M row routine draws too (and then removes the triangle).
pub(crate) const LAST_IN_ROUTINE: u8 = 8;
/// [`ActiveTri::flags`]: the row where [`ActiveTri::routine_rows`] runs out is the one before
/// the short edge's switch, which the Cortex-M row routine draws too, switching to the edge
/// kept by [`ActiveTri::set_pending`] (a fast Gouraud triangle only).
pub(crate) const SWITCH_IN_ROUTINE: u8 = 16;

/// [`ActiveTri::flags`]: a [`FAST`] Gouraud triangle set up while dithering whose packed
/// fields are within ¼ unit of the exact colour plane and keep 15/32 of a channel unit of
/// headroom at both ends of their ranges at every point of the triangle
/// ([`ActiveTri::dither_fits`]), so the dithered fast span ([`span_packed_dither`]) may add any
/// Bayer offset without a carry between fields. (A triangle that fails is set up without the
/// fast path; a fast triangle set up while dithering was off is dithered by
/// [`span_packed_dither_clamped`].)
pub(crate) const DITHER_OK: u8 = 32;

/// A triangle on the active list (84 bytes).
///
/// Attribute values are 32-bit and updated with wrapping arithmetic: every value that is
/// *used* is the plane at a pixel centre inside the triangle, which lies within the attribute's
/// range, and two's-complement arithmetic is exact modulo 2³², so intermediate wrap-arounds
/// (far outside the triangle) cannot change it.
#[derive(Clone, Debug)]
#[repr(C)] // field offsets are used by the Cortex-M row loop (`kernel::thumb`)
pub(crate) struct ActiveTri {
    /// [`MID_LEFT`], [`FLAT`], [`FAST`], [`LAST_IN_ROUTINE`], [`SWITCH_IN_ROUTINE`],
    /// [`DITHER_OK`].
    pub(crate) flags: u8,
    /// Rows from the current one on that the Cortex-M row routine may draw without asking:
    /// a fast Gouraud triangle's rows before the one that switches its short edge or ends it
    /// (0..=255; 0 for every other triangle). Set at setup and after every portable row
    /// ([`ActiveTri::set_routine_rows`]); the routine counts it down.
    pub(crate) routine_rows: u8,
    /// Unused by the row routines (explicit padding, so that the record has no implicit
    /// padding bytes); a renderer without depth lines keeps the painter's key here (the
    /// farthest vertex's 16-bit depth, as `u16` bits).
    pub(crate) spare: i16,
    /// The left and right edges.
    pub(crate) edges: [EdgeDda; 2],
    /// `dy` of the left and right edges (see [`EdgeDda`]).
    pub(crate) dy: [u16; 2],
    /// Row where the short edge changes from a→b to b→c (|·| ≤ 1025).
    pub(crate) row_mid: i16,
    /// First row not covered (≤ 1024).
    pub(crate) row_end: i16,
    /// x and y of the middle and bottom vertices (sorted by y), in subpixels (12.4), for the
    /// short edge's switch.
    pub(crate) bx: i16,
    pub(crate) by: i16,
    pub(crate) cx: i16,
    pub(crate) cy: i16,
    /// Per-pixel x gradients, the low 32 bits of the exact ones (a sliver's can exceed the
    /// `i32` range; every value used is exact modulo 2³², see above): depth (16.12 per pixel)
    /// and r, g, b (channel units, 20 fraction bits per pixel). Flat triangles keep their final channel bytes in `gx[1]`.
    /// (The y gradient lives on in `inc`, and the values at the first vertex in `row`, so
    /// neither is stored.)
    pub(crate) gx: [i32; 4],
    /// Values at the centre of the current row's first pixel (column `left.c`), same formats.
    /// A [`FAST`] Gouraud triangle keeps three *packed* values here, in `gx` and in `inc`
    /// instead ([`pack_zrgb`]): depth with its ½-step rounding bias, times 2⁴ (16.16, the
    /// depth is the high half); red and blue in one word, red in the high half and blue in the
    /// low half, each with `16 − bits` fraction bits, rounded from the 20-bit values at setup,
    /// plus ½ unit each; green plus ½ unit, shifted so that its `bits` whole bits are the
    /// word's top bits (`32 − bits` fraction bits). All steps are wrapping additions, so the
    /// packed word is exactly `R·2¹⁶ + B (mod 2³²)` of the stepped red and blue, and its
    /// halves read back as the channels whenever `B` is in `0..2¹⁶`, which holds at every
    /// pixel centre inside the triangle (the ½-unit bias leaves ½ unit of headroom at both
    /// ends, and the stepping of values rounded to `16 − bits` fraction bits drifts by under
    /// 2⁻¹² unit per row and per pixel).
    pub(crate) row: [i32; 4],
    /// Change of `row` when the left edge moves by `sq` columns: `gy + gx·sq`.
    pub(crate) inc: [i32; 4],
}

// The routine's row count and a spare halfword fill what was padding: an active triangle stays
// 84 bytes.
const _: () = assert!(core::mem::size_of::<ActiveTri>() == 84);
// Five 16-bit fields and no padding (the Cortex-M edge setup writes all of them).
const _: () = assert!(core::mem::size_of::<Edge>() == 10);

/// The active triangles of the current row: up to `N` records in drawing order. Removal is
/// `swap_remove` (the last record moves into the removed one's slot: on a Cortex-M0 the row
/// routine does it with six `ldm`/`stm` pairs, once per triangle, where an order kept apart
/// from the records cost a lookup on every row). Slots are added when the list first grows
/// past them and then reused, frame after frame.
#[derive(Debug)]
pub(crate) struct ActiveList<const N: usize> {
    /// The slots used so far (never shrinks; a vector, so a new list is built without
    /// writing, or copying, `N` records on the stack).
    pub(crate) slots: Vec<ActiveTri, N>,
    /// Triangles on the list (≤ `slots.len()`).
    len: usize,
}

impl<const N: usize> ActiveList<N> {
    /// Sets every active triangle's routine row count again for `row` (the next row to draw)
    /// after dithering was switched to `dithered` between strips ([`ActiveTri::set_routine_rows`]).
    pub(crate) fn refresh_routine_rows(&mut self, row: i32, dithered: bool) {
        for t in &mut self.slots[..self.len] {
            t.set_routine_rows(row, dithered);
        }
    }

    pub(crate) const fn new() -> Self {
        ActiveList {
            slots: Vec::new(),
            len: 0,
        }
    }

    #[inline(always)]
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    pub(crate) fn clear(&mut self) {
        self.len = 0;
    }

    /// Most slots (the renderer's limit on `ACTIVE`).
    pub(crate) const MAX: usize = 1 << 15;

    /// Entry `i` of the list (`i < len`).
    #[inline(always)]
    pub(crate) fn get_mut(&mut self, i: usize) -> &mut ActiveTri {
        &mut self.slots[i]
    }

    /// Sets up a triangle in the next free slot with `f`, which returns whether it is kept.
    /// Returns false when the list is full.
    #[inline(always)]
    pub(crate) fn push_with(&mut self, f: impl FnOnce(&mut ActiveTri) -> bool) -> bool {
        if self.len >= N {
            return false;
        }
        if self.len == self.slots.len() {
            let _ = self.slots.push(ActiveTri::EMPTY);
        }
        if f(&mut self.slots[self.len]) {
            self.len += 1;
        }
        true
    }

    /// Sets the length to `n`, at most the slots set up so far (for re-inserting the
    /// entries one at a time in another order).
    pub(crate) fn set_len(&mut self, n: usize) {
        self.len = n.min(self.slots.len());
    }

    /// Removes entry `i` (`i < len`); the last entry takes its place.
    #[inline(always)]
    pub(crate) fn swap_remove(&mut self, i: usize) {
        let last = self.len - 1;
        if i != last {
            self.slots[i] = self.slots[last].clone();
        }
        self.len = last;
    }

    /// Removes entry `i` (`i < len`), keeping the order of the others (the painter's order of
    /// a renderer without depth lines).
    pub(crate) fn remove_in_order(&mut self, i: usize) {
        self.slots[i..self.len].rotate_left(1);
        self.len -= 1;
    }

    /// The list length after the Cortex-M row routine removed finished triangles (as
    /// [`ActiveList::swap_remove`] does); `n ≤ len`.
    #[cfg_attr(not(scanline3d_thumb), allow(dead_code))]
    #[inline(always)]
    pub(crate) fn set_len_after_routine(&mut self, n: usize) {
        self.len = n.min(self.len);
    }

    /// Whether the Cortex-M row routine would draw entry `i` (`i < len`) on this row (given
    /// its left edge on screen): entering it for one that it declines costs about 60
    /// instructions, which a frame of flat or clipped triangles pays on every row.
    #[cfg_attr(not(scanline3d_thumb), allow(dead_code))]
    #[inline(always)]
    pub(crate) fn routine_may_draw(&self, i: usize) -> bool {
        let t = &self.slots[i];
        t.routine_rows != 0 || t.flags & (LAST_IN_ROUTINE | SWITCH_IN_ROUTINE) != 0
    }

    /// The slot records (for the Cortex-M row routine) and the list length.
    #[cfg_attr(not(scanline3d_thumb), allow(dead_code))]
    #[inline(always)]
    pub(crate) fn raw_parts(&mut self) -> (*mut ActiveTri, usize) {
        (self.slots.as_mut_ptr(), self.len)
    }
}

/// A triangle's vertices sorted by y, with what [`attribute_words`] needs of its setup
/// (seven words in this order: the Cortex-M0 setup, `kernel::gouraud_setup`, reads them).
#[repr(C)]
pub(crate) struct Sorted<'v> {
    /// The vertices, top to bottom.
    pub v: [&'v ScreenVertex; 3],
    /// Twice the signed area, `(b − a) × (c − a)` in subpixels² (nonzero, |·| < 2³¹).
    pub det: i32,
    /// The first row to draw.
    pub row: i32,
    /// The left edge's column on that row.
    pub left_c: i32,
    /// The left edge's whole step in columns per row.
    pub left_sq: i32,
}

/// [`dither_words`] of RGB565 (red and blue with 11 fraction bits, green with 26) for the
/// four Bayer rows, as the Cortex-M routines read them: per row, eight words, the red-blue
/// and green offsets of column phases 0, 1, 2, 3 in turn.
#[cfg_attr(not(scanline3d_thumb), allow(dead_code))]
pub(crate) static DITHER565: [[u32; 8]; 4] = {
    let mut t = [[0u32; 8]; 4];
    let mut r = 0;
    while r < 4 {
        let mut p = 0;
        while p < 4 {
            let d = 2 * BAYER[r][p] as i32 - 15;
            t[r][2 * p] = ((d << 6) as u32).wrapping_mul(0x1_0001);
            t[r][2 * p + 1] = (d as u32).wrapping_shl(21);
            p += 1;
        }
        r += 1;
    }
    t
};

/// Where a stored triangle goes: the triangle store and the per-row counts of the bucket sort
/// (the renderer's bucket sort, `bin.rs`), for a `view.0 × view.1` viewport (`view.1` ≤ the
/// counts' length).
pub(crate) struct Bins<'a, const T: usize> {
    pub store: &'a mut Vec<TriRecord, T>,
    pub heads: &'a mut [u16],
    pub starts: &'a mut [i16],
    pub view: (usize, usize),
}

impl<const T: usize> Bins<'_, T> {
    /// Stores triangle `t` (vertices `v`) under its first covered row, or counts it as empty or
    /// off-screen. Returns whether it is stored (or counted as needed when the store is full).
    /// `needed` counts the triangles stored or that would have been (full store). Always
    /// inlined: generic over the triangle store's size only, it is shared by every renderer of
    /// that size, and with one more of them (the shadow map's benchmark scene) the compiler
    /// called it out of line from the others' triangle loops (M0 `shadow` +0.4 %).
    #[inline(always)]
    pub(crate) fn push(
        &mut self,
        t: TriRecord,
        v: [&ScreenVertex; 3],
        n: &mut CullCounts,
        needed: &mut usize,
    ) -> bool {
        let [a, b, c] = v;
        let (ax, bx, cx) = (a.x as i32, b.x as i32, c.x as i32);
        let (ay, by, cy) = (a.y as i32, b.y as i32, c.y as i32);
        let (x0, x1) = (ax.min(bx).min(cx), ax.max(bx).max(cx));
        let (y0, y1) = (ay.min(by).min(cy), ay.max(by).max(cy));
        let (px0, px1, py0, py1) = (
            first_pixel(x0),
            first_pixel(x1),
            first_pixel(y0),
            first_pixel(y1),
        );
        if px0 >= px1 || py0 >= py1 {
            n.empty += 1;
            return false;
        }
        let (vw, vh) = self.view;
        if px1 <= 0 || py1 <= 0 || px0 >= vw as i32 || py0 >= vh as i32 {
            n.outside += 1;
            return false;
        }
        *needed += 1;
        let row = bucket_row(y0);
        let end = py1.min(vh as i32) as usize;
        if self.store.push(t).is_err() {
            return true;
        }
        let (Some(h), Some(s)) = (self.heads.get_mut(row), self.starts.get_mut(row)) else {
            return true;
        };
        *h = h.wrapping_add(1);
        *s = s.wrapping_add(1);
        if end < vh {
            if let Some(e) = self.starts.get_mut(end) {
                *e = e.wrapping_sub(1);
            }
        }
        n.drawn += 1;
        true
    }
}

/// Why [`crate::kernel::cull_push`] stopped.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum CullStop {
    /// Every triangle is done.
    Done,
    /// The triangle at the cursor needs the object loop's full path: an index out of range, an
    /// invalid vertex, or clipping.
    Portable,
}

/// What the cull kernel and [`Bins::push`] count (`repr(C)`: the Thumb cull kernel adds to the
/// fields by offset); the renderer adds them into its `Stats`. Each field counts triangles
/// (0..=2³² − 1, wrapping beyond: a frame holds at most 2¹⁵ triangles per object pass).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
#[repr(C)]
pub(crate) struct CullCounts {
    /// Entirely outside the view volume or the screen.
    pub outside: u32,
    /// Back faces.
    pub culled: u32,
    /// Zero snapped area.
    pub degenerate: u32,
    /// Covering no pixel centre.
    pub empty: u32,
    /// Stored for the rasterizer.
    pub drawn: u32,
}

/// First pixel index whose centre is at or right of (below) the subpixel coordinate `v`:
/// `ceil((v − 8) / 16)`, which for a power of two is `(v − 8 + 15) >> 4` (arithmetic shift =
/// floor), exact for every `v` in the coordinate range.
#[inline(always)]
pub(crate) fn first_pixel(v: i32) -> i32 {
    (v - SUBPIXELS / 2 + (SUBPIXELS - 1)) >> SUBPIXEL_BITS
}

/// The row bucket of a triangle whose topmost vertex is at `y_min` subpixels: its first covered
/// row, clamped to the screen. [`Bins::push`] counts by it and the bucket sort places by it,
/// so both must agree.
#[inline(always)]
pub(crate) fn bucket_row(y_min: i32) -> usize {
    first_pixel(y_min).max(0) as usize
}

/// The smallest `shift − l` (`raster::attribute_words`) for which a triangle's colour
/// gradients come from the 20-bit coefficients (the Thumb attribute setup uses it too).
pub(crate) const COARSE_MIN: i32 = 16;

/// The 4×4 Bayer matrix of the ordered dither, `BAYER[y & 3][x & 3]` in 0..16 (the dithered
/// span kernels read it through `DITHER565`).
pub const BAYER: [[u8; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];
