//! Layered frames: each strip row drawn in layers — the shadow receivers, the projected shadow
//! polygons (stencilled, so overlaps darken once), the other opaque objects, then the
//! translucent triangles back to front — with the lists and the stencil lines in a
//! [`Layers`] the caller owns. A frame drawn by [`Renderer::render`] uses none of this and pays
//! nothing for it: no field, no branch.

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::primitives::Rectangle;
use heapless::Vec;

use crate::color::{rgb565_word, rgb565_words_mut, TargetColor};
use crate::kernel;
use crate::kernel::records::{first_pixel, ActiveList, ActiveTri, ScreenVertex, TriRecord, FLAT};
use crate::project::{DEPTH_FRAC_BITS, DEPTH_MAX};

use crate::raster::{SpanMode, COLOR_FRAC_BITS};
use crate::renderer::*;
use crate::scalar::Scalar;
use crate::scene::{Object, Scene};
use crate::shade::Material;
use crate::shadow::{blob_disc, LayerError, Layering, ShadowMethod, BLOB_FAN};
use crate::strip::draw_list_row;
use crate::textured::{attach_pushed, is_textured};

/// The most translucent objects one layered frame draws.
pub const MAX_TRANSLUCENT: usize = 16;

/// [`Layers`] post-list entry kinds.
const SHADOW: u8 = 1;
const TRANSLUCENT: u8 = 2;

/// Stencil bit: this pixel was darkened by a shadow polygon on this row.
const SHADOWED: u8 = 1;

/// What a layered frame needs besides the renderer, owned by the caller (a `static` on a
/// microcontroller, like the renderer): `W` and `LINES` as the renderer's, `RA` receiver
/// triangles and `PA` shadow and translucent triangles active on one row at once.
///
/// RAM: `LINES·W` (the stencil lines, one byte per pixel) `+ 84·(RA + PA)` (the two active
/// lists) `+ 12·PA` (each post triangle's kind, opacity and sort key) plus about 300 bytes
/// (the shadow's blend tables and the translucent objects' table);
/// [`Layers::RAM_BYTES`] is the exact figure.
#[derive(Debug)]
pub struct Layers<const W: usize, const LINES: usize, const RA: usize, const PA: usize> {
    /// Per pixel of each strip line: [`SHADOWED`] once a shadow polygon darkened it.
    stencil: [[u8; W]; LINES],
    receivers: ActiveList<RA>,
    post: ActiveList<PA>,
    /// Per post-list entry: kind in bits 0..=7, opacity (0..=255) in bits 8..=15.
    meta: [u16; PA],
    /// Per post-list entry: back-to-front sort key (larger is drawn first).
    key: [u64; PA],
    /// Vertex-store index where the receivers' vertices end, the opaque objects' vertices
    /// end, and the shadow polygons' vertices end; the translucent objects' vertices follow.
    bounds: [u16; 3],
    /// The translucent objects: the vertex-store index where each one's vertices end, and its
    /// opacity.
    translucent: Vec<(u16, u8), MAX_TRANSLUCENT>,
    /// The shadow's blend per channel value, for channels of at most 6 bits (RGB565):
    /// `round((c·(255 − α) + s·α)/255)`, in the channel's units.
    lut: [[u8; 64]; 3],
    /// The shadow's colour in the target's channel units, and its opacity (0: no shadow).
    shadow: ([u8; 3], u8),
    /// The shadow is blobs: nested discs that each darken (no stencil).
    blob: bool,
    skipped: u32,
}

impl<const W: usize, const LINES: usize, const RA: usize, const PA: usize>
    Layers<W, LINES, RA, PA>
{
    /// Exact RAM of these layers in bytes.
    pub const RAM_BYTES: usize = core::mem::size_of::<Self>();

    /// Empty layers (a `const fn`, for a `static`).
    #[must_use]
    pub const fn new() -> Self {
        Layers {
            stencil: [[0; W]; LINES],
            receivers: ActiveList::new(),
            post: ActiveList::new(),
            meta: [0; PA],
            key: [0; PA],
            bounds: [0; 3],
            translucent: Vec::new(),
            lut: [[0; 64]; 3],
            shadow: ([0; 3], 0),
            blob: false,
            skipped: 0,
        }
    }

    /// Shadow and translucent triangles left out of the last frame for want of room (only
    /// under [`OverflowPolicy::DrawWhatFits`]).
    #[must_use]
    pub fn skipped(&self) -> u32 {
        self.skipped
    }

    fn remove_post(&mut self, i: usize) {
        let last = self.post.len() - 1;
        self.meta[i] = self.meta[last];
        self.key[i] = self.key[last];
        self.post.swap_remove(i);
    }
}

impl<const W: usize, const LINES: usize, const RA: usize, const PA: usize> Default
    for Layers<W, LINES, RA, PA>
{
    fn default() -> Self {
        Self::new()
    }
}

/// `round(x / 255)` for `0 ≤ x ≤ 255·255`, without a division.
#[inline(always)]
fn div255(x: u32) -> u32 {
    let x = x + 128;
    (x + (x >> 8)) >> 8
}

/// Channel `c` blended toward `s` by `a` (0..=255): `round((c·(255 − a) + s·a)/255)`.
#[inline(always)]
fn blend(c: u32, s: u32, a: u32) -> u32 {
    div255(c * (255 - a) + s * a)
}

impl<
        S: Scalar,
        C: TargetColor,
        const W: usize,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const ACTIVE: usize,
        const LINES: usize,
        const XV: usize,
        const XA: usize,
    > Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA>
{
    /// Draws one frame of `scene` into `target` in layers: each row of each strip draws the
    /// `layering`'s receivers, then its projected shadow (each receiver pixel darkened at most
    /// once, the stencil of `layers` keeping count), then the other opaque objects, then the
    /// translucent triangles ([`crate::Material::alpha`]) back to front, depth-tested against
    /// the opaque ones and not writing depth. The shadow and the translucent triangles blend
    /// onto the strip's pixels (`C = Csrc·α + Cdst·(1 − α)`): one product per channel and
    /// pixel (the only per-pixel products of the renderer), a table lookup for the shadow on
    /// a target of at most 6 bits per channel (RGB565).
    ///
    /// Translucent triangles are sorted per row by the sum of their vertices' depths (then by
    /// their screen positions), so the image does not depend on the order they are given in;
    /// triangles that cross in depth are not split.
    ///
    /// # Errors
    ///
    /// As [`Renderer::render`], and [`Error::Layers`] for a layering that cannot be drawn
    /// ([`LayerError`]); all before anything is drawn.
    pub fn render_layered<D, const L: usize, const RA: usize, const PA: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
        layering: &Layering<'_, S>,
        layers: &mut Layers<W, LINES, RA, PA>,
        target: &mut D,
    ) -> Result<Stats, Error<D::Error>>
    where
        D: DrawTarget<Color = C>,
    {
        self.render_layered_probed(scene, layering, layers, target, &mut NoProbe)
    }

    /// [`Renderer::render_layered`], reporting each stage change to `probe`.
    pub fn render_layered_probed<D, P, const L: usize, const RA: usize, const PA: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
        layering: &Layering<'_, S>,
        layers: &mut Layers<W, LINES, RA, PA>,
        target: &mut D,
        probe: &mut P,
    ) -> Result<Stats, Error<D::Error>>
    where
        D: DrawTarget<Color = C>,
        P: Probe,
    {
        probe.frame_start();
        let result = self
            .check_target(target)
            .and_then(|_| self.geometry_layered(scene, layering, layers, probe))
            .and_then(|_| {
                probe.enter(Stage::Raster);
                let vw = self.vw;
                while let Some((y0, lines)) = self.draw_strip_layered(layers, probe) {
                    let area = Rectangle::new(
                        Point::new(0, y0 as i32),
                        Size::new(vw as u32, lines as u32),
                    );
                    probe.enter(Stage::Output);
                    let sent = target.fill_contiguous(
                        &area,
                        self.color[..lines]
                            .iter()
                            .flat_map(|line| line[..vw].iter())
                            .copied(),
                    );
                    probe.enter(Stage::Raster);
                    if let Err(e) = sent {
                        self.next_row = self.vh;
                        return Err(Error::Target(e));
                    }
                }
                Ok(self.stats)
            });
        probe.enter(Stage::Done);
        probe.frame_end();
        result
    }

    /// The geometry stage of a layered frame: the receivers' objects first, then the other
    /// opaque ones, the casters' shadow polygons and the translucent objects, each group's
    /// vertices contiguous in the store (which is how the strip pass tells them apart).
    fn geometry_layered<E, P: Probe, const L: usize, const RA: usize, const PA: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
        layering: &Layering<'_, S>,
        layers: &mut Layers<W, LINES, RA, PA>,
        probe: &mut P,
    ) -> Result<Stats, Error<E>> {
        let n = scene.objects.len();
        let bad = |index: usize| Error::Layers(LayerError::NoSuchObject { index });
        for &i in layering.receivers.iter().chain(layering.casters) {
            if i >= n {
                return Err(bad(i));
            }
        }
        let shadow = match &layering.shadow {
            Some(s) => Some((s.matrix().ok_or(Error::Layers(LayerError::Shadow))?, s)),
            None => None,
        };
        let translucent = scene.objects.iter().any(|o| o.material.alpha < 255);
        // (A [`crate::TriangleId`] target records the opaque triangles only: nothing blends.)
        if (shadow.is_some() || translucent)
            && C::from_channels([0; 3]).channels().is_none()
            && C::triangle_id(0).is_none()
        {
            return Err(Error::Layers(LayerError::Blending));
        }
        if let Some(i) = scene
            .objects
            .iter()
            .position(|o| o.material.alpha < 255 && o.material.needs_attribute_stores())
        {
            return Err(Error::Layers(LayerError::Translucent { object: i }));
        }
        if scene
            .objects
            .iter()
            .filter(|o| o.material.alpha < 255)
            .count()
            > MAX_TRANSLUCENT
        {
            return Err(Error::Layers(LayerError::TooManyTranslucent));
        }
        if let Some((_, s)) = &shadow {
            for &i in layering.receivers {
                if scene.objects[i].material.alpha == 255 && !s.holds(&scene.objects[i]) {
                    return Err(Error::Layers(LayerError::OffPlane { object: i }));
                }
            }
        }
        let receiver = |i: usize| {
            shadow.is_some()
                && scene.objects[i].material.alpha == 255
                && layering.receivers.contains(&i)
        };
        let c = self.frame_begin(scene, true)?;
        let mut f = crate::geometry::Frame::default();
        for (i, o) in scene.objects.iter().enumerate() {
            if receiver(i) {
                self.frame_object(&c, &mut f, scene, o, i, probe)?;
            }
        }
        let end = |r: &Self| r.verts.len().min(u16::MAX as usize) as u16;
        layers.bounds[0] = end(self);
        for (i, o) in scene.objects.iter().enumerate() {
            if !receiver(i) && o.material.alpha == 255 {
                self.frame_object(&c, &mut f, scene, o, i, probe)?;
            }
        }
        layers.bounds[1] = end(self);
        layers.shadow = ([0; 3], 0);
        layers.blob = false;
        if let Some((m, s)) = shadow {
            // Flat and unlit: only the coverage of these triangles is used.
            let material = Material::matte(s.color, S::ONE, S::ZERO).flat();
            let disc = blob_disc::<S>();
            let blob = s.method == ShadowMethod::Blob;
            for (i, o) in scene.objects.iter().enumerate() {
                if !layering.casters.contains(&i) {
                    continue;
                }
                if !blob {
                    // The caster's triangles flattened onto the plane.
                    let flat = Object {
                        mesh: o.mesh,
                        transform: m.mul(&o.transform),
                        material,
                    };
                    self.frame_object(&c, &mut f, scene, &flat, i, probe)?;
                } else if let Some(rings) = s.blob_rings(&m, o) {
                    let mesh = crate::Mesh::new(&disc, &BLOB_FAN)
                        .map_err(|_| Error::Layers(LayerError::Shadow))?;
                    for transform in rings {
                        let ring = Object {
                            mesh,
                            transform,
                            material,
                        };
                        self.frame_object(&c, &mut f, scene, &ring, i, probe)?;
                    }
                }
            }
            let max = C::CHANNEL_MAX;
            let sc: [u8; 3] =
                core::array::from_fn(|k| div255(s.color[k] as u32 * max[k] as u32) as u8);
            let alpha = if blob { s.blob_ring_alpha() } else { s.alpha };
            layers.shadow = (sc, alpha);
            layers.blob = blob;
            for k in 0..3 {
                for (c, e) in layers.lut[k].iter_mut().enumerate() {
                    *e = blend(c as u32, sc[k] as u32, alpha as u32) as u8;
                }
            }
        }
        layers.bounds[2] = end(self);
        layers.translucent.clear();
        for (i, o) in scene.objects.iter().enumerate() {
            if o.material.alpha < 255 {
                self.frame_object(&c, &mut f, scene, o, i, probe)?;
                // Cannot fail: counted above.
                let _ = layers.translucent.push((end(self), o.material.alpha));
            }
        }
        let stats = self.frame_end(scene, &c, &mut f)?;
        // Each list's most triangles on one row, against its capacity.
        for (list, capacity) in [(0u8, RA), (1, PA)] {
            let needed = self.layer_overlap(&layers.bounds, list);
            if needed > capacity && self.overflow == OverflowPolicy::Error {
                self.next_row = self.vh;
                return Err(Error::Layers(LayerError::Capacity {
                    list,
                    needed,
                    capacity,
                }));
            }
        }
        layers.receivers.clear();
        layers.post.clear();
        layers.skipped = 0;
        Ok(stats)
    }

    /// The most triangles of list `list` (0: receivers, 1: shadow polygons and translucent
    /// triangles) covering one row, by a sweep over the row-change counts (in `starts`, free
    /// once the buckets are sorted).
    fn layer_overlap(&mut self, bounds: &[u16; 3], list: u8) -> usize {
        let vh = self.vh;
        self.starts[..vh].fill(0);
        for t in self.tris.iter() {
            let i = t.v[1] as usize;
            let post = i >= bounds[1] as usize;
            if (list == 0 && i >= bounds[0] as usize) || (list == 1 && !post) {
                continue;
            }
            let [a, b, c] = t.indices().map(|k| self.verts[k].y as i32);
            let first = first_pixel(a.min(b).min(c)).clamp(0, vh as i32) as usize;
            let end = first_pixel(a.max(b).max(c)).clamp(0, vh as i32) as usize;
            if first < end {
                self.starts[first] += 1;
                if end < vh {
                    self.starts[end] -= 1;
                }
            }
        }
        let (mut cur, mut max) = (0i32, 0i32);
        for &s in &self.starts[..vh] {
            cur += s as i32;
            max = max.max(cur);
        }
        max as usize
    }

    /// Draws the next strip of a layered frame into the renderer's lines; its first row and
    /// height, or `None` when the frame is complete.
    fn draw_strip_layered<P: Probe, const RA: usize, const PA: usize>(
        &mut self,
        layers: &mut Layers<W, LINES, RA, PA>,
        probe: &mut P,
    ) -> Option<(usize, usize)> {
        let y0 = self.next_row;
        let (vw, vh) = (self.vw, self.vh);
        if y0 >= vh {
            return None;
        }
        let mode = SpanMode::new::<C>(self.depth_test, self.dither);
        let lines = LINES.min(vh - y0);
        for l in 0..lines {
            let row = y0 + l;
            match (
                rgb565_words_mut(&mut self.color[l][..vw]),
                rgb565_word(self.background),
            ) {
                (Some(words), Some(bg)) => {
                    kernel::clear_line565(words, &mut self.depth[l][..vw], bg)
                }
                _ => {
                    self.color[l][..vw].fill(self.background);
                    self.depth[l][..vw].fill(u16::MAX);
                }
            }
            layers.stencil[l][..vw].fill(0);
            let end = if row + 1 < vh {
                self.heads[row + 1] as usize
            } else {
                self.tris.len()
            };
            let bucket = self.heads[row] as usize..end;
            if !bucket.is_empty() {
                probe.enter(Stage::Setup);
            }
            for t in bucket {
                let rec = self.tris[t];
                if !self.setup_layered(&rec, row, mode, layers) {
                    self.active_skipped = self.active_skipped.saturating_add(1);
                }
            }
            probe.enter(Stage::Raster);
            let Renderer {
                xactive,
                active,
                color,
                depth,
                depth_test,
                dither,
                stats,
                ..
            } = self;
            let (colors, depth) = (&mut color[l][..vw], &mut depth[l][..vw]);
            draw_list_row::<C, RA, XA>(
                &mut layers.receivers,
                xactive,
                row,
                colors,
                depth,
                *depth_test,
                *dither,
                stats,
            );
            let mut i = 0;
            while i < layers.post.len() {
                if layers.meta[i] as u8 != SHADOW {
                    i += 1;
                    continue;
                }
                let (frag, written, done) = shadow_row(
                    layers.post.get_mut(i),
                    row as i32,
                    colors,
                    depth,
                    &mut layers.stencil[l][..vw],
                    &layers.lut,
                    layers.shadow,
                    layers.blob,
                );
                stats.add_row(frag, written);
                if done {
                    layers.remove_post(i);
                } else {
                    i += 1;
                }
            }
            draw_list_row::<C, ACTIVE, XA>(
                active,
                xactive,
                row,
                colors,
                depth,
                *depth_test,
                *dither,
                stats,
            );
            // Translucent triangles, farthest first: their indices sorted by key per row.
            let mut order = [0u16; PA];
            let mut n = 0;
            for j in 0..layers.post.len() {
                if layers.meta[j] as u8 == TRANSLUCENT {
                    order[n] = j as u16;
                    n += 1;
                }
            }
            let key = &layers.key;
            order[..n].sort_unstable_by(|a, b| key[*b as usize].cmp(&key[*a as usize]));
            for &j in &order[..n] {
                let j = j as usize;
                let alpha = (layers.meta[j] >> 8) as u32;
                let (frag, written) =
                    translucent_row(layers.post.get_mut(j), row as i32, colors, depth, alpha);
                stats.add_row(frag, written);
            }
            // Advance (or retire) them after all are drawn: removal reorders the list.
            let mut j = 0;
            while j < layers.post.len() {
                if layers.meta[j] as u8 == TRANSLUCENT {
                    let t = layers.post.get_mut(j);
                    let next = row as i32 + 1;
                    if next >= t.row_end as i32 {
                        layers.remove_post(j);
                        continue;
                    }
                    t.advance(next);
                }
                j += 1;
            }
        }
        self.next_row = y0 + lines;
        Some((y0, lines))
    }

    /// Sets triangle `rec` (first covered row `row`) up in its layer's list. False when that
    /// list is full (under [`OverflowPolicy::DrawWhatFits`]; the triangle is left out).
    fn setup_layered<const RA: usize, const PA: usize>(
        &mut self,
        rec: &TriRecord,
        row: usize,
        mode: SpanMode,
        layers: &mut Layers<W, LINES, RA, PA>,
    ) -> bool {
        let (verts, h) = (&self.verts[..], self.vh as i32);
        let v = rec.v[1] as usize;
        if v >= layers.bounds[1] as usize {
            // A shadow polygon or a translucent triangle: unpacked rows (no fast path).
            let m = SpanMode::default();
            let before = layers.post.len();
            if !layers
                .post
                .push_with(|a| a.setup::<C>(rec, verts, row as i32, h, m))
            {
                return false;
            }
            if layers.post.len() > before {
                let (kind, alpha) = if v < layers.bounds[2] as usize {
                    (SHADOW, 0)
                } else {
                    let a = layers
                        .translucent
                        .iter()
                        .find(|(end, _)| v < *end as usize)
                        .map_or(255, |e| e.1);
                    (TRANSLUCENT, a)
                };
                layers.meta[before] = kind as u16 | (alpha as u16) << 8;
                layers.key[before] = sort_key(rec, verts);
            }
            return true;
        }
        let textured = XV > 0 && XA > 0 && is_textured(rec, &self.xverts);
        let m = if textured { SpanMode::default() } else { mode };
        macro_rules! push {
            ($list:expr) => {{
                let before = $list.len();
                $list.push_with(|a| a.setup::<C>(rec, verts, row as i32, h, m))
                    && (!textured
                        || attach_pushed::<C, _>(
                            &mut $list,
                            before,
                            &mut self.xactive,
                            rec,
                            verts,
                            &self.xverts,
                        ))
            }};
        }
        if v < layers.bounds[0] as usize {
            push!(layers.receivers)
        } else {
            push!(self.active)
        }
    }
}

/// A translucent triangle's back-to-front key: the sum of its vertices' depths (16.8 each),
/// then the sums of their x and y (so that equal depths sort the same whatever the order the
/// triangles were given in).
fn sort_key(t: &TriRecord, verts: &[ScreenVertex]) -> u64 {
    let [a, b, c] = t.indices().map(|k| verts[k]);
    let z = |v: &ScreenVertex| ((v.z as u64) << 8) | v.zf as u64;
    let x = (a.x as i32 + b.x as i32 + c.x as i32 + (1 << 17)) as u64 & 0xf_ffff;
    let y = (a.y as i32 + b.y as i32 + c.y as i32 + (1 << 17)) as u64 & 0xf_ffff;
    ((z(&a) + z(&b) + z(&c)) << 40) | (x << 20) | y
}

/// One row of a shadow polygon: each pixel a receiver drew (depth below the far plane: on this
/// row only the receivers have drawn yet) and no shadow polygon darkened yet is blended toward
/// the shadow colour, and marked in the stencil (a blob disc, `blob`, darkens whatever the
/// stencil says: the nested discs add up). Returns `(fragments, written, finished)`.
#[allow(clippy::too_many_arguments)]
fn shadow_row<C: TargetColor>(
    t: &mut ActiveTri,
    row: i32,
    colors: &mut [C],
    depth: &[u16],
    stencil: &mut [u8],
    lut: &[[u8; 64]; 3],
    shadow: ([u8; 3], u8),
    blob: bool,
) -> (u32, u32, bool) {
    // A blob never sets the stencil bit, so every pixel stays open to the next disc.
    let mark = if blob { 0 } else { SHADOWED };
    let width = colors.len().min(depth.len()).min(stencil.len()) as i32;
    let (xs, xe) = (t.edges[0].c().max(0), t.edges[1].c().min(width));
    let mut written = 0;
    if xs < xe {
        let r = xs as usize..xe as usize;
        let (zs, ss) = (&depth[r.clone()], &mut stencil[r.clone()]);
        let small = C::CHANNEL_MAX.iter().all(|&m| m <= 63);
        if let (Some(words), true) = (rgb565_words_mut(&mut colors[r.clone()]), small) {
            for ((w, &z), s) in words.iter_mut().zip(zs).zip(ss.iter_mut()) {
                if z != u16::MAX && *s & SHADOWED == 0 {
                    *s |= mark;
                    let v = *w as usize;
                    *w = (lut[0][v >> 11] as u16) << 11
                        | (lut[1][(v >> 5) & 63] as u16) << 5
                        | lut[2][v & 31] as u16;
                    written += 1;
                }
            }
        } else {
            for ((c, &z), s) in colors[r].iter_mut().zip(zs).zip(ss.iter_mut()) {
                if z != u16::MAX && *s & SHADOWED == 0 {
                    *s |= mark;
                    if let Some(ch) = c.channels() {
                        let k = |i: usize| {
                            if small {
                                lut[i][ch[i] as usize & 63]
                            } else {
                                blend(ch[i] as u32, shadow.0[i] as u32, shadow.1 as u32) as u8
                            }
                        };
                        *c = C::from_channels([k(0), k(1), k(2)]);
                        written += 1;
                    }
                }
            }
        }
    }
    let next = row + 1;
    if next >= t.row_end as i32 {
        return ((xe - xs).max(0) as u32, written, true);
    }
    t.advance(next);
    ((xe - xs).max(0) as u32, written, false)
}

/// One row of a translucent triangle (set up without the fast path: unpacked depth and
/// colour rows), blended with opacity `alpha` (0..=255) over the pixels it is in front of;
/// depth is tested, not written. Does not advance the triangle. Returns
/// `(fragments, written)`.
fn translucent_row<C: TargetColor>(
    t: &ActiveTri,
    _row: i32,
    colors: &mut [C],
    depth: &[u16],
    alpha: u32,
) -> (u32, u32) {
    let width = colors.len().min(depth.len()) as i32;
    let (lc, rc) = (t.edges[0].c(), t.edges[1].c());
    let (xs, xe) = (lc.max(0), rc.min(width));
    if xs >= xe {
        return (0, 0);
    }
    let skip = xs - lc;
    let flat = t.flags & FLAT != 0;
    let at = |k: usize| t.row[k].wrapping_add(t.gx[k].wrapping_mul(skip));
    let half = 1i32 << (COLOR_FRAC_BITS - 1);
    let mut z = at(0).clamp(0, DEPTH_MAX << DEPTH_FRAC_BITS) + (1 << (DEPTH_FRAC_BITS - 1));
    let (mut v, g) = if flat {
        let c = t.flat_channels();
        (c.map(|b| ((b as i32) << COLOR_FRAC_BITS) + half), [0i32; 3])
    } else {
        let max = C::CHANNEL_MAX;
        (
            core::array::from_fn(|k| at(k + 1).clamp(0, (max[k] as i32) << COLOR_FRAC_BITS) + half),
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
