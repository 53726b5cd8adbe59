//! The built-in scenes used by the examples, tests and benchmarks.
//!
//! The **default scene** is the torus peers are measured on: R = 1.0, r = 0.4, 32 × 16
//! segments (512 vertices, 1024 triangles), rotated 30° about X then 20° about Y; eye
//! (0, 1.2, 3) looking at the origin, up +Y, vertical field of view 45°, near 0.1, far 10;
//! one white light toward (−1, 1, 1); ambient 0.15, diffuse 0.85, no specular; colour
//! (255, 160, 64) on black; Gouraud; 240 × 240.

use crate::camera::{Camera, CameraError, Projection};
use crate::math::Mat4;
use crate::scalar::Scalar;
use crate::scene::Object;
use crate::shade::{Light, Material};
use crate::shapes::{Shape, ShapeError};

/// The default torus mesh.
pub type TorusShape<S> = Shape<S, 512, 1024>;

/// Degrees to radians in `S`.
#[must_use]
pub fn deg<S: Scalar>(d: f64) -> S {
    S::from_f64(d * core::f64::consts::PI / 180.0)
}

/// The default torus: R = 1.0, r = 0.4, 32 × 16 segments.
pub fn torus<S: Scalar>() -> Result<TorusShape<S>, ShapeError> {
    Shape::torus(1.0, 0.4, 32, 16)
}

/// The default model transform: 30° about X, then 20° about Y, then `spin_deg` about Y.
#[must_use]
pub fn torus_transform<S: Scalar>(spin_deg: f64) -> Mat4<S> {
    Mat4::rotate_x(deg(30.0))
        .then(&Mat4::rotate_y(deg(20.0)))
        .then(&Mat4::rotate_y(deg(spin_deg)))
}

/// The default material: colour (255, 160, 64), ambient 0.15, diffuse 0.85, Gouraud.
#[must_use]
pub fn torus_material<S: Scalar>() -> Material<S> {
    Material::matte([255, 160, 64], S::from_f64(0.15), S::from_f64(0.85))
}

/// The default torus placed in the world.
#[must_use]
pub fn torus_object<S: Scalar>(shape: &TorusShape<S>) -> Object<'_, S> {
    Object {
        mesh: shape.mesh(),
        transform: torus_transform(0.0),
        material: torus_material(),
    }
}

/// The default camera: eye (0, 1.2, 3), target origin, up +Y, 45° vertical field of view,
/// near 0.1, far 10.
pub fn camera<S: Scalar>() -> Result<Camera<S>, CameraError> {
    let f = S::from_f64;
    Camera::look_at(
        [f(0.0), f(1.2), f(3.0)],
        [S::ZERO; 3],
        [S::ZERO, S::ONE, S::ZERO],
        Projection::Perspective {
            fov_y: deg(45.0),
            near: f(0.1),
            far: f(10.0),
        },
    )
}

/// The default light: white, toward (−1, 1, 1).
#[must_use]
pub fn lights<S: Scalar>() -> [Light<S>; 1] {
    [Light::white([-S::ONE, S::ONE, S::ONE])]
}

/// A renderer sized for the default scene at 240 × 240 with a one-line strip: 512 vertices,
/// 512 triangles (a full turn about Y keeps at most 466 after culling) and 64 active triangles
/// per row (at most 61 seen). `cargo run --release --example render` prints its RAM.
pub type TorusRenderer<S, C> = crate::Renderer<S, C, 240, 240, 512, 512, 64>;
