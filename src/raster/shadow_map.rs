//! Shadow mapping (the seeds' fourth shadow method, for parts with the RAM for a map): the
//! casters drawn depth-only from the light into a caller-owned [`ShadowMap`] by
//! [`crate::Renderer::shadow_map_pass`], through the renderer's own geometry stage and strip
//! pass (each map row is a row of a strip, with the same clipping and fill rule as a frame),
//! with the light's view fitted to the receivers ([`ShadowMapping::light_camera`]).
//!
//! A scene without a map pays nothing for it: the map, its size and the light's view are the
//! caller's, outside the renderer (as [`crate::Layers`] are).

use crate::error::{Error, LayerError};
use crate::num::math::{add, cross, dot, length, scale, sub, Mat4};
use crate::num::scalar::Scalar;
use crate::raster::shadow::{object_sphere, ShadowLight};
use crate::raster::span_map::MapLookup;
pub use crate::raster::span_map::ShadowFilter;
use crate::scene::camera::{Camera, Projection, MAX_DEPTH_RATIO};
use crate::scene::Scene;

/// The widest full angle (radians) a point light's map is fitted to: 2.6 rad, 149°. Receivers
/// spread wider around the light fail with [`LayerError::LightInside`] (one perspective view
/// cannot hold them; the texels at the map's rim would be stretched `1/cos²` of 75°, 15 times).
pub const MAX_MAP_FOV: f64 = 2.6;

/// Texels of margin on each side of the receivers in a fitted map (so that a filter reading
/// the texels around a receiver's edge pixel stays inside the map).
pub const MAP_MARGIN: usize = 2;

/// What a shadow map is drawn from: the light, the objects that cast into the map, and the
/// objects that receive their shadows (the light's view is fitted to both), or a light camera
/// given outright.
///
/// ```
/// # use scanline3d::shadow::{ShadowLight, ShadowMapping};
/// let mapping = ShadowMapping::new(ShadowLight::Directional([1.0f32, 2.0, 1.0]), &[1], &[0]);
/// assert!(mapping.camera.is_none());
/// ```
#[derive(Copy, Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct ShadowMapping<'a, S> {
    /// The light: a direction (an orthographic view along it) or a point (a perspective view
    /// from it, toward the receivers).
    pub light: ShadowLight<S>,
    /// The objects drawn into the map (indices into the scene's objects).
    pub casters: &'a [usize],
    /// The objects shadowed by the map; empty: every opaque object of the scene.
    pub receivers: &'a [usize],
    /// The light's camera as given (any view and projection; the map's aspect is 1), or `None`
    /// to fit it ([`ShadowMapping::light_camera`]).
    pub camera: Option<Camera<S>>,
    /// The shadow's colour, 8 bits per channel (black by default).
    pub color: [u8; 3],
    /// The shadow's opacity, 0..=255: a shadowed pixel is `color·α + C·(1 − α)`,
    /// `α = alpha/255`, as the other shadow methods blend.
    pub alpha: u8,
    /// The depth bias, `[constant, slope]`: a receiver's pixel is in shadow when its depth from
    /// the light exceeds the map's by more than `constant` depth steps plus `slope/256` times
    /// its triangle's depth change across one texel (so that a surface does not shadow itself
    /// where the map's texels are coarser than its pixels: "shadow acne"). Default
    /// [`DEFAULT_BIAS`].
    pub bias: [u16; 2],
    /// How a pixel reads the map: one texel, or the share of 2 × 2 or 3 × 3 texels that hide
    /// it from the light (soft edges). Default [`ShadowFilter::Nearest`].
    pub filter: ShadowFilter,
}

/// [`ShadowMapping::bias`]'s default: 64 depth steps, plus 1.5 times a receiver's depth change
/// across a texel.
pub const DEFAULT_BIAS: [u16; 2] = [64, 384];

impl<'a, S: Scalar> ShadowMapping<'a, S> {
    /// A map from `light` of `casters`, fitted to `receivers` (empty: every opaque object).
    #[must_use]
    pub const fn new(light: ShadowLight<S>, casters: &'a [usize], receivers: &'a [usize]) -> Self {
        ShadowMapping {
            light,
            casters,
            receivers,
            camera: None,
            color: [0; 3],
            alpha: 140,
            bias: DEFAULT_BIAS,
            filter: ShadowFilter::Nearest,
        }
    }

    /// This mapping read through `filter` ([`ShadowMapping::filter`]).
    #[must_use]
    pub const fn with_filter(self, filter: ShadowFilter) -> Self {
        ShadowMapping { filter, ..self }
    }

    /// This mapping with a shadow of `color` and opacity `alpha` (default black, 140).
    #[must_use]
    pub const fn with_shadow(self, color: [u8; 3], alpha: u8) -> Self {
        ShadowMapping {
            color,
            alpha,
            ..self
        }
    }

    /// This mapping with the depth bias `[constant, slope]` ([`ShadowMapping::bias`]).
    #[must_use]
    pub const fn with_bias(self, bias: [u16; 2]) -> Self {
        ShadowMapping { bias, ..self }
    }

    /// This mapping drawn from `camera` instead of a fitted one (a spot light's cone, or a
    /// fixed view that does not move with the receivers).
    #[must_use]
    pub const fn with_camera(self, camera: Camera<S>) -> Self {
        ShadowMapping {
            camera: Some(camera),
            ..self
        }
    }

    /// Whether object `i` of `scene` is one of the receivers (with none given, every opaque
    /// object is).
    pub(crate) fn receives<const L: usize>(&self, scene: &Scene<'_, S, L>, i: usize) -> bool {
        if self.receivers.is_empty() {
            scene.objects[i].material.alpha == 255
        } else {
            self.receivers.contains(&i)
        }
    }

    /// The light's camera for a map of `size` texels a side: the given one, or one fitted to
    /// where the casters' shadows can fall on the receivers, from the objects' bounding spheres
    /// ([`MAP_MARGIN`] texels inside the map's border). The map's texels are spent there only: a
    /// receiver's pixel outside the map is lit.
    ///
    /// - A directional light: an orthographic view along the light, square, around the overlap
    ///   of the receivers' and the casters' spheres as seen along it (the casters' alone when
    ///   they do not overlap), and deep enough for the receivers and every caster whose sphere
    ///   reaches that square.
    /// - A point light: a perspective view from the light, around the casters' spheres (the
    ///   receivers' when every caster's sphere holds the light), from the nearest receiver's or
    ///   caster's sphere (casters around the light are clipped at the near plane) to the
    ///   farthest receiver's.
    ///
    /// Computed in f64 once per map (the same on every core), then built in the number type
    /// with [`Camera::look_at`].
    ///
    /// # Errors
    ///
    /// [`LayerError::NoSuchObject`], [`LayerError::Shadow`] (a light direction or position
    /// that is not a finite non-zero number), [`LayerError::EmptyBounds`],
    /// [`LayerError::LightInside`] (inside [`Error::Layers`]), and [`Error::Camera`] when the
    /// fitted camera does not fit the number type.
    pub fn light_camera<const L: usize>(
        &self,
        scene: &Scene<'_, S, L>,
        size: usize,
    ) -> Result<Camera<S>, Error<core::convert::Infallible>> {
        let n = scene.objects.len();
        for &i in self.casters.iter().chain(self.receivers) {
            if i >= n {
                return Err(Error::Layers(LayerError::NoSuchObject { index: i }));
            }
        }
        if let Some(c) = self.camera {
            c.validate().map_err(Error::Camera)?;
            return Ok(c);
        }
        // Object `i`'s bounding sphere, when it has one (finite, not empty).
        let sphere = |i: usize| {
            let (c, r) = object_sphere(&scene.objects[i]);
            (c.iter().all(|v| v.is_finite()) && r.is_finite() && r > 0.0).then_some((i, c, r))
        };
        // The receivers' and the casters' spheres (recomputed by each loop over them: no
        // store, whatever their number).
        let rec = || {
            (0..n)
                .filter(|&i| self.receives(scene, i))
                .filter_map(sphere)
        };
        let casters = || self.casters.iter().filter_map(move |&i| sphere(i));
        let Some(first) = rec().next() else {
            return Err(Error::Layers(LayerError::EmptyBounds));
        };
        let shrink = size as f64 / (size as f64 - 2.0 * MAP_MARGIN as f64).max(1.0);
        let (eye, target, up, projection) = match self.light {
            ShadowLight::Directional(d) => {
                let l = unit(d.map(|v| v.to_f64())).ok_or(Error::Layers(LayerError::Shadow))?;
                let up = up_for(l);
                let u = unit(cross(up, l)).ok_or(Error::Layers(LayerError::Shadow))?;
                let v = cross(l, u);
                // The receivers' and the casters' boxes as seen along the light: a shadow falls
                // only where they overlap (the casters' box alone when they do not, or the
                // receivers' without a caster).
                let bounds = |spheres: &mut dyn Iterator<Item = (usize, [f64; 3], f64)>| {
                    let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
                    for (_, c, r) in spheres {
                        for (k, axis) in [u, v].iter().enumerate() {
                            lo[k] = lo[k].min(dot(c, *axis) - r);
                            hi[k] = hi[k].max(dot(c, *axis) + r);
                        }
                    }
                    (lo, hi)
                };
                let (mut lo, mut hi) = bounds(&mut rec());
                let (clo, chi) = bounds(&mut casters());
                if clo[0] <= chi[0] {
                    let both = [0, 1].map(|k| (lo[k].max(clo[k]), hi[k].min(chi[k])));
                    if both.iter().all(|(a, b)| a < b) {
                        (lo, hi) = (both.map(|b| b.0), both.map(|b| b.1));
                    } else {
                        (lo, hi) = (clo, chi);
                    }
                }
                let side = (hi[0] - lo[0]).max(hi[1] - lo[1]);
                let height = side * shrink;
                let mid = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
                // Depth along the light: the receivers, and the casters that overlap them as
                // seen along it.
                let (mut t0, mut t1) = (f64::MAX, f64::MIN);
                let overlaps = |c: [f64; 3], r: f64| {
                    (dot(c, u) - mid[0]).abs() <= height / 2.0 + r
                        && (dot(c, v) - mid[1]).abs() <= height / 2.0 + r
                };
                for (_, c, r) in rec().chain(casters()) {
                    if overlaps(c, r) {
                        t0 = t0.min(dot(c, l) - r);
                        t1 = t1.max(dot(c, l) + r);
                    }
                }
                let pad = (t1 - t0) / 64.0;
                let eye = add(add(scale(u, mid[0]), scale(v, mid[1])), scale(l, t1 + pad));
                let far = t1 - t0 + 2.0 * pad;
                (
                    eye,
                    sub(eye, l),
                    up,
                    Projection::Orthographic {
                        height,
                        near: 0.0,
                        far,
                    },
                )
            }
            ShadowLight::Point(p) => {
                let p = p.map(|v| v.to_f64());
                if !p.iter().all(|v| v.is_finite()) {
                    return Err(Error::Layers(LayerError::Shadow));
                }
                let mut far = 0.0f64;
                for (i, c, r) in rec() {
                    let dist = length(sub(c, p));
                    if dist <= r {
                        return Err(Error::Layers(LayerError::LightInside { object: i }));
                    }
                    far = far.max(dist + r);
                }
                // The view frames the casters the light is outside of (their shadows are
                // inside that cone), or the receivers without one.
                let outside = || casters().filter(|&(_, c, r)| length(sub(c, p)) > r);
                let framed = |f: &mut dyn FnMut((usize, [f64; 3], f64))| {
                    if outside().next().is_some() {
                        outside().for_each(f);
                    } else {
                        rec().for_each(f);
                    }
                };
                let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
                framed(&mut |(_, c, r)| {
                    for k in 0..3 {
                        lo[k] = lo[k].min(c[k] - r);
                        hi[k] = hi[k].max(c[k] + r);
                    }
                });
                let centre = [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0);
                let axis = unit(sub(centre, p))
                    .or_else(|| unit(sub(first.1, p)))
                    .ok_or(Error::Layers(LayerError::Shadow))?;
                let (mut half, mut widest) = (0.0f64, first.0);
                framed(&mut |(i, c, r)| {
                    let d = sub(c, p);
                    let dist = length(d);
                    let a = libm::acos((dot(d, axis) / dist).clamp(-1.0, 1.0))
                        + libm::asin((r / dist).min(1.0));
                    if a > half {
                        (half, widest) = (a, i);
                    }
                });
                let half = libm::atan(libm::tan(half.min(1.5)) * shrink);
                if half.is_nan() || 2.0 * half >= MAX_MAP_FOV {
                    return Err(Error::Layers(LayerError::LightInside { object: widest }));
                }
                let far = far * (1.0 + 1.0 / 64.0);
                let mut near = f64::MAX;
                for (_, c, r) in rec().chain(casters()) {
                    let gap = length(sub(c, p)) - r;
                    if gap > 0.0 {
                        near = near.min(gap);
                    }
                }
                let near = (near * (1.0 - 1.0 / 64.0)).max(2.0 * far / MAX_DEPTH_RATIO);
                let projection = Projection::Perspective {
                    fov_y: 2.0 * half,
                    near,
                    far,
                };
                (p, add(p, axis), up_for(axis), projection)
            }
        };
        let s = |v: [f64; 3]| v.map(S::from_f64);
        let projection = match projection {
            Projection::Perspective { fov_y, near, far } => Projection::Perspective {
                fov_y: S::from_f64(fov_y),
                near: S::from_f64(near),
                far: S::from_f64(far),
            },
            Projection::Orthographic { height, near, far } => Projection::Orthographic {
                height: S::from_f64(height),
                near: S::from_f64(near),
                far: S::from_f64(far),
            },
        };
        Camera::look_at(s(eye), s(target), s(up), projection).map_err(Error::Camera)
    }
}

/// A shadow map of `N × N` texels, owned by the caller (a `static` on a device, as
/// [`crate::Layers`] are): the depth of the nearest caster at each texel as the light sees it,
/// drawn by [`crate::Renderer::shadow_map_pass`]. `N` is a power of two from 8 to 256
/// (`2·N²` bytes: 2 KB at 32, 8 KB at 64, 32 KB at 128), and at most the renderer's `W` and
/// `H` (the map's rows are drawn as rows of the renderer's strips).
#[derive(Clone, Debug)]
pub struct ShadowMap<const N: usize> {
    /// Row `r`, column `c`: the depth at texel centre `(c + ½, r + ½)` of the map (row 0 at the
    /// top of the light's view), u16, 0 = the light's near plane, 65535 = its far plane or no
    /// caster (step 1/65535 of the depth range: linear in distance for a directional light,
    /// `z/w` for a point light, as a frame's depth lines).
    pub(crate) depth: [[u16; N]; N],
    /// The light's matrix and the frame's lookup.
    pub(crate) setup: MapSetup,
}

/// A light-view image without depth of `N × N` texels, owned by the caller (the seeds' first
/// kind of shadow map): how much of each texel the casters cover as the light sees them, in
/// five levels. Drawn as a [`ShadowMap`] is ([`crate::Renderer::shadow_map_pass`]), and read
/// through [`crate::FrameOptions::shadow_map`] the same way, but with one byte a texel (`N²`
/// bytes: half a depth map's) and no depth compare per pixel, the cheapest read. Without
/// depth, a caster would shadow itself wherever the light sees it, so the casters receive
/// nothing: the image shadows the other receivers (the ground, a curved receiver below the
/// casters), wherever a caster covers them from the light.
///
/// Its soft edges are computed once per map rather than per pixel: with
/// [`ShadowFilter::Pcf2`] or [`ShadowFilter::Pcf3`] the pass blurs the image with a 3 × 3 box
/// (each texel the share of its 3 × 3 neighbourhood covered, in the five levels).
#[derive(Clone, Debug)]
pub struct ShadowImage<const N: usize> {
    /// Row `r`, column `c`: the cover at texel centre `(c + ½, r + ½)` (row 0 at the top of the
    /// light's view), u8 in 0..=4 (0 = no caster, 4 = covered, 1..=3 the blurred edges' quarter
    /// steps).
    pub(crate) cover: [[u8; N]; N],
    /// The light's matrix and the frame's lookup.
    pub(crate) setup: MapSetup,
}

/// What a [`ShadowMap`] and a [`ShadowImage`] hold besides their texels.
#[derive(Clone, Debug)]
pub(crate) struct MapSetup {
    /// World → map, homogeneous: `(x, y, d, w)` with texel coordinates `x/w`, `y/w` (0..N,
    /// texel `c` from `c` to `c + 1`) and depth `d/w` (0..=65535), in f64 from the camera the
    /// map was drawn with (its number type's values). Zero before the first pass.
    pub(crate) to_map: [[f64; 4]; 4],
    /// A pass drew the map.
    pub(crate) drawn: bool,
    /// What a mapped frame's spans read besides the texels (set when the frame is prepared).
    pub(crate) look: MapLookup,
}

/// The storage a shadow map pass draws into and a mapped frame reads: a [`ShadowMap`] (depth)
/// or a [`ShadowImage`] (cover, no depth). Sealed: these two only.
pub trait ShadowStore: sealed::Store {}
impl<const N: usize> ShadowStore for ShadowMap<N> {}
impl<const N: usize> ShadowStore for ShadowImage<N> {}

// The sealed trait's methods name the crate's own types: no one outside can call or implement
// them (the module is not public), which the `private_interfaces` lint cannot see.
#[allow(private_interfaces)]
pub(crate) mod sealed {
    use super::*;
    use crate::raster::span_map::MapView;
    /// What the pass and the frame do with a [`super::ShadowStore`].
    pub trait Store {
        /// The side, in texels.
        const SIDE: usize;
        /// Whether the texels are depths (else cover: the casters receive nothing).
        const DEPTH: bool;
        /// The matrix and the lookup.
        fn setup(&mut self) -> &mut MapSetup;
        /// Stores row `y` of the pass's depth lines (`SIDE` depths).
        fn put_row(&mut self, y: usize, depth: &[u16]);
        /// After the pass's last row, with the mapping's filter.
        fn finish(&mut self, filter: ShadowFilter);
        /// What the spans read.
        fn view(&self) -> MapView<'_>;
    }
}

#[allow(private_interfaces)]
impl<const N: usize> sealed::Store for ShadowMap<N> {
    const SIDE: usize = N;
    const DEPTH: bool = true;
    fn setup(&mut self) -> &mut MapSetup {
        &mut self.setup
    }
    fn put_row(&mut self, y: usize, depth: &[u16]) {
        self.depth[y].copy_from_slice(&depth[..N]);
    }
    fn finish(&mut self, _: ShadowFilter) {}
    fn view(&self) -> crate::raster::span_map::MapView<'_> {
        crate::raster::span_map::MapView {
            look: &self.setup.look,
            depth: self.depth.as_flattened(),
            cover: &[],
        }
    }
}

#[allow(private_interfaces)]
impl<const N: usize> sealed::Store for ShadowImage<N> {
    const SIDE: usize = N;
    const DEPTH: bool = false;
    fn setup(&mut self) -> &mut MapSetup {
        &mut self.setup
    }
    fn put_row(&mut self, y: usize, depth: &[u16]) {
        for (c, &d) in self.cover[y].iter_mut().zip(&depth[..N]) {
            *c = if d == u16::MAX { 0 } else { 4 };
        }
    }
    fn finish(&mut self, filter: ShadowFilter) {
        if filter != ShadowFilter::Nearest {
            blur3(&mut self.cover);
        }
    }
    fn view(&self) -> crate::raster::span_map::MapView<'_> {
        crate::raster::span_map::MapView {
            look: &self.setup.look,
            depth: &[],
            cover: self.cover.as_flattened(),
        }
    }
}

/// Blurs a cover image of levels 0 and 4 in place with a 3 × 3 box: each texel becomes its
/// neighbourhood's covered count (0..=9, outside the image uncovered) rounded to the five
/// levels (`round(4·count/9)`). Two row copies of at most 256 bytes on the stack.
fn blur3<const N: usize>(cover: &mut [[u8; N]; N]) {
    let covered = |row: &[u8], x: usize| -> usize {
        let lo = x.saturating_sub(1);
        let hi = (x + 1).min(N - 1);
        row[lo..=hi].iter().filter(|&&c| c == 4).count()
    };
    let mut above = [0u8; 256];
    let mut here = [0u8; 256];
    for y in 0..N {
        here[..N].copy_from_slice(&cover[y]);
        for x in 0..N {
            let mut count = covered(&here[..N], x);
            if y > 0 {
                count += covered(&above[..N], x);
            }
            if y + 1 < N {
                count += covered(&cover[y + 1], x);
            }
            cover[y][x] = crate::raster::span_map::LEVEL9[count];
        }
        above[..N].copy_from_slice(&here[..N]);
    }
}

impl<const N: usize> ShadowMap<N> {
    /// The map's bytes (`size_of::<Self>()`: the texels, the light's matrix and the blend
    /// tables).
    pub const RAM_BYTES: usize = core::mem::size_of::<Self>();
    const CHECK: () = assert!(
        N.is_power_of_two() && N >= 8 && N <= 256,
        "a shadow map's side N must be a power of two from 8 to 256"
    );

    /// An empty map (every texel 65535, no caster), as a `const fn` for a `static`.
    #[must_use]
    pub const fn new() -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::CHECK;
        ShadowMap {
            depth: [[u16::MAX; N]; N],
            setup: MapSetup::EMPTY,
        }
    }

    /// The texels, row by row (see the type's docs).
    #[must_use]
    pub fn depth(&self) -> &[[u16; N]; N] {
        &self.depth
    }

    /// The world → map matrix of the last pass (homogeneous `(x, y, d, w)`: texel `x/w`,
    /// `y/w` in 0..N, depth `d/w` in 0..=65535, as the map stores it), or `None` before the
    /// first pass.
    #[must_use]
    pub fn world_to_map(&self) -> Option<[[f64; 4]; 4]> {
        self.setup.world_to_map()
    }
}

impl<const N: usize> ShadowImage<N> {
    /// The image's bytes (`size_of::<Self>()`: the texels, the light's matrix and the blend
    /// tables).
    pub const RAM_BYTES: usize = core::mem::size_of::<Self>();
    const CHECK: () = assert!(
        N.is_power_of_two() && N >= 8 && N <= 256,
        "a shadow image's side N must be a power of two from 8 to 256"
    );

    /// An empty image (no caster), as a `const fn` for a `static`.
    #[must_use]
    pub const fn new() -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::CHECK;
        ShadowImage {
            cover: [[0; N]; N],
            setup: MapSetup::EMPTY,
        }
    }

    /// The texels' cover levels (0..=4), row by row (see the type's docs).
    #[must_use]
    pub fn cover(&self) -> &[[u8; N]; N] {
        &self.cover
    }

    /// The world → map matrix of the last pass (as [`ShadowMap::world_to_map`]).
    #[must_use]
    pub fn world_to_map(&self) -> Option<[[f64; 4]; 4]> {
        self.setup.world_to_map()
    }
}

impl<const N: usize> Default for ShadowImage<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl MapSetup {
    pub(crate) const EMPTY: MapSetup = MapSetup {
        to_map: [[0.0; 4]; 4],
        drawn: false,
        look: MapLookup::EMPTY,
    };

    fn world_to_map(&self) -> Option<[[f64; 4]; 4]> {
        self.drawn.then_some(self.to_map)
    }

    /// Records the camera a map of `n` texels a side was drawn with (see
    /// [`ShadowMap::world_to_map`]): its view and projection (aspect 1) in the number type,
    /// then the viewport's map to texels and depth steps.
    pub(crate) fn set_camera<S: Scalar>(&mut self, camera: &Camera<S>, n: usize) {
        let h = n as f64 / 2.0;
        self.to_map = viewport_rows(clip_f64(camera, S::ONE), [h, h, 65535.0]);
        self.drawn = true;
    }

    /// Sets the lookup of a frame drawn with `camera` at a `vw × vh` viewport, whose receivers'
    /// vertices end at `receivers_end`, with `mapping`'s shadow, for target colour `C`: the
    /// screen → map matrix (f64, once per frame, then integers), the darkening tables. False
    /// when the map was not drawn or the screen → map matrix does not exist (a singular
    /// camera).
    pub(crate) fn prepare_lookup<S: Scalar, C: crate::scene::color::TargetColor>(
        &mut self,
        n: usize,
        depth: bool,
        camera: &Camera<S>,
        (vw, vh): (usize, usize),
        mapping: &ShadowMapping<'_, S>,
        receivers_end: u16,
    ) -> bool {
        if !self.drawn {
            return false;
        }
        let aspect = S::from_f64(vw as f64 / vh.max(1) as f64);
        // World → screen (homogeneous): x = (x_c/w + 1)·8·vw subpixels, y = (1 − y_c/w)·8·vh,
        // d = z_c/w·65535·256.
        let (sx, sy) = (8.0 * vw as f64, 8.0 * vh as f64);
        let screen = viewport_rows(clip_f64(camera, aspect), [sx, sy, 65535.0 * 4096.0]);
        let Some(inv) = invert4(screen) else {
            return false;
        };
        let mut m = Mat4 { m: self.to_map }.mul(&Mat4 { m: inv }).m;
        // W > 0 in front of the light: checked at the screen's centre, halfway in depth.
        let mid = [sx, sy, 65535.0 * 2048.0, 1.0];
        if (0..4).map(|j| m[3][j] * mid[j]).sum::<f64>() < 0.0 {
            m = m.map(|r| r.map(|v| -v));
        }
        const RANGE: [f64; 4] = [32768.0, 32768.0, 268435456.0, 1.0];
        let largest = m
            .iter()
            .map(|r| (0..4).map(|j| r[j].abs() * RANGE[j]).sum::<f64>())
            .fold(0.0f64, f64::max);
        if !(largest.is_finite() && largest > 0.0) {
            return false;
        }
        let sigma = libm::floor(libm::log2((1u64 << 60) as f64 / largest));
        let scale = libm::pow(2.0, sigma);
        self.look.m = m.map(|r| r.map(|v| libm::round(v * scale) as i64));
        self.look.log2n = n.trailing_zeros() as u8;
        self.look.image = !depth;
        self.look.receivers_end = receivers_end;
        self.look.bias = mapping.bias;
        self.look.filter = mapping.filter;
        // Level k of 4 blends with α·k/4 (rounded).
        let a = mapping.alpha as u32;
        for (k, lut) in self.look.lut.iter_mut().enumerate() {
            let alpha = ((a * (k as u32 + 1) + 2) / 4) as u8;
            self.look.alphas[k + 1] = alpha;
            self.look.shadow =
                crate::raster::layer_rows::blend_tables::<C>(lut, mapping.color, alpha);
        }
        true
    }
}

/// `camera`'s world → clip matrix for a viewport of `aspect`, in f64 from the number type's
/// values.
fn clip_f64<S: Scalar>(camera: &Camera<S>, aspect: S) -> [[f64; 4]; 4] {
    let p = camera.projection.matrix(aspect).cast::<f64>();
    p.mul(&camera.view.cast::<f64>()).m
}

/// World → viewport (homogeneous) from world → `clip`: `x = (x_c/w + 1)·sx`,
/// `y = (1 − y_c/w)·sy` and `d = z_c/w·sd` for `[sx, sy, sd]`, then `w`.
fn viewport_rows(clip: [[f64; 4]; 4], [sx, sy, sd]: [f64; 3]) -> [[f64; 4]; 4] {
    [
        core::array::from_fn(|j| sx * (clip[0][j] + clip[3][j])),
        core::array::from_fn(|j| sy * (clip[3][j] - clip[1][j])),
        core::array::from_fn(|j| sd * clip[2][j]),
        clip[3],
    ]
}

/// The inverse of a 4 × 4 matrix (Gauss–Jordan with partial pivoting), or `None` when it is
/// singular or not finite.
fn invert4(m: [[f64; 4]; 4]) -> Option<[[f64; 4]; 4]> {
    let mut a = m;
    let mut inv = [[0.0; 4]; 4];
    for (i, row) in inv.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for col in 0..4 {
        let mut pivot = col;
        for r in col + 1..4 {
            if a[r][col].abs() > a[pivot][col].abs() {
                pivot = r;
            }
        }
        let p = a[pivot][col];
        if !(p.abs() > 1e-300 && p.is_finite()) {
            return None;
        }
        a.swap(col, pivot);
        inv.swap(col, pivot);
        for j in 0..4 {
            a[col][j] /= p;
            inv[col][j] /= p;
        }
        for r in 0..4 {
            if r != col {
                let k = a[r][col];
                for j in 0..4 {
                    a[r][j] -= k * a[col][j];
                    inv[r][j] -= k * inv[col][j];
                }
            }
        }
    }
    Some(inv)
}

impl<const N: usize> Default for ShadowMap<N> {
    fn default() -> Self {
        Self::new()
    }
}

/// `a` normalized, or `None` when it is zero or not finite.
fn unit(a: [f64; 3]) -> Option<[f64; 3]> {
    let l = length(a);
    (l.is_finite() && l > 0.0).then(|| scale(a, 1.0 / l))
}
/// An up vector not parallel to the view direction `d` (a unit vector): +Y, or +X when `d` is
/// within 8° of vertical.
fn up_for(d: [f64; 3]) -> [f64; 3] {
    if d[1].abs() > 0.99 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    }
}
