//! The shadow map's seam in the strip pass: a context every row loop, [`enter`] and
//! [`draw_row`] take by value and pass on, so that a mapped frame's shadow span kinds can read
//! the map and a frame without one compiles to the code it had. Plain, layered and seeking
//! passes give [`NoMap`], a zero-sized type (no register, no branch: the kinds' arms are under
//! [`SpanMap::ON`], a constant).
//!
//! [`enter`]: crate::raster::kind::enter
//! [`draw_row`]: crate::raster::kind::draw_row

/// What a strip pass knows of a shadow map (issue #42's lookup): nothing ([`NoMap`]) or the
/// map of a mapped frame.
pub(crate) trait SpanMap: Copy {
    /// Whether there is a map: the shadow kinds' code is compiled only where it is true.
    // (Read by the shadow kinds' arms, issue #42's lookup slice; this slice only threads the
    // context through, so that the ratchet shows the seam alone.)
    #[allow(dead_code)]
    const ON: bool;
}

/// No shadow map: the context of every frame without one.
#[derive(Copy, Clone, Debug, Default)]
pub(crate) struct NoMap;

impl SpanMap for NoMap {
    const ON: bool = false;
}
