//! Rows and spans: an active triangle's row (its two edges stepped exactly, its attributes
//! stepped by additions), the short edge's switch, and the span loops that test and write the
//! strip's pixels (flat, Gouraud, packed, dithered). The Thumb row and span kernels
//! (`kernel::rows565`, `kernel::span565_*`) take the RGB565 `DepthTest::Less` case where they
//! run.

use core::iter::repeat;

use crate::geometry::project::{channel_bits, DEPTH_FRAC_BITS, DEPTH_MAX};
use crate::kernel;
use crate::raster::*;
use crate::scene::color::BAYER;
use crate::scene::color::{rgb565_word, rgb565_words_mut, TargetColor};

impl ActiveTri {
    /// Keeps the short edge `b → c` at row `row_mid` for a fast Gouraud triangle, in the
    /// fourth words of `gx`, `row` and `inc`, which its packed attributes leave unused (the
    /// Cortex-M row routine and the portable [`ActiveTri::advance`] switch to it).
    pub(crate) fn set_pending(&mut self, e: Edge) {
        let (d, dy) = e.dda();
        self.gx[3] = d.w as i32;
        self.row[3] = d.s as i32;
        self.inc[3] = dy as i32;
    }

    /// The edge kept by [`ActiveTri::set_pending`].
    pub(crate) fn pending(&self) -> (EdgeDda, u16) {
        (
            EdgeDda {
                w: self.gx[3] as u32,
                s: self.row[3] as u32,
            },
            self.inc[3] as u16,
        )
    }

    /// Sets [`ActiveTri::routine_rows`] for `row`, the next row to draw: rows `x` from `row`
    /// on with `x + 1 < row_end` and `x + 1 ≠ row_mid`, up to the first that fails; and
    /// [`LAST_IN_ROUTINE`] when that one is the last row (`x + 1 = row_end`), or
    /// [`SWITCH_IN_ROUTINE`] when it is the row before the short edge's switch
    /// (`x + 1 = row_mid`), if the count reaches it.
    ///
    /// With `dithered` (the strip dithers its colour), a triangle without [`DITHER_OK`] gets
    /// no routine rows: the dithered Cortex-M row routine draws only `DITHER_OK` triangles
    /// and, so that it need not test the flag on every row, relies on this. A setup passes
    /// false: a fast Gouraud triangle set up while dithering has `DITHER_OK` or is set up again
    /// without the fast path ([`ActiveTri::setup_dither`]); a triangle set up while dithering
    /// was off gets its count again when dithering is switched on
    /// ([`ActiveList::refresh_routine_rows`]).
    #[inline(always)]
    pub(crate) fn set_routine_rows(&mut self, row: i32, dithered: bool) {
        let mut k = 0;
        // (Clears the routine's bits of a fast kind only: a pool kind keeps its code there.)
        self.flags &= !((self.flags & FAST) * 6);
        if self.flags & (FAST | FLAT) == FAST && (!dithered || self.flags & DITHER_OK != 0) {
            let last = self.row_end as i32 - 1;
            let mid = self.row_mid as i32 - 1;
            let stop = if mid >= row && mid < last { mid } else { last };
            k = (stop - row).clamp(0, 255);
            if stop - row <= 255 {
                self.flags |= if stop == last {
                    LAST_IN_ROUTINE
                } else {
                    SWITCH_IN_ROUTINE
                };
            }
        }
        self.routine_rows = k as u8;
    }

    #[inline(always)]
    pub(crate) fn n_attrs(&self) -> usize {
        if self.flags & FLAT != 0 {
            1
        } else if self.flags & FAST != 0 {
            3
        } else {
            4
        }
    }

    /// The final channel bytes of a flat triangle.
    #[inline(always)]
    pub(crate) fn flat_channels(&self) -> [u8; 3] {
        let b = self.gx[1].to_le_bytes();
        [b[0], b[1], b[2]]
    }

    /// Moves to `next_row` (the row after the one just drawn). Out of line, for the layered
    /// rows and the seek ([`ActiveTri::advance_inlined`] is the plain row's); as an
    /// `#[inline]` wrapper the compiler inlined it, and with it the whole step, into the
    /// layered rows, which made them dearer on the M4F and M33 (shadow volumes +6 %).
    #[inline(never)]
    pub(crate) fn advance(&mut self, next_row: i32) {
        self.advance_inlined(next_row);
    }

    /// [`ActiveTri::advance`] always inlined, for the plain kinds' row (`raster::kind`): there
    /// the compiler kept `advance` a function of its own on every core (RISC-V torus +4.7 %,
    /// the painter's cube +1.7 % on a Cortex-M0, fast Phong +2-3 %), while inlining it at
    /// every call made the layered rows dearer on the M4F and M33 (shadow volumes +6 %).
    #[inline(always)]
    pub(crate) fn advance_inlined(&mut self, next_row: i32) {
        let mid_left = self.flags & MID_LEFT != 0;
        // The short edge b → c from the switch on: a fast Gouraud triangle has it from setup
        // ([`ActiveTri::set_pending`], the one the Cortex-M row routine switches to).
        let switch = (next_row == self.row_mid as i32).then(|| {
            if self.flags & (FAST | FLAT) == FAST {
                self.pending()
            } else {
                Edge::new(
                    self.bx as i32,
                    self.by as i32,
                    self.cx as i32,
                    self.cy as i32,
                    next_row,
                )
                .dda()
            }
        });
        let [left, right] = &mut self.edges;
        let [left_dy, right_dy] = &mut self.dy;
        let (long, long_dy, short, short_dy) = if mid_left {
            (right, *right_dy, left, left_dy)
        } else {
            (left, *left_dy, right, right_dy)
        };
        let long_carry = long.step(long_dy);
        if let Some((new_short, new_dy)) = switch {
            if mid_left {
                // Carry the attribute rows over exactly: step along the old left edge's line
                // to the new row (`EdgeDda::peek`, in 32 bits: extrapolated past its lower end,
                // that column may leave the packed half), then move by whole pixels to the new
                // edge's first column, and change the row increment for the new edge's slope.
                let (c_old, carry) = short.peek();
                let dc = new_short.c() - c_old;
                let dsq = new_short.sq() - short.sq();
                *short = new_short;
                *short_dy = new_dy;
                self.step_attrs(carry);
                for k in 0..self.n_attrs() {
                    let g = self.gx[k];
                    self.row[k] = self.row[k].wrapping_add(g.wrapping_mul(dc));
                    self.inc[k] = self.inc[k].wrapping_add(g.wrapping_mul(dsq));
                }
                return;
            }
            *short = new_short;
            *short_dy = new_dy;
            self.step_attrs(long_carry);
        } else {
            let short_carry = short.step(*short_dy);
            self.step_attrs(if mid_left { short_carry } else { long_carry });
        }
    }

    /// Moves from `row` (a row the triangle has been set up or stepped to) to `target`, exactly
    /// as [`ActiveTri::advance`] for each row in between would: the rows where the short edge
    /// takes over are stepped one by one, the runs between them are jumped ([`EdgeDda::jump`]:
    /// a multiply and a divide per edge, and per attribute its increments times the rows and
    /// the carries). For a seek: its cost does not grow with the distance. Inlined into the
    /// seek: as a function of its own, its call of [`ActiveTri::advance`] changed how the
    /// compiler inlines `advance` into the portable row loop (+4.5 % on the RISC-V torus).
    #[inline(always)]
    pub(crate) fn advance_to(&mut self, row: i32, target: i32) {
        let mut r = row;
        while r < target {
            let mid = self.row_mid as i32;
            // The last row to reach by plain steps: before the switch if it is on the way.
            let plain_end = if mid > r && mid <= target {
                mid - 1
            } else {
                target
            };
            if plain_end > r {
                self.jump_rows((plain_end - r) as u32);
                r = plain_end;
            }
            if r < target {
                self.advance(r + 1);
                r += 1;
            }
        }
    }

    /// `n` plain rows at once (no switch among them): both edges jumped, the attributes moved
    /// by `n` increments plus one `gx` per carry of the left edge.
    fn jump_rows(&mut self, n: u32) {
        let [left, right] = &mut self.edges;
        let [left_dy, right_dy] = self.dy;
        // The attributes follow the left edge's carries (the short edge when the middle vertex
        // is on the left, the long one otherwise: [`ActiveTri::advance`]).
        let carries = left.jump(n, left_dy) as i32;
        right.jump(n, right_dy);
        for k in 0..self.n_attrs() {
            self.row[k] = self.row[k]
                .wrapping_add(self.inc[k].wrapping_mul(n as i32))
                .wrapping_add(self.gx[k].wrapping_mul(carries));
        }
    }

    #[inline(always)]
    pub(crate) fn step_attrs(&mut self, carry: bool) {
        // Unrolled for the three attribute counts.
        if self.flags & FLAT != 0 {
            self.step_first::<1>(carry);
        } else if self.flags & FAST != 0 {
            self.step_first::<3>(carry);
        } else {
            self.step_first::<4>(carry);
        }
    }

    #[inline(always)]
    pub(crate) fn step_first<const N: usize>(&mut self, carry: bool) {
        for k in 0..N {
            let mut v = self.row[k].wrapping_add(self.inc[k]);
            if carry {
                v = v.wrapping_add(self.gx[k]);
            }
            self.row[k] = v;
        }
    }

    /// The span of a [`FAST`] kind on columns `xs..xe` of `row` (`lc`: the left edge's
    /// column; depth test `Less`, or none for `Z` = [`NONE`]); returns the pixels written.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn fast_span<C: TargetColor, const Z: u8>(
        &self,
        lc: i32,
        xs: i32,
        xe: i32,
        row: i32,
        colors: &mut [C],
        depth: &mut [u16],
        dither: bool,
    ) -> u32 {
        // The common case, without clamps, dispatch or a span record.
        let (x0, x1) = (xs as usize, xe as usize);
        let skip = xs - lc;
        let mut v = [self.row[0], self.row[1], self.row[2]];
        if skip != 0 {
            for k in 0..3 {
                v[k] = v[k].wrapping_add(self.gx[k].wrapping_mul(skip));
            }
        }
        let (zs, cs) = (zline::<Z>(depth, x0, x1), &mut colors[x0..x1]);
        if self.flags & FLAT != 0 {
            let c = C::from_channels(self.flat_channels());
            span_flat::<C, Z>(zs, cs, v[0], self.gx[0], c)
        } else if dither {
            let (z, rb, g) = (
                [v[0], self.gx[0]],
                [v[1] as u32, self.gx[1] as u32],
                [v[2], self.gx[2]],
            );
            if self.flags & DITHER_OK != 0 {
                span_packed_dither::<C, Z>(zs, cs, z, rb, g, x0, row)
            } else {
                span_packed_dither_clamped::<C, Z>(zs, cs, z, rb, g, x0, row)
            }
        } else {
            span_packed::<C, Z>(
                zs,
                cs,
                [v[0], self.gx[0]],
                [v[1] as u32, self.gx[1] as u32],
                [v[2], self.gx[2]],
            )
        }
    }

    /// The span of the [`GOURAUD`](crate::raster::kind::GOURAUD) and
    /// [`FLAT_KIND`](crate::raster::kind::FLAT_KIND) kinds on columns `xs..xe` of `row`
    /// (`lc`: the left edge's column): the attribute rows clamped to their ranges at the span's
    /// start, depth test `test` (none for `Z` = [`NONE`]); returns the pixels written.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn span<C: TargetColor, const Z: u8>(
        &self,
        lc: i32,
        xs: i32,
        xe: i32,
        row: i32,
        colors: &mut [C],
        depth: &mut [u16],
        test: DepthTest,
        dither: bool,
    ) -> u32 {
        let flat = self.flags & FLAT != 0;
        let skip = xs - lc;
        let mut start = [0i32; 4];
        for k in 0..self.n_attrs() {
            let max = if k == 0 {
                DEPTH_MAX << DEPTH_FRAC_BITS
            } else {
                (C::CHANNEL_MAX[k - 1] as i32) << COLOR_FRAC_BITS
            };
            let v = if skip == 0 {
                self.row[k]
            } else {
                self.row[k].wrapping_add(self.gx[k].wrapping_mul(skip))
            };
            start[k] = v.clamp(0, max);
        }
        let span = Span {
            x0: xs as usize,
            x1: xe as usize,
            row,
            start,
            gx: self.gx,
        };
        if Z == NONE {
            if flat {
                let c = C::from_channels(self.flat_channels());
                span.fill_flat::<C, NONE>(colors, depth, c)
            } else {
                span.fill_gouraud::<C, NONE>(colors, depth, dither)
            }
        } else if flat {
            let c = C::from_channels(self.flat_channels());
            by_depth_test!(test, T => span.fill_flat::<C, T>(colors, depth, c))
        } else {
            by_depth_test!(test, T => span.fill_gouraud::<C, T>(colors, depth, dither))
        }
    }
}

/// Flat span: depth test `T`, constant colour. `z` carries the half-step rounding bias.
// A function of its own: inlined into the row loop, the pixel loop inherits that loop's
// register pressure and spills its accumulators on a Cortex-M0.
#[inline(never)]
pub(crate) fn span_flat<C: TargetColor, const T: u8>(
    zs: &mut [u16],
    cs: &mut [C],
    z: i32,
    gz: i32,
    color: C,
) -> u32 {
    if T == NONE {
        return span_flat_portable::<C, T>(repeat(NoDepth), cs, z, gz, color);
    }
    if T == LESS {
        if let (Some(word), Some(words)) = (rgb565_word(color), rgb565_words_mut(cs)) {
            if let Some(written) = kernel::span565_flat_less(zs, words, z, gz, word) {
                return written;
            }
        }
    }
    span_flat_portable::<C, T>(zs, cs, z, gz, color)
}

/// [`span_flat`]'s portable loop (the flat span kernel's twin).
#[inline(always)]
pub(crate) fn span_flat_portable<C: TargetColor, const T: u8>(
    zs: impl IntoIterator<Item = impl DepthSlot>,
    cs: &mut [C],
    mut z: i32,
    gz: i32,
    color: C,
) -> u32 {
    let mut written = 0;
    for (zb, cb) in zs.into_iter().zip(cs.iter_mut()) {
        let z16 = (z >> DEPTH_FRAC_BITS) as u16;
        if zb.pass::<T>(z16) {
            *cb = color;
            written += 1;
        }
        z = z.wrapping_add(gz);
    }
    written
}

/// Gouraud span with red and blue packed in one accumulator (see
/// [`Span::fill_gouraud_packed`] for why that is exact), depth test `T`: `z`, `rb`, `g` are
/// `[start, per-pixel step]` in the packed formats ([`pack_zrgb`]) with their rounding biases
/// already added.
#[inline(never)]
pub(crate) fn span_packed<C: TargetColor, const T: u8>(
    zs: &mut [u16],
    cs: &mut [C],
    z: [i32; 2],
    rb: [u32; 2],
    g: [i32; 2],
) -> u32 {
    if T == NONE {
        return span_packed_portable::<C, T>(repeat(NoDepth), cs, z, rb, g);
    }
    if T == LESS {
        if let Some(words) = rgb565_words_mut(cs) {
            if let Some(written) = kernel::span565_less(zs, words, z, rb, g) {
                return written;
            }
        }
    }
    span_packed_portable::<C, T>(zs, cs, z, rb, g)
}

/// [`span_packed`]'s portable loop (the Gouraud span kernel's twin).
#[inline(always)]
pub(crate) fn span_packed_portable<C: TargetColor, const T: u8>(
    zs: impl IntoIterator<Item = impl DepthSlot>,
    cs: &mut [C],
    z: [i32; 2],
    rb: [u32; 2],
    g: [i32; 2],
) -> u32 {
    let ([mut z, gz], [mut rb, grb], [mut g, gg]) = (z, rb, g);
    let mut written = 0;
    for (zb, cb) in zs.into_iter().zip(cs.iter_mut()) {
        let z16 = (z as u32 >> 16) as u16;
        if zb.pass::<T>(z16) {
            *cb = packed_color::<C>(rb, g as u32);
            written += 1;
        }
        z = z.wrapping_add(gz);
        rb = rb.wrapping_add(grb);
        g = g.wrapping_add(gg);
    }
    written
}

/// [`span_packed`] with 4×4 ordered dithering, for a [`DITHER_OK`] triangle: the pixels are
/// columns `x0..` of pixel row `row`, and each written pixel's packed red-blue and green
/// values get the offset of its column phase from [`dither_words`] before the channels are
/// read, so each channel is `floor(v + (2·B + 1)/32)` of the packed value `v` (the ½ bias
/// the start values carry and the offset `d` add up to the threshold). The accumulators step
/// as in [`span_packed`]. This is the definition the Cortex-M routine
/// (`kernel::span565_less_dither`, and the row routine's dithered variant) equals bit
/// for bit.
#[inline(never)]
pub(crate) fn span_packed_dither<C: TargetColor, const T: u8>(
    zs: &mut [u16],
    cs: &mut [C],
    z: [i32; 2],
    rb: [u32; 2],
    g: [i32; 2],
    x0: usize,
    row: i32,
) -> u32 {
    if T == NONE {
        return span_packed_dither_portable::<C, T>(repeat(NoDepth), cs, z, rb, g, x0, row);
    }
    if T == LESS {
        if let Some(words) = rgb565_words_mut(cs) {
            if let Some(written) = kernel::span565_less_dither(zs, words, z, rb, g, x0, row) {
                return written;
            }
        }
    }
    span_packed_dither_portable::<C, T>(zs, cs, z, rb, g, x0, row)
}

/// [`span_packed_dither`] in portable code (the twin of the Cortex-M routines).
#[inline(always)]
pub(crate) fn span_packed_dither_portable<C: TargetColor, const T: u8>(
    zs: impl IntoIterator<Item = impl DepthSlot>,
    cs: &mut [C],
    z: [i32; 2],
    rb: [u32; 2],
    g: [i32; 2],
    x0: usize,
    row: i32,
) -> u32 {
    let offsets = dither_words::<C>(row);
    let ([mut z, gz], [mut rb, grb], [mut g, gg]) = (z, rb, g);
    let mut written = 0;
    for (x, (zb, cb)) in (x0..).zip(zs.into_iter().zip(cs.iter_mut())) {
        let z16 = (z as u32 >> 16) as u16;
        if zb.pass::<T>(z16) {
            let [drb, dg] = offsets[x & 3];
            *cb = packed_color::<C>(rb.wrapping_add(drb), (g as u32).wrapping_add(dg));
            written += 1;
        }
        z = z.wrapping_add(gz);
        rb = rb.wrapping_add(grb);
        g = g.wrapping_add(gg);
    }
    written
}

/// The dithered fast span (`DepthTest::Less`) for a fast triangle without [`DITHER_OK`] (its
/// packed values may come within 15/32 of a unit of a field's end, or it was set up while
/// dithering was off): each field is read out of the packed words (exact: the ½ bias keeps
/// every field inside `0..2¹⁶` at pixel centres of the triangle, see [`ActiveTri::row`]),
/// the offset `d` is added in an `i32` and the channel is clamped to its range. Portable on
/// every core (rare).
#[inline(never)]
pub(crate) fn span_packed_dither_clamped<C: TargetColor, const T: u8>(
    zs: &mut [u16],
    cs: &mut [C],
    z: [i32; 2],
    rb: [u32; 2],
    g: [i32; 2],
    x0: usize,
    row: i32,
) -> u32 {
    if T == NONE {
        dither_clamped_loop::<C, T>(repeat(NoDepth), cs, z, rb, g, x0, row)
    } else {
        dither_clamped_loop::<C, T>(zs, cs, z, rb, g, x0, row)
    }
}

/// [`span_packed_dither_clamped`]'s loop over any depth slots.
#[inline(always)]
fn dither_clamped_loop<C: TargetColor, const T: u8>(
    zs: impl IntoIterator<Item = impl DepthSlot>,
    cs: &mut [C],
    z: [i32; 2],
    rb: [u32; 2],
    g: [i32; 2],
    x0: usize,
    row: i32,
) -> u32 {
    let (fr, fb) = packed_frac_bits::<C>();
    let gbits = channel_bits(C::CHANNEL_MAX[1]);
    let bayer = &BAYER[(row & 3) as usize];
    let ([mut z, gz], [mut rb, grb], [mut g, gg]) = (z, rb, g);
    let q = |v: i64, frac: u32, max: u8| (v >> frac).clamp(0, max as i64) as u8;
    let mut written = 0;
    for (x, (zb, cb)) in (x0..).zip(zs.into_iter().zip(cs.iter_mut())) {
        let z16 = (z as u32 >> 16) as u16;
        if zb.pass::<T>(z16) {
            let d = 2 * bayer[x & 3] as i64 - 15;
            *cb = C::from_channels([
                q((rb >> 16) as i64 + (d << (fr - 5)), fr, C::CHANNEL_MAX[0]),
                q(
                    g as u32 as i64 + (d << (32 - gbits - 5)),
                    32 - gbits,
                    C::CHANNEL_MAX[1],
                ),
                q(
                    (rb & 0xffff) as i64 + (d << (fb - 5)),
                    fb,
                    C::CHANNEL_MAX[2],
                ),
            ]);
            written += 1;
        }
        z = z.wrapping_add(gz);
        rb = rb.wrapping_add(grb);
        g = g.wrapping_add(gg);
    }
    written
}

/// One span: pixels `x0..x1` of a row, with attribute values at `x0` and per-pixel gradients.
pub(crate) struct Span {
    x0: usize,
    x1: usize,
    row: i32,
    /// z (16.12, clamped to 0..=65535·2¹²) and r, g, b (channel units, 20 fraction bits).
    start: [i32; 4],
    gx: [i32; 4],
}

/// `$body` with `$t` the const generic of the span loops for depth test `$test` ([`LESS`],
/// ...): the one place a runtime [`DepthTest`] becomes the constant the per-pixel loops are
/// compiled for. A new test is a variant here, a constant here and its comparison in
/// [`passes`].
macro_rules! by_depth_test {
    ($test:expr, $t:ident => $body:expr) => {
        match $test {
            $crate::raster::DepthTest::Less => {
                const $t: u8 = $crate::raster::span::LESS;
                $body
            }
            $crate::raster::DepthTest::LessEqual => {
                const $t: u8 = $crate::raster::span::LESS_EQUAL;
                $body
            }
            $crate::raster::DepthTest::Equal => {
                const $t: u8 = $crate::raster::span::EQUAL;
                $body
            }
            $crate::raster::DepthTest::Always => {
                const $t: u8 = $crate::raster::span::ALWAYS;
                $body
            }
        }
    };
}
pub(crate) use by_depth_test;

pub(crate) const LESS: u8 = 0;
pub(crate) const LESS_EQUAL: u8 = 1;
pub(crate) const EQUAL: u8 = 2;
pub(crate) const ALWAYS: u8 = 3;
/// No depth line at all (a renderer without depth lines, [`crate::NoDepthRenderer`]): every
/// fragment is written and no depth is read or stored.
pub(crate) const NONE: u8 = 4;

/// One pixel's depth slot in a span loop: the strip's stored depth, or [`NoDepth`].
pub(crate) trait DepthSlot {
    /// Whether a fragment at depth `z` passes test `T` here; stores `z` when it does.
    fn pass<const T: u8>(self, z: u16) -> bool;
}

impl DepthSlot for &mut u16 {
    #[inline(always)]
    fn pass<const T: u8>(self, z: u16) -> bool {
        if passes::<T>(z, *self) {
            *self = z;
            true
        } else {
            false
        }
    }
}

/// The depth slot of a renderer without depth lines: every fragment passes, nothing is stored
/// (the span loops' depth arithmetic is then dead code and compiled out).
#[derive(Copy, Clone)]
pub(crate) struct NoDepth;

impl DepthSlot for NoDepth {
    #[inline(always)]
    fn pass<const T: u8>(self, _z: u16) -> bool {
        true
    }
}

/// The depth slots of columns `x0..x1` for test `T`: none for [`NONE`].
#[inline(always)]
fn zline<const T: u8>(depth: &mut [u16], x0: usize, x1: usize) -> &mut [u16] {
    if T == NONE {
        &mut []
    } else {
        &mut depth[x0..x1]
    }
}

/// The depth test, resolved at compile time in each monomorphized span loop.
#[inline(always)]
pub(crate) fn passes<const T: u8>(z: u16, stored: u16) -> bool {
    match T {
        LESS => z < stored,
        LESS_EQUAL => z <= stored,
        EQUAL => z == stored,
        _ => true,
    }
}

impl Span {
    /// Depth with a half-step bias so that the shift rounds to nearest. Gradient rounding can
    /// overshoot the clamped range by at most ½ per pixel (< 2¹¹ over a 2048-px span), which
    /// the bias absorbs, so the shift never leaves 0..=65535.
    #[inline(always)]
    pub(crate) fn z_start(&self) -> i32 {
        self.start[0] + (1 << (DEPTH_FRAC_BITS - 1))
    }

    pub(crate) fn fill_flat<C: TargetColor, const T: u8>(
        &self,
        colors: &mut [C],
        depth: &mut [u16],
        color: C,
    ) -> u32 {
        span_flat::<C, T>(
            zline::<T>(depth, self.x0, self.x1),
            &mut colors[self.x0..self.x1],
            self.z_start(),
            self.gx[0],
            color,
        )
    }

    pub(crate) fn fill_gouraud<C: TargetColor, const T: u8>(
        &self,
        colors: &mut [C],
        depth: &mut [u16],
        dither: bool,
    ) -> u32 {
        if dither {
            self.fill_gouraud_dither::<C, T>(colors, depth)
        } else if packable::<C>() && self.x1 - self.x0 <= 1024 {
            self.fill_gouraud_packed::<C, T>(colors, depth)
        } else {
            self.fill_gouraud_round::<C, T>(colors, depth)
        }
    }

    /// Gouraud span for channels of at most 6 bits (RGB565, RGB555, RGB666), rounding to
    /// nearest. Red and blue share one 32-bit accumulator as two 16-bit fields with
    /// `16 − bits` fraction bits each (red in the high half): `P = R·2¹⁶ + B` is exact as long
    /// as `B` stays in `0..2¹⁶`, which holds because the clamped start plus the half-step bias
    /// leaves `2^(15 − bits)` of headroom and rounding of the gradient drifts by at most ½ unit
    /// per pixel over at most 1024 pixels. Fewer live values keep the loop in registers on a
    /// Cortex-M0.
    // A function of its own: inlined into the row loop, the span loop inherits that loop's
    // register pressure and spills its accumulators on a Cortex-M0.
    pub(crate) fn fill_gouraud_packed<C: TargetColor, const T: u8>(
        &self,
        colors: &mut [C],
        depth: &mut [u16],
    ) -> u32 {
        // The stored gradients are the low 32 bits of the exact ones, which are the exact ones
        // whenever the span has two pixels or more: two pixel centres of one row inside the
        // triangle differ by less than a channel's range, so |gx| < 2⁸ units per pixel. (With
        // one pixel the gradient is never added.)
        let [s, g] = [self.start, self.gx].map(|w| w.map(|v| v as i64));
        let [z, rb, g0] = pack_zrgb::<C>(
            self.z_start() as i64,
            s[1],
            s[2] + (1 << (COLOR_FRAC_BITS - 1)),
            s[3],
        );
        let rb = (rb as u32).wrapping_add(packed_rb_half::<C>());
        let [gz, grb, gg] = pack_zrgb::<C>(g[0], g[1], g[2], g[3]);
        let (zs, cs) = (
            zline::<T>(depth, self.x0, self.x1),
            &mut colors[self.x0..self.x1],
        );
        span_packed::<C, T>(zs, cs, [z, gz], [rb, grb as u32], [g0, gg])
    }

    /// Gouraud span, rounding to nearest: the half is folded into the start values.
    // A function of its own: inlined into the row loop, the span loop inherits that loop's
    // register pressure and spills its accumulators on a Cortex-M0.
    #[inline(never)]
    pub(crate) fn fill_gouraud_round<C: TargetColor, const T: u8>(
        &self,
        colors: &mut [C],
        depth: &mut [u16],
    ) -> u32 {
        let cs = &mut colors[self.x0..self.x1];
        if T == NONE {
            self.round_loop::<C, T>(repeat(NoDepth), cs)
        } else {
            self.round_loop::<C, T>(&mut depth[self.x0..self.x1], cs)
        }
    }

    /// [`Span::fill_gouraud_round`]'s loop over any depth slots.
    #[inline(always)]
    fn round_loop<C: TargetColor, const T: u8>(
        &self,
        zs: impl IntoIterator<Item = impl DepthSlot>,
        cs: &mut [C],
    ) -> u32 {
        let half = 1i32 << (COLOR_FRAC_BITS - 1);
        let mut z = self.z_start();
        let [_, r0, g0, b0] = self.start;
        let (mut r, mut g, mut b) = (r0 + half, g0 + half, b0 + half);
        let [gz, gr, gg, gb] = self.gx;
        let mut written = 0;
        for (zb, cb) in zs.into_iter().zip(cs.iter_mut()) {
            let z16 = (z >> DEPTH_FRAC_BITS) as u16;
            if zb.pass::<T>(z16) {
                *cb = C::from_channels([
                    (r >> COLOR_FRAC_BITS) as u8,
                    (g >> COLOR_FRAC_BITS) as u8,
                    (b >> COLOR_FRAC_BITS) as u8,
                ]);
                written += 1;
            }
            z = z.wrapping_add(gz);
            r = r.wrapping_add(gr);
            g = g.wrapping_add(gg);
            b = b.wrapping_add(gb);
        }
        written
    }

    /// Gouraud span with 4×4 ordered dithering: the rounding bias is the Bayer threshold
    /// (2·B + 1)/32 of a channel unit for the pixel's column phase.
    // A function of its own: inlined into the row loop, the span loop inherits that loop's
    // register pressure and spills its accumulators on a Cortex-M0.
    #[inline(never)]
    pub(crate) fn fill_gouraud_dither<C: TargetColor, const T: u8>(
        &self,
        colors: &mut [C],
        depth: &mut [u16],
    ) -> u32 {
        let cs = &mut colors[self.x0..self.x1];
        if T == NONE {
            self.dither_loop::<C, T>(repeat(NoDepth), cs)
        } else {
            self.dither_loop::<C, T>(&mut depth[self.x0..self.x1], cs)
        }
    }

    /// [`Span::fill_gouraud_dither`]'s loop over any depth slots.
    #[inline(always)]
    fn dither_loop<C: TargetColor, const T: u8>(
        &self,
        zs: impl IntoIterator<Item = impl DepthSlot>,
        cs: &mut [C],
    ) -> u32 {
        let mut bias = [0i32; 4];
        let row = &BAYER[(self.row & 3) as usize];
        for (k, t) in bias.iter_mut().enumerate() {
            *t = (2 * row[k] as i32 + 1) << (COLOR_FRAC_BITS - 5);
        }
        let mut z = self.z_start();
        let [_, mut r, mut g, mut b] = self.start;
        let [gz, gr, gg, gb] = self.gx;
        let mut written = 0;
        for (x, (zb, cb)) in (self.x0..).zip(zs.into_iter().zip(cs.iter_mut())) {
            let z16 = (z >> DEPTH_FRAC_BITS) as u16;
            if zb.pass::<T>(z16) {
                let t = bias[x & 3];
                *cb = C::from_channels([
                    ((r + t) >> COLOR_FRAC_BITS) as u8,
                    ((g + t) >> COLOR_FRAC_BITS) as u8,
                    ((b + t) >> COLOR_FRAC_BITS) as u8,
                ]);
                written += 1;
            }
            z = z.wrapping_add(gz);
            r = r.wrapping_add(gr);
            g = g.wrapping_add(gg);
            b = b.wrapping_add(gb);
        }
        written
    }
}
