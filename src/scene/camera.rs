//! The camera: a look-at view transform (U-V-N) and a perspective or parallel projection.
//!
//! View space is right-handed with the camera at the origin looking down −Z, +Y up. Clip space
//! keeps `x, y ∈ [−w, w]` and **`z ∈ [0, w]`** (near plane at z = 0, far plane at z = w), so the
//! near plane test is `z ≥ 0` and stored depth is `z/w · 65535` (0 = nearest).

use crate::num::math::{cross, dot, normalize, sub, Mat4, Vec3};
use crate::num::scalar::Scalar;

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

/// Why a camera could not be built (or, from [`crate::Renderer::render`], why a camera whose
/// public fields were changed is not drawn). Every variant names the parameter and its value.
///
/// Values are the parameter as the number type holds it, converted to `f64` (exact for every
/// [`Scalar`]). Equality compares them bit for bit, so an error carrying NaN equals itself.
#[derive(Copy, Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum CameraError {
    /// `eye` equals `target` (in the number type): no view direction.
    EyeAtTarget,
    /// `up` is parallel to the view direction (or zero).
    UpParallelToView,
    /// A parameter is NaN or infinite (float types).
    NotFinite {
        /// The parameter, e.g. `"eye[0]"`, `"near"`.
        param: &'static str,
        /// Its value.
        value: f64,
    },
    /// A parameter, or a quantity the camera computes from it, is at the saturation rail of a
    /// fixed-point type or overflows a float type: a value beyond the type's range (Q16.16:
    /// ±32 768) — and, in fixed point, a NaN or ±∞ input, which [`Scalar::from_f64`]
    /// saturates there.
    OutOfRange {
        /// The parameter or quantity, e.g. `"eye[2]"`, `"eye - target"`, `"view[2][3]"`.
        param: &'static str,
        /// Its value in the number type.
        value: f64,
        /// The number type ([`Scalar::NAME`]).
        number_type: &'static str,
    },
    /// A projection parameter outside its valid range.
    BadProjection {
        /// `"fov_y"`, `"near"`, `"far"` or `"height"`.
        param: &'static str,
        /// Its value.
        value: f64,
        /// The valid range, e.g. `"0 < fov_y < π (radians)"`.
        expected: &'static str,
    },
    /// A parameter that must be positive is zero in the number type — e.g. a perspective near
    /// plane of 10⁻⁶ in Q16.16, whose smallest positive value is 2⁻¹⁶ ≈ 1.5·10⁻⁵.
    RoundsToZero {
        /// The parameter (`"near"`).
        param: &'static str,
        /// The number type ([`Scalar::NAME`]).
        number_type: &'static str,
        /// The type's smallest positive value ([`Scalar::MIN_POSITIVE`]); inputs below half
        /// of it round to 0.
        smallest: f64,
    },
    /// A perspective `far / near` above [`MAX_DEPTH_RATIO`]: the 16-bit depth buffer cannot
    /// hold the scene. Stored depth is `65535·(1 − near/d)/(1 − near/far)` at distance `d`, so
    /// everything farther than about `far / (1 + ratio/131 070)` rounds to the clear depth
    /// (65 535) and fails the depth test: at the limit, geometry beyond a ninth of the far
    /// distance would vanish, and with near 10⁻⁵, far 20 nothing beyond 1.3 units is drawn.
    DepthPrecision {
        /// `near` in the number type.
        near: f64,
        /// `far` in the number type.
        far: f64,
        /// `far / near`.
        ratio: f64,
        /// [`MAX_DEPTH_RATIO`].
        limit: f64,
    },
}

/// The largest perspective `far / near` a camera accepts: 2²⁰ = 1 048 576 (see
/// [`CameraError::DepthPrecision`]). A larger ratio is an error, not a blank frame.
pub const MAX_DEPTH_RATIO: f64 = (1u32 << 20) as f64;

impl CameraError {
    /// The variant and its fields in a form compared bit for bit.
    fn key(&self) -> (u8, &'static str, &'static str, [u64; 4]) {
        let b = |v: f64| v.to_bits();
        match *self {
            CameraError::EyeAtTarget => (0, "", "", [0; 4]),
            CameraError::UpParallelToView => (1, "", "", [0; 4]),
            CameraError::NotFinite { param, value } => (2, param, "", [b(value), 0, 0, 0]),
            CameraError::OutOfRange {
                param,
                value,
                number_type,
            } => (3, param, number_type, [b(value), 0, 0, 0]),
            CameraError::BadProjection {
                param,
                value,
                expected,
            } => (4, param, expected, [b(value), 0, 0, 0]),
            CameraError::RoundsToZero {
                param,
                number_type,
                smallest,
            } => (5, param, number_type, [b(smallest), 0, 0, 0]),
            CameraError::DepthPrecision {
                near,
                far,
                ratio,
                limit,
            } => (6, "", "", [b(near), b(far), b(ratio), b(limit)]),
        }
    }
}

impl PartialEq for CameraError {
    fn eq(&self, other: &Self) -> bool {
        self.key() == other.key()
    }
}

impl Eq for CameraError {}

impl core::fmt::Display for CameraError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            CameraError::EyeAtTarget => write!(f, "camera eye equals target: no view direction"),
            CameraError::UpParallelToView => {
                write!(
                    f,
                    "camera up vector is zero or parallel to the view direction"
                )
            }
            CameraError::NotFinite { param, value } => {
                write!(f, "camera {param} is {value}: must be finite")
            }
            CameraError::OutOfRange {
                param,
                value,
                number_type,
            } => write!(
                f,
                "camera {param} = {value} is out of the range of {number_type} (a fixed-point \
                 value at its saturation rail comes from an out-of-range, NaN or infinite input)"
            ),
            CameraError::BadProjection {
                param,
                value,
                expected,
            } => write!(f, "camera {param} = {value}: must be {expected}"),
            CameraError::RoundsToZero {
                param,
                number_type,
                smallest,
            } => write!(
                f,
                "camera {param} is 0 in {number_type} (its smallest positive value is \
                 {smallest:e}; smaller inputs round to 0): must be > 0"
            ),
            CameraError::DepthPrecision {
                near,
                far,
                ratio,
                limit,
            } => write!(
                f,
                "camera far/near = {far}/{near} = {ratio:.0} exceeds the 16-bit depth buffer's \
                 limit {limit:.0}: geometry beyond far/(1 + ratio/131070) would round to the \
                 clear depth and vanish; raise near or lower far"
            ),
        }
    }
}

impl core::error::Error for CameraError {}

/// `Err` naming `param` unless `v` is valid in `S`: [`CameraError::NotFinite`] for a float NaN
/// or infinity, [`CameraError::OutOfRange`] for a finite value the type reports invalid (a
/// fixed-point rail).
fn finite<S: Scalar>(param: &'static str, v: S) -> Result<(), CameraError> {
    if v.is_valid() {
        return Ok(());
    }
    let value = v.to_f64();
    Err(if value.is_finite() {
        CameraError::OutOfRange {
            param,
            value,
            number_type: S::NAME,
        }
    } else {
        CameraError::NotFinite { param, value }
    })
}

/// [`finite`] for each component of a vector, named `names[i]`.
fn finite3<S: Scalar>(names: [&'static str; 3], v: Vec3<S>) -> Result<(), CameraError> {
    for i in 0..3 {
        finite(names[i], v[i])?;
    }
    Ok(())
}

impl<S: Scalar> Camera<S> {
    /// A camera at `eye` looking at `target` with `up` roughly up, using the U-V-N frame of the
    /// seeds: `n = normalize(eye − target)` (view +Z points away from what is seen),
    /// `u = normalize(up × n)` (screen right), `v = n × u` (screen up).
    ///
    /// # Errors
    ///
    /// A [`CameraError`] naming the parameter and its value: non-finite or out of the number
    /// type's range (eye, target, up, `eye − target`, the view matrix), eye at target, up
    /// parallel to the view, or a projection outside its valid range (see
    /// [`Camera::validate`]).
    pub fn look_at(
        eye: Vec3<S>,
        target: Vec3<S>,
        up: Vec3<S>,
        projection: Projection<S>,
    ) -> Result<Self, CameraError> {
        // The checks, the frame and the validation in functions of their own, so that the
        // deepest of them, not their sum, adds to the caller's stack (on a 16 KB part the
        // renderer's frame is most of the RAM).
        let camera = Self::look_at_unvalidated(eye, target, up, projection)?;
        camera.validate()?;
        Ok(camera)
    }

    /// [`Camera::look_at`] without the final [`Camera::validate`].
    #[inline(never)]
    fn look_at_unvalidated(
        eye: Vec3<S>,
        target: Vec3<S>,
        up: Vec3<S>,
        projection: Projection<S>,
    ) -> Result<Self, CameraError> {
        finite3(["eye[0]", "eye[1]", "eye[2]"], eye)?;
        finite3(["target[0]", "target[1]", "target[2]"], target)?;
        finite3(["up[0]", "up[1]", "up[2]"], up)?;
        let zero = [S::ZERO; 3];
        let d = sub(eye, target);
        // Finite inputs whose difference overflows the type.
        finite3(
            [
                "eye[0] - target[0]",
                "eye[1] - target[1]",
                "eye[2] - target[2]",
            ],
            d,
        )
        .map_err(|e| match e {
            CameraError::NotFinite { param, value } => CameraError::OutOfRange {
                param,
                value,
                number_type: S::NAME,
            },
            e => e,
        })?;
        let n = normalize(d);
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
        Ok(Camera {
            view,
            projection,
            eye,
        })
    }

    /// Checks what [`Camera::look_at`] checks of a camera's public fields, for a camera built
    /// or changed by hand ([`crate::Renderer::render`] calls it every frame; a few dozen
    /// comparisons): every entry of `view` and `eye` valid in the number type, and the
    /// projection in range ([`Projection::validate`]).
    ///
    /// # Errors
    ///
    /// The first problem found, naming the field and its value.
    pub fn validate(&self) -> Result<(), CameraError> {
        const VIEW: [[&str; 4]; 4] = [
            ["view[0][0]", "view[0][1]", "view[0][2]", "view[0][3]"],
            ["view[1][0]", "view[1][1]", "view[1][2]", "view[1][3]"],
            ["view[2][0]", "view[2][1]", "view[2][2]", "view[2][3]"],
            ["view[3][0]", "view[3][1]", "view[3][2]", "view[3][3]"],
        ];
        finite3(["eye[0]", "eye[1]", "eye[2]"], self.eye)?;
        for i in 0..4 {
            for j in 0..4 {
                finite(VIEW[i][j], self.view.m[i][j])?;
            }
        }
        self.projection.validate()
    }
}

impl<S: Scalar> Projection<S> {
    /// Checks the projection's parameters: each finite and in the number type's range;
    /// perspective `0 < fov_y < π`, `near > 0` (and not rounded to 0), `far > near` and
    /// `far / near ≤` [`MAX_DEPTH_RATIO`]; orthographic `height > 0`, `far > near` and
    /// `far − near` in range.
    ///
    /// # Errors
    ///
    /// The first problem found, naming the parameter and its value.
    pub fn validate(&self) -> Result<(), CameraError> {
        let bad = |param, value: S, expected| {
            Err(CameraError::BadProjection {
                param,
                value: value.to_f64(),
                expected,
            })
        };
        match *self {
            Projection::Perspective { fov_y, near, far } => {
                finite("fov_y", fov_y)?;
                finite("near", near)?;
                finite("far", far)?;
                let pi = S::from_f64(core::f64::consts::PI);
                if !(fov_y > S::ZERO && fov_y < pi) {
                    return bad("fov_y", fov_y, "0 < fov_y < π (radians)");
                }
                if near == S::ZERO {
                    return Err(CameraError::RoundsToZero {
                        param: "near",
                        number_type: S::NAME,
                        smallest: S::MIN_POSITIVE,
                    });
                }
                if near < S::ZERO {
                    return bad("near", near, "> 0 for a perspective projection");
                }
                if far <= near {
                    return bad("far", far, "> near");
                }
                let (n, f) = (near.to_f64(), far.to_f64());
                if f > n * MAX_DEPTH_RATIO {
                    return Err(CameraError::DepthPrecision {
                        near: n,
                        far: f,
                        ratio: f / n,
                        limit: MAX_DEPTH_RATIO,
                    });
                }
            }
            Projection::Orthographic { height, near, far } => {
                finite("height", height)?;
                finite("near", near)?;
                finite("far", far)?;
                if height <= S::ZERO {
                    return bad("height", height, "> 0");
                }
                if far <= near {
                    return bad("far", far, "> near");
                }
                finite("far - near", far - near)?;
            }
        }
        Ok(())
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

    /// The near and far distances, of either kind of projection.
    pub(crate) fn near_far(&self) -> (S, S) {
        match *self {
            Projection::Perspective { near, far, .. }
            | Projection::Orthographic { near, far, .. } => (near, far),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::scalar::Fx;
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
            near: -1.0,
            far: 10.0,
        };
        assert_eq!(
            Camera::look_at([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0], bad),
            Err(CameraError::BadProjection {
                param: "near",
                value: -1.0,
                expected: "> 0 for a perspective projection"
            })
        );
    }
}
