//! The geometry stage's stores: what it makes of a frame's scene and the strip pass reads.
//! The renderer owns one ([`crate::Renderer`]'s RAM is mostly these and the strip lines); the
//! geometry stage's functions are methods of it, and their other inputs (the scene, the
//! overflow policy, the capacities an error reports) are their arguments.

use core::marker::PhantomData;

use heapless::Vec;

use crate::geometry::pool::{ActiveExtra, FREE, TRI};
use crate::geometry::project::ScreenVertex;
use crate::geometry::vertex_extra::VertexExtra;
use crate::kernel::records::TriRecord;

/// A frame's screen vertices, triangles, attribute stores and row buckets, for a renderer of
/// `H` rows, `VERTS` vertices, `TRIS` triangles and attribute stores of `XV` vertices and `XA`
/// pool entries. `S` and `C` are the renderer's number and colour types (the stage's
/// functions compute in `S` and pack channels for `C`).
#[derive(Debug)]
pub(crate) struct Stores<
    S,
    C,
    const H: usize,
    const VERTS: usize,
    const TRIS: usize,
    const XV: usize,
    const XA: usize,
> {
    /// The screen vertices (12 bytes each, formats in [`ScreenVertex`]).
    pub(crate) verts: Vec<ScreenVertex, VERTS>,
    /// Texture or Phong attributes of the first `XV` vertices of the store (see "Textures").
    pub(crate) xverts: [VertexExtra; XV],
    /// The attribute pool: the frame's Phong lights, point lights, fog and materials (written
    /// here), and the extra planes of up to `XA` active textured or Phong triangles (written by
    /// the strip pass, [`TRI`] entries).
    pub(crate) xactive: [ActiveExtra; XA],
    /// The stored triangles, sorted by first covered row once the stage ends.
    pub(crate) tris: Vec<TriRecord, TRIS>,
    /// Per row: during geometry the number of triangles whose first row it is; then the index
    /// of the first of them in `tris` (sorted by first row).
    pub(crate) heads: [u16; H],
    /// Per row: during geometry the change of the active-triangle count (+1 for each triangle
    /// starting, −1 for each ending); then the insertion cursors of the bucket sort (and, for
    /// the strip pass, scratch space while it seeks a row).
    pub(crate) starts: [i16; H],
    /// The viewport the frame is projected onto, `vw ≤ W`, `vh ≤ H` pixels.
    pub(crate) vw: usize,
    pub(crate) vh: usize,
    /// Under [`crate::OverflowPolicy::DrawWhatFits`]: the triangles the prepared frame needed
    /// but did not store (0..=`u32::MAX`, saturating).
    pub(crate) store_skipped: u32,
    pub(crate) _t: PhantomData<(S, C)>,
}

impl<
        S,
        C,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const XV: usize,
        const XA: usize,
    > Stores<S, C, H, VERTS, TRIS, XV, XA>
{
    /// Empty stores for a `vw × vh` viewport.
    pub(crate) const fn new(vw: usize, vh: usize) -> Self {
        Stores {
            verts: Vec::new(),
            xverts: [VertexExtra::NONE; XV],
            xactive: [ActiveExtra::EMPTY; XA],
            tris: Vec::new(),
            heads: [0; H],
            starts: [0; H],
            vw,
            vh,
            store_skipped: 0,
            _t: PhantomData,
        }
    }

    /// Frees the pool entries of active triangles (the frame's Phong lights, materials and fog
    /// stay).
    pub(crate) fn free_triangle_entries(&mut self) {
        for e in self.xactive.iter_mut() {
            if e.kind == TRI {
                e.kind = FREE;
            }
        }
    }
}
