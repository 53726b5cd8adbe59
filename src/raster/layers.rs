//! Layered frames: each strip row drawn in layers — the planar shadow's receivers, its
//! projected polygons (stencilled, so overlaps darken once), the other opaque objects, the
//! shadow volumes' faces (counted in the stencil, then every pixel with a non-zero count
//! darkened), the outlines, then the translucent triangles back to front — with the lists and
//! the stencil lines in a [`Layers`] the caller owns. A frame drawn by [`crate::Renderer::render`]
//! uses none of this and pays nothing for it: no field, no branch.

use heapless::Vec;

use crate::error::Error;
use crate::error::{LayerError, MAX_TRANSLUCENT};
use crate::geometry::stores::Stores;
use crate::kernel;
use crate::kernel::records::{ActiveList, ScreenVertex, TriRecord};
use crate::num::scalar::Scalar;
use crate::raster::kind::enter;
use crate::raster::layer_rows::{
    darken_span, outline_row, shadow_row, translucent_row, volume_row, Darken, Post,
};
use crate::raster::shadow::{Edges, ShadowLight};
use crate::raster::span_map::NoMap;
use crate::raster::state::Raster;
use crate::raster::strip::draw_list_row;
use crate::raster::volume::volume_sign;
use crate::raster::SpanMode;
use crate::scene::color::{rgb565_word, rgb565_words_mut, TargetColor};
use crate::scene::Scene;
use crate::stats::{Probe, Stage};

/// [`Layers`] post-list entry kinds.
const SHADOW: u8 = 1;
const TRANSLUCENT: u8 = 2;
/// A shadow-volume face; its sign (1, or 255 for −1) in the opacity byte.
const VOLUME: u8 = 3;
const OUTLINE: u8 = 4;

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
    /// Per pixel of each strip line: a planar shadow's mark once a shadow polygon darkened it,
    /// or the shadow volumes' count (modulo 256: a pixel inside at most 255 nested volumes
    /// counts right). During the geometry stage, a bit per triangle of one object (which faces
    /// turn toward the light or the eye).
    pub(crate) stencil: [[u8; W]; LINES],
    pub(crate) receivers: ActiveList<RA>,
    pub(crate) post: ActiveList<PA>,
    /// Per post-list entry: kind in bits 0..=7, opacity (0..=255) in bits 8..=15.
    pub(crate) meta: [u16; PA],
    /// Per post-list entry: back-to-front sort key (larger is drawn first).
    pub(crate) key: [u64; PA],
    /// Vertex-store index where the receivers' vertices end, the opaque objects' vertices
    /// end, the shadow polygons' (or volumes') vertices end and the outlines' vertices end;
    /// the translucent objects' vertices follow.
    pub(crate) bounds: [u16; 4],
    /// The translucent objects: the vertex-store index where each one's vertices end, and its
    /// opacity.
    pub(crate) translucent: Vec<(u16, u8), MAX_TRANSLUCENT>,
    /// The shadow's blend per channel value, for channels of at most 6 bits (RGB565):
    /// `round((c·(255 − α) + s·α)/255)`, in the channel's units.
    pub(crate) lut: [[u8; 64]; 3],
    /// The shadow's colour in the target's channel units, and its opacity (0: no shadow).
    pub(crate) shadow: ([u8; 3], u8),
    /// The shadow is blobs: nested discs that each darken (no stencil).
    pub(crate) blob: bool,
    /// The shadow is volumes, counted in the stencil.
    pub(crate) volume: bool,
    /// The outlines are drawn without the depth test ([`crate::shadow::Outline::see_through`]).
    pub(crate) see_through: bool,
    pub(crate) skipped: u32,
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
            bounds: [0; 4],
            translucent: Vec::new(),
            lut: [[0; 64]; 3],
            shadow: ([0; 3], 0),
            blob: false,
            volume: false,
            see_through: false,
            skipped: 0,
        }
    }

    /// Shadow and translucent triangles left out of the last frame for want of room (only
    /// under [`crate::OverflowPolicy::DrawWhatFits`]).
    #[must_use]
    pub fn skipped(&self) -> u32 {
        self.skipped
    }
}

impl<const W: usize, const LINES: usize, const RA: usize, const PA: usize> Default
    for Layers<W, LINES, RA, PA>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<C: TargetColor, const W: usize, const LINES: usize, const ZL: usize, const ACTIVE: usize>
    Raster<C, W, LINES, ZL, ACTIVE>
{
    /// Draws the next strip of a layered frame into the renderer's lines; its first row and
    /// height, or `None` when the frame is complete.
    #[allow(clippy::type_complexity)]
    pub(crate) fn draw_strip_layered<
        S,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const XV: usize,
        const XA: usize,
        P: Probe,
        const RA: usize,
        const PA: usize,
    >(
        &mut self,
        geo: &mut Stores<S, C, H, VERTS, TRIS, XV, XA>,
        layers: &mut Layers<W, LINES, RA, PA>,
        limit: usize,
        probe: &mut P,
    ) -> Option<(usize, usize)> {
        let y0 = self.next_row;
        let (vw, vh) = (geo.vw, geo.vh);
        if y0 >= vh {
            return None;
        }
        let mode = SpanMode::new::<C>(self.depth_test, self.dither);
        let lines = LINES.min(limit).min(vh - y0);
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
                geo.heads[row + 1] as usize
            } else {
                geo.tris.len()
            };
            let bucket = geo.heads[row] as usize..end;
            if !bucket.is_empty() {
                probe.enter(Stage::Setup);
            }
            for t in bucket {
                let rec = geo.tris[t];
                if !self.setup_layered(geo, &rec, row, mode, layers) {
                    self.active_skipped = self.active_skipped.saturating_add(1);
                }
            }
            probe.enter(Stage::Raster);
            let Raster {
                active,
                color,
                depth,
                depth_test,
                dither,
                stats,
                ..
            } = self;
            let (colors, depth) = (&mut color[l][..vw], &mut depth[l][..vw]);
            draw_list_row::<C, RA, XA, NoMap>(
                &mut layers.receivers,
                &mut geo.xactive,
                row,
                colors,
                depth,
                *depth_test,
                *dither,
                stats,
                NoMap,
            );
            let Layers {
                stencil,
                lut,
                shadow,
                blob,
                volume,
                post,
                meta,
                key,
                ..
            } = layers;
            let stencil = &mut stencil[l][..vw];
            let d = Darken {
                lut,
                shadow: *shadow,
            };
            let (row, blob) = (row as i32, *blob);
            let mut post = Post {
                list: post,
                meta,
                key,
            };
            post.rows(SHADOW, row, |t, _, _| {
                let (frag, written) = shadow_row(t, colors, depth, stencil, d, blob);
                stats.add_row(frag, written);
            });
            draw_list_row::<C, ACTIVE, XA, NoMap>(
                active,
                &mut geo.xactive,
                row as usize,
                colors,
                depth,
                *depth_test,
                *dither,
                stats,
                NoMap,
            );
            if *volume {
                // Count the volume faces behind the surface, then darken where the count is
                // not zero, over the columns the faces covered.
                let (mut lo, mut hi) = (vw, 0);
                post.rows(VOLUME, row, |t, meta, _| {
                    let (frag, r) = volume_row(t, depth, stencil, (meta >> 8) as u8);
                    if !r.is_empty() {
                        (lo, hi) = (lo.min(r.start), hi.max(r.end));
                    }
                    stats.add_row(frag, 0);
                });
                if lo < hi {
                    let r = lo..hi;
                    let written = darken_span(
                        &mut colors[r.clone()],
                        &depth[r.clone()],
                        &mut stencil[r],
                        d,
                        |s| *s != 0,
                    );
                    stats.add_row(0, written);
                }
            }
            post.rows(OUTLINE, row, |t, meta, _| {
                let (frag, written) = outline_row(t, colors, depth, meta >> 8 != 0);
                stats.add_row(frag, written);
            });
            // Translucent triangles, farthest first: their indices sorted by key per row. A
            // row without any (every row of a frame without translucency) neither fills nor
            // sorts the index array.
            let len = post.list.len();
            if post.meta[..len].iter().any(|&m| m as u8 == TRANSLUCENT) {
                let mut order = [0u16; PA];
                let mut n = 0;
                for j in 0..len {
                    if post.meta[j] as u8 == TRANSLUCENT {
                        order[n] = j as u16;
                        n += 1;
                    }
                }
                let key = &post.key;
                order[..n].sort_unstable_by(|a, b| key[*b as usize].cmp(&key[*a as usize]));
                for &j in &order[..n] {
                    let j = j as usize;
                    let alpha = (post.meta[j] >> 8) as u32;
                    let (frag, written) =
                        translucent_row(post.list.get_mut(j), colors, depth, alpha);
                    stats.add_row(frag, written);
                }
                // Advance (or retire) them after all are drawn: removal reorders the list.
                post.rows(TRANSLUCENT, row, |_, _, _| {});
            }
        }
        self.next_row = y0 + lines;
        Some((y0, lines))
    }

    /// Sets triangle `rec` (first covered row `row`) up in its layer's list. False when that
    /// list is full (under [`crate::OverflowPolicy::DrawWhatFits`]; the triangle is left out).
    #[allow(clippy::type_complexity)]
    fn setup_layered<
        S,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const XV: usize,
        const XA: usize,
        const RA: usize,
        const PA: usize,
    >(
        &mut self,
        geo: &mut Stores<S, C, H, VERTS, TRIS, XV, XA>,
        rec: &TriRecord,
        row: usize,
        mode: SpanMode,
        layers: &mut Layers<W, LINES, RA, PA>,
    ) -> bool {
        let (verts, h) = (&geo.verts[..], geo.vh as i32);
        let v = rec.v[1] as usize;
        if v >= layers.bounds[1] as usize {
            // A shadow polygon or a translucent triangle: unpacked rows (no fast path).
            let before = layers.post.len();
            let m = SpanMode::default();
            if !enter::<C, PA, NoMap>(
                false,
                &mut layers.post,
                &mut [],
                rec,
                verts,
                &[],
                row as i32,
                h,
                m,
                NoMap,
                |_| {},
            ) {
                return false;
            }
            if layers.post.len() > before {
                let (kind, alpha) = if v < layers.bounds[2] as usize {
                    if layers.volume {
                        (VOLUME, volume_sign(rec))
                    } else {
                        (SHADOW, 0)
                    }
                } else if v < layers.bounds[3] as usize {
                    (OUTLINE, layers.see_through as u8)
                } else {
                    let a = layers
                        .translucent
                        .iter()
                        .find(|(end, _)| v < *end as usize)
                        .map_or(255, |e| e.1);
                    (TRANSLUCENT, a)
                };
                layers.meta[before] = kind as u16 | (alpha as u16) << 8;
                if kind == TRANSLUCENT {
                    layers.key[before] = sort_key(rec, verts);
                }
            }
            return true;
        }
        let pooled = XV > 0 && XA > 0;
        macro_rules! push {
            ($list:expr, $n:ident) => {
                enter::<C, $n, NoMap>(
                    pooled,
                    &mut $list,
                    &mut geo.xactive,
                    rec,
                    verts,
                    &geo.xverts,
                    row as i32,
                    h,
                    mode,
                    NoMap,
                    |_| {},
                )
            };
        }
        if v < layers.bounds[0] as usize {
            push!(layers.receivers, RA)
        } else {
            push!(self.active, ACTIVE)
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

/// The shadow's colour in the target's channel units and its opacity, and the blend table for
/// channels of at most 6 bits (RGB565), into `layers`.
pub(crate) fn set_blend<
    C: TargetColor,
    const W: usize,
    const LINES: usize,
    const RA: usize,
    const PA: usize,
>(
    layers: &mut Layers<W, LINES, RA, PA>,
    color: [u8; 3],
    alpha: u8,
) {
    layers.shadow = crate::raster::layer_rows::blend_tables::<C>(&mut layers.lut, color, alpha);
}

/// Checks each object of `objects` has an adjacency table (`adjacency`, in the same order)
/// checked against its mesh ([`crate::mesh::Adjacency::is_for`]: two pointer comparisons, the table
/// itself was checked when it was made), and at most `bits` triangles.
pub(crate) fn check_adjacency<S: Scalar, E, const L: usize>(
    scene: &Scene<'_, S, L>,
    objects: &[usize],
    adjacency: &[crate::scene::adjacency::Adjacency<'_, S>],
    bits: usize,
) -> Result<(), Error<E>> {
    for (k, &object) in objects.iter().enumerate() {
        let mesh = &scene.objects[object].mesh;
        if !adjacency.get(k).is_some_and(|a| a.is_for(mesh)) {
            return Err(Error::Layers(LayerError::Adjacency { object }));
        }
        let triangles = mesh.indices().len();
        if triangles > bits {
            return Err(Error::Layers(LayerError::TooManyTriangles {
                object,
                triangles,
                capacity: bits,
            }));
        }
    }
    Ok(())
}

/// Checks an outline's crease tables ([`Edges::Crease`]): one per outlined object, of at least
/// 3 bits per triangle.
pub(crate) fn check_creases<S: Scalar, E, const L: usize>(
    scene: &Scene<'_, S, L>,
    o: &crate::raster::shadow::Outline<'_, S>,
) -> Result<(), Error<E>> {
    if let Edges::Crease(tables) = o.edges {
        for (k, &object) in o.objects.iter().enumerate() {
            let bytes = (3 * scene.objects[object].mesh.indices().len()).div_ceil(8);
            if tables.get(k).is_none_or(|t| t.len() < bytes) {
                return Err(Error::Layers(LayerError::Creases { object }));
            }
        }
    }
    Ok(())
}

/// Checks a shadow volume's light, reach and the casters' adjacency tables.
pub(crate) fn check_volume<S: Scalar, E, const L: usize>(
    scene: &Scene<'_, S, L>,
    casters: &[usize],
    v: &crate::raster::shadow::VolumeShadow<'_, S>,
    bits: usize,
) -> Result<(), Error<E>> {
    let light_ok = match v.light {
        ShadowLight::Directional(d) => {
            d.iter().all(|c| c.is_valid()) && d.iter().any(|&c| c != S::ZERO)
        }
        ShadowLight::Point(p) => p.iter().all(|c| c.is_valid()),
    };
    if !light_ok {
        return Err(Error::Layers(LayerError::Shadow));
    }
    if !(v.reach.is_valid() && v.reach > S::ZERO) {
        return Err(Error::Layers(LayerError::Reach));
    }
    check_adjacency(scene, casters, v.adjacency, bits)
}
