//! A scene: objects (mesh + model transform + material), a camera, lights and a background.
//!
//! A scanline renderer must know every triangle before it fills the first line, so a frame is
//! one [`Scene`] drawn in one strip pass by [`crate::Renderer::render`].

pub(crate) mod adjacency;
pub(crate) mod camera;
pub(crate) mod color;
pub(crate) mod effects;
pub(crate) mod mesh;
pub(crate) mod shade;
pub(crate) mod shapes;
pub(crate) mod texture;
pub(crate) mod textured_shapes;
pub(crate) mod tone;

use crate::num::math::Mat4;
use crate::num::scalar::Scalar;
use crate::scene::camera::Camera;
use crate::scene::effects::{Effects, Fog, PointLight};
use crate::scene::mesh::Mesh;
use crate::scene::shade::{Light, Material};

/// One mesh placed in the world.
#[derive(Copy, Clone, Debug)]
pub struct Object<'a, S> {
    /// The mesh (borrowed; may live in flash).
    pub mesh: Mesh<'a, S>,
    /// Model → world transform.
    pub transform: Mat4<S>,
    /// Surface properties and shading mode.
    pub material: Material<S>,
}

/// Everything one frame draws, with `L` directional lights, any number of point lights and
/// optional fog.
#[derive(Copy, Clone, Debug)]
pub struct Scene<'a, S, const L: usize> {
    /// The objects, drawn together (depth-tested against each other).
    pub objects: &'a [Object<'a, S>],
    /// The camera.
    pub camera: Camera<S>,
    /// The directional lights.
    pub lights: [Light<S>; L],
    /// Point lights and fog ([`Effects`], borrowed; `None` by default: a scene without them
    /// pays one pointer).
    pub effects: Option<&'a Effects<'a, S>>,
    /// Background colour, 8 bits per channel.
    pub background: [u8; 3],
}

impl<'a, S: Scalar, const L: usize> Scene<'a, S, L> {
    /// A scene on a black background.
    #[must_use]
    pub fn new(objects: &'a [Object<'a, S>], camera: Camera<S>, lights: [Light<S>; L]) -> Self {
        Scene {
            objects,
            camera,
            lights,
            effects: None,
            background: [0; 3],
        }
    }

    /// This scene with point lights and fog.
    #[must_use]
    pub fn with_effects(self, effects: &'a Effects<'a, S>) -> Self {
        Scene {
            effects: Some(effects),
            ..self
        }
    }

    /// The point lights (none without [`Scene::effects`]).
    #[must_use]
    pub fn point_lights(&self) -> &'a [PointLight<S>] {
        self.effects.map_or(&[], |e| e.point_lights)
    }

    /// The fog (none without [`Scene::effects`]).
    #[must_use]
    pub fn fog(&self) -> Option<&'a Fog<S>> {
        self.effects.and_then(|e| e.fog.as_ref())
    }

    /// The tone map (none without [`Scene::effects`]).
    #[must_use]
    pub fn tone(&self) -> Option<&'a crate::ToneMap<S>> {
        self.effects.and_then(|e| e.tone.as_ref())
    }

    /// This scene on background colour `background`.
    #[must_use]
    pub fn with_background(self, background: [u8; 3]) -> Self {
        Scene { background, ..self }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::camera::Projection;
    use crate::scene::shade::Shading;
    use crate::Renderer;
    use embedded_graphics::mock_display::MockDisplay;
    use embedded_graphics_core::pixelcolor::Rgb888;

    fn quad(z: f64, x0: f64) -> [[f64; 3]; 4] {
        [
            [x0, -1.0, z],
            [x0 + 2.0, -1.0, z],
            [x0 + 2.0, 1.0, z],
            [x0, 1.0, z],
        ]
    }

    /// Two overlapping objects at different depths: the nearer one wins whatever their order
    /// in the scene, in one pass.
    #[test]
    fn objects_are_depth_tested_against_each_other_in_any_order() {
        let idx = [[0u16, 1, 2], [0, 2, 3]];
        let near = quad(0.5, -1.5);
        let far = quad(-0.5, -0.5);
        let mat = |c: [u8; 3]| Material {
            color: c,
            ambient: 1.0,
            diffuse: 0.0,
            specular: 0.0,
            shininess: 1,
            shading: Shading::Flat,
            texture: None,
            alpha: 255,
        };
        let near_s: &[[f64; 3]] = &near;
        let far_s: &[[f64; 3]] = &far;
        let a = Object {
            mesh: Mesh::new(near_s, &idx).unwrap(),
            transform: Mat4::identity(),
            material: mat([255, 0, 0]),
        };
        let b = Object {
            mesh: Mesh::new(far_s, &idx).unwrap(),
            transform: Mat4::identity(),
            material: mat([0, 0, 255]),
        };
        let cam = Camera::look_at(
            [0.0, 0.0, 4.0],
            [0.0; 3],
            [0.0, 1.0, 0.0],
            Projection::Perspective {
                fov_y: 1.0,
                near: 0.1,
                far: 10.0,
            },
        )
        .unwrap();
        let light = [Light::white([0.0, 0.0, 1.0])];
        let render = |objs: &[Object<'_, f64>]| {
            let scene = Scene::new(objs, cam, light);
            let mut r = Renderer::<f64, Rgb888, 32, 32, 16, 16, 8>::new();
            let mut d = MockDisplay::<Rgb888>::new();
            r.render(&scene, &mut d).unwrap();
            d
        };
        let ab = render(&[a, b]);
        let ba = render(&[b, a]);
        assert_eq!(ab, ba);
        // Where they overlap (centre), the nearer red quad shows.
        assert_eq!(
            ab.get_pixel(embedded_graphics_core::geometry::Point::new(16, 16)),
            Some(Rgb888::new(255, 0, 0))
        );
    }
}
