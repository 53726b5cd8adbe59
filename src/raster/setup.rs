//! Triangle setup: when a triangle becomes active on its first row, its edges, its depth and
//! colour planes (gradients from one normalized reciprocal of its area), its first-pixel
//! values and row steps, packed for the span loops when it qualifies; and the dither check of
//! a fast triangle. The Thumb setup kernels (`kernel::setup565`, `kernel::gouraud_setup`,
//! `kernel::dither_fits565`) take the common RGB565 case where they run.

use crate::geometry::project::{
    channel_bits, vertex_frac_bits, ScreenVertex, DEPTH_FRAC_BITS, SUBPIXELS,
};
use crate::kernel;
use crate::kernel::wide::{mul_shr_16, wide_plane};
use crate::kernel::Setup565;
use crate::num::scalar::{mul_wide, mul_wide16, recip_norm, round_shr64};
use crate::raster::*;
use crate::scene::color::TargetColor;

/// `1/d` for a triangle's doubled area `d ≠ 0` (|d| < 2⁶²), as `±m · 2^-e` with `m` in
/// (2²⁹, 2³⁰] (see [`crate::num::scalar::recip_norm`]).
#[derive(Copy, Clone, Debug)]
pub(crate) struct Reciprocal {
    pub(crate) m: i32,
    pub(crate) e: u32,
    pub(crate) neg: bool,
}

impl Reciprocal {
    pub(crate) fn new(d: i64) -> Self {
        let (m, e) = recip_norm(d.unsigned_abs());
        Reciprocal { m, e, neg: d < 0 }
    }
}

/// A gradient `S · 2^-shift` (see [`ActiveTri::setup`]) rounded half up, for `shift ≥ 1`
/// (a triangle's setup has `shift ≥ 10`) and `|S| < 2⁶²`: exact, not clamped. A sliver's
/// gradient can exceed the `i32` range; the planes are stepped in wrapping arithmetic (see
/// [`ActiveTri`]), so only its low bits matter where it is used, but those must be exact.
#[inline]
pub(crate) fn scale_gradient(s: i64, shift: i32) -> i64 {
    if shift >= 63 {
        // |S| < 2⁶², so S / 2^shift rounds to 0.
        0
    } else {
        round_shr64(s, shift.max(1) as u32)
    }
}

/// A colour channel's x and y gradients from the exact 64-bit sums, for the triangles whose
/// 20-bit coefficients are not precise enough (see [`attribute_words`]). Out of line and
/// cold: inlined, LLVM computed parts of it for every triangle and spilled them.
#[cold]
#[inline(never)]
pub(crate) fn exact_color_gradients(
    b: [i32; 4],
    d1: i32,
    d2: i32,
    sh: u32,
    shift: i32,
) -> [i64; 2] {
    let [bx1, bx2, by1, by2] = b;
    // |b| ≤ 2³⁰ and |d| < 2¹⁰, so each sum is below 2⁴¹ and, shifted by sh ≤ 18, below 2⁵⁹.
    [
        scale_gradient((mul_wide16(bx1, d1) - mul_wide16(bx2, d2)) << sh, shift),
        scale_gradient((mul_wide16(by1, d2) - mul_wide16(by2, d1)) << sh, shift),
    ]
}

/// The attribute words of a triangle set up on `tri.row` ([`ActiveTri::gx`], `row` and
/// `inc`): the planes of depth and colour, their gradients, their values at the centre of the
/// first pixel of the first row and their steps from row to row along the left edge; packed
/// for the span loops when `fast` and not `flat`.
#[inline(always)]
pub(crate) fn attribute_words<C: TargetColor>(
    tri: &Sorted<'_>,
    flat: bool,
    fast: bool,
    flat_rgb: [u16; 3],
) -> [[i32; 4]; 3] {
    let [a, b, c] = tri.v;
    let (ax, ay, bx, by, cx, cy) = (
        a.x as i32, a.y as i32, b.x as i32, b.y as i32, c.x as i32, c.y as i32,
    );
    let (dx1, dy1) = (bx - ax, by - ay);
    let (dx2, dy2) = (cx - ax, cy - ay);
    // Barycentric gradient coefficients, 16·(dy2, dy1, dx2, dx1)/det, with a shared
    // exponent: gx = da1·bx1 − da2·bx2, gy = da2·by1 − da1·by2.
    let inv = Reciprocal::new(tri.det as i64);
    let vmax = dy2
        .unsigned_abs()
        .max(dy1.unsigned_abs())
        .max(dx1.unsigned_abs())
        .max(dx2.unsigned_abs());
    let l = crate::num::scalar::bitlen32(vmax); // ≤ 16
    let coef = |v: i32| -> i32 {
        let q = mul_shr_16(inv.m, v, l);
        if inv.neg {
            -q
        } else {
            q
        }
    };
    let (bx1, bx2, by1, by2) = (coef(dy2), coef(dy1), coef(dx1), coef(dx2));
    // g = S · 2^(l + 4 − e), S = Σ da·b.
    let shift = inv.e as i32 - (l as i32 + 4);
    // The 20-bit coefficients below move a colour anywhere in the triangle by at most
    // (|d1| + |d2|)·2^(2l − bitlen(det) − 18) channel units (10-bit): each is within 2¹⁰ of
    // its coefficient (≤ 2³⁰, so 2⁻²⁰ of the largest), that error in a gradient is
    // (|d1| + |d2|)·2^(l − 15 − bitlen(det)) per pixel, and no pixel is more than 2^(l − 3)
    // pixels (x plus y) from the first vertex. With |d| < 2¹⁰ that is at most 1/8 of a 5-bit
    // unit when 2l − bitlen(det) ≤ 9, i.e. shift − l ≥ 16 (a triangle at most about 500 times
    // longer than it is thick). Thinner ones take the exact sums.
    let coarse_ok = shift - l as i32 >= COARSE_MIN;

    let n_attrs = if flat { 1 } else { 4 };
    // The coefficients rounded to 20 bits (|c| ≤ 2^19) for the colour gradients.
    let c20 = [bx1, bx2, by1, by2].map(|v| (v + (1 << 10)) >> 11);
    let (ca, cb, cc) = (a.color(), b.color(), c.color());
    // Values at the first vertex, and the gradients per pixel: exact, in 64 bits (a sliver's
    // gradients may exceed the i32 range; see [`scale_gradient`]).
    let mut a0 = [0i32; 4];
    let mut gx = [0i64; 4];
    let mut gy = [0i64; 4];
    {
        let (v0, v1, v2) = (a.depth(), b.depth(), c.depth());
        let (da1, da2) = (v1 - v0, v2 - v0); // |da| < 2^28
        a0[0] = v0;
        gx[0] = scale_gradient(mul_wide(da1, bx1) - mul_wide(da2, bx2), shift);
        gy[0] = scale_gradient(mul_wide(da2, by1) - mul_wide(da1, by2), shift);
    }
    // Constant trip counts (with a break), so that the channels are unrolled: with a
    // variable count LLVM kept the arrays in memory and the loop cost about twice as much.
    for k in 1..4 {
        if flat {
            break;
        }
        // Colours are 10-bit channels scaled by a constant power of two: the products are
        // 32 × 16-bit, shifted afterwards (the same values).
        let sh = COLOR_FRAC_BITS - vertex_frac_bits(C::CHANNEL_MAX[k - 1]);
        let c0 = ca[k - 1] as i32;
        let (d1, d2) = (cb[k - 1] as i32 - c0, cc[k - 1] as i32 - c0); // |d| < 2^10
        a0[k] = c0 << sh;
        // The gradients from the coefficients rounded to 20 bits: sums of single 32-bit
        // products (|d·c| < 2^29), rounded once by a 32-bit shift (see `coarse_ok`).
        // Triangles thin enough to need a shift of less than 1 keep the exact 64-bit sums.
        let r = shift - 11 - sh as i32;
        if r >= 1 && coarse_ok {
            // v / 2^r rounded half up, as `round_shr64` (r ≤ 62).
            let round = |v: i32| -> i64 { (((v >> (r - 1).min(31)) + 1) >> 1) as i64 };
            gx[k] = round(c20[0] * d1 - c20[1] * d2);
            gy[k] = round(c20[2] * d2 - c20[3] * d1);
        } else {
            [gx[k], gy[k]] = exact_color_gradients([bx1, bx2, by1, by2], d1, d2, sh, shift);
        }
    }
    // Evaluate every attribute plane at the centre of pixel (left.c, row), modulo 2⁶⁴ (the
    // exact value where it is used: see [`ActiveTri`]).
    let dx = SUBPIXELS * tri.left_c + SUBPIXELS / 2 - ax;
    let dy = SUBPIXELS * tri.row + SUBPIXELS / 2 - ay;
    let mut row64 = [0i64; 4];
    for k in 0..4 {
        if k == n_attrs {
            break;
        }
        let p = wide_plane(gx[k], dx).wrapping_add(wide_plane(gy[k], dy));
        row64[k] = (a0[k] as i64).wrapping_add(p >> crate::geometry::project::SUBPIXEL_BITS);
    }
    let sq = tri.left_sq;
    if fast && !flat {
        // Pack once here, so that rows and spans step three words and convert nothing. Red
        // and blue are packed from the 64-bit values (a wrapped 32-bit blue would put a wrong
        // borrow into red), and the row step from the packed gradients, `Gy + Gx·sq`, so that
        // stepping rows adds no error beyond the packed gradients' own (see
        // [`ActiveTri::dither_fits`]).
        let [z, rb, g] = pack_zrgb::<C>(
            row64[0].wrapping_add(1 << (DEPTH_FRAC_BITS - 1)),
            row64[1],
            row64[2].wrapping_add(1 << (COLOR_FRAC_BITS - 1)),
            row64[3],
        );
        let row_v = [z, rb.wrapping_add(packed_rb_half::<C>() as i32), g, 0];
        let px = pack_zrgb::<C>(gx[0], gx[1], gx[2], gx[3]);
        let py = pack_zrgb::<C>(gy[0], gy[1], gy[2], gy[3]);
        let inc = [0, 1, 2].map(|k| py[k].wrapping_add(px[k].wrapping_mul(sq)));
        return [[px[0], px[1], px[2], 0], row_v, [inc[0], inc[1], inc[2], 0]];
    }
    let mut out_gx = gx.map(|g| g as i32);
    let mut row_v = row64.map(|v| v as i32);
    let inc = [0, 1, 2, 3].map(|k| (gy[k] as i32).wrapping_add((gx[k] as i32).wrapping_mul(sq)));
    if flat {
        // Final channel values, rounded from the vertex bytes.
        let mut ch = [0u8; 3];
        for k in 0..3 {
            let f = vertex_frac_bits(C::CHANNEL_MAX[k]);
            ch[k] = ((flat_rgb[k] as u32 + (1 << (f - 1))) >> f) as u8;
        }
        out_gx[1] = i32::from_le_bytes([ch[0], ch[1], ch[2], 0]);
    }
    if fast {
        row_v[0] = row_v[0].wrapping_add(1 << (DEPTH_FRAC_BITS - 1));
    }
    [out_gx, row_v, inc]
}

/// [`attribute_words`] into `rec`, out of line, where the setup kernels run
/// ([`kernel::SETUP_KERNELS`]): there the kernel takes the common case, and inlined the
/// portable words and their spills would grow the frame of [`ActiveTri::setup`] (on a 16 KB
/// part the stack has no room).
#[inline(never)]
pub(crate) fn set_attribute_words<C: TargetColor>(
    rec: &mut ActiveTri,
    tri: &Sorted<'_>,
    flat: bool,
    fast: bool,
    flat_rgb: [u16; 3],
) {
    [rec.gx, rec.row, rec.inc] = attribute_words::<C>(tri, flat, fast, flat_rgb);
}

impl ActiveTri {
    /// An inactive record to set up in place (see [`ActiveTri::setup`]).
    pub(crate) const EMPTY: ActiveTri = ActiveTri {
        flags: 0,
        routine_rows: 0,
        spare: 0,
        edges: [EdgeDda { w: 0, s: 0 }; 2],
        dy: [1; 2],
        row_mid: 0,
        row_end: 0,
        bx: 0,
        by: 0,
        cx: 0,
        cy: 0,
        gx: [0; 4],
        row: [0; 4],
        inc: [0; 4],
    };

    /// Sets up triangle `t` starting at `row` (its first covered row, clamped to the screen)
    /// in place — the record is 84 bytes, and building it elsewhere to copy it into the
    /// active list cost two block copies per triangle on a Cortex-M0. `mode` is the strip's
    /// [`SpanMode`]. Returns false (leaving `self` unspecified) if the triangle covers no row
    /// from `row` on.
    pub(crate) fn setup<C: TargetColor>(
        &mut self,
        t: &TriRecord,
        verts: &[ScreenVertex],
        row: i32,
        height: i32,
        mode: SpanMode,
    ) -> bool {
        // The setup kernel also makes the dither check of `setup_dither`.
        if kernel::SETUP_KERNELS && mode.fast_gouraud && C::CHANNEL_MAX == [31, 63, 31] {
            match kernel::setup565(self, t, verts, row, height, mode.dither) {
                Some(Setup565::Kept) => return true,
                Some(Setup565::Empty) => return false,
                Some(Setup565::NotDitherable) => {
                    let slow = SpanMode {
                        fast_gouraud: false,
                        ..mode
                    };
                    return self.setup_portable::<C>(t, verts, row, height, slow);
                }
                None => {}
            }
        }
        if mode.dither {
            return self.setup_dither::<C>(t, verts, row, height, mode);
        }
        self.setup_portable::<C>(t, verts, row, height, mode)
    }

    /// [`ActiveTri::setup`] while dithering: a fast Gouraud triangle gets [`DITHER_OK`] if
    /// [`ActiveTri::dither_fits`] holds, and otherwise is set up again without the fast path
    /// (its rows are then dithered from the 20-bit values by `Span::fill_gouraud_dither`, as
    /// every dithered triangle was before). Out of line, so that the undithered setup is the
    /// same code as before.
    #[inline(never)]
    pub(crate) fn setup_dither<C: TargetColor>(
        &mut self,
        t: &TriRecord,
        verts: &[ScreenVertex],
        row: i32,
        height: i32,
        mode: SpanMode,
    ) -> bool {
        // (Where the setup kernel runs, `setup` came here only if it declined.)
        let kept = self.setup_portable::<C>(t, verts, row, height, mode);
        if !kept || self.flags & (FAST | FLAT) != FAST {
            return kept;
        }
        let [i0, i1, i2] = t.indices();
        let p = [&verts[i0], &verts[i1], &verts[i2]];
        let fits = match kernel::dither_fits565(self, p, row) {
            Some(fits) if C::CHANNEL_MAX == [31, 63, 31] => fits,
            _ => self.dither_fits::<C>(p, row),
        };
        if fits {
            self.flags |= DITHER_OK;
            return true;
        }
        let slow = SpanMode {
            fast_gouraud: false,
            ..mode
        };
        self.setup_portable::<C>(t, verts, row, height, slow)
    }

    /// Whether the packed fields of this fast Gouraud triangle (just set up on `row`, `p` its
    /// vertices) are fit for the dithered fast span: at every pixel centre of the triangle,
    /// each field is within ¼ unit of the exact plane through the vertex colours (plus the
    /// ½-unit bias), and at least 15/32 of a unit inside its range, so that adding any offset
    /// of [`dither_words`] (|d| ≤ 15/32 of a unit) neither carries from blue into red nor
    /// leaves the red half or the green word.
    ///
    /// Why this is checked per triangle: the packed fields hold the value plus ½ unit, and the
    /// values the packed rows produce are not exactly within the channel's range. The colour
    /// gradients come from coefficients rounded to 20 bits (a few 2⁻¹⁸ of the channel's change
    /// across the triangle), and the packed steps are rounded to `16 − bits` fraction bits:
    /// 2⁻¹² unit per pixel, and per row 2⁻¹² unit times `1 + |sq|` (the row step is
    /// `inc = gy + gx·sq`, and after the short edge's switch `inc` changes by the *packed*
    /// `gx·dsq`, so the rounding of `gx` comes back `|sq|` times per row): a steep left edge
    /// across a tall triangle drifts by units. Rounding to nearest tolerates ½ unit (less in
    /// such triangles); the thresholds 1/32 and 31/32 leave 1/32 unit, so a field near 0 or
    /// the channel's maximum would borrow or carry between fields (blue 0 would read as 31).
    /// Neither bound holds in general, so both are checked, exactly:
    ///
    /// The packed rows are stepped with wrapping additions of constant words, so every packed
    /// field is an exact linear function of the pixel: `F(c, r) = F₀ + Gx·(c − c₀) +
    /// Gy·(r − r₀)` with `F₀` the field at the first pixel `(c₀, r₀)` (the left edge's column
    /// on `row`), `Gx` the field of `gx` and `Gy = inc − gx·sq` (the left edge's `sq`). The
    /// row step `inc + carry·gx` and the column move `sq + carry` keep `Gy` constant, and so
    /// does the switch to the short edge b → c (`inc` changes by `gx·dsq` when `sq` changes by
    /// `dsq`; `row` moves by `gx·dc`). The exact plane is linear too, so the extremes of `F`
    /// and of `F` minus the exact plane over the triangle are at its vertices: checking `16·F`
    /// at the three vertices (in subpixels, so in integers) bounds both at every pixel centre
    /// inside. Reading the word as fields (blue the low half, red the high half minus blue's
    /// borrow, gradients as signed halves) picks one of the decompositions `R·2¹⁶ + B
    /// (mod 2³²)`; any other one differs by a multiple of 2¹⁶ in `B` everywhere and fails the
    /// range check, so a pass proves that the word's halves are these fields at every pixel.
    /// Range: the fields are below 2¹⁶, their gradient halves below 2¹⁵ and the vertices
    /// within 16 400 subpixels of the first pixel (width + height ≤ 1024 px), so each sum is
    /// below 2³¹; green is summed in 64 bits.
    pub(crate) fn dither_fits<C: TargetColor>(&self, p: [&ScreenVertex; 3], row: i32) -> bool {
        let c0 = self.edges[0].c();
        let sq = self.edges[0].sq() as u32;
        let (ox, oy) = (
            SUBPIXELS * c0 + SUBPIXELS / 2,
            SUBPIXELS * row + SUBPIXELS / 2,
        );
        // Red and blue: the halves of the packed word (F₀, Gx, Gy of each).
        let (a, gx) = (self.row[1] as u32, self.gx[1] as u32);
        let gy = (self.inc[1] as u32).wrapping_sub(gx.wrapping_mul(sq));
        let (bx, by) = (gx as i16 as i32, gy as i16 as i32);
        let (rx, ry) = (
            (gx.wrapping_sub(bx as u32) as i32) >> 16,
            (gy.wrapping_sub(by as u32) as i32) >> 16,
        );
        let (b0, r0) = ((a & 0xffff) as i32, (a >> 16) as i32);
        // Green: the whole word.
        let (ga, ggx) = (self.row[2] as u32, self.gx[2]);
        let ggy = (self.inc[2] as u32).wrapping_sub((ggx as u32).wrapping_mul(sq)) as i32;
        // Vertex by vertex, leaving at the first field that does not fit (fewer live values
        // than field by field: this runs once per dithered fast triangle).
        p.iter().all(|v| {
            let (dx, dy) = (v.x as i32 - ox, v.y as i32 - oy);
            let c = v.color();
            field16_fits::<C, 2>(b0, bx, by, dx, dy, c[2])
                && field16_fits::<C, 0>(r0, rx, ry, dx, dy, c[0])
                && green_fits::<C>(ga, ggx, ggy, dx, dy, c[1])
        })
    }

    /// [`ActiveTri::setup`] in portable code (where the setup kernels run, for what
    /// `kernel::setup565` declines).
    #[inline]
    pub(crate) fn setup_portable<C: TargetColor>(
        &mut self,
        t: &TriRecord,
        verts: &[ScreenVertex],
        row: i32,
        height: i32,
        mode: SpanMode,
    ) -> bool {
        let [i0, i1, i2] = t.indices();
        let flat = t.v[0] & FLAT_BIT != 0;
        let (v0, v1, v2) = (&verts[i0], &verts[i1], &verts[i2]);
        let flat_rgb = v0.color();
        // Sort by y (for equal y the order does not matter: horizontal edges are unused),
        // moving references rather than 12-byte vertices.
        let mut p = [v0, v1, v2];
        if p[1].y < p[0].y {
            p.swap(0, 1);
        }
        if p[2].y < p[1].y {
            p.swap(1, 2);
        }
        if p[1].y < p[0].y {
            p.swap(0, 1);
        }
        let [a, b, c] = p;
        let (ax, ay, bx, by, cx, cy) = (
            a.x as i32, a.y as i32, b.x as i32, b.y as i32, c.x as i32, c.y as i32,
        );
        let row_end = first_pixel(cy).min(height);
        let row_mid = first_pixel(by);
        if row >= row_end {
            return false;
        }
        let (dx1, dy1) = (bx - ax, by - ay);
        let (dx2, dy2) = (cx - ax, cy - ay);
        // |d| ≤ 32 766 each: 2·32 766² < 2³¹.
        let det = dx1 * dy2 - dx2 * dy1;
        if det == 0 {
            return false;
        }
        let mid_left = det < 0;
        let long = Edge::new(ax, ay, cx, cy, row);
        let short = if row < row_mid {
            Edge::new(ax, ay, bx, by, row)
        } else {
            Edge::new(bx, by, cx, cy, row)
        };
        let (left, right) = if mid_left {
            (short, long)
        } else {
            (long, short)
        };

        let (x_lo, x_hi) = (ax.min(bx).min(cx), ax.max(bx).max(cx));
        let small = (x_hi - x_lo) + (cy - ay) <= 1024 * SUBPIXELS;
        let fast = small
            && if flat {
                mode.fast_flat
            } else {
                mode.fast_gouraud
            };
        let tri = Sorted {
            v: [a, b, c],
            det,
            row,
            left_c: left.c as i32,
            left_sq: left.sq as i32,
        };
        let done = kernel::SETUP_KERNELS
            && fast
            && !flat
            && C::CHANNEL_MAX == [31, 63, 31]
            && kernel::gouraud_setup(self, &tri);
        if !done {
            if kernel::SETUP_KERNELS {
                set_attribute_words::<C>(self, &tri, flat, fast, flat_rgb);
            } else {
                [self.gx, self.row, self.inc] = attribute_words::<C>(&tri, flat, fast, flat_rgb);
            }
        }
        let flags = (mid_left as u8 * MID_LEFT) | (flat as u8 * FLAT) | (fast as u8 * FAST);
        let ((lw, ldy), (rw, rdy)) = (left.dda(), right.dda());
        self.edges = [lw, rw];
        self.dy = [ldy, rdy];
        self.row_mid = row_mid as i16;
        self.row_end = row_end as i16;
        self.bx = bx as i16;
        self.by = by as i16;
        self.cx = cx as i16;
        self.cy = cy as i16;
        self.flags = flags;
        if fast && !flat && row < row_mid && row_mid < row_end {
            self.set_pending(Edge::new(bx, by, cx, cy, row_mid));
        }
        self.set_routine_rows(row, false);
        true
    }
}

/// For [`ActiveTri::dither_fits`]: whether a 16-bit field of the packed red-blue word (channel
/// `K`, `16 − bits` fraction bits), `F = f0 + (gx·dx + gy·dy)/16` at a vertex `(dx, dy)`
/// subpixels from the first pixel's centre with vertex colour `c`, is at least 15/32 of a unit
/// inside `0..2¹⁶` and within ¼ unit of the exact value plus the ½-unit bias. Each sum is below
/// 2³¹ (see `dither_fits`).
#[inline(always)]
pub(crate) fn field16_fits<C: TargetColor, const K: usize>(
    f0: i32,
    gx: i32,
    gy: i32,
    dx: i32,
    dy: i32,
    c: u16,
) -> bool {
    let frac = 16 - channel_bits(C::CHANNEL_MAX[K]);
    let vf = vertex_frac_bits(C::CHANNEL_MAX[K]);
    let (lo, e) = (15 << (frac - 5), 1 << (frac - 2));
    let v = 16 * f0 + gx * dx + gy * dy;
    let ideal = 16 * (((c as i32) << (frac - vf)) + (1 << (frac - 1)));
    // One unsigned comparison per interval: 16·lo ≤ v < 16·(2¹⁶ − lo), |v − ideal| ≤ 16·e.
    (v.wrapping_sub(16 * lo) as u32) < (16 * ((1 << 16) - 2 * lo)) as u32
        && (v.wrapping_sub(ideal).wrapping_add(16 * e) as u32) <= (32 * e) as u32
}

/// For [`ActiveTri::dither_fits`]: the same test for the green word (`32 − bits` fraction
/// bits, unsigned `a`): `16·F = 16·a + gx·dx + gy·dy` (a 64-bit value in principle) at least
/// `16·lo` and below `16·(2³² − lo)`, and within `16·e` of `16·ideal` ([`green_fits_wide`]
/// states it in 64 bits). A Cortex-M0 has no 64-bit arithmetic, so here `16·F` is formed as
/// `T·2¹⁶ + L` (`0 ≤ L < 2¹⁶`) in 32-bit operations: `T = 16·a_hi + gx_hi·dx + gy_hi·dy` plus
/// the carries of the low products `16·a_lo`, `gx_lo·dx`, `gy_lo·dy` (each |·| < 2³¹: |dx|,
/// |dy| ≤ 16 400). Every bound is a multiple of 2¹⁶ (`frac ≥ 24`, `frac − vf = 22` for the
/// packable colour types), so the comparisons need `T` alone, and `L` only for equality at
/// the upper bound of the distance. The same decisions (tested on random and extreme cases).
#[inline(always)]
pub(crate) fn green_fits<C: TargetColor>(
    a: u32,
    gx: i32,
    gy: i32,
    dx: i32,
    dy: i32,
    c: u16,
) -> bool {
    let frac = 32 - channel_bits(C::CHANNEL_MAX[1]);
    let vf = vertex_frac_bits(C::CHANNEL_MAX[1]);
    green_fits_split(a, gx, gy, dx, dy, c, frac, vf)
}

/// [`green_fits`] for `frac` and `vf` given (`frac ≥ 17`, `frac − vf ≥ 12`).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn green_fits_split(
    a: u32,
    gx: i32,
    gy: i32,
    dx: i32,
    dy: i32,
    c: u16,
    frac: u32,
    vf: u32,
) -> bool {
    // The bounds over 2¹⁶: 16·lo, 16·(2³² − lo), 16·ideal and 16·e.
    let floor = 15 << (frac - 17);
    let ceil = (1 << 20) - floor;
    let ideal = ((c as i32) << (frac - vf - 12)) + (1 << (frac - 13));
    let e = 1 << (frac - 14);
    let (ah, al) = ((a >> 16) as i32, (a & 0xffff) as i32);
    let (p1, p2) = ((gx & 0xffff) * dx, (gy & 0xffff) * dy);
    let low = ((al << 4) & 0xffff) + (p1 & 0xffff) + (p2 & 0xffff);
    let t = 16 * ah
        + (gx >> 16) * dx
        + (gy >> 16) * dy
        + (al >> 12)
        + (p1 >> 16)
        + (p2 >> 16)
        + (low >> 16);
    let upper = ideal + e;
    t >= floor.max(ideal - e) && t < ceil && (t < upper || (t == upper && low & 0xffff == 0))
}

/// [`green_fits`] as it is specified, in 64-bit arithmetic (the reference of its test).
#[cfg(test)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn green_fits_wide(
    a: u32,
    gx: i32,
    gy: i32,
    dx: i32,
    dy: i32,
    c: u16,
    frac: u32,
    vf: u32,
) -> bool {
    let (lo, e) = (15i64 << (frac - 5), 1i64 << (frac - 2));
    let v = 16 * a as i64 + gx as i64 * dx as i64 + gy as i64 * dy as i64;
    let ideal = 16 * (((c as i64) << (frac - vf)) + (1i64 << (frac - 1)));
    v >= 16 * lo && v < 16 * ((1i64 << 32) - lo) && (v - ideal).abs() <= 16 * e
}
