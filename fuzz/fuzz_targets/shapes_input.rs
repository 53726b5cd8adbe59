//! Decodes fuzzer bytes into a shape constructor call (cube, torus, icosphere, terrain or plane,
//! and the textured cube, torus, icosphere and terrain of `TexturedShape`) with any parameters — NaN, infinities, huge and tiny lengths, counts up to `usize::MAX` — and runs
//! it with `Fx<I16F16>`, `Fx<I12F20>`, `f32` and `f64`. Shared by the fuzz target
//! (`fuzz_targets/shapes.rs`) and the host test `tests/hostile_shapes.rs`, which replays the
//! committed corpus (`fuzz/corpus/shapes`).
//!
//! A constructor must return `Ok` or a `ShapeError` that agrees with its documentation; any
//! panic (including a debug overflow) or failed check below is a crash. The capacities are
//! fixed and small (289 vertices, 512 triangles), so one input costs at most a few hundred
//! vertices per number type: a constructor that loops past its capacity check would time out.

use scanline3d::fixed::types::{I12F20, I16F16};
use scanline3d::mesh::ParamValue;
use scanline3d::prelude::*;
use scanline3d::{errors::ShapeError, Shape, TexturedShape};

const V: usize = 289;
const T: usize = 512;

struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn u8(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }
    fn u64(&mut self) -> u64 {
        u64::from_le_bytes([0; 8].map(|_| self.u8()))
    }
    /// A length: mode 0 any f64 bit pattern, 1 a small signed value (step 1/256, |v| < 128),
    /// 2 a power of two between 2⁻⁶⁴ and 2⁶³ (signed), 3 a special value.
    fn real(&mut self) -> f64 {
        match self.u8() % 4 {
            0 => f64::from_bits(self.u64()),
            1 => f64::from(i16::from_le_bytes([self.u8(), self.u8()])) / 256.0,
            2 => {
                let b = self.u8();
                let v = libm_exp2(i32::from(b & 0x7f) - 64);
                if b & 0x80 != 0 {
                    -v
                } else {
                    v
                }
            }
            _ => [
                0.0,
                -0.0,
                f64::NAN,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::MAX,
                f64::MIN_POSITIVE,
                32767.99999,
                2047.9,
                1e39,
                1.0,
                0.4,
            ][usize::from(self.u8()) % 12],
        }
    }
    /// A count: mode 0 a small value (0..=31), 1 any 64-bit value (truncated to usize), 2 a
    /// value next to a power of two (2^k − 1, 2^k, 2^k + 1).
    fn count(&mut self) -> usize {
        match self.u8() % 3 {
            0 => usize::from(self.u8() % 32),
            1 => self.u64() as usize,
            _ => {
                let k = u32::from(self.u8()) % usize::BITS;
                (1usize << k)
                    .wrapping_add(usize::from(self.u8() % 3))
                    .wrapping_sub(1)
            }
        }
    }
}

/// 2^e for |e| ≤ 64, exactly.
fn libm_exp2(e: i32) -> f64 {
    if e >= 0 {
        (1u128 << e) as f64
    } else {
        1.0 / (1u128 << -e) as f64
    }
}

#[derive(Copy, Clone, Debug)]
enum Call {
    Cube(f64),
    Torus(f64, f64, usize, usize),
    Icosphere(f64, u32),
    Terrain(f64, usize, f64),
    Plane(f64, f64, usize, usize),
}

/// A call and whether it is `TexturedShape`'s (the plane has no textured variant).
fn decode(data: &[u8]) -> (Call, bool) {
    let mut b = Bytes(data);
    let selector = b.u8();
    // 5, 13, 21, ...: the textured shapes, added after the seed corpus was written (no seed
    // of the plain shapes has such a selector); the next byte picks the shape, whose
    // parameters decode as the plain one's.
    if selector % 8 == 5 {
        let call = match b.u8() % 4 {
            0 => Call::Cube(b.real()),
            1 => Call::Torus(b.real(), b.real(), b.count(), b.count()),
            2 => Call::Icosphere(
                b.real(),
                u32::from(b.u8()) | (u32::from(b.u8() & 0x80) << 24),
            ),
            _ => Call::Terrain(b.real(), b.count(), b.real()),
        };
        return (call, true);
    }
    (decode_plain(selector, &mut b), false)
}

fn decode_plain(selector: u8, b: &mut Bytes) -> Call {
    // 4, 12, 20, ...: the plane, added after the seed corpus was written (whose selectors are
    // 0..=3 and 251); every other selector decodes as before.
    if selector % 8 == 4 {
        return Call::Plane(b.real(), b.real(), b.count(), b.count());
    }
    match selector % 4 {
        0 => Call::Cube(b.real()),
        1 => Call::Torus(b.real(), b.real(), b.count(), b.count()),
        2 => Call::Icosphere(
            b.real(),
            u32::from(b.u8()) | (u32::from(b.u8() & 0x80) << 24),
        ),
        _ => Call::Terrain(b.real(), b.count(), b.real()),
    }
}

fn usize_of(n: u128) -> Option<usize> {
    usize::try_from(n).ok()
}

/// Whether `value` of parameter `name` breaks the rule the constructor documents.
fn is_bad(call: Call, name: &str, value: ParamValue) -> bool {
    let bad_len = |v: f64| !(v.is_finite() && v > 0.0);
    match (call, name, value) {
        (Call::Cube(h), "h", ParamValue::Real(v)) => v.to_bits() == h.to_bits() && bad_len(h),
        (Call::Torus(br, _, _, _), "big_r", ParamValue::Real(v)) => {
            v.to_bits() == br.to_bits() && bad_len(br)
        }
        (Call::Torus(br, r, _, _), "r", ParamValue::Real(v)) => {
            v.to_bits() == r.to_bits() && (bad_len(r) || r > br)
        }
        (Call::Torus(_, _, nu, _), "nu", ParamValue::Count(n)) => n == nu as u64 && nu < 3,
        (Call::Torus(_, _, _, nv), "nv", ParamValue::Count(n)) => n == nv as u64 && nv < 3,
        (Call::Icosphere(rad, _), "radius", ParamValue::Real(v)) => {
            v.to_bits() == rad.to_bits() && bad_len(rad)
        }
        (Call::Icosphere(_, s), "subdivisions", ParamValue::Count(n)) => n == u64::from(s) && s > 4,
        (Call::Terrain(size, _, _), "size", ParamValue::Real(v)) => {
            v.to_bits() == size.to_bits()
                && (bad_len(size) || !(2.0 * core::f64::consts::PI * (size * 0.5)).is_finite())
        }
        (Call::Terrain(_, c, _), "cells", ParamValue::Count(n)) => n == c as u64 && c == 0,
        (Call::Terrain(_, _, a), "amplitude", ParamValue::Real(v)) => {
            v.to_bits() == a.to_bits() && !a.is_finite()
        }
        (Call::Plane(sx, _, _, _), "size_x", ParamValue::Real(v)) => {
            v.to_bits() == sx.to_bits() && bad_len(sx)
        }
        (Call::Plane(_, sz, _, _), "size_z", ParamValue::Real(v)) => {
            v.to_bits() == sz.to_bits() && bad_len(sz)
        }
        (Call::Plane(_, _, cx, _), "cells_x", ParamValue::Count(n)) => n == cx as u64 && cx == 0,
        (Call::Plane(_, _, _, cz), "cells_z", ParamValue::Count(n)) => n == cz as u64 && cz == 0,
        _ => false,
    }
}

/// Counts the call needs, exactly (`u128` holds every product of two `usize` values; a doubled
/// product can exceed it and saturates, which is still beyond `usize`).
fn needed(call: Call) -> (u128, u128) {
    match call {
        Call::Cube(_) => (24, 12),
        Call::Torus(_, _, nu, nv) => {
            let n = nu as u128 * nv as u128;
            (n, n.saturating_mul(2))
        }
        Call::Icosphere(_, s) => {
            let n4 = 1u128 << (2 * s.min(4));
            (10 * n4 + 2, 20 * n4)
        }
        Call::Terrain(_, c, _) => {
            let n = c as u128 + 1;
            (
                n.saturating_mul(n),
                (c as u128 * c as u128).saturating_mul(2),
            )
        }
        Call::Plane(_, _, cx, cz) => (
            (cx as u128 + 1).saturating_mul(cz as u128 + 1),
            (cx as u128 * cz as u128).saturating_mul(2),
        ),
    }
}

fn check<S: Scalar>(call: Call) {
    let r = match call {
        Call::Cube(h) => Shape::<S, V, T>::cube(h),
        Call::Torus(br, r, nu, nv) => Shape::<S, V, T>::torus(br, r, nu, nv),
        Call::Icosphere(rad, s) => Shape::<S, V, T>::icosphere(rad, s),
        Call::Terrain(size, c, a) => Shape::<S, V, T>::terrain(size, c, a),
        Call::Plane(sx, sz, cx, cz) => Shape::<S, V, T>::plane(sx, sz, cx, cz),
    };
    let (nv, nt) = needed(call);
    match r {
        Ok(s) => {
            assert_eq!(
                (s.positions.len() as u128, s.indices.len() as u128),
                (nv, nt),
                "{call:?}"
            );
            assert_eq!(s.normals.len(), s.positions.len());
            for t in &s.indices {
                assert!(
                    t.iter().all(|&i| usize::from(i) < s.positions.len()),
                    "{call:?}"
                );
            }
            for p in s.positions.iter().chain(s.normals.iter()) {
                assert!(
                    p.iter().all(|v| v.is_valid()),
                    "{call:?} gave {p:?} in {}",
                    S::NAME
                );
            }
            assert!(Mesh::new(&s.positions, &s.indices).is_ok());
        }
        Err(ShapeError::BadParameter { name, value, .. }) => {
            assert!(
                is_bad(call, name, value),
                "{call:?}: {name} = {value} is not bad"
            );
        }
        Err(ShapeError::OutOfRange {
            extent,
            number_type,
            rounds_to_zero,
        }) => {
            assert_eq!(number_type, S::NAME);
            let (hi, lo) = (S::from_f64(extent), S::from_f64(-extent));
            if rounds_to_zero {
                assert!(hi <= S::ZERO, "{call:?}: extent {extent} in {number_type}");
            } else {
                assert!(!(hi.is_valid() && lo.is_valid()), "{call:?}: {extent} fits");
            }
        }
        Err(ShapeError::Capacity {
            vertices,
            triangles,
            vertex_capacity,
            triangle_capacity,
        }) => {
            assert_eq!(
                (vertices, triangles),
                (usize_of(nv), usize_of(nt)),
                "{call:?}"
            );
            assert_eq!((vertex_capacity, triangle_capacity), (V, T));
            assert!(
                nv > V as u128 || nt > T as u128,
                "{call:?} fits but was refused"
            );
        }
        Err(e) => panic!("{call:?}: unknown error {e:?}"),
    }
}

/// The textured constructor's needs, exactly, when they differ from the plain shape's: the
/// torus splits its seams, `(nu + 1)·(nv + 1)` vertices (`u128` holds them: both factors are
/// at most 2⁶⁴; their product saturates, still beyond `usize`).
fn textured_needed(call: Call) -> (u128, u128) {
    match call {
        Call::Torus(_, _, nu, nv) => (
            (nu as u128 + 1).saturating_mul(nv as u128 + 1),
            needed(call).1,
        ),
        _ => needed(call),
    }
}

/// `TexturedShape`'s constructor: `Ok` with one texture coordinate per vertex (and a mesh that
/// carries them), or the plain constructor's errors with the textured vertex counts (the
/// icosphere's seam copies are not known in advance: its vertex count is only bounded below).
fn check_textured<S: Scalar>(call: Call) {
    let r = match call {
        Call::Cube(h) => TexturedShape::<S, V, T>::cube(h),
        Call::Torus(br, r, nu, nv) => TexturedShape::<S, V, T>::torus(br, r, nu, nv),
        Call::Icosphere(rad, s) => TexturedShape::<S, V, T>::icosphere(rad, s),
        Call::Terrain(size, c, a) => TexturedShape::<S, V, T>::terrain(size, c, a),
        Call::Plane(..) => unreachable!("the plane has no textured variant"),
    };
    let (nv, nt) = textured_needed(call);
    let ico = matches!(call, Call::Icosphere(..));
    match r {
        Ok(s) => {
            let shape = &s.shape;
            let nvs = shape.positions.len() as u128;
            if ico {
                assert!(nvs >= nv, "{call:?}");
                assert_eq!(shape.indices.len() as u128, nt, "{call:?}");
            } else {
                assert_eq!((nvs, shape.indices.len() as u128), (nv, nt), "{call:?}");
            }
            assert_eq!(shape.normals.len(), shape.positions.len(), "{call:?}");
            assert_eq!(s.uvs.len(), shape.positions.len(), "{call:?}");
            for t in &shape.indices {
                assert!(
                    t.iter().all(|&i| usize::from(i) < shape.positions.len()),
                    "{call:?}"
                );
            }
            for p in shape.positions.iter().chain(shape.normals.iter()) {
                assert!(
                    p.iter().all(|v| v.is_valid()),
                    "{call:?} gave {p:?} in {}",
                    S::NAME
                );
            }
            for uv in &s.uvs {
                assert!(
                    uv.iter().all(|v| v.is_valid()),
                    "{call:?} gave texture coordinates {uv:?} in {}",
                    S::NAME
                );
            }
            assert!(
                s.mesh().uvs().is_some(),
                "{call:?}: the mesh lost its texture coordinates in {}",
                S::NAME
            );
        }
        Err(ShapeError::BadParameter { name, value, .. }) => {
            assert!(
                is_bad(call, name, value),
                "{call:?}: {name} = {value} is not bad"
            );
        }
        Err(ShapeError::OutOfRange {
            extent,
            number_type,
            rounds_to_zero,
        }) => {
            assert_eq!(number_type, S::NAME);
            let (hi, lo) = (S::from_f64(extent), S::from_f64(-extent));
            if rounds_to_zero {
                assert!(hi <= S::ZERO, "{call:?}: extent {extent} in {number_type}");
            } else {
                assert!(!(hi.is_valid() && lo.is_valid()), "{call:?}: {extent} fits");
            }
        }
        Err(ShapeError::Capacity {
            vertices,
            triangles,
            vertex_capacity,
            triangle_capacity,
        }) => {
            assert_eq!((vertex_capacity, triangle_capacity), (V, T));
            assert_eq!(triangles, usize_of(nt), "{call:?}");
            if ico {
                // Either the plain icosphere does not fit, or its seam copies do not.
                let v = vertices.map_or(u128::MAX, |v| v as u128);
                assert!(v >= nv, "{call:?}: {vertices:?}");
                assert!(
                    v > V as u128 || nt > T as u128,
                    "{call:?} fits but was refused"
                );
            } else {
                assert_eq!(vertices, usize_of(nv), "{call:?}");
                assert!(
                    nv > V as u128 || nt > T as u128,
                    "{call:?} fits but was refused"
                );
            }
        }
        Err(e) => panic!("{call:?}: unknown error {e:?}"),
    }
}

/// Runs the constructor call encoded in `data` with every number type.
pub fn shapes_all(data: &[u8]) {
    let (call, textured) = decode(data);
    if textured {
        check_textured::<Fx<I16F16>>(call);
        check_textured::<Fx<I12F20>>(call);
        check_textured::<f32>(call);
        check_textured::<f64>(call);
        return;
    }
    check::<Fx<I16F16>>(call);
    check::<Fx<I12F20>>(call);
    check::<f32>(call);
    check::<f64>(call);
}
