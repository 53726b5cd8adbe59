//! The shadow map's seam in the strip pass: a context every row loop, [`enter`] and
//! [`draw_row`] take by value and pass on, so that a mapped frame's shadow span kinds can read
//! the map and a frame without one compiles to the code it had. Plain, layered and seeking
//! passes give [`NoMap`], a zero-sized type (no register, no branch: the kinds' arms are under
//! [`SpanMap::ON`], a constant).
//!
//! [`enter`]: crate::raster::kind::enter
//! [`draw_row`]: crate::raster::kind::draw_row

use crate::kernel::records::TriRecord;
use crate::raster::shadow_map::ShadowFilter;

/// What a strip pass knows of a shadow map: nothing ([`NoMap`]) or the map of a mapped frame
/// ([`MapView`]).
pub(crate) trait SpanMap: Copy {
    /// Whether there is a map: the shadow kinds' code is compiled only where it is true.
    const ON: bool;
    /// The map, if there is one.
    fn view(&self) -> Option<MapView<'_>>;
}

/// No shadow map: the context of every frame without one.
#[derive(Copy, Clone, Debug, Default)]
pub(crate) struct NoMap;

impl SpanMap for NoMap {
    const ON: bool = false;
    #[inline(always)]
    fn view(&self) -> Option<MapView<'_>> {
        None
    }
}

/// A mapped frame's shadow map, read by its shadow spans: the texels (row by row, `N × N`)
/// and the lookup.
#[derive(Copy, Clone, Debug)]
pub(crate) struct MapView<'m> {
    pub(crate) look: &'m MapLookup,
    /// A depth map's texels (empty for an image).
    pub(crate) depth: &'m [u16],
    /// An image's texels, cover levels 0..=4 (empty for a depth map).
    pub(crate) cover: &'m [u8],
}

impl SpanMap for MapView<'_> {
    const ON: bool = true;
    #[inline(always)]
    fn view(&self) -> Option<MapView<'_>> {
        Some(*self)
    }
}

impl MapView<'_> {
    /// Whether triangle `t` is a receiver's (its vertices among the receivers', which come
    /// first in the vertex store).
    #[inline(always)]
    pub(crate) fn receives(&self, t: &TriRecord) -> bool {
        t.v[1] < self.look.receivers_end
    }
}

/// The largest bias a receiver's triangle gets (depth steps): a triangle nearly edge-on to the
/// light would otherwise lift its whole depth range out of the map.
pub const MAX_BIAS: i32 = 4096;

/// What a mapped frame's shadow spans read of the map besides its texels
/// (`ShadowMap::prepare_lookup`, once per frame).
#[derive(Clone, Debug)]
pub(crate) struct MapLookup {
    /// Screen → map, homogeneous: `(X, Y, Z, W)`, row `r` = `Σ_j m[r][j]·s_j` for a screen
    /// point `s = (x, y, d, 1)` (x and y in subpixels, the depth `d` in 2⁻¹² steps, unsigned
    /// 16.12 as the spans step it); texel `X/W`, `Y/W`, map depth `Z/W`. Every row is scaled
    /// by the same `2^σ`, the largest with each row's sum at most 2⁶⁰ over the screen's range
    /// (|x|, |y| < 2¹⁵, d < 2²⁸), and signed so that `W > 0` in front of the light.
    pub(crate) m: [[i64; 4]; 4],
    /// log2 of the map's side.
    pub(crate) log2n: u8,
    /// The end of the receivers' vertices in the vertex store (they come first).
    pub(crate) receivers_end: u16,
    /// `ShadowMapping::bias`.
    pub(crate) bias: [u16; 2],
    /// Per level `k` = 1..=4 of the shadow (entry `k − 1`: `k` quarters of its opacity) and
    /// per channel value of a target of at most 6 bits per channel, the value blended toward
    /// the shadow (`layers::blend_tables`). A nearest read uses level 4 only.
    pub(crate) lut: [[[u8; 64]; 3]; 4],
    /// The shadow colour in the target's channel units and its full opacity (0..=255).
    pub(crate) shadow: ([u8; 3], u8),
    /// The opacity of each level 0..=4 (`round(α·k/4)`), for targets wider than 6 bits.
    pub(crate) alphas: [u8; 5],
    /// How the spans read the map.
    pub(crate) filter: ShadowFilter,
    /// The map is an image (cover levels, no depth: [`MapView::cover`]).
    pub(crate) image: bool,
}

impl MapLookup {
    pub(crate) const EMPTY: MapLookup = MapLookup {
        m: [[0; 4]; 4],
        log2n: 0,
        receivers_end: 0,
        bias: [0; 2],
        lut: [[[0; 64]; 3]; 4],
        shadow: ([0; 3], 0),
        alphas: [0; 5],
        filter: ShadowFilter::Nearest,
        image: false,
    };
}
