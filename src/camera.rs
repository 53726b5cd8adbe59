//! The camera: a look-at view transform (U-V-N) and a perspective or parallel projection.
//!
//! View space is right-handed with the camera at the origin looking down −Z, +Y up. Clip space
//! keeps `x, y ∈ [−w, w]` and **`z ∈ [0, w]`** (near plane at z = 0, far plane at z = w), so the
//! near plane test is `z ≥ 0` and stored depth is `z/w · 65535` (0 = nearest).

use crate::math::{cross, dot, normalize, sub, Mat4, Vec3};
use crate::scalar::Scalar;

/// How view space is projected.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum Projection<S> {
    /// Perspective projection.
    Perspective {
        /// Vertical field of view in radians (0, π).
        fov_y: S,
        /// Distance to the near plane (> 0).
        near: S,
        /// Distance to the far plane (> near).
        far: S,
    },
    /// Parallel (orthographic) projection.
    Orthographic {
        /// Height of the view volume in world units (> 0); its width follows from the aspect.
        height: S,
        /// Distance to the near plane (may be negative or zero).
        near: S,
        /// Distance to the far plane (> near).
        far: S,
    },
}

/// A camera: view transform plus projection.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Camera<S> {
    /// World → view space.
    pub view: Mat4<S>,
    /// The projection.
    pub projection: Projection<S>,
    /// The eye position in world space (used by specular lighting).
    pub eye: Vec3<S>,
}

/// Why a camera could not be built.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum CameraError {
    /// `eye` equals `target`: no view direction.
    EyeAtTarget,
    /// `up` is parallel to the view direction (or zero).
    UpParallelToView,
    /// near/far/fov/height out of range (near ≤ 0 for perspective, far ≤ near, fov ∉ (0, π),
    /// height ≤ 0) or not finite.
    BadProjection,
}

impl<S: Scalar> Camera<S> {
    /// A camera at `eye` looking at `target` with `up` roughly up, using the U-V-N frame of the
    /// seeds: `n = normalize(eye − target)` (view +Z points away from what is seen),
    /// `u = normalize(up × n)` (screen right), `v = n × u` (screen up).
    pub fn look_at(
        eye: Vec3<S>,
        target: Vec3<S>,
        up: Vec3<S>,
        projection: Projection<S>,
    ) -> Result<Self, CameraError> {
        let zero = [S::ZERO; 3];
        let n = normalize(sub(eye, target));
        if n == zero {
            return Err(CameraError::EyeAtTarget);
        }
        let u = normalize(cross(up, n));
        if u == zero {
            return Err(CameraError::UpParallelToView);
        }
        let v = cross(n, u);
        let z = S::ZERO;
        let view = Mat4 {
            m: [
                [u[0], u[1], u[2], -dot(u, eye)],
                [v[0], v[1], v[2], -dot(v, eye)],
                [n[0], n[1], n[2], -dot(n, eye)],
                [z, z, z, S::ONE],
            ],
        };
        projection.check()?;
        Ok(Camera {
            view,
            projection,
            eye,
        })
    }
}

impl<S: Scalar> Projection<S> {
    fn check(&self) -> Result<(), CameraError> {
        let ok = match *self {
            Projection::Perspective { fov_y, near, far } => {
                let pi = S::from_f64(core::f64::consts::PI);
                [fov_y, near, far].iter().all(|v| v.is_valid())
                    && fov_y > S::ZERO
                    && fov_y < pi
                    && near > S::ZERO
                    && far > near
            }
            Projection::Orthographic { height, near, far } => {
                [height, near, far].iter().all(|v| v.is_valid()) && height > S::ZERO && far > near
            }
        };
        if ok {
            Ok(())
        } else {
            Err(CameraError::BadProjection)
        }
    }

    /// The projection matrix for a viewport of `aspect` = width / height, mapping view space to
    /// clip space with `z_clip ∈ [0, w]` between the near and far planes.
    ///
    /// Orthographic: `x_c = 2/(height·aspect)·x`, `y_c = 2/height·y`,
    /// `z_c = (−z − near)/(far − near)`, `w_c = 1`. In fixed point the depth row's entries are
    /// ±1/(far − near), so the stored depth of a point at view distance `z` is exact only to
    /// about `|z| · 2⁻¹⁷/(far − near) · 65535` steps (Q16.16; about 9 steps at the far plane of
    /// a camera with near 1, far 19). That error is the same affine map for every surface, so
    /// depth *ordering* is unaffected; scaling the matrix to remove it would shrink the x/y
    /// range instead.
    ///
    /// Perspective: `x_c = f/aspect·x`, `y_c = f·y`, `z_c = A·z + B`, `w_c = −z` with
    /// `f = 1/tan(fov_y/2)`, `A = far/(near − far)`, `B = near·A` (= `near·far/(near − far)`,
    /// computed without the product `near·far`, which overflows fixed point for large scenes).
    #[must_use]
    pub fn matrix(&self, aspect: S) -> Mat4<S> {
        let z = S::ZERO;
        let one = S::ONE;
        let two = one + one;
        match *self {
            Projection::Perspective { fov_y, near, far } => {
                let f = one / (fov_y / two).tan();
                let a = far / (near - far);
                let b = near * a;
                Mat4 {
                    m: [
                        [f / aspect, z, z, z],
                        [z, f, z, z],
                        [z, z, a, b],
                        [z, z, -one, z],
                    ],
                }
            }
            Projection::Orthographic { height, near, far } => {
                let sy = two / height;
                let d = far - near;
                Mat4 {
                    m: [
                        [sy / aspect, z, z, z],
                        [z, sy, z, z],
                        [z, z, -one / d, -near / d],
                        [z, z, z, one],
                    ],
                }
            }
        }
    }

    /// True for perspective projections.
    #[must_use]
    pub fn is_perspective(&self) -> bool {
        matches!(self, Projection::Perspective { .. })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Fx;
    use fixed::types::I16F16;

    fn frustum_maps_near_to_0_and_far_to_w<S: Scalar>(tol: f64) {
        let p = Projection::Perspective {
            fov_y: S::from_f64(1.0),
            near: S::from_f64(0.5),
            far: S::from_f64(8.0),
        };
        let m = p.matrix(S::ONE);
        let at = |d: f64| m.transform_point([S::ZERO, S::ZERO, S::from_f64(-d)]);
        let n = at(0.5);
        assert!(n[2].to_f64().abs() <= tol, "{n:?}");
        assert!((n[3].to_f64() - 0.5).abs() <= tol);
        let f = at(8.0);
        assert!((f[2].to_f64() - f[3].to_f64()).abs() <= tol * 8.0, "{f:?}");
    }

    #[test]
    fn depth_range_is_zero_to_w() {
        frustum_maps_near_to_0_and_far_to_w::<f64>(1e-12);
        frustum_maps_near_to_0_and_far_to_w::<f32>(1e-6);
        frustum_maps_near_to_0_and_far_to_w::<Fx<I16F16>>(8.0 / 65536.0);
    }

    #[test]
    fn large_near_and_far_do_not_overflow_fixed_point() {
        // near·far = 1e6 is far outside Q16.16; the matrix must still map near → 0, far → w.
        type Q = Fx<I16F16>;
        let p = Projection::Perspective {
            fov_y: Q::lit(0.8),
            near: Q::lit(100.0),
            far: Q::lit(10000.0),
        };
        let m = p.matrix(Q::ONE);
        let at = |d: f64| m.transform_point([Q::ZERO, Q::ZERO, Q::lit(-d)]);
        let n = at(100.0);
        assert!(n[2].to_f64().abs() < 0.01, "{n:?}");
        let f = at(10000.0);
        assert!((f[2].to_f64() / f[3].to_f64() - 1.0).abs() < 1e-3, "{f:?}");
    }

    #[test]
    fn look_at_puts_target_on_negative_z() {
        let proj = Projection::Perspective {
            fov_y: 0.8,
            near: 0.1,
            far: 10.0,
        };
        let cam = Camera::<f64>::look_at([0.0, 1.2, 3.0], [0.0; 3], [0.0, 1.0, 0.0], proj).unwrap();
        let t = cam.view.transform_point([0.0; 3]);
        assert!(t[0].abs() < 1e-12 && t[1].abs() < 1e-12);
        assert!((t[2] + libm::sqrt(1.44 + 9.0)).abs() < 1e-12);
        // World up stays up on screen.
        let up = cam.view.transform_dir([0.0, 1.0, 0.0]);
        assert!(up[1] > 0.0);
    }

    #[test]
    fn bad_cameras_are_errors() {
        let proj = Projection::Perspective {
            fov_y: 0.8f32,
            near: 0.1,
            far: 10.0,
        };
        assert_eq!(
            Camera::look_at([0.0; 3], [0.0; 3], [0.0, 1.0, 0.0], proj),
            Err(CameraError::EyeAtTarget)
        );
        assert_eq!(
            Camera::look_at([0.0, 5.0, 0.0], [0.0; 3], [0.0, 1.0, 0.0], proj),
            Err(CameraError::UpParallelToView)
        );
        let bad = Projection::Perspective {
            fov_y: 0.8f32,
            near: 0.0,
            far: 10.0,
        };
        assert_eq!(
            Camera::look_at([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0], bad),
            Err(CameraError::BadProjection)
        );
    }
}
