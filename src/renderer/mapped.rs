//! The shadow map's pass ([`Renderer::shadow_map_pass`]): the casters through the renderer's
//! geometry stage from the light's camera, at a viewport of the map's size, and through its
//! strip pass; each strip's depth lines are the map's rows.

use crate::error::LayerError;
use crate::num::scalar::Scalar;
use crate::raster::shadow_map::{ShadowMapping, ShadowStore};
use crate::renderer::*;
use crate::scene::color::TargetColor;
use crate::scene::shade::Material;
use crate::scene::{Object, Scene};

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
        const ZL: usize,
    > Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA, ZL>
{
    /// Draws `mapping`'s casters into `map`, depth only, from the light's camera
    /// ([`ShadowMapping::light_camera`]): through this renderer's geometry stage (the same
    /// transform, clipping, culling of faces turned away from the light, and overflow policy as
    /// a frame) at an `N × N` viewport, and its strip pass (the same fill rule: a texel is
    /// covered when its centre is), each strip's depth lines copied into the map's rows. The
    /// casters' materials are not used (no lighting, no texture). Returns the pass's
    /// statistics.
    ///
    /// The pass uses the renderer's stores: a frame prepared before it is given up (prepare
    /// the frame after the map). The viewport and options are as they were.
    ///
    /// # Errors
    ///
    /// [`Error::NoDepthLines`] on a renderer without depth lines;
    /// [`LayerError::MapLargerThanViewport`] when `N` exceeds `W` or `H`; the errors of
    /// [`ShadowMapping::light_camera`]; and a frame's [`Error::Shortfall`] (under
    /// [`OverflowPolicy::Error`]) for the casters as the light sees them. The map is left
    /// as it was on any error.
    pub fn shadow_map_pass<const L: usize, M: ShadowStore>(
        &mut self,
        scene: &Scene<'_, S, L>,
        mapping: &ShadowMapping<'_, S>,
        map: &mut M,
    ) -> Result<Stats, Error<core::convert::Infallible>> {
        let n = M::SIDE;
        if ZL == 0 {
            return Err(Error::NoDepthLines);
        }
        if n > W || n > H {
            return Err(Error::Layers(LayerError::MapLargerThanViewport {
                size: n,
                width: W,
                height: H,
            }));
        }
        let camera = mapping.light_camera(scene, n)?;
        let want = self.want_viewport;
        self.want_viewport = (n as u16, n as u16);
        let result = self.map_geometry(scene, mapping, &camera);
        self.want_viewport = want;
        if let Err(e) = result {
            self.take_viewport();
            return Err(e);
        }
        while let Some((y0, n)) = self.draw_strip::<NoProbe, true>(None, LINES, &mut NoProbe) {
            for (y, line) in (y0..y0 + n).zip(&self.ras.depth) {
                map.put_row(y, line);
            }
        }
        map.finish(mapping.filter);
        map.setup().set_camera(&camera, M::SIDE);
        let stats = self.ras.stats;
        self.take_viewport();
        Ok(stats)
    }

    /// A mapped frame's geometry ([`crate::FrameOptions::shadow_map`]): the map pass, then the
    /// frame's geometry stage with the receivers' objects first (their vertices' end is how
    /// the strip pass tells their triangles), then the map's lookup for this frame's camera
    /// and viewport.
    pub(crate) fn geometry_mapped<P: Probe, const L: usize, M: ShadowStore>(
        &mut self,
        scene: &Scene<'_, S, L>,
        mapping: &ShadowMapping<'_, S>,
        map: &mut M,
        probe: &mut P,
    ) -> Result<Stats, Error<core::convert::Infallible>> {
        if ZL == 0 {
            return Err(Error::NoDepthLines);
        }
        // (A [`crate::color::TriangleId`] target records the triangles only: nothing is
        // darkened, as in a layered frame.)
        let ids = C::triangle_id(0).is_some();
        if !ids && C::from_channels([0; 3]).channels().is_none() {
            return Err(Error::Layers(LayerError::Blending));
        }
        let n = scene.objects.len();
        if let Some(&i) = mapping
            .receivers
            .iter()
            .chain(mapping.casters)
            .find(|&&i| i >= n)
        {
            return Err(Error::Layers(LayerError::NoSuchObject { index: i }));
        }
        // (An image has no depth: its casters would shadow themselves, and receive nothing.)
        let receives =
            |i: usize| mapping.receives(scene, i) && (M::DEPTH || !mapping.casters.contains(&i));
        if let Some(i) = (0..n).find(|&i| scene.objects[i].material.needs_attribute_stores()) {
            return Err(Error::Layers(LayerError::MapShading { object: i }));
        }
        if XA == 0 {
            let object = (0..n).find(|&i| receives(i)).unwrap_or(0);
            return Err(Error::AttributeStore {
                object,
                vertices_needed: 0,
                vertex_capacity: XV,
                active_needed: 1,
                active_capacity: XA,
            });
        }
        self.shadow_map_pass(scene, mapping, map)?;
        self.frame_start();
        let c = self.geo.frame_begin(scene, false)?;
        let mut f = crate::geometry::Frame::default();
        for (i, o) in scene.objects.iter().enumerate() {
            if receives(i) {
                self.geo.frame_object(&c, &mut f, scene, o, i, probe)?;
            }
        }
        let end = if ids {
            0
        } else {
            self.geo.verts.len().min(u16::MAX as usize) as u16
        };
        for (i, o) in scene.objects.iter().enumerate() {
            if !receives(i) {
                self.geo.frame_object(&c, &mut f, scene, o, i, probe)?;
            }
        }
        let stats =
            self.geo
                .frame_end(scene, &c, &mut f, ACTIVE, self.ras.overflow, Self::CAPACITY)?;
        self.frame_ready(scene, stats);
        let viewport = (self.geo.vw, self.geo.vh);
        if !map.setup().prepare_lookup::<S, C>(
            M::SIDE,
            M::DEPTH,
            &scene.camera,
            viewport,
            mapping,
            end,
        ) {
            self.ras.next_row = self.geo.vh;
            return Err(Error::Layers(LayerError::Shadow));
        }
        Ok(stats)
    }

    /// The map pass's geometry stage: the casters, flat and unlit, from `camera`.
    fn map_geometry<const L: usize>(
        &mut self,
        scene: &Scene<'_, S, L>,
        mapping: &ShadowMapping<'_, S>,
        camera: &crate::Camera<S>,
    ) -> Result<Stats, Error<core::convert::Infallible>> {
        // No object of its own (the casters are given one by one with their index, under a
        // material of one colour: no normals, attributes or Phong entries needed).
        let light_scene = Scene {
            objects: &[],
            camera: *camera,
            lights: scene.lights,
            effects: None,
            background: [0; 3],
        };
        let material = Material::matte([255; 3], S::ONE, S::ZERO).flat();
        self.frame_start();
        let c = self.geo.frame_begin(&light_scene, true)?;
        let mut f = crate::geometry::Frame::default();
        for &i in mapping.casters {
            let o = &scene.objects[i];
            let caster = Object {
                mesh: o.mesh,
                transform: o.transform,
                material,
            };
            self.geo
                .frame_object(&c, &mut f, &light_scene, &caster, i, &mut NoProbe)?;
        }
        let stats = self.geo.frame_end(
            &light_scene,
            &c,
            &mut f,
            ACTIVE,
            self.ras.overflow,
            Self::CAPACITY,
        )?;
        self.frame_ready(&light_scene, stats);
        Ok(stats)
    }
}

#[cfg(test)]
mod tests {
    use crate::error::{Error, LayerError};
    use crate::num::math::Mat4;
    use crate::num::scalar::Fx;
    use crate::num::scalar::Scalar;
    use crate::raster::shadow::ShadowLight;
    use crate::raster::shadow_map::{ShadowMap, ShadowMapping, MAP_MARGIN};
    use crate::scene::shade::{Light, Material};
    use crate::scene::shapes::Shape;
    use crate::scene::{Object, Scene};
    use crate::{Camera, Projection, Renderer};
    use embedded_graphics_core::pixelcolor::Rgb565;

    type Q = Fx<fixed::types::I16F16>;

    /// A 4 × 4 ground (object 0) and a unit cube 1.5 above it (object 1), seen from the front.
    fn with_scene<S: Scalar, R>(
        f: impl FnOnce(&Scene<'_, S, 1>, &Shape<S, 4, 2>, &Shape<S, 24, 12>) -> R,
    ) -> R {
        let ground = Shape::<S, 4, 2>::plane(4.0, 4.0, 1, 1).unwrap();
        let cube = Shape::<S, 24, 12>::cube(0.5).unwrap();
        let m = Material::matte([200, 200, 200], S::from_f64(0.2), S::from_f64(0.8));
        let objects = [
            Object {
                mesh: ground.mesh(),
                transform: Mat4::identity(),
                material: m,
            },
            Object {
                mesh: cube.mesh(),
                transform: Mat4::translate([0.0, 1.5, 0.0].map(S::from_f64)),
                material: m,
            },
        ];
        let camera = Camera::look_at(
            [0.0, 4.0, 6.0].map(S::from_f64),
            [S::ZERO; 3],
            [0.0, 1.0, 0.0].map(S::from_f64),
            Projection::Perspective {
                fov_y: S::from_f64(0.9),
                near: S::from_f64(0.5),
                far: S::from_f64(20.0),
            },
        )
        .unwrap();
        let scene = Scene::new(
            &objects,
            camera,
            [Light::white([-1.0, 2.0, 1.0].map(S::from_f64))],
        );
        f(&scene, &ground, &cube)
    }

    /// The map's rows are, texel for texel, the depth lines of an ordinary frame of the casters
    /// (flat, unlit) drawn from the light's camera at an `N × N` viewport in one strip: the
    /// same geometry stage, clipping and fill rule.
    fn map_is_a_frame<S: Scalar>(light: ShadowLight<S>) {
        with_scene::<S, _>(|scene, _, _| {
            let mapping = ShadowMapping::new(light, &[1], &[0]);
            let mut r = Renderer::<S, Rgb565, 64, 64, 256, 256, 32, 8>::new();
            let mut map = ShadowMap::<32>::new();
            let stats = r.shadow_map_pass(scene, &mapping, &mut map).unwrap();
            assert!(stats.drawn > 0);
            assert_eq!(r.viewport(), (64, 64));
            let camera = mapping.light_camera(scene, 32).unwrap();
            let o = scene.objects[1];
            let caster = [Object {
                material: Material::matte([255; 3], S::ONE, S::ZERO).flat(),
                ..o
            }];
            let light_scene = Scene::new(&caster, camera, scene.lights);
            let mut one = Renderer::<S, Rgb565, 32, 32, 256, 256, 32, 32>::new();
            one.geometry::<core::convert::Infallible, _, 1>(
                &light_scene,
                &mut crate::stats::NoProbe,
            )
            .unwrap();
            one.draw_strip::<crate::stats::NoProbe, true>(None, 32, &mut crate::stats::NoProbe)
                .unwrap();
            let covered = map
                .depth()
                .iter()
                .flatten()
                .filter(|&&d| d != u16::MAX)
                .count();
            assert!(covered > 20, "{covered} texels covered");
            for (k, row) in map.depth().iter().enumerate() {
                assert_eq!(row[..], one.ras.depth[k][..], "row {k}");
            }
        });
    }

    fn to<S: Scalar>(l: ShadowLight<f64>) -> ShadowLight<S> {
        match l {
            ShadowLight::Directional(d) => ShadowLight::Directional(d.map(S::from_f64)),
            ShadowLight::Point(p) => ShadowLight::Point(p.map(S::from_f64)),
        }
    }

    #[test]
    fn map_rows_are_the_light_frames_depth_lines() {
        for light in [
            ShadowLight::Directional([1.0, 3.0, 0.5]),
            ShadowLight::Point([1.0, 5.0, 0.5]),
        ] {
            map_is_a_frame::<f64>(light);
            map_is_a_frame::<f32>(to::<f32>(light));
            map_is_a_frame::<Q>(to::<Q>(light));
        }
    }

    /// The fitted view holds the caster (its bounding sphere, so its corners) at least
    /// [`MAP_MARGIN`] texels inside the map, and the receiver in depth range.
    #[test]
    fn fitted_view_frames_the_casters() {
        for light in [
            ShadowLight::Directional([1.0, 3.0, 0.5]),
            ShadowLight::Directional([0.0, 1.0, 0.0]),
            ShadowLight::Point([1.0, 5.0, 0.5]),
        ] {
            with_scene::<f64, _>(|scene, _, _| {
                let mapping = ShadowMapping::new(light, &[1], &[0]);
                let mut r = Renderer::<f64, Rgb565, 64, 64, 256, 256, 32, 8>::new();
                let mut map = ShadowMap::<32>::new();
                assert!(map.world_to_map().is_none());
                r.shadow_map_pass(scene, &mapping, &mut map).unwrap();
                let m = map.world_to_map().unwrap();
                let to_map = |p: [f64; 3]| {
                    let h: [f64; 4] = core::array::from_fn(|i| {
                        m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3]
                    });
                    [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
                };
                let lo = MAP_MARGIN as f64 - 1e-6;
                let hi = 32.0 - MAP_MARGIN as f64 + 1e-6;
                for k in 0..8 {
                    let bit = |b: usize| if k >> b & 1 == 1 { 0.5 } else { -0.5 };
                    let p = [bit(0), 1.5 + bit(1), bit(2)];
                    let [x, y, _] = to_map(p);
                    assert!(
                        x > lo && x < hi && y > lo && y < hi,
                        "{light:?}: {p:?} at {x}, {y}"
                    );
                }
                for p in [
                    [-2.0, 0.0, -2.0],
                    [2.0, 0.0, -2.0],
                    [2.0, 0.0, 2.0],
                    [-2.0, 0.0, 2.0],
                ] {
                    let [_, _, d] = to_map(p);
                    assert!((0.0..=65535.0).contains(&d), "{light:?}: {p:?} depth {d}");
                }
                // The cube's corners are in depth range, nearer the light than the ground under it.
                for p in [[0.5, 2.0, 0.5], [-0.5, 1.0, -0.5]] {
                    let [_, _, d] = to_map(p);
                    assert!((0.0..65535.0).contains(&d), "{light:?}: {p:?} depth {d}");
                    assert!(d < to_map([p[0], 0.0, p[2]])[2]);
                }
                // The texel of the top face's centre holds the top face's depth (to the depth's
                // change over half a texel: up to a few hundred steps from a near point light),
                // nearer than the ground under it.
                let [x, y, d] = to_map([0.0, 2.0, 0.0]);
                let texel = map.depth()[y as usize][x as usize];
                let ground = to_map([0.0, 0.0, 0.0])[2];
                assert!(
                    (texel as f64 - d).abs() < 1024.0,
                    "{light:?}: {texel} vs {d}"
                );
                assert!(
                    (texel as f64) < ground - 1024.0,
                    "{light:?}: {texel} vs ground {ground}"
                );
            });
        }
    }

    #[test]
    fn map_errors() {
        with_scene::<f32, _>(|scene, _, _| {
            let dir = ShadowLight::Directional([1.0, 3.0, 0.5]);
            let mut small = Renderer::<f32, Rgb565, 48, 16, 256, 256, 32, 8>::new();
            let mut map = ShadowMap::<32>::new();
            assert_eq!(
                small.shadow_map_pass(scene, &ShadowMapping::new(dir, &[1], &[0]), &mut map),
                Err(Error::Layers(LayerError::MapLargerThanViewport {
                    size: 32,
                    width: 48,
                    height: 16
                }))
            );
            let mut r = Renderer::<f32, Rgb565, 64, 64, 256, 256, 32, 8>::new();
            let err =
                |m: ShadowMapping<'_, f32>,
                 r: &mut Renderer<f32, Rgb565, 64, 64, 256, 256, 32, 8>| {
                    let mut map = ShadowMap::<32>::new();
                    let e = r.shadow_map_pass(scene, &m, &mut map).unwrap_err();
                    assert!(
                        map.world_to_map().is_none()
                            && map.depth().iter().flatten().all(|&d| d == u16::MAX)
                    );
                    e
                };
            let layer = |e| Error::Layers(e);
            assert_eq!(
                err(ShadowMapping::new(dir, &[2], &[0]), &mut r),
                layer(LayerError::NoSuchObject { index: 2 })
            );
            assert_eq!(
                err(
                    ShadowMapping::new(ShadowLight::Point([0.0, 1.5, 0.0]), &[0], &[1]),
                    &mut r
                ),
                layer(LayerError::LightInside { object: 1 })
            );
            // Just above the ground's middle: the ground spreads over nearly 180°.
            assert_eq!(
                err(
                    ShadowMapping::new(ShadowLight::Point([0.0, 0.05, 0.0]), &[1], &[0]),
                    &mut r
                ),
                layer(LayerError::LightInside { object: 0 })
            );
            assert_eq!(
                err(
                    ShadowMapping::new(ShadowLight::Directional([0.0; 3]), &[1], &[0]),
                    &mut r
                ),
                layer(LayerError::Shadow)
            );
            assert_eq!(
                err(
                    ShadowMapping::new(ShadowLight::Directional([f32::NAN, 1.0, 0.0]), &[1], &[0]),
                    &mut r
                ),
                layer(LayerError::Shadow)
            );
            // A scene of translucent objects only has no receiver to fit to.
            let clear: [Object<'_, f32>; 2] = core::array::from_fn(|i| Object {
                material: Material {
                    alpha: 100,
                    ..scene.objects[i].material
                },
                ..scene.objects[i]
            });
            let glass = Scene {
                objects: &clear,
                ..*scene
            };
            let mut map = ShadowMap::<32>::new();
            assert_eq!(
                r.shadow_map_pass(&glass, &ShadowMapping::new(dir, &[1], &[]), &mut map),
                Err(layer(LayerError::EmptyBounds))
            );
            // After the errors, a pass succeeds and the viewport is the renderer's.
            r.shadow_map_pass(scene, &ShadowMapping::new(dir, &[1], &[]), &mut map)
                .unwrap();
            assert_eq!(r.viewport(), (64, 64));
        });
    }
}
