//! The shadow map's seam in the strip pass: a context every row loop, [`enter`] and
//! [`draw_row`] take by value and pass on, so that a mapped frame's shadow span kinds can read
//! the map and a frame without one compiles to the code it had. Plain, layered and seeking
//! passes give [`NoMap`], a zero-sized type (no register, no branch: the kinds' arms are under
//! [`SpanMap::ON`], a constant).
//!
//! [`enter`]: crate::raster::kind::enter
//! [`draw_row`]: crate::raster::kind::draw_row

use crate::kernel::records::TriRecord;

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

/// How a receiver's pixel reads a [`crate::shadow::ShadowMap`]
/// ([`crate::shadow::ShadowMapping::filter`]).
///
/// The filtered kinds are percentage-closer filtering: each of the texels around the pixel's
/// point in the map is compared with the pixel's light depth, and the pixel is darkened by the
/// share that hide it, in five levels (none, ¼, ½, ¾, all of the shadow's opacity). Their
/// bias's slope term grows with the taps' reach (×2 for 2 × 2, ×3 for 3 × 3), since a tap
/// one texel away reads the surface one texel's depth change away.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum ShadowFilter {
    /// The texel under the pixel: in shadow or not (hard edges; 1 load and compare a pixel).
    #[default]
    Nearest,
    /// The 2 × 2 texels around the pixel's point (their centres within one texel of it):
    /// 4 loads and compares, levels 0..=4 by the count.
    Pcf2,
    /// The 3 × 3 texels around the pixel's texel: 9 loads and compares, the count 0..=9
    /// rounded to the nearest of the five levels.
    Pcf3,
}

impl ShadowFilter {
    /// The bias's slope factor: the taps' reach in half texels (1, 2, 3).
    pub(crate) const fn reach(self) -> i64 {
        match self {
            ShadowFilter::Nearest => 1,
            ShadowFilter::Pcf2 => 2,
            ShadowFilter::Pcf3 => 3,
        }
    }
}

/// A 3 × 3 read's count of hiding texels (0..=9) to its level (0..=4): `round(4·count/9)`.
pub(crate) const LEVEL9: [u8; 10] = [0, 0, 1, 1, 2, 2, 3, 3, 4, 4];
