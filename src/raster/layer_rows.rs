//! One row of each kind of layered triangle ([`crate::Layers`]): shadow polygons and
//! shadow-volume faces (through the stencil line), outlines and translucent triangles, and the
//! blend they share. Every routine here is per pixel: additions, compares, table lookups and
//! stores, except the translucent blend (one product per channel).

use crate::geometry::project::{DEPTH_FRAC_BITS, DEPTH_MAX};
use crate::kernel::records::{ActiveList, ActiveTri, FLAT};
use crate::raster::COLOR_FRAC_BITS;
use crate::scene::color::{rgb565_words_mut, TargetColor};

/// Stencil bit: this pixel was darkened by a shadow polygon on this row.
pub(crate) const SHADOWED: u8 = 1;

/// Depth units (of 65 535) a volume face must lie behind the visible surface to count. The
/// near cap is the caster's own faces turned from the light (the same vertex records, drawn
/// through another span path whose rounding may differ by a unit), which must not count for
/// themselves. (A margin growing with each face's depth slope would spare the terminator of a
/// curved caster a few pixels, but two faces meeting at an edge then get different margins and
/// stray pixels appear along the shadow's rim; one margin for all keeps neighbours exact.)
pub(crate) const VOLUME_BIAS: u32 = 4;

/// Depth units an outline may lie behind the surface at its pixel and still show: the edge is
/// on the object's rim, where its faces turn edge-on and their depth changes fast across the
/// pixel the line covers.
pub(crate) const OUTLINE_BIAS: u32 = 320;

/// `round(x / 255)` for `0 ≤ x ≤ 255·255`, without a division.
#[inline(always)]
pub(crate) fn div255(x: u32) -> u32 {
    let x = x + 128;
    (x + (x >> 8)) >> 8
}

/// Channel `c` blended toward `s` by `a` (0..=255): `round((c·(255 − a) + s·a)/255)`.
#[inline(always)]
pub(crate) fn blend(c: u32, s: u32, a: u32) -> u32 {
    div255(c * (255 - a) + s * a)
}

/// The shadow colour `color` (8 bits per channel) in `C`'s channel units with opacity `alpha`,
/// and, for channels of at most 6 bits (`darken_span`: wider ones blend directly), `lut`
/// filled with each channel value blended toward it.
pub(crate) fn blend_tables<C: TargetColor>(
    lut: &mut [[u8; 64]; 3],
    color: [u8; 3],
    alpha: u8,
) -> ([u8; 3], u8) {
    let max = C::CHANNEL_MAX;
    let sc: [u8; 3] = core::array::from_fn(|k| div255(color[k] as u32 * max[k] as u32) as u8);
    if max.iter().all(|&m| m <= 63) {
        for k in 0..3 {
            for (c, e) in lut[k].iter_mut().enumerate() {
                *e = blend(c as u32, sc[k] as u32, alpha as u32) as u8;
            }
        }
    }
    (sc, alpha)
}

/// The shadow's blend: per channel value of a target of at most 6 bits per channel (RGB565)
/// the table `lut`, else the shadow colour and opacity `shadow`.
#[derive(Copy, Clone)]
pub(crate) struct Darken<'l> {
    pub(crate) lut: &'l [[u8; 64]; 3],
    pub(crate) shadow: ([u8; 3], u8),
}

/// Darkens each pixel of `colors` a surface was drawn on (depth below the far plane) for
/// which `take` (given its stencil byte, which it may update) says so. Returns the pixels
/// written.
#[inline(always)]
pub(crate) fn darken_span<C: TargetColor>(
    colors: &mut [C],
    depth: &[u16],
    stencil: &mut [u8],
    d: Darken<'_>,
    mut take: impl FnMut(&mut u8) -> bool,
) -> u32 {
    let mut written = 0;
    let small = C::CHANNEL_MAX.iter().all(|&m| m <= 63);
    let lut = d.lut;
    if let (Some(words), true) = (rgb565_words_mut(colors), small) {
        for ((w, &z), s) in words.iter_mut().zip(depth).zip(stencil.iter_mut()) {
            if z != u16::MAX && take(s) {
                let v = *w as usize;
                *w = (lut[0][v >> 11] as u16) << 11
                    | (lut[1][(v >> 5) & 63] as u16) << 5
                    | lut[2][v & 31] as u16;
                written += 1;
            }
        }
        return written;
    }
    for ((c, &z), s) in colors.iter_mut().zip(depth).zip(stencil.iter_mut()) {
        if z != u16::MAX && take(s) {
            if let Some(ch) = c.channels() {
                let k = |i: usize| {
                    if small {
                        lut[i][ch[i] as usize & 63]
                    } else {
                        blend(ch[i] as u32, d.shadow.0[i] as u32, d.shadow.1 as u32) as u8
                    }
                };
                *c = C::from_channels([k(0), k(1), k(2)]);
                written += 1;
            }
        }
    }
    written
}

/// The visible columns of triangle `t` on this row, `xs..xe` within `width`, and the skip
/// from its first pixel.
#[inline(always)]
fn columns(t: &ActiveTri, width: usize) -> (i32, i32, i32) {
    let (lc, rc) = (t.edges[0].c(), t.edges[1].c());
    let (xs, xe) = (lc.max(0), rc.min(width as i32));
    (xs, xe, xs - lc)
}

/// Attribute `k` of `t` (unpacked rows) at `skip` pixels from the row's first pixel.
#[inline(always)]
fn attr_at(t: &ActiveTri, k: usize, skip: i32) -> i32 {
    t.row[k].wrapping_add(t.gx[k].wrapping_mul(skip))
}

/// The depth word at the first visible pixel (16.12, with the half-step rounding bias).
#[inline(always)]
fn depth_start(t: &ActiveTri, skip: i32) -> i32 {
    attr_at(t, 0, skip).clamp(0, DEPTH_MAX << DEPTH_FRAC_BITS) + (1 << (DEPTH_FRAC_BITS - 1))
}

/// The whole depth steps of depth word `z`, within `0..=65535`.
#[inline(always)]
fn depth_of(z: i32) -> u32 {
    (z >> DEPTH_FRAC_BITS).clamp(0, DEPTH_MAX) as u32
}

/// One row of a shadow polygon: each pixel a receiver drew (on this row only the receivers have
/// drawn yet) and no shadow polygon darkened yet is darkened and marked in the stencil (a blob
/// disc, `blob`, darkens whatever the stencil says: the nested discs add up). Returns
/// `(fragments, written)`.
pub(crate) fn shadow_row<C: TargetColor>(
    t: &ActiveTri,
    colors: &mut [C],
    depth: &[u16],
    stencil: &mut [u8],
    d: Darken<'_>,
    blob: bool,
) -> (u32, u32) {
    let width = colors.len().min(depth.len()).min(stencil.len());
    let (xs, xe, _) = columns(t, width);
    if xs >= xe {
        return (0, 0);
    }
    let r = xs as usize..xe as usize;
    // A blob never sets the stencil bit, so every pixel stays open to the next disc.
    let mark = if blob { 0 } else { SHADOWED };
    let written = darken_span(
        &mut colors[r.clone()],
        &depth[r.clone()],
        &mut stencil[r],
        d,
        |s| {
            let open = *s & SHADOWED == 0;
            *s |= mark;
            open
        },
    );
    ((xe - xs) as u32, written)
}

/// One row of a shadow-volume face of sign `delta` (1, or 255 for −1): adds it to the stencil
/// count of each pixel where the face lies behind the visible surface by more than
/// [`VOLUME_BIAS`]. Returns the fragments and the covered columns.
pub(crate) fn volume_row(
    t: &ActiveTri,
    depth: &[u16],
    stencil: &mut [u8],
    delta: u8,
) -> (u32, core::ops::Range<usize>) {
    let (xs, xe, skip) = columns(t, depth.len().min(stencil.len()));
    if xs >= xe {
        return (0, 0..0);
    }
    let r = xs as usize..xe as usize;
    let mut z = depth_start(t, skip);
    let dz = t.gx[0];
    for (s, &zb) in stencil[r.clone()].iter_mut().zip(&depth[r.clone()]) {
        if depth_of(z) > zb as u32 + VOLUME_BIAS {
            *s = s.wrapping_add(delta);
        }
        z = z.wrapping_add(dz);
    }
    ((xe - xs) as u32, r)
}

/// One row of an outline quad (flat, its colour the line's): each pixel where it lies in front
/// of the surface, or behind it by at most [`OUTLINE_BIAS`], takes the line's colour (every
/// pixel it covers when `see_through`); depth is not written. Returns `(fragments, written)`.
pub(crate) fn outline_row<C: TargetColor>(
    t: &ActiveTri,
    colors: &mut [C],
    depth: &[u16],
    see_through: bool,
) -> (u32, u32) {
    let (xs, xe, skip) = columns(t, colors.len().min(depth.len()));
    if xs >= xe {
        return (0, 0);
    }
    let ink = C::from_channels(t.flat_channels());
    let r = xs as usize..xe as usize;
    if see_through {
        colors[r].fill(ink);
        return ((xe - xs) as u32, (xe - xs) as u32);
    }
    let mut z = depth_start(t, skip);
    let mut written = 0;
    for (c, &zb) in colors[r.clone()].iter_mut().zip(&depth[r]) {
        if depth_of(z) <= zb as u32 + OUTLINE_BIAS {
            *c = ink;
            written += 1;
        }
        z = z.wrapping_add(t.gx[0]);
    }
    ((xe - xs) as u32, written)
}

/// One row of a translucent triangle (set up without the fast path: unpacked depth and
/// colour rows), blended with opacity `alpha` (0..=255) over the pixels it is in front of;
/// depth is tested, not written. Returns `(fragments, written)`.
pub(crate) fn translucent_row<C: TargetColor>(
    t: &ActiveTri,
    colors: &mut [C],
    depth: &[u16],
    alpha: u32,
) -> (u32, u32) {
    let (xs, xe, skip) = columns(t, colors.len().min(depth.len()));
    if xs >= xe {
        return (0, 0);
    }
    let flat = t.flags & FLAT != 0;
    let half = 1i32 << (COLOR_FRAC_BITS - 1);
    let mut z = depth_start(t, skip);
    let (mut v, g) = if flat {
        let c = t.flat_channels();
        (c.map(|b| ((b as i32) << COLOR_FRAC_BITS) + half), [0i32; 3])
    } else {
        let max = C::CHANNEL_MAX;
        (
            core::array::from_fn(|k| {
                attr_at(t, k + 1, skip).clamp(0, (max[k] as i32) << COLOR_FRAC_BITS) + half
            }),
            [t.gx[1], t.gx[2], t.gx[3]],
        )
    };
    let mut written = 0;
    let r = xs as usize..xe as usize;
    if let Some(words) = rgb565_words_mut(&mut colors[r.clone()]) {
        // RGB565 words: the channels by shifts (the same values as `channels`).
        for (w, &zb) in words.iter_mut().zip(&depth[r]) {
            if ((z >> DEPTH_FRAC_BITS) as u16) < zb {
                let d = *w as u32;
                let s = v.map(|s| (s >> COLOR_FRAC_BITS) as u32);
                *w = (blend(d >> 11, s[0], alpha) << 11
                    | blend((d >> 5) & 63, s[1], alpha) << 5
                    | blend(d & 31, s[2], alpha)) as u16;
                written += 1;
            }
            z = z.wrapping_add(t.gx[0]);
            for k in 0..3 {
                v[k] = v[k].wrapping_add(g[k]);
            }
        }
        return ((xe - xs) as u32, written);
    }
    for (c, &zb) in colors[r.clone()].iter_mut().zip(&depth[r]) {
        if ((z >> DEPTH_FRAC_BITS) as u16) < zb {
            if let Some(d) = c.channels() {
                let src = v.map(|s| (s >> COLOR_FRAC_BITS) as u32);
                *c = C::from_channels(core::array::from_fn(|k| {
                    blend(d[k] as u32, src[k], alpha) as u8
                }));
                written += 1;
            }
        }
        z = z.wrapping_add(t.gx[0]);
        for k in 0..3 {
            v[k] = v[k].wrapping_add(g[k]);
        }
    }
    ((xe - xs) as u32, written)
}

/// The post list with its per-entry kind and opacity words and sort keys, as one borrow.
pub(crate) struct Post<'p, const PA: usize> {
    pub(crate) list: &'p mut ActiveList<PA>,
    pub(crate) meta: &'p mut [u16; PA],
    pub(crate) key: &'p mut [u64; PA],
}

impl<const PA: usize> Post<'_, PA> {
    /// Removes entry `i`; the last entry takes its place.
    pub(crate) fn remove(&mut self, i: usize) {
        let last = self.list.len() - 1;
        self.meta[i] = self.meta[last];
        self.key[i] = self.key[last];
        self.list.swap_remove(i);
    }

    /// Draws row `row` of each entry of kind `kind` with `draw` (given the entry, its meta
    /// word and its key), then moves it to the next row or retires it.
    pub(crate) fn rows(
        &mut self,
        kind: u8,
        row: i32,
        mut draw: impl FnMut(&mut ActiveTri, u16, u64),
    ) {
        let mut i = 0;
        while i < self.list.len() {
            if self.meta[i] as u8 != kind {
                i += 1;
                continue;
            }
            let t = self.list.get_mut(i);
            draw(t, self.meta[i], self.key[i]);
            if row + 1 >= t.row_end as i32 {
                self.remove(i);
                continue;
            }
            t.advance(row + 1);
            i += 1;
        }
    }
}
