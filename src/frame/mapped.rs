//! A mapped frame's options ([`FrameOptions::shadow_map`]): a plain frame whose receivers are
//! darkened where a shadow map, drawn first in the same [`Renderer::prepare`], holds a caster
//! nearer the light.

use super::*;
use crate::raster::shadow_map::{ShadowMapping, ShadowStore};
use crate::raster::span_map::MapView;

impl<P, O> FrameOptions<P, Plain, O> {
    /// A mapped frame: [`Renderer::shadow_map_pass`] draws `mapping`'s casters into `map`,
    /// then the frame is drawn as a plain one whose receivers' pixels (`mapping.receivers`, or
    /// every object) are darkened where the map holds a caster nearer the light than they
    /// are, blended toward the mapping's colour by its opacity as the other shadow methods
    /// blend. Any receiver can be shadowed, curved ones and the casters themselves included
    /// (a torus shadows its own inner ring).
    ///
    /// A receiver's triangle takes a pool entry while it is active (the renderer's `XA`: a
    /// triangle that finds none is left out and counted, [`crate::Shortfall::skipped`]); a face
    /// turned away from the light is drawn as it is (lit by the ambient term only). The
    /// frame's objects are flat or Gouraud-shaded (textured and per-pixel lit objects are
    /// refused), and receivers are not dithered.
    ///
    /// [`Renderer::prepare`] fails with [`Error::NoDepthLines`] on a renderer without depth
    /// lines, [`Error::AttributeStore`] on one without a pool (`XA = 0`),
    /// [`crate::errors::LayerError::MapShading`] for a textured or per-pixel lit object,
    /// [`crate::errors::LayerError::Blending`] for a target colour that cannot blend (a
    /// [`crate::color::TriangleId`] target records the triangles, none darkened), and the
    /// errors of [`Renderer::shadow_map_pass`].
    pub fn shadow_map<'l, 's, S, M: ShadowStore>(
        self,
        mapping: &'l ShadowMapping<'s, S>,
        map: &'l mut M,
    ) -> FrameOptions<P, Mapped<'l, 's, S, M>, O> {
        FrameOptions {
            probe: self.probe,
            kind: Mapped { mapping, map },
            overlay: self.overlay,
        }
    }
}

/// A mapped frame's options ([`FrameOptions::shadow_map`]).
#[derive(Debug)]
pub struct Mapped<'l, 's, S, M> {
    mapping: &'l ShadowMapping<'s, S>,
    map: &'l mut M,
}

/// A mapped frame's map, which its strips read (what [`Mapped`] becomes once the frame is
/// prepared).
#[derive(Debug)]
pub struct MappedStrips<'l, M> {
    map: &'l M,
}

impl<S, M> sealed::Sealed for Mapped<'_, '_, S, M> {}
impl<M> sealed::Sealed for MappedStrips<'_, M> {}

impl<'l, S, const W: usize, const LINES: usize, M: ShadowStore> FrameKind<S, W, LINES>
    for Mapped<'l, '_, S, M>
{
    type Strips = MappedStrips<'l, M>;
    #[inline(always)]
    fn geometry<
        C: TargetColor,
        P: Probe,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const ACTIVE: usize,
        const XV: usize,
        const XA: usize,
        const ZL: usize,
        const L: usize,
    >(
        self,
        renderer: &mut Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA, ZL>,
        scene: &Scene<'_, S, L>,
        probe: &mut P,
    ) -> Result<Self::Strips, Error<core::convert::Infallible>>
    where
        S: Scalar,
    {
        let Mapped { mapping, map } = self;
        renderer.geometry_mapped(scene, mapping, map, probe)?;
        Ok(MappedStrips { map })
    }
}

impl<const W: usize, const LINES: usize, M: ShadowStore> StripSource<W, LINES>
    for MappedStrips<'_, M>
{
    const INLINE_LOOP: bool = false;
    #[inline(always)]
    fn draw<
        S: Scalar,
        C: TargetColor,
        P: Probe,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const ACTIVE: usize,
        const XV: usize,
        const XA: usize,
        const ZL: usize,
    >(
        &mut self,
        renderer: &mut Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA, ZL>,
        ext: Option<&mut [[C; W]]>,
        limit: usize,
        probe: &mut P,
    ) -> Option<(usize, usize)> {
        let view = self.map.view();
        renderer
            .ras
            .draw_strip_with::<S, H, VERTS, TRIS, XV, XA, P, true, MapView<'_>>(
                &mut renderer.geo,
                ext,
                limit,
                probe,
                view,
            )
    }
}
