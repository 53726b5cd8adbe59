//! Integer arithmetic shared by the number types, the kernels and the rasterizer: exact wide
//! products, rounding shifts, bit lengths, the normalized reciprocal and floor divisions, in
//! the 32-bit pieces a Cortex-M0 computes cheaply (no 64-bit multiply or divide instruction;
//! every `i64` product or division there is a library call, so these split them). Where the
//! core has a 32 × 32 → 64-bit multiply and a count-leading-zeros instruction (neither of
//! the capability cfgs `scanline3d_no_mul64`, `scanline3d_no_clz` of `build.rs`) the products
//! and bit lengths are the native ones, with the same results (the `*_split` forms are
//! compared with them by the host tests). Plain functions on integers: no number type, no
//! record, no target.

/// `v ^ (v >> 31)`: `v` for `v ≥ 0`, `|v| − 1` below; an OR of these is below `2^k` exactly
/// when every value is in `[−2^k, 2^k)`.
#[inline(always)]
#[must_use]
pub(crate) fn spread_bits(v: i32) -> i32 {
    v ^ (v >> 31)
}

/// The 16-bit halves of `v`: the low one unsigned, the high one signed (`v = h·2^16 + l`).
#[inline(always)]
pub(crate) fn halves(v: i32) -> (u32, i32) {
    ((v & 0xffff) as u32, v >> 16)
}

/// `(a·b + 2^15) >> 16` (a Q16.16 product rounded half up) for `a`, `b` in `[−2^23, 2^23)`,
/// in 32-bit arithmetic: the result is below 2^30 in magnitude, so it is the sum of
/// `(al·bl + 2^15) >> 16` (at most 2^32 − 2^17 + 2^15 before the shift: no carry is lost),
/// the cross products `al·bh + ah·bl` and `ah·bh·2^16`, each far inside `i32`.
#[inline(always)]
#[must_use]
pub(crate) fn mul_q16_small(a: i32, b: i32) -> i32 {
    if cfg!(scanline3d_no_mul64) {
        mul_q16_small_split(a, b)
    } else {
        ((a as i64 * b as i64 + (1 << 15)) >> 16) as i32
    }
}

/// [`mul_q16_small`] in 32-bit products, for cores without a 32 × 32 → 64-bit multiply (the
/// `scanline3d_no_mul64` cfg); compared with the native form by the host tests.
#[inline(always)]
#[must_use]
pub(crate) fn mul_q16_small_split(a: i32, b: i32) -> i32 {
    let ((al, ah), (bl, bh)) = (halves(a), halves(b));
    let low = ((al * bl + (1 << 15)) >> 16) as i32;
    low.wrapping_add((al as i32).wrapping_mul(bh))
        .wrapping_add(ah.wrapping_mul(bl as i32))
        .wrapping_add(ah.wrapping_mul(bh) << 16)
}

/// `(a·b + 2^15) >> 16` for the dot product of two 3-vectors with every component in
/// `[−2^22, 2^22)`, in 32-bit arithmetic (the result is below 3·2^28 in magnitude): the low
/// products' high halves are added as they are and their low halves summed (below 3·2^16)
/// before the rounding shift, so no carry between them is lost.
#[inline(always)]
#[must_use]
pub(crate) fn dot3_q16_small(a: [i32; 3], b: [i32; 3]) -> i32 {
    if cfg!(scanline3d_no_mul64) {
        dot3_q16_small_split(a, b)
    } else {
        ((a[0] as i64 * b[0] as i64
            + a[1] as i64 * b[1] as i64
            + a[2] as i64 * b[2] as i64
            + (1 << 15))
            >> 16) as i32
    }
}

/// [`dot3_q16_small`] in 32-bit products, for cores without a 32 × 32 → 64-bit multiply (the
/// `scanline3d_no_mul64` cfg); compared with the native form by the host tests.
#[inline(always)]
#[must_use]
pub(crate) fn dot3_q16_small_split(a: [i32; 3], b: [i32; 3]) -> i32 {
    let mut high = 0i32;
    let mut low = 1u32 << 15;
    let mut rest = 0i32;
    for k in 0..3 {
        let ((al, ah), (bl, bh)) = (halves(a[k]), halves(b[k]));
        let t = al * bl;
        high = high.wrapping_add((t >> 16) as i32);
        low += t & 0xffff;
        rest = rest
            .wrapping_add((al as i32).wrapping_mul(bh))
            .wrapping_add(ah.wrapping_mul(bl as i32))
            .wrapping_add(ah.wrapping_mul(bh) << 16);
    }
    high.wrapping_add((low >> 16) as i32).wrapping_add(rest)
}

/// The exact 64-bit product of two `i32`, from four 16 × 16-bit products.
///
/// On a Cortex-M0 `(a as i64) * (b as i64)` becomes a call to the general 64 × 64-bit
/// `__aeabi_lmul`; this needs only four single-instruction `MULS` and a few adds.
#[inline(always)]
#[must_use]
pub fn mul_wide(a: i32, b: i32) -> i64 {
    if cfg!(scanline3d_no_mul64) {
        mul_wide_split(a, b)
    } else {
        a as i64 * b as i64
    }
}

/// [`mul_wide`] in 32-bit products, for cores without a 32 × 32 → 64-bit multiply (the
/// `scanline3d_no_mul64` cfg); compared with the native form by the host tests.
#[inline(always)]
#[must_use]
pub(crate) fn mul_wide_split(a: i32, b: i32) -> i64 {
    let (al, ah) = ((a & 0xffff) as u32, a >> 16);
    let (bl, bh) = ((b & 0xffff) as u32, b >> 16);
    let lo = al * bl; // < 2^32
    let m1 = ah * bl as i32; // |.| < 2^31
    let m2 = al as i32 * bh; // |.| < 2^31
    let hi = ah * bh; // |.| ≤ 2^30
    ((hi as i64) << 32) + (((m1 as i64) + (m2 as i64)) << 16) + lo as i64
}

/// `x >> k` (arithmetic, `k ≤ 63`) as its high and low 32-bit words, from 32-bit shifts: a
/// 64-bit shift by a variable amount is a library call on a Cortex-M0.
#[inline(always)]
pub(crate) fn shr_words(x: i64, k: u32) -> (i32, u32) {
    let (lo, hi) = (x as u32, (x >> 32) as i32);
    if k >= 32 {
        let h = hi >> (k - 32).min(31);
        (h >> 31, h as u32)
    } else if k == 0 {
        (hi, lo)
    } else {
        (hi >> k, (lo >> k) | ((hi as u32) << (32 - k)))
    }
}

/// `x >> s` (arithmetic, `s < 32`) for a result that fits in an `i32`, from 32-bit shifts: a
/// 64-bit shift by a variable amount is a library call on a Cortex-M0.
#[inline(always)]
#[must_use]
#[cfg(test)]
pub fn shr_to_i32(x: i64, s: u32) -> i32 {
    shr_words(x, s).1 as i32
}

/// `clamp((x >> (s − 1)) + 1) >> 1, −limit, limit)` — `x / 2^s` rounded half up — for
/// `1 ≤ s ≤ 63` and `limit ≤ 2³⁰`, from 32-bit shifts (a 64-bit shift by a variable amount
/// is a library call on a Cortex-M0). Results beyond the `i32` range saturate, as they would
/// have after the clamp.
#[inline]
#[must_use]
#[cfg(test)]
pub fn round_shr_sat(x: i64, s: u32, limit: i32) -> i32 {
    let (thi, tlo) = shr_words(x, s - 1);
    if thi != (tlo as i32) >> 31 {
        // |t| ≥ 2³¹, so |t + 1| / 2 ≥ 2³⁰ ≥ limit.
        return if thi < 0 { -limit } else { limit };
    }
    let t = tlo as i32;
    ((t >> 1) + (t & 1)).clamp(-limit, limit)
}

/// `(x + 2^(s−1)) >> s` — `x / 2^s` rounded half up — for `1 ≤ s ≤ 62` and `|x| < 2⁶²`, from
/// 32-bit shifts (a 64-bit shift by a variable amount is a library call on a Cortex-M0).
#[inline]
#[must_use]
pub fn round_shr64(x: i64, s: u32) -> i64 {
    let k = s - 1;
    let half = if k >= 32 {
        ((1u32 << (k - 32).min(31)) as i64) << 32
    } else {
        (1u32 << k) as i64
    };
    let (hi, lo) = shr_words(x + half, s);
    ((hi as i64) << 32) | lo as i64
}

/// The exact product of an `i32` and a 16-bit `b` (`−2¹⁵ ≤ b < 2¹⁵`), from two 16 × 16-bit
/// products (see [`mul_wide`], which needs four).
#[inline(always)]
#[must_use]
pub fn mul_wide16(a: i32, b: i32) -> i64 {
    if cfg!(scanline3d_no_mul64) {
        mul_wide16_split(a, b)
    } else {
        a as i64 * b as i64
    }
}

/// [`mul_wide16`] in 32-bit products, for cores without a 32 × 32 → 64-bit multiply (the
/// `scanline3d_no_mul64` cfg); compared with the native form by the host tests.
#[inline(always)]
#[must_use]
pub(crate) fn mul_wide16_split(a: i32, b: i32) -> i64 {
    let (al, ah) = (a & 0xffff, a >> 16);
    // |al·b| ≤ 65535·2¹⁵ < 2³¹, |ah·b| ≤ 2³⁰.
    (((ah * b) as i64) << 16) + (al * b) as i64
}

/// The exact product of two `u32`, from four 16 × 16-bit products (see [`mul_wide`]).
#[inline(always)]
#[must_use]
pub fn mul_wide_u(a: u32, b: u32) -> u64 {
    if cfg!(scanline3d_no_mul64) {
        mul_wide_u_split(a, b)
    } else {
        a as u64 * b as u64
    }
}

/// [`mul_wide_u`] in 32-bit products, for cores without a 32 × 32 → 64-bit multiply (the
/// `scanline3d_no_mul64` cfg); compared with the native form by the host tests.
#[inline(always)]
#[must_use]
pub(crate) fn mul_wide_u_split(a: u32, b: u32) -> u64 {
    let (al, ah) = (a & 0xffff, a >> 16);
    let (bl, bh) = (b & 0xffff, b >> 16);
    // Summed in 32-bit words with explicit carries: written as one 64-bit expression, LLVM
    // folds it back into a library 64 × 64-bit multiply on a Cortex-M0.
    let (mid, c1) = (ah * bl).overflowing_add(al * bh);
    let (low, c2) = (al * bl).overflowing_add(mid << 16);
    let high = ah * bh + (mid >> 16) + ((c1 as u32) << 16) + c2 as u32;
    ((high as u64) << 32) | low as u64
}

/// Significant bits of each byte value (0 for 0): the last step of [`bitlen32`]. 256 bytes
/// of flash.
const BITLEN8: [u8; 256] = {
    let mut t = [0u8; 256];
    let mut i = 1;
    while i < 256 {
        t[i] = (8 - (i as u8).leading_zeros()) as u8;
        i += 1;
    }
    t
};

/// Number of significant bits of a `u32` (0 for 0; `32 − leading_zeros`): two halving steps
/// and a table, about 12 instructions inline on a Cortex-M0, which has no count-leading-zeros
/// instruction (the library `__clzsi2` is a call of about 33).
#[inline(always)]
#[must_use]
pub fn bitlen32(x: u32) -> u32 {
    if cfg!(scanline3d_no_clz) {
        bitlen32_split(x)
    } else {
        32 - x.leading_zeros()
    }
}

/// [`bitlen32`] without a count-leading-zeros instruction (the `scanline3d_no_clz` cfg);
/// compared with the native form by the host tests.
#[inline(always)]
#[must_use]
pub(crate) fn bitlen32_split(x: u32) -> u32 {
    let (mut n, mut x) = (0, x);
    if x >> 16 != 0 {
        n = 16;
        x >>= 16;
    }
    if x >> 8 != 0 {
        n += 8;
        x >>= 8;
    }
    // At most 24 + 8; the `min` tells the compiler so (shifts by the result then need no
    // masking or 64-bit library calls).
    (n + BITLEN8[(x & 0xff) as usize] as u32).min(32)
}

/// Number of significant bits of a `u64` (0 for 0), from [`bitlen32`].
#[inline]
pub(crate) fn bitlen64(a: u64) -> u32 {
    if cfg!(scanline3d_no_clz) {
        bitlen64_split(a)
    } else {
        64 - a.leading_zeros()
    }
}

/// [`bitlen64`] without a count-leading-zeros instruction (the `scanline3d_no_clz` cfg);
/// compared with the native form by the host tests.
#[inline(always)]
#[must_use]
pub(crate) fn bitlen64_split(a: u64) -> u32 {
    let hi = (a >> 32) as u32;
    if hi != 0 {
        32 + bitlen32(hi)
    } else {
        bitlen32(a as u32)
    }
}

/// `2³²/d` for `d` in the middle of each of the 128 intervals `[2⁸·(128 + i), 2⁸·(129 + i))`,
/// less 2¹⁶ (so it fits a `u16`): the seed of [`recip_norm`], relative error ≤ 2⁻⁸ over the
/// interval
/// (half its width over its start, 2⁷/2¹⁵). 256 bytes of flash.
pub(crate) const RECIP_SEED: [u16; 128] = {
    let mut t = [0u16; 128];
    let mut i = 0;
    while i < 128 {
        // Midpoint 2⁸·(128 + i) + 2⁷, rounded quotient.
        let d = (256 * (128 + i) + 128) as u64;
        t[i] = (((1u64 << 32) + d / 2) / d - (1 << 16)) as u16;
        i += 1;
    }
    t
};

/// `1/a` for `a ≥ 1` as `m · 2^-e` with `m` in (2²⁹, 2³⁰] (relative error below 2⁻²⁸), with no
/// division at all — on a Cortex-M0 even a 32-bit division is a library call of about 200
/// instructions. From the 16 leading bits `d` of `a`: a table seed for `2³²/d` (2⁻⁸), one
/// Newton step in 32-bit products (about 2⁻¹⁵), then one in 64-bit products for all 32
/// leading bits of `a` (below 2⁻²⁹).
#[must_use]
pub fn recip_norm(a: u64) -> (i32, u32) {
    let a = a.max(1);
    let s = bitlen64(a);
    // a32 in [2^31, 2^32) carries the 32 leading bits of a: a ≈ a32 · 2^(s − 32).
    // In 32-bit shifts (s ≥ 1 here; a 64-bit shift by a variable amount is a library call on
    // a Cortex-M0).
    let a32 = if s > 32 {
        let (hi, lo, k) = ((a >> 32) as u32, a as u32, s - 32); // 1 ≤ k ≤ 32
        if k == 32 {
            hi
        } else {
            (hi << (32 - k)) | (lo >> k)
        }
    } else {
        (a as u32) << (32 - s)
    };
    let d = a32 >> 16; // [2^15, 2^16)
    let x0 = RECIP_SEED[((d >> 8) & 127) as usize] as u32 + (1 << 16); // ≈ 2^32/d, (2^16, 2^17]
                                                                       // e = 2^32 − d·x0, exact modulo 2^32 and |e| ≤ 2^24, so it is exact as an i32.
    let e = 0u32.wrapping_sub(d.wrapping_mul(x0)) as i32;
    // x1 = x0 + x0·e/2^32, in a 16 × 15-bit product: |(x0/2)·(e/2^10)| ≤ 2^30.
    let x1 = (x0 as i32 + (((x0 >> 1) as i32 * (e >> 10)) >> 21)) as u32;
    // 2^61 / a32 ≈ x1 · 2^13, then m' = m + m·(2^61 − a32·m)/2^61.
    let m0 = (x1 as u64) << 13;
    // |err| < 2^47, so the correction is below 2¹⁷ in magnitude (m0 ≤ 2³⁰) and m1 fits an
    // i32.
    let err = (1i64 << 61) - mul_wide_u(a32, m0 as u32) as i64;
    let m1 = m0 as i32 + (mul_wide(m0 as i32, (err >> 30) as i32) >> 31) as i32;
    // 1/a = m1 · 2^-(61 + s − 32).
    (m1.clamp(1, 1 << 30), 29 + s)
}

/// `round(n · k / 2³²)` for `|n| < 2⁶²`, `k < 2³¹`, without a 64 × 64-bit multiply: `n` is split
/// into its high and low words. Saturates instead of overflowing.
#[inline]
#[must_use]
pub fn mul_q32(n: i64, k: u32) -> i64 {
    let hi = n >> 32; // signed
    let lo = n as u32;
    if hi == hi as i16 as i64 && k < 1 << 16 {
        return mul_q32_short(hi, lo, k);
    }
    let l = (mul_wide_u(lo, k) + (1 << 31)) >> 32;
    if hi == 0 {
        return l as i64;
    }
    if hi == hi as i16 as i64 && k < 1 << 31 {
        // The common case (on-screen coordinates): |hi·k| < 2⁴⁶, nothing to saturate, and a
        // 32 × 16-bit product instead of a library 64-bit multiply.
        return mul_wide16(k as i32, hi as i32) + l as i64;
    }
    (hi.saturating_mul(k as i64)).saturating_add(l as i64)
}

/// [`mul_q32`] of `n = hi·2³² + lo` for `hi` in the `i16` range and `k < 2¹⁶` (screen scales,
/// 8 × the viewport size): `|hi·k| < 2³¹`, one 32-bit product. (Written as a 32 × 16-bit
/// `mul_wide16`, LLVM turned it back into a library 64-bit multiply.) The low word's rounded
/// part in two 16-bit products: `lo·k = t·2¹⁶ + r` with
/// `t = (lo >> 16)·k + ((lo & 0xffff)·k >> 16) < 2³² − 2¹⁶` and `r < 2¹⁶`, and `r` cannot
/// carry the rounding, so `(lo·k + 2³¹) >> 32 = (t + 2¹⁵) >> 16`.
#[inline(always)]
pub(crate) fn mul_q32_short(hi: i64, lo: u32, k: u32) -> i64 {
    let t = (lo >> 16) * k + (((lo & 0xffff) * k) >> 16);
    let l = (t + (1 << 15)) >> 16;
    (hi as i32 * k as i32) as i64 + l as i64
}

/// `(p + 2^(s−1)) >> s` (arithmetic, `0 < s < 32`) as its high and low words, in 32-bit
/// shifts: the common case of the fixed-point [`Scalar::ndc`].
#[inline(always)]
pub(crate) fn round_shr_words(p: i64, s: u32) -> (i32, u32) {
    let (hi, lo) = ((p >> 32) as i32, p as u32);
    let (lo, c) = lo.overflowing_add(1 << (s - 1));
    let hi = hi + c as i32;
    (hi >> s, (lo >> s) | ((hi as u32) << (32 - s)))
}

/// Saturates an `i64` to `i32`.
#[inline(always)]
pub(crate) fn sat32(v: i64) -> i32 {
    if v > i32::MAX as i64 {
        i32::MAX
    } else if v < i32::MIN as i64 {
        i32::MIN
    } else {
        v as i32
    }
}

/// `(floor(n / d), n − d·floor(n / d))` for `d > 0` and a quotient that fits in `i32`: one
/// 32-bit division when `n` fits.
#[inline]
pub(crate) fn div_floor(n: i64, d: i32) -> (i32, i32) {
    if let Ok(n32) = i32::try_from(n) {
        let (mut q, mut r) = (n32 / d, n32 % d);
        if r < 0 {
            q -= 1;
            r += d;
        }
        (q, r)
    } else {
        let d = d as i64;
        (n.div_euclid(d) as i32, n.rem_euclid(d) as i32)
    }
}

/// `(n / d, n % d)` for `d > 0` by shift and subtract, one step per quotient bit (the
/// kernel's small division on cores without a divide instruction; tested on the host too).
#[inline]
#[cfg_attr(not(any(test, scanline3d_no_divide)), allow(dead_code))]
pub(crate) fn udiv_shift_subtract(n: u32, d: u32) -> (u32, u32) {
    if n < d {
        return (0, n);
    }
    let (mut dd, mut bit) = (d, 1u32);
    let half = n >> 1;
    while dd <= half {
        dd <<= 1;
        bit <<= 1;
    }
    // d·bit ≤ n < 2·d·bit.
    let (mut q, mut r) = (0, n);
    loop {
        if r >= dd {
            r -= dd;
            q |= bit;
        }
        if bit == 1 {
            return (q, r);
        }
        bit >>= 1;
        dd >>= 1;
    }
}

/// `n / 3` (floor) for every `u32`, by shifts and adds: `q ≈ n·0.0101…₂` from below, then
/// the remainder `r = n − 3q` (0..=15 here) corrects it, `r·11 >> 5` = `r/3` for such `r`
/// (the method of Warren's *Hacker's Delight*, 10–18). Checked against `/` in the tests.
#[inline(always)]
fn udiv3(n: u32) -> u32 {
    let mut q = (n >> 2) + (n >> 4);
    q += q >> 4;
    q += q >> 8;
    q += q >> 16;
    let r = n - q * 3;
    q + ((r * 11) >> 5)
}

/// `n / 5` (floor) for every `u32`, as [`udiv3`]: `q ≈ n·0.00110011…₂`, `r = n − 5q` below
/// 32, `r·13 >> 6` = `r/5` for such `r`.
#[inline(always)]
fn udiv5(n: u32) -> u32 {
    let mut q = (n >> 3) + (n >> 4);
    q += q >> 4;
    q += q >> 8;
    q += q >> 16;
    let r = n - q * 5;
    q + ((r * 13) >> 6)
}

/// `n / 7` (floor) for every `u32`, as [`udiv3`]: `q ≈ n·0.001001…₂`, `r = n − 7q` below 64,
/// `(r + 1) >> 3` = `r/7` for such `r`.
#[inline(always)]
fn udiv7(n: u32) -> u32 {
    let mut q = (n >> 1) + (n >> 4);
    q += q >> 6;
    q += (q >> 12) + (q >> 24);
    q >>= 2;
    let r = n - q * 7;
    q + ((r + 1) >> 3)
}

/// `⌈2¹⁹/d⌉` for `d` in 9..=15 (index `d − 9`), the reciprocals of [`udiv_chunks`].
const RECIP19: [u32; 7] = {
    let mut t = [0u32; 7];
    let mut i = 0;
    while i < 7 {
        let d = i as u32 + 9;
        t[i] = (1u32 << 19).div_ceil(d);
        i += 1;
    }
    t
};

/// `n / d` (floor) for every `u32` and `d` in 9..=15, in 32-bit products: the quotient's 10,
/// 11 and 11 bits from the top, each of a partial numerator `x = r·2^bits + chunk` below
/// `d·2¹¹ ≤ 2¹⁵` (`r` the remainder so far) as `x·⌈2¹⁹/d⌉ >> 19`. That is exact for such `x`:
/// the reciprocal's excess `e = m·d − 2¹⁹ < d` adds `x·e/(d·2¹⁹) < 1/d` to `x/d`, whose
/// fraction is at most `(d − 1)/d`; `x·m < 2¹⁵·2¹⁶`.
#[inline(always)]
fn udiv_chunks(n: u32, d: u32) -> u32 {
    let m = RECIP19[(d - 9) as usize];
    let (mut q, mut r) = (0u32, 0u32);
    for (shift, bits) in [(22, 10), (11, 11), (0, 11)] {
        let x = (r << bits) | ((n >> shift) & ((1 << bits) - 1));
        let qi = (x * m) >> 19;
        r = x - qi * d;
        q = (q << bits) | qi;
    }
    q
}

/// `n / len` (toward zero, as Rust's `/`) for `1 ≤ len ≤ 15` and any `n`, without a division:
/// shifts for 1, 2, 4, 8, [`udiv3`], [`udiv5`], [`udiv7`] (6: 3 after 2), [`udiv_chunks`]
/// for 9 to 15, on `|n|`, the sign put back. Other divisors take `/`. A span's segment step
/// on cores without a divide instruction (ARMv6-M: the library's division takes some tens of
/// instructions, these about ten to thirty).
#[inline]
#[cfg_attr(not(any(test, scanline3d_no_divide)), allow(dead_code))]
pub(crate) fn div_by_small_shift_add(n: i32, len: i32) -> i32 {
    let a = n.unsigned_abs();
    let q = match len {
        1 => a,
        2 => a >> 1,
        3 => udiv3(a),
        4 => a >> 2,
        5 => udiv5(a),
        6 => udiv3(a >> 1),
        7 => udiv7(a),
        8 => a >> 3,
        9..=15 => udiv_chunks(a, len as u32),
        _ => return n.wrapping_div(len),
    };
    // q ≤ 2³¹ (2³¹ for n = i32::MIN, len = 1: wraps back to i32::MIN, as `wrapping_div`).
    if n < 0 {
        (q as i32).wrapping_neg()
    } else {
        q as i32
    }
}

/// `(m·v) >> l` (floor) for `0 < m ≤ 2³⁰`, `1 ≤ l ≤ 16` and `|v| < 2^l`, in 32-bit
/// products: with `m = mh·2¹⁵ + ml`, both `mh·v` and `ml·v` are below 2³¹; for `l ≤ 15` the
/// first term shifted is a whole multiple of `2^l`, and for `l = 16` the two floors nest. The
/// result, below 2³⁰ in magnitude, is that of the 64-bit product (a triangle's gradient
/// coefficients: about 20 instructions fewer each on a Cortex-M0).
#[inline(always)]
pub(crate) fn mul_shr_16(m: i32, v: i32, l: u32) -> i32 {
    if !cfg!(scanline3d_no_mul64) {
        return ((m as i64 * v as i64) >> l) as i32; // one long multiply
    }
    let (mh, ml) = (m >> 15, m & 0x7fff);
    if l <= 15 {
        ((mh * v) << (15 - l)) + ((ml * v) >> l)
    } else {
        ((mh * v) + ((ml * v) >> 15)) >> 1
    }
}

/// `g·d` modulo 2⁶⁴ for a gradient `g` and a subpixel offset `|d| < 2¹⁵` ([`mul_wide16`]'s
/// range) or any `d` (a 64-bit multiply).
#[inline(always)]
pub(crate) fn wide_plane(g: i64, d: i32) -> i64 {
    if !cfg!(scanline3d_no_mul64) {
        return g.wrapping_mul(d as i64);
    }
    if g == g as i32 as i64 && d == d as i16 as i32 {
        mul_wide16(g as i32, d)
    } else {
        g.wrapping_mul(d as i64)
    }
}

#[cfg(test)]
mod split_tests {
    use super::*;

    fn xorshift(s: &mut u32) -> u32 {
        *s ^= *s << 13;
        *s ^= *s >> 17;
        *s ^= *s << 5;
        *s
    }

    /// The formulations for cores without a long multiply or CLZ (ARMv6-M) against the native
    /// ones the host runs, over their documented ranges.
    #[test]
    fn split_formulations_equal_native() {
        let mut s = 0x1234_5678;
        for i in 0..200_000u32 {
            let (a, b) = (xorshift(&mut s) as i32, xorshift(&mut s) as i32);
            let sh = i % 32;
            let (a, b) = (a >> sh, b >> (31 - sh));
            assert_eq!(mul_wide_split(a, b), a as i64 * b as i64);
            assert_eq!(
                mul_wide16_split(a, b as i16 as i32),
                a as i64 * b as i16 as i64
            );
            assert_eq!(
                mul_wide_u_split(a as u32, b as u32),
                a as u32 as u64 * b as u32 as u64
            );
            assert_eq!(bitlen32_split(a as u32), 32 - (a as u32).leading_zeros());
            let w = ((a as u64) << (sh + 1)) ^ b as u32 as u64;
            assert_eq!(bitlen64_split(w), 64 - w.leading_zeros());
            let (p, q) = (a >> 8, b >> 8); // [−2²³, 2²³)
            assert_eq!(
                mul_q16_small_split(p, q),
                ((p as i64 * q as i64 + (1 << 15)) >> 16) as i32
            );
            let c = [a >> 9, b >> 9, (a ^ b) >> 9]; // [−2²², 2²²)
            let d = [b >> 10, a >> 9, (a.wrapping_add(b)) >> 9];
            let want = (c
                .iter()
                .zip(d)
                .map(|(&x, y)| x as i64 * y as i64)
                .sum::<i64>()
                + (1 << 15))
                >> 16;
            assert_eq!(dot3_q16_small_split(c, d), want as i32);
        }
    }

    /// The shift-and-add division against `wrapping_div`: every numerator below 2¹⁸ in
    /// magnitude, random ones over the whole `i32` range, and the ends, for each divisor
    /// 1..=17 (16 and 17 take `/` themselves).
    #[test]
    fn shift_add_division_equals_native() {
        let check = |n: i32, len: i32| {
            assert_eq!(
                div_by_small_shift_add(n, len),
                n.wrapping_div(len),
                "{n} / {len}"
            );
        };
        for len in 1..=17 {
            for n in -(1 << 18)..=1 << 18 {
                check(n, len);
            }
            for n in [i32::MIN, i32::MIN + 1, i32::MAX, i32::MAX - 1, -1, 0, 1] {
                check(n, len);
            }
            let mut s = 0x9e37_79b9 ^ len as u32;
            for i in 0..200_000u32 {
                check((xorshift(&mut s) >> (i % 8)) as i32, len);
            }
        }
    }

    /// [`udiv_chunks`]'s step: every partial numerator below `d·2¹¹`, every divisor.
    #[test]
    fn chunk_step_is_exact() {
        for d in 9..=15u32 {
            let m = RECIP19[(d - 9) as usize];
            for x in 0..d << 11 {
                assert_eq!((x * m) >> 19, x / d, "{x} / {d}");
            }
        }
    }

    /// The unsigned divisions over every `u32` (about 43 billion operations, a few minutes:
    /// run with `cargo test --release -p scanline3d -- --ignored every_u32`).
    #[test]
    #[ignore]
    fn shift_add_division_every_u32() {
        for n in 0..=u32::MAX {
            assert_eq!((udiv3(n), udiv5(n), udiv7(n)), (n / 3, n / 5, n / 7), "{n}");
            for d in 9..=15 {
                assert_eq!(udiv_chunks(n, d), n / d, "{n} / {d}");
            }
        }
    }
}
