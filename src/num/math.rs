//! 3-vectors and 4×4 homogeneous matrices over a [`Scalar`].
//!
//! Matrices act on **column vectors** (`p' = M·p`) and compose right to left:
//! `a.then(b)` is `b·a`, i.e. first `a`, then `b`. The seeds write row vectors (`p' = p·A`);
//! our matrices are the transposes of theirs.

use crate::num::scalar::Scalar;

/// A 3-vector (x, y, z); precision is that of `S`.
pub type Vec3<S> = [S; 3];

/// `a + b`.
#[must_use]
pub fn add<S: Scalar>(a: Vec3<S>, b: Vec3<S>) -> Vec3<S> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `a − b`.
#[must_use]
pub fn sub<S: Scalar>(a: Vec3<S>, b: Vec3<S>) -> Vec3<S> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a · k`.
#[must_use]
pub fn scale<S: Scalar>(a: Vec3<S>, k: S) -> Vec3<S> {
    [a[0] * k, a[1] * k, a[2] * k]
}

/// Dot product.
#[must_use]
pub fn dot<S: Scalar>(a: Vec3<S>, b: Vec3<S>) -> S {
    S::dot3_add(a, b, S::ZERO)
}

/// Cross product `a × b` (right-handed).
#[must_use]
pub fn cross<S: Scalar>(a: Vec3<S>, b: Vec3<S>) -> Vec3<S> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Euclidean length.
#[must_use]
pub fn length<S: Scalar>(a: Vec3<S>) -> S {
    dot(a, a).sqrt()
}

/// `a / |a|`; the zero vector (or one too short to normalize in `S`) gives the zero vector,
/// which lights as ambient only.
///
/// Fixed-point vectors are pre-scaled by a power of two so that their squared length neither
/// overflows nor underflows the format before the square root.
#[must_use]
pub fn normalize<S: Scalar>(a: Vec3<S>) -> Vec3<S> {
    let two = S::ONE + S::ONE;
    let sixteenth = S::from_f64(0.0625);
    let mut v = a;
    let m = a[0].abs().max(a[1].abs()).max(a[2].abs());
    if m == S::ZERO || !m.is_valid() {
        return [S::ZERO; 3];
    }
    // Bring the largest component into [1, 2) with exact power-of-two steps.
    let mut mm = m;
    let mut guard = 0;
    while mm >= two && guard < 64 {
        v = [v[0] / two, v[1] / two, v[2] / two];
        mm = mm / two;
        guard += 1;
    }
    while mm < S::ONE && guard < 64 {
        if mm < sixteenth {
            v = scale(v, S::from_f64(16.0));
            mm = mm * S::from_f64(16.0);
        } else {
            v = scale(v, two);
            mm = mm * two;
        }
        guard += 1;
    }
    let len = length(v);
    if len == S::ZERO {
        return [S::ZERO; 3];
    }
    [v[0] / len, v[1] / len, v[2] / len]
}

/// A 4×4 matrix, row-major: `m[row][col]`, acting on column vectors.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Mat4<S> {
    /// The entries, `m[row][col]`.
    pub m: [[S; 4]; 4],
}

impl<S: Scalar> Mat4<S> {
    /// The identity.
    #[must_use]
    pub fn identity() -> Self {
        let (o, z) = (S::ONE, S::ZERO);
        Mat4 {
            m: [[o, z, z, z], [z, o, z, z], [z, z, o, z], [z, z, z, o]],
        }
    }

    /// Translation by `t`.
    #[must_use]
    pub fn translate(t: Vec3<S>) -> Self {
        let mut r = Self::identity();
        r.m[0][3] = t[0];
        r.m[1][3] = t[1];
        r.m[2][3] = t[2];
        r
    }

    /// Scaling by `k` along each axis.
    #[must_use]
    pub fn scale(k: Vec3<S>) -> Self {
        let mut r = Self::identity();
        r.m[0][0] = k[0];
        r.m[1][1] = k[1];
        r.m[2][2] = k[2];
        r
    }

    /// Rotation by `angle` radians about +X (counter-clockwise looking down the axis at the origin).
    #[must_use]
    pub fn rotate_x(angle: S) -> Self {
        let (s, c) = angle.sin_cos();
        let mut r = Self::identity();
        r.m[1][1] = c;
        r.m[1][2] = -s;
        r.m[2][1] = s;
        r.m[2][2] = c;
        r
    }

    /// Rotation by `angle` radians about +Y.
    #[must_use]
    pub fn rotate_y(angle: S) -> Self {
        let (s, c) = angle.sin_cos();
        Self::rotate_y_sin_cos(s, c)
    }

    /// [`Mat4::rotate_y`] of the angle whose sine and cosine are `s` and `c` (for a caller that
    /// keeps them in a table).
    #[must_use]
    pub fn rotate_y_sin_cos(s: S, c: S) -> Self {
        let mut r = Self::identity();
        r.m[0][0] = c;
        r.m[0][2] = s;
        r.m[2][0] = -s;
        r.m[2][2] = c;
        r
    }

    /// Rotation by `angle` radians about +Z.
    #[must_use]
    pub fn rotate_z(angle: S) -> Self {
        let (s, c) = angle.sin_cos();
        let mut r = Self::identity();
        r.m[0][0] = c;
        r.m[0][1] = -s;
        r.m[1][0] = s;
        r.m[1][1] = c;
        r
    }

    /// The matrix product `self · o`.
    #[must_use]
    pub fn mul(&self, o: &Self) -> Self {
        let mut r = [[S::ZERO; 4]; 4];
        for (i, row) in r.iter_mut().enumerate() {
            for (j, e) in row.iter_mut().enumerate() {
                *e = S::dot3_add(
                    [self.m[i][0], self.m[i][1], self.m[i][2]],
                    [o.m[0][j], o.m[1][j], o.m[2][j]],
                    self.m[i][3] * o.m[3][j],
                );
            }
        }
        Mat4 { m: r }
    }

    /// `self` first, then `next`: the product `next · self` (the same as `next * self`).
    #[must_use]
    pub fn then(&self, next: &Self) -> Self {
        next.mul(self)
    }

    /// `M · (p, 1)`: the homogeneous image of a point.
    #[must_use]
    pub fn transform_point(&self, p: Vec3<S>) -> [S; 4] {
        S::transform4(&self.m, p)
    }

    /// The upper 3×3 block times `v` (a direction: no translation).
    #[must_use]
    pub fn transform_dir(&self, v: Vec3<S>) -> Vec3<S> {
        S::transform_dir3(&self.m, v)
    }

    /// The transpose.
    #[must_use]
    pub fn transpose(&self) -> Self {
        let mut r = *self;
        for i in 0..4 {
            for j in 0..4 {
                r.m[i][j] = self.m[j][i];
            }
        }
        r
    }

    /// The matrix that transforms normals for this matrix's upper 3×3 block `A`: the cofactor
    /// matrix (`det(A)·A⁻ᵀ`, which needs no division), scaled by a power of two so its largest
    /// column has length in [1/2, 2) — and negated when `det(A) < 0` (a mirror), so that it is
    /// a positive multiple of `A⁻ᵀ` and outward normals stay outward — plus whether `A` is a
    /// similarity (rotation times uniform scale), in which case normals stay unit length and
    /// need no renormalization.
    #[must_use]
    pub fn normal_matrix(&self) -> (Self, bool) {
        let (c, sim, _) = self.normal_matrix_mirrored();
        (c, sim)
    }

    /// Whether the upper 3×3 block has a negative determinant (a mirror: it turns
    /// counter-clockwise triangles clockwise, and the renderer then swaps their winding).
    /// The sign is taken after scaling the block by a power of two, so tiny and huge scales
    /// keep it in fixed point; a singular block is not mirrored.
    #[must_use]
    pub fn is_mirrored(&self) -> bool {
        self.normal_matrix_mirrored().2
    }

    /// [`Mat4::normal_matrix`] and [`Mat4::is_mirrored`] from one cofactor computation.
    #[must_use]
    pub(crate) fn normal_matrix_mirrored(&self) -> (Self, bool, bool) {
        // First bring the 3×3 block's largest entry into [1/2, 2) by a power of two (exact), so
        // that the cofactors — products of two entries — keep their precision in fixed point
        // even for tiny or huge scales; the overall scale of a normal matrix does not matter.
        let two = S::ONE + S::ONE;
        let half = S::from_f64(0.5);
        let mut a3 = [[S::ZERO; 3]; 3];
        let mut big = S::ZERO;
        for i in 0..3 {
            for j in 0..3 {
                a3[i][j] = self.m[i][j];
                big = big.max(self.m[i][j].abs());
            }
        }
        let mut guard = 0;
        while big >= two && guard < 48 {
            a3 = a3.map(|r| r.map(|e| e / two));
            big = big / two;
            guard += 1;
        }
        while big < half && big > S::ZERO && guard < 48 {
            a3 = a3.map(|r| r.map(|e| e * two));
            big = big * two;
            guard += 1;
        }
        let a = |i: usize, j: usize| a3[i][j];
        let mut c = Self::identity();
        for i in 0..3 {
            for j in 0..3 {
                let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
                let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
                c.m[i][j] = a(i1, j1) * a(i2, j2) - a(i1, j2) * a(i2, j1);
            }
        }
        // det(A) = Σ a₀ⱼ·C₀ⱼ, in the scaled block (entries below 2, cofactors below 8: no
        // saturation in any format).
        let det = a(0, 0) * c.m[0][0] + a(0, 1) * c.m[0][1] + a(0, 2) * c.m[0][2];
        let mirrored = det < S::ZERO;
        if mirrored {
            for row in c.m.iter_mut().take(3) {
                for e in row.iter_mut().take(3) {
                    *e = -*e;
                }
            }
        }
        let col = |c: &Self, j: usize| [c.m[0][j], c.m[1][j], c.m[2][j]];
        let max_len = |c: &Self| {
            length(col(c, 0))
                .max(length(col(c, 1)))
                .max(length(col(c, 2)))
        };
        let mut guard = 0;
        while max_len(&c) >= two && guard < 48 {
            for row in c.m.iter_mut().take(3) {
                for e in row.iter_mut().take(3) {
                    *e = *e / two;
                }
            }
            guard += 1;
        }
        while max_len(&c) < half && max_len(&c) > S::ZERO && guard < 48 {
            for row in c.m.iter_mut().take(3) {
                for e in row.iter_mut().take(3) {
                    *e = *e * two;
                }
            }
            guard += 1;
        }
        // Similarity: columns orthogonal and of equal length (within 2^-10 relative).
        let tol = S::from_f64(1.0 / 1024.0);
        let l0 = length(col(&c, 0));
        let mut sim = l0 > S::ZERO;
        for j in 0..3 {
            let lj = length(col(&c, j));
            sim &= (lj - S::ONE).abs() <= tol && (lj - l0).abs() <= tol;
            for k in (j + 1)..3 {
                sim &= dot(col(&c, j), col(&c, k)).abs() <= tol;
            }
        }
        (c, sim, mirrored)
    }

    /// Converts every entry to another scalar type (through `f64`).
    #[must_use]
    pub fn cast<T: Scalar>(&self) -> Mat4<T> {
        let mut r = [[T::ZERO; 4]; 4];
        for i in 0..4 {
            for j in 0..4 {
                r[i][j] = T::from_f64(self.m[i][j].to_f64());
            }
        }
        Mat4 { m: r }
    }
}

/// The matrix product `a · b`, the same as [`Mat4::mul`]`(&a, &b)`: with column vectors, `b`
/// acts first and `a` second, so `a * b` is `b.then(&a)`. A model transform that scales, then
/// rotates, then translates is `translate * rotate * scale`, or
/// `scale.then(&rotate).then(&translate)`:
///
/// ```
/// # use scanline3d::prelude::*;
/// let (s, r) = (Mat4::scale([2.0f32; 3]), Mat4::rotate_y(0.5f32));
/// let t = Mat4::translate([1.0f32, 0.0, 0.0]);
/// assert_eq!(t * r * s, s.then(&r).then(&t));
/// ```
impl<S: Scalar> core::ops::Mul for Mat4<S> {
    type Output = Self;

    fn mul(self, rhs: Self) -> Self {
        Mat4::mul(&self, &rhs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::scalar::Fx;
    use fixed::types::I16F16;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    fn rotation_is_counter_clockwise<S: Scalar>(tol: f64) {
        let q = S::from_f64(core::f64::consts::FRAC_PI_2);
        let p = Mat4::<S>::rotate_z(q).transform_point([S::ONE, S::ZERO, S::ZERO]);
        assert!(close(p[0].to_f64(), 0.0, tol) && close(p[1].to_f64(), 1.0, tol));
        let p = Mat4::<S>::rotate_x(q).transform_point([S::ZERO, S::ONE, S::ZERO]);
        assert!(close(p[2].to_f64(), 1.0, tol));
        let p = Mat4::<S>::rotate_y(q).transform_point([S::ZERO, S::ZERO, S::ONE]);
        assert!(close(p[0].to_f64(), 1.0, tol));
    }

    #[test]
    fn rotations_follow_the_right_hand_rule() {
        rotation_is_counter_clockwise::<f64>(1e-12);
        rotation_is_counter_clockwise::<f32>(1e-6);
        rotation_is_counter_clockwise::<Fx<I16F16>>(4.0 / 65536.0);
    }

    #[test]
    fn mul_operator_is_the_matrix_product_and_then_reversed() {
        fn check<S: Scalar>() {
            let a = Mat4::<S>::rotate_x(S::from_f64(0.7))
                .then(&Mat4::translate([1.5, -0.25, 3.0].map(S::from_f64)));
            let b = Mat4::<S>::scale([2.0, 0.5, 1.25].map(S::from_f64))
                .then(&Mat4::rotate_z(S::from_f64(-1.1)));
            assert_eq!(a * b, a.mul(&b));
            assert_eq!(a * b, b.then(&a));
            assert_eq!(a * Mat4::identity(), a);
            // `b` acts first: translate by x = 1, then scale by 2 → x = 2.
            let t = Mat4::<S>::translate([S::ONE, S::ZERO, S::ZERO]);
            let s = Mat4::<S>::scale([S::from_f64(2.0); 3]);
            let p = (s * t).transform_point([S::ZERO; 3]);
            assert_eq!(p, [S::from_f64(2.0), S::ZERO, S::ZERO, S::ONE]);
        }
        check::<f64>();
        check::<f32>();
        check::<Fx<I16F16>>();
    }

    #[test]
    fn then_applies_left_first() {
        let t = Mat4::<f64>::translate([1.0, 0.0, 0.0]);
        let s = Mat4::<f64>::scale([2.0, 2.0, 2.0]);
        let p = t.then(&s).transform_point([0.0, 0.0, 0.0]);
        assert_eq!(p, [2.0, 0.0, 0.0, 1.0]);
    }

    #[test]
    fn normalize_handles_tiny_huge_and_zero() {
        type Q = Fx<I16F16>;
        for e in -8..=8 {
            let k = libm::pow(2.0, e as f64);
            let (x, z) = (Q::lit(0.6 * k), Q::lit(-0.8 * k));
            // Compare with the exact direction of the (already quantized) input.
            let l = libm::hypot(x.to_f64(), z.to_f64());
            let v = normalize([x, Q::ZERO, z]);
            assert!(
                close(v[0].to_f64(), x.to_f64() / l, 3.0 / 65536.0),
                "2^{e}: {v:?}"
            );
            assert!(
                close(v[2].to_f64(), z.to_f64() / l, 3.0 / 65536.0),
                "2^{e}: {v:?}"
            );
        }
        assert_eq!(normalize([Q::ZERO; 3]), [Q::ZERO; 3]);
        assert_eq!(normalize([0.0f32; 3]), [0.0; 3]);
        assert_eq!(normalize([f32::NAN, 0.0, 0.0]), [0.0; 3]);
    }

    #[test]
    fn normal_matrix_keeps_precision_for_tiny_scales() {
        type Q = Fx<I16F16>;
        let m = Mat4::<Q>::scale([Q::lit(0.006); 3]).then(&Mat4::rotate_x(Q::lit(0.7)));
        // The quantized scale (393 steps) is only a similarity to 1/393, so the flag may be
        // off (normals are then renormalized); the directions must still be right.
        let (n, _) = m.normal_matrix();
        let r = Mat4::<f64>::rotate_x(Q::lit(0.7).to_f64());
        for j in 0..3 {
            let col = normalize([n.m[0][j], n.m[1][j], n.m[2][j]]);
            for i in 0..3 {
                assert!(
                    (col[i].to_f64() - r.m[i][j]).abs() < 2e-3,
                    "{i},{j}: {:?}",
                    col[i]
                );
            }
        }
    }

    #[test]
    fn normal_matrix_of_rotation_is_itself_and_similar() {
        let r = Mat4::<f64>::rotate_x(0.3).then(&Mat4::rotate_y(1.1));
        let (n, sim) = r.normal_matrix();
        assert!(sim);
        for i in 0..3 {
            for j in 0..3 {
                assert!(close(n.m[i][j], r.m[i][j], 1e-12));
            }
        }
        let (_, sim) = Mat4::<f64>::scale([1.0, 2.0, 1.0]).normal_matrix();
        assert!(!sim);
    }
}
