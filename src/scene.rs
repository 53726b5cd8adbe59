//! A scene: objects (mesh + model transform + material), a camera, lights and a background.
//!
//! A scanline renderer must know every triangle before it fills the first line, so a frame is
//! one [`Scene`] drawn in one strip pass by [`crate::Renderer::render`].

use crate::camera::Camera;
use crate::math::Mat4;
use crate::mesh::Mesh;
use crate::scalar::Scalar;
use crate::shade::{Light, Material};

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

/// Everything one frame draws, with `L` directional lights.
#[derive(Copy, Clone, Debug)]
pub struct Scene<'a, S, const L: usize> {
    /// The objects, drawn together (depth-tested against each other).
    pub objects: &'a [Object<'a, S>],
    /// The camera.
    pub camera: Camera<S>,
    /// The directional lights.
    pub lights: [Light<S>; L],
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
            background: [0; 3],
        }
    }
}
