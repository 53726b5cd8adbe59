//! The number type of the geometry pipeline.
//!
//! Every stage before rasterization (transforms, lighting, clipping, the perspective divide) is
//! written once, generic over [`Scalar`]. It is implemented for
//!
//! | type | format | range | step | notes |
//! |---|---|---|---|---|
//! | [`Fx<I16F16>`](Fx) | signed Q16.16 in an `i32` | ±32768 | 2⁻¹⁶ ≈ 1.5·10⁻⁵ | the default fixed-point type |
//! | [`Fx<I20F12>`](Fx) | signed Q20.12 in an `i32` | ±524288 | 2⁻¹² ≈ 2.4·10⁻⁴ | large scenes, coarser |
//! | [`Fx<I12F20>`](Fx) | signed Q12.20 in an `i32` | ±2048 | 2⁻²⁰ ≈ 9.5·10⁻⁷ | small scenes, finer |
//! | `f32` | IEEE binary32 | ±3.4·10³⁸ | 2⁻²⁴ relative | float twin |
//! | `micromath::F32` | IEEE binary32 | ±3.4·10³⁸ | 2⁻²⁴ relative | approximate sqrt/sin: a benchmark candidate |
//! | `f64` | IEEE binary64 | ±1.8·10³⁰⁸ | 2⁻⁵³ relative | the reference |
//!
//! The rasterizer after the perspective divide is integer code shared by all of them, so the
//! float pipelines are twins of the fixed-point one, not second implementations.
//!
//! **Scene scale.** `Fx<I16F16>` renders a scene correctly (the same image as f64 within a few
//! silhouette pixels) when its models and camera distances are between about 10⁻² and 10³
//! world units: smaller scenes lose position precision to the 2⁻¹⁶ step, larger ones approach
//! the ±32 768 range. Use `Fx<I12F20>` for smaller scenes and `Fx<I20F12>` for larger ones; the
//! hard-case suite (`tests/hard_cases.rs`, `scene_scales`) checks these ranges.
//!
//! Fixed-point arithmetic in [`Fx`] **saturates** instead of wrapping or panicking. A vertex whose
//! clip coordinates reach the saturation rails is reported invalid by [`Scalar::is_valid`] and
//! its triangles are skipped and counted, never drawn as garbage.
//!
//! The perspective divide needs more precision than Q16.16 offers for 1/w (w up to 10³ would
//! leave 1/w with about six significant bits), so each type supplies its own reciprocal
//! representation ([`Scalar::Recip`]): for `Fx` a 31-bit normalized mantissa with a shift, for
//! floats the float itself.

use core::fmt::Debug;
use core::ops::{Add, Div, Mul, Neg, Sub};

use fixed::types::{I12F20, I16F16, I20F12};

use crate::kernel;

mod sealed {
    pub trait Sealed {}
}

/// Fraction bits of the normalized-device-coordinate values that [`Scalar::ndc`] returns
/// (signed Q31.32 in an `i64`; step 2⁻³² ≈ 2.3·10⁻¹⁰; range ±2³¹).
pub const NDC_FRAC_BITS: u32 = 32;

/// A number type the geometry pipeline can run on (sealed: implemented for [`Fx`] over
/// `I16F16`, `I20F12`, `I12F20`, and for `f32` and `f64`).
pub trait Scalar:
    Copy
    + Debug
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + sealed::Sealed
    + 'static
{
    /// Zero.
    const ZERO: Self;
    /// One.
    const ONE: Self;
    /// A short name for reports (`"I16F16"`, `"f32"`, ...).
    const NAME: &'static str;
    /// The reciprocal of a positive w, in whatever form keeps [`Scalar::ndc`] precise.
    type Recip: Copy + Debug;

    /// The smallest positive value, as `f64`: 2⁻¹⁶ for Q16.16 (2⁻ᶠ for `f` fraction bits), the
    /// smallest subnormal for floats (`f32`: ≈1.4·10⁻⁴⁵, `f64`: ≈4.9·10⁻³²⁴). A positive input
    /// below half of it converts to zero.
    const MIN_POSITIVE: f64;

    /// Converts from `f64`, rounding to nearest; saturating for fixed-point types. A fixed-point
    /// type maps NaN to its negative rail (the most negative value), ±∞ and out-of-range values
    /// to the nearer rail, and [`Scalar::is_valid`] reports every rail invalid: a non-finite
    /// input is counted and skipped like a float NaN, never drawn as 0.
    #[must_use]
    fn from_f64(v: f64) -> Self;
    /// A literal: [`Scalar::from_f64`] under a short name, for generic code over every number
    /// type (`S::lit(0.5)`).
    #[must_use]
    #[inline]
    fn lit(v: f64) -> Self {
        Self::from_f64(v)
    }
    /// Converts to `f64` (exact for every implemented type except `f64` → itself).
    #[must_use]
    fn to_f64(self) -> f64;
    /// Converts from `f32` (see [`Scalar::from_f64`]).
    #[must_use]
    fn from_f32(v: f32) -> Self {
        Self::from_f64(v as f64)
    }
    /// Converts from an integer (saturating for fixed-point types).
    #[must_use]
    fn from_i32(v: i32) -> Self {
        Self::from_f64(v as f64)
    }
    /// `self · k` for a small integer `k` (|k| ≤ 2¹¹): the same value as
    /// `self * Self::from_i32(k)`, which a type may compute without a general product.
    #[must_use]
    #[inline(always)]
    fn mul_int(self, k: i32) -> Self {
        self * Self::from_i32(k)
    }
    /// Square root; negative input gives zero.
    #[must_use]
    fn sqrt(self) -> Self;
    /// Sine and cosine of an angle in radians.
    #[must_use]
    fn sin_cos(self) -> (Self, Self);
    /// `a·b + c` for 3-vectors: `a₀b₀ + a₁b₁ + a₂b₂ + c`. Fixed-point types sum the exact
    /// products and round once; floats evaluate it left to right.
    #[must_use]
    #[inline(always)]
    fn dot3_add(a: [Self; 3], b: [Self; 3], c: Self) -> Self {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + c
    }
    /// `m · (p, 1)` for a 4 × 4 matrix `m` (rows): [`Scalar::dot3_add`] of each row with `p`
    /// and the row's last entry. A type may compute it another way, with the same result.
    #[must_use]
    #[inline(always)]
    fn transform4(m: &[[Self; 4]; 4], p: [Self; 3]) -> [Self; 4] {
        dot3_rows(m, p)
    }
    /// The upper 3 × 3 block of `m` times the direction `v`: [`Scalar::dot3_add`] of each of
    /// the first three rows with `v` and zero. A type may compute it another way, with the
    /// same result.
    #[must_use]
    #[inline(always)]
    fn transform_dir3(m: &[[Self; 4]; 4], v: [Self; 3]) -> [Self; 3] {
        dot3_dir_rows(m, v)
    }
    /// Tangent of an angle in radians (saturating for fixed-point types).
    #[must_use]
    fn tan(self) -> Self {
        let (s, c) = self.sin_cos();
        s / c
    }
    /// False for NaN and infinities, and for fixed-point values at a saturation rail (which may
    /// be the result of an overflow).
    #[must_use]
    fn is_valid(self) -> bool;
    /// `self == o`, for setup code that compares many values ([`crate::mesh::mesh_adjacency`]
    /// matches every pair of edges by their ends' positions). The fixed-point types compare
    /// their raw bits here: `fixed`'s own `==` accepts two fraction widths and, in an
    /// unoptimized build, works them out on every call (most of `mesh_adjacency`'s time in a
    /// debug build). The same result as `==`.
    #[must_use]
    #[inline]
    fn same(self, o: Self) -> bool {
        self == o
    }
    /// Absolute value.
    #[must_use]
    fn abs(self) -> Self {
        if self < Self::ZERO {
            -self
        } else {
            self
        }
    }
    /// The larger of two values.
    #[must_use]
    fn max(self, o: Self) -> Self {
        if o > self {
            o
        } else {
            self
        }
    }
    /// The smaller of two values.
    #[must_use]
    fn min(self, o: Self) -> Self {
        if o < self {
            o
        } else {
            self
        }
    }
    /// The reciprocal of `w` for [`Scalar::ndc`]. `w` must be positive; otherwise the result
    /// is unspecified but `ndc` still does not panic.
    #[must_use]
    fn recip(w: Self) -> Self::Recip;
    /// `v / w` as signed Q31.32 ([`NDC_FRAC_BITS`]), rounded to nearest and saturated to
    /// `±2⁶²`; `r` is [`Scalar::recip`]`(w)`.
    #[must_use]
    fn ndc(v: Self, r: Self::Recip) -> i64;
    /// `mul_q32`(±ndc(v, r), k)`, `−` when `negate`: the offset of `v/w` from the screen
    /// centre in subpixels for a scale `k` ([`crate::geometry::project::Viewport::project`]). A type may
    /// compute it more directly, with the same result.
    #[must_use]
    #[inline(always)]
    fn ndc_scaled(v: Self, r: Self::Recip, k: u32, negate: bool) -> i64 {
        let n = Self::ndc(v, r);
        mul_q32(if negate { -n } else { n }, k)
    }
    /// `self` as a signed integer with `frac` fraction bits, rounded to nearest, saturated to
    /// `i32` (a float NaN → 0).
    #[must_use]
    fn to_fixed_i32(self, frac: u32) -> i32;
    /// A lit channel: `self · k` clamped to 0..=255 and rounded to 8.8 fixed point
    /// (0..=65280): [`channel_8_8`] of [`Scalar::mul_int`]; a type may give the same
    /// values faster.
    #[doc(hidden)]
    #[must_use]
    #[inline(always)]
    fn lit_channel(self, k: u8) -> u16 {
        channel_8_8(self.mul_int(k as i32))
    }
    /// The values of `v` as signed Q16.16 words (`i32`, step 2⁻¹⁶) when this type *is* Q16.16
    /// in an `i32` (`Fx<I16F16>`: `repr(transparent)`, so this is a view, not a copy); `None`
    /// for every other type. The Q16.16 kernels (`src/kernel`) work on these words.
    #[must_use]
    #[inline(always)]
    fn q16_words<const N: usize>(v: &[[Self; N]]) -> Option<&[[i32; N]]> {
        let _ = v;
        None
    }
    /// `self` as a signed Q16.16 word when this type is Q16.16 (see [`Scalar::q16_words`]).
    #[must_use]
    #[inline(always)]
    fn q16_bits(self) -> Option<i32> {
        Self::q16_words(&[[self]]).map(|w| w[0][0])
    }
}

/// A lit channel (0..=255 in channel units) clamped and rounded to 8.8 fixed point
/// (0..=65280).
#[inline(always)]
pub(crate) fn channel_8_8<S: Scalar>(v: S) -> u16 {
    let v = v.max(S::ZERO).min(S::from_i32(255));
    v.to_fixed_i32(8).clamp(0, 255 << 8) as u16
}

pub(crate) use crate::kernel::wide::{
    bitlen32, mul_q32, mul_wide, mul_wide16, recip_norm, round_shr64,
};
pub(crate) use crate::kernel::wide::{
    dot3_q16_small, mul_q16_small, mul_q32_short, round_shr_words, sat32, spread_bits,
};

/// Rounds and saturates an `f64` to `i64` (NaN → 0).
fn f64_to_i64(v: f64) -> i64 {
    // `as` saturates and maps NaN to 0.
    libm::round(v) as i64
}

impl sealed::Sealed for f64 {}
impl Scalar for f64 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const NAME: &'static str = "f64";
    const MIN_POSITIVE: f64 = f64::from_bits(1);
    type Recip = f64;
    fn from_f64(v: f64) -> Self {
        v
    }
    fn to_f64(self) -> f64 {
        self
    }
    fn sqrt(self) -> Self {
        if self > 0.0 {
            libm::sqrt(self)
        } else {
            0.0
        }
    }
    fn sin_cos(self) -> (Self, Self) {
        libm::sincos(self)
    }
    fn tan(self) -> Self {
        libm::tan(self)
    }
    fn is_valid(self) -> bool {
        self.is_finite()
    }
    fn recip(w: Self) -> f64 {
        1.0 / w
    }
    fn ndc(v: Self, r: f64) -> i64 {
        f64_to_i64(v * r * (1u64 << NDC_FRAC_BITS) as f64).clamp(-(1 << 62), 1 << 62)
    }
    fn to_fixed_i32(self, frac: u32) -> i32 {
        libm::round(self * (1u64 << frac) as f64) as i32
    }
}

impl sealed::Sealed for f32 {}
impl Scalar for f32 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const NAME: &'static str = "f32";
    const MIN_POSITIVE: f64 = f32::from_bits(1) as f64;
    type Recip = f32;
    fn from_f64(v: f64) -> Self {
        v as f32
    }
    fn to_f64(self) -> f64 {
        self as f64
    }
    fn sqrt(self) -> Self {
        if self > 0.0 {
            libm::sqrtf(self)
        } else {
            0.0
        }
    }
    fn sin_cos(self) -> (Self, Self) {
        libm::sincosf(self)
    }
    fn tan(self) -> Self {
        libm::tanf(self)
    }
    fn is_valid(self) -> bool {
        self.is_finite()
    }
    fn recip(w: Self) -> f32 {
        1.0 / w
    }
    fn ndc(v: Self, r: f32) -> i64 {
        // The product v·r is rounded once in f32; the scaling by 2^32 in f64 is exact.
        f64_to_i64((v * r) as f64 * (1u64 << NDC_FRAC_BITS) as f64).clamp(-(1 << 62), 1 << 62)
    }
    fn to_fixed_i32(self, frac: u32) -> i32 {
        libm::round(self as f64 * (1u64 << frac) as f64) as i32
    }
}

impl sealed::Sealed for micromath::F32 {}
/// micromath's approximate `f32`: IEEE arithmetic, but square root (up to ±6.5 %) and sine/cosine
/// (±0.002) by micromath's fast approximations. A speed/accuracy **candidate** for the
/// comparison benchmarks, not a recommended rendering type: normalization error of a few
/// percent shows in the lighting.
impl Scalar for micromath::F32 {
    const ZERO: Self = micromath::F32(0.0);
    const ONE: Self = micromath::F32(1.0);
    const NAME: &'static str = "micromath-f32";
    const MIN_POSITIVE: f64 = f32::from_bits(1) as f64;
    type Recip = f32;
    fn from_f64(v: f64) -> Self {
        micromath::F32(v as f32)
    }
    fn to_f64(self) -> f64 {
        self.0 as f64
    }
    fn sqrt(self) -> Self {
        if self.0 > 0.0 {
            self.sqrt()
        } else {
            Self::ZERO
        }
    }
    fn sin_cos(self) -> (Self, Self) {
        (self.sin(), self.cos())
    }
    fn is_valid(self) -> bool {
        self.0.is_finite()
    }
    fn recip(w: Self) -> f32 {
        1.0 / w.0
    }
    fn ndc(v: Self, r: f32) -> i64 {
        <f32 as Scalar>::ndc(v.0, r)
    }
    fn to_fixed_i32(self, frac: u32) -> i32 {
        self.0.to_fixed_i32(frac)
    }
}

/// A fixed-point number from the `fixed` crate with **saturating** arithmetic.
///
/// `Fx<I16F16>` is the default number type of the fixed-point pipeline. The operators
/// saturate at the type's range instead of wrapping (release) or panicking (debug); a value at a
/// rail is treated as invalid by [`Scalar::is_valid`]. Division by zero saturates.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[repr(transparent)]
pub struct Fx<T>(pub T);

/// Normalized reciprocal used by the fixed-point perspective divide:
/// `1/w = mantissa · 2^-(shift)` with `mantissa` in (2²⁹, 2³⁰] (relative error below 2⁻²⁸).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct FxRecip {
    mantissa: i32,
    shift: u32,
}

macro_rules! impl_fx {
    ($t:ident, $frac:expr, $name:expr) => {
        impl Fx<$t> {
            /// Builds a value from a float literal (rounds to nearest, saturates; NaN → the
            /// negative rail): [`Scalar::lit`], callable without the trait in scope.
            #[must_use]
            pub fn lit(v: f64) -> Self {
                <Self as Scalar>::from_f64(v)
            }
            /// The raw bits.
            #[must_use]
            pub fn to_bits(self) -> i32 {
                self.0.to_bits()
            }
        }
        impl Add for Fx<$t> {
            type Output = Self;
            #[inline(always)]
            fn add(self, o: Self) -> Self {
                Fx(self.0.saturating_add(o.0))
            }
        }
        impl Sub for Fx<$t> {
            type Output = Self;
            #[inline(always)]
            fn sub(self, o: Self) -> Self {
                Fx(self.0.saturating_sub(o.0))
            }
        }
        impl Mul for Fx<$t> {
            type Output = Self;
            /// Rounds to nearest (ties up) and saturates.
            #[inline(always)]
            fn mul(self, o: Self) -> Self {
                let (a, b) = (self.0.to_bits(), o.0.to_bits());
                if $frac == 16 && (spread_bits(a) | spread_bits(b)) < 1 << 23 {
                    return Fx($t::from_bits(mul_q16_small(a, b)));
                }
                let p = mul_wide(a, b);
                Fx($t::from_bits(sat32((p + (1i64 << ($frac - 1))) >> $frac)))
            }
        }
        impl Div for Fx<$t> {
            type Output = Self;
            fn div(self, o: Self) -> Self {
                if o.0 == $t::ZERO {
                    return Fx(if self.0 < $t::ZERO { $t::MIN } else { $t::MAX });
                }
                Fx(self.0.saturating_div(o.0))
            }
        }
        impl Neg for Fx<$t> {
            type Output = Self;
            #[inline(always)]
            fn neg(self) -> Self {
                Fx(self.0.saturating_neg())
            }
        }
        impl sealed::Sealed for Fx<$t> {}
        impl Scalar for Fx<$t> {
            const ZERO: Self = Fx($t::ZERO);
            const ONE: Self = Fx($t::ONE);
            const NAME: &'static str = $name;
            const MIN_POSITIVE: f64 = 1.0 / (1u64 << $frac) as f64;
            type Recip = FxRecip;
            fn from_f64(v: f64) -> Self {
                if v.is_nan() {
                    // The negative rail, which `is_valid` rejects (as a float NaN).
                    return Fx($t::MIN);
                }
                // Round to nearest in f64, then saturate (±∞ to the rails).
                Fx($t::from_bits(
                    f64_to_i64(v * (1u64 << $frac) as f64).clamp(i32::MIN as i64, i32::MAX as i64)
                        as i32,
                ))
            }
            fn to_f64(self) -> f64 {
                self.0.to_bits() as f64 / (1u64 << $frac) as f64
            }
            fn from_i32(v: i32) -> Self {
                Fx($t::saturating_from_num(v))
            }
            #[inline(always)]
            fn mul_int(self, k: i32) -> Self {
                // The rounded product with an exact integer is exact; both saturate alike.
                // (`from_i32` saturates first for |k| beyond the integer range.)
                if k.unsigned_abs() < 1 << (31 - $frac).min(15) {
                    Fx($t::from_bits(sat32(mul_wide16(self.0.to_bits(), k))))
                } else {
                    self * Self::from_i32(k)
                }
            }
            #[inline(always)]
            fn lit_channel(self, k: u8) -> u16 {
                // The exact product, clamped to [0, 255·2^frac] (255·2^frac fits an i32, so
                // `mul_int`'s saturation before the clamp changes nothing), then rounded half
                // up to 8 fraction bits as `to_fixed_i32(8)`: at most 65280. A non-positive
                // value gives 0; below 2^23 the product fits an i32 (k < 2^8).
                let b = self.0.to_bits();
                let max = 255i32 << $frac;
                let p = if b <= 0 {
                    0
                } else if b < 1 << 23 {
                    (b * k as i32).min(max)
                } else {
                    mul_wide16(b, k as i32).min(max as i64) as i32
                };
                // Every Fx type has at least 8 fraction bits (a type with fewer would not
                // compile here).
                let s = $frac - 8;
                ((p + (1 << s >> 1)) >> s) as u16
            }
            fn sqrt(self) -> Self {
                if self.0 <= $t::ZERO {
                    Self::ZERO
                } else {
                    // The square root of a positive in-range value never overflows for
                    // formats with at least one integer bit.
                    Fx(self.0.wrapping_sqrt())
                }
            }
            fn sin_cos(self) -> (Self, Self) {
                // Evaluated in f64 by libm (pure software, so bit-identical on every target)
                // and rounded once: setup-time only. A rail (where NaN, ±∞ and out-of-range
                // inputs land) gives rails, as NaN gives NaN in a float: a rotation by it is
                // an invalid transform, skipped and counted, not one at an arbitrary angle.
                if !self.is_valid() {
                    return (self, self);
                }
                let (s, c) = libm::sincos(self.to_f64());
                (Self::from_f64(s), Self::from_f64(c))
            }
            fn tan(self) -> Self {
                Self::from_f64(libm::tan(self.to_f64()))
            }
            #[inline]
            fn same(self, o: Self) -> bool {
                self.0.to_bits() == o.0.to_bits()
            }
            fn is_valid(self) -> bool {
                self.0 != $t::MAX && self.0 != $t::MIN
            }
            #[inline(always)]
            fn dot3_add(a: [Self; 3], b: [Self; 3], c: Self) -> Self {
                let (a, b) = (a.map(|v| v.0.to_bits()), b.map(|v| v.0.to_bits()));
                // With every factor in [−2³⁰, 2³⁰) each product is at most 2⁶⁰ in magnitude
                // and the sum below 2⁶², so plain 64-bit additions (two instructions each on
                // a Cortex-M0) cannot overflow and give the same value as the saturating ones.
                let spread = spread_bits(a[0])
                    | spread_bits(a[1])
                    | spread_bits(a[2])
                    | spread_bits(b[0])
                    | spread_bits(b[1])
                    | spread_bits(b[2]);
                if $frac == 16 && spread < 1 << 22 {
                    return Fx($t::from_bits(
                        dot3_q16_small(a, b).saturating_add(c.0.to_bits()),
                    ));
                }
                if spread < 1 << 30 {
                    let p = mul_wide(a[0], b[0])
                        + mul_wide(a[1], b[1])
                        + mul_wide(a[2], b[2])
                        + ((c.0.to_bits() as i64) << $frac)
                        + (1i64 << ($frac - 1));
                    return Fx($t::from_bits(sat32(p >> $frac)));
                }
                // Each product is below 2^62 in magnitude; the sum saturates instead of
                // overflowing, and a saturated sum saturates the result.
                let p = mul_wide(a[0], b[0])
                    .saturating_add(mul_wide(a[1], b[1]))
                    .saturating_add(mul_wide(a[2], b[2]))
                    .saturating_add((c.0.to_bits() as i64) << $frac)
                    .saturating_add(1i64 << ($frac - 1));
                Fx($t::from_bits(sat32(p >> $frac)))
            }
            #[inline(always)]
            fn transform4(m: &[[Self; 4]; 4], p: [Self; 3]) -> [Self; 4] {
                // The Q16.16 transform kernel where there is one; its fallback out of line.
                if kernel::TRANSFORM && $frac == 16 {
                    if let (Some(mw), Some(pw)) = (Self::q16_words(&m[..]), Self::q16_words(&[p])) {
                        if let Ok(mw) = <&[[i32; 4]; 4]>::try_from(mw) {
                            if let Some(r) = kernel::transform_q16(mw, pw[0]) {
                                return r.map(|b| Fx($t::from_bits(b)));
                            }
                        }
                    }
                    return dot3_rows_cold(m, p);
                }
                dot3_rows(m, p)
            }
            #[inline(always)]
            fn transform_dir3(m: &[[Self; 4]; 4], v: [Self; 3]) -> [Self; 3] {
                if kernel::TRANSFORM && $frac == 16 {
                    if let (Some(mw), Some(vw)) = (Self::q16_words(&m[..]), Self::q16_words(&[v])) {
                        if let Ok(mw) = <&[[i32; 4]; 4]>::try_from(mw) {
                            if let Some(r) = kernel::transform_dir_q16(mw, vw[0]) {
                                return r.map(|b| Fx($t::from_bits(b)));
                            }
                        }
                    }
                    return dot3_dir_rows_cold(m, v);
                }
                dot3_dir_rows(m, v)
            }
            fn recip(w: Self) -> FxRecip {
                let (mantissa, shift) = recip_norm(w.0.to_bits().max(1) as u64);
                FxRecip { mantissa, shift }
            }
            #[inline(always)]
            fn ndc(v: Self, r: FxRecip) -> i64 {
                // v/w = v_bits / w_bits = v_bits · mantissa · 2^-shift; |product| < 2^61.
                let p = mul_wide(v.0.to_bits(), r.mantissa);
                let s = r.shift as i32 - NDC_FRAC_BITS as i32;
                if s > 0 && s < 32 {
                    // Every positive 32-bit w: shift = 29 + bitlen(w) ≤ 60, so s ≤ 28.
                    let (hi, lo) = round_shr_words(p, s as u32);
                    ((hi as i64) << 32) | lo as i64
                } else if s > 0 {
                    round_shr64(p, s as u32)
                } else {
                    p.saturating_mul(1i64 << (-s).min(62))
                        .clamp(-(1 << 62), 1 << 62)
                }
            }
            /// The common case in 32-bit words, without forming the 64-bit `ndc`: a 32-bit
            /// shift (`0 < s < 32`, every positive w), a screen scale `k < 2¹⁶` and a
            /// quotient whose high word fits an `i16` (every vertex inside the guard band).
            /// The same roundings as [`Scalar::ndc`] then `mul_q32`'s 16-bit path, so the same
            /// value; anything else takes that path.
            #[inline(always)]
            fn ndc_scaled(v: Self, r: FxRecip, k: u32, negate: bool) -> i64 {
                let s = r.shift as i32 - NDC_FRAC_BITS as i32;
                if s > 0 && s < 32 && k < 1 << 16 {
                    let p = mul_wide(v.0.to_bits(), r.mantissa);
                    let (mut hi, mut lo) = round_shr_words(p, s as u32);
                    if negate {
                        // −(hi·2³² + lo), |·| < 2⁶¹.
                        hi = (!hi).wrapping_add((lo == 0) as i32);
                        lo = lo.wrapping_neg();
                    }
                    if hi == hi as i16 as i32 {
                        return mul_q32_short(hi as i64, lo, k);
                    }
                }
                let n = Self::ndc(v, r);
                mul_q32(if negate { -n } else { n }, k)
            }
            #[inline(always)]
            #[allow(unsafe_code)]
            fn q16_words<const N: usize>(v: &[[Self; N]]) -> Option<&[[i32; N]]> {
                if $frac != 16 {
                    return None;
                }
                // SAFETY: `Fx<T>` is `repr(transparent)` over `T`, and the `fixed` types are
                // `repr(transparent)` over their bits, so `[Fx<I16F16>; N]` has the layout of
                // `[i32; N]` and every `i32` is a valid value; the view borrows `v`.
                Some(unsafe { core::slice::from_raw_parts(v.as_ptr() as *const [i32; N], v.len()) })
            }
            fn to_fixed_i32(self, frac: u32) -> i32 {
                let b = self.0.to_bits() as i64;
                let v = if frac >= $frac {
                    b << (frac - $frac)
                } else {
                    let s = $frac - frac;
                    (b + (1i64 << (s - 1))) >> s
                };
                v.clamp(i32::MIN as i64, i32::MAX as i64) as i32
            }
        }
    };
}

impl_fx!(I16F16, 16, "I16F16");
impl_fx!(I20F12, 12, "I20F12");
impl_fx!(I12F20, 20, "I12F20");

/// [`Scalar::dot3_add`] of each row of `m` with `p` and the row's last entry.
#[inline(always)]
fn dot3_rows<S: Scalar>(m: &[[S; 4]; 4], p: [S; 3]) -> [S; 4] {
    let row = |i: usize| S::dot3_add([m[i][0], m[i][1], m[i][2]], p, m[i][3]);
    [row(0), row(1), row(2), row(3)]
}

/// [`dot3_rows`] out of line, for the values an assembly transform declines: inlined, its
/// spills would grow the frame of every caller (on a 16 KB part the stack has no room).
#[inline(never)]
fn dot3_rows_cold<S: Scalar>(m: &[[S; 4]; 4], p: [S; 3]) -> [S; 4] {
    dot3_rows(m, p)
}

/// [`Scalar::dot3_add`] of each of the first three rows of `m` with `v` and zero.
#[inline(always)]
fn dot3_dir_rows<S: Scalar>(m: &[[S; 4]; 4], v: [S; 3]) -> [S; 3] {
    let row = |i: usize| S::dot3_add([m[i][0], m[i][1], m[i][2]], v, S::ZERO);
    [row(0), row(1), row(2)]
}

/// [`dot3_dir_rows`] out of line (see [`dot3_rows_cold`]).
#[inline(never)]
fn dot3_dir_rows_cold<S: Scalar>(m: &[[S; 4]; 4], v: [S; 3]) -> [S; 3] {
    dot3_dir_rows(m, v)
}

#[cfg(test)]
#[path = "scalar_tests.rs"]
mod tests;
