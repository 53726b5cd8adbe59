//! The renderer type without depth lines ([`NoDepthRenderer`]) and its draw-order settings
//! (the strip pass's no-depth rows and the painter's order are in `depth_mode`).

use crate::num::scalar::Scalar;
use crate::raster::depth_mode::DrawOrder;
use crate::renderer::Renderer;
use crate::scene::color::TargetColor;

/// A [`Renderer`] without depth lines: `LINES · W · 2` bytes less RAM and no per-pixel depth
/// test, for scenes that do not need one ([`DrawOrder`]). It draws flat and Gouraud
/// triangles (no texture or Phong stores: `XV = XA = 0`) and no layered effects (shadows,
/// outlines, translucency need the depth lines: [`crate::Error::NoDepthLines`]).
///
/// ```
/// # use embedded_graphics::pixelcolor::Rgb565;
/// # use scanline3d::prelude::*;
/// # use scanline3d::{DrawOrder, NoDepthRenderer};
/// # type Q = Fx<scanline3d::fixed::types::I16F16>;
/// type Z = Renderer<Q, Rgb565, 240, 240, 64, 64, 16>;
/// type P = NoDepthRenderer<Q, Rgb565, 240, 240, 64, 64, 16>;
/// assert_eq!(P::RAM_BYTES, Z::RAM_BYTES - 240 * 2);
/// let mut painter = P::new();
/// assert_eq!(painter.order(), DrawOrder::FarToNear);
/// painter.set_order(DrawOrder::Any); // one closed convex object
/// ```
pub type NoDepthRenderer<
    S,
    C,
    const W: usize,
    const H: usize,
    const VERTS: usize,
    const TRIS: usize,
    const ACTIVE: usize,
    const LINES: usize = 1,
> = Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, 0, 0, 0>;

impl<
        S: Scalar,
        C: TargetColor,
        const W: usize,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const ACTIVE: usize,
        const LINES: usize,
    > Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, 0, 0, 0>
{
    /// The order of the triangles of a row (default [`DrawOrder::FarToNear`]).
    #[must_use]
    pub fn order(&self) -> DrawOrder {
        self.ras.order
    }

    /// Sets the order of the triangles of a row; it applies from the next prepared frame.
    pub fn set_order(&mut self, order: DrawOrder) {
        self.ras.order = order;
    }

    /// [`Self::set_order`] on a renderer by value.
    #[must_use]
    pub fn with_order(mut self, order: DrawOrder) -> Self {
        self.ras.order = order;
        self
    }
}

/// Sets the draw order of any renderer (the support crate's generic benchmark driver, which
/// builds renderers with and without depth lines from one function; a renderer with depth
/// lines ignores the order). Not API: [`Renderer::set_order`] is, on [`NoDepthRenderer`].
#[doc(hidden)]
pub fn set_order_any<
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
    const ZL: usize,
>(
    r: &mut Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA, ZL>,
    order: DrawOrder,
) {
    r.ras.order = order;
}
