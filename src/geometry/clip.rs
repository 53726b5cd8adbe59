//! Clipping in homogeneous clip space, before the perspective divide.
//!
//! Every vertex gets a 6-bit outcode against the view volume (`−w ≤ x ≤ w`, `−w ≤ y ≤ w`,
//! `0 ≤ z ≤ w`) plus a seventh bit when it lies outside the x/y **guard band**
//! (`|x|, |y| ≤ G·w`). A triangle whose three outcodes share a bit is rejected; one with no
//! near, far or guard bit set needs no clipping at all (the rasterizer scissors x/y to the
//! screen). Otherwise the triangle is clipped by Sutherland–Hodgman against the near plane, the
//! far plane and, only where needed, the guard-band planes, so that no vertex behind the eye is
//! ever divided by and no projected coordinate can overflow.
//!
//! Intersections are always computed from the inside vertex toward the outside one, so an edge
//! shared by two triangles is cut at bit-identical points in both (no cracks).

use crate::num::scalar::Scalar;

pub use crate::kernel::records::{BOTTOM, FAR, GUARD, LEFT, NEAR, NEEDS_CLIP, RIGHT, TOP};

/// The 6-bit outcode of `p = (x, y, z, w)`, plus [`GUARD`] when `|x|` or `|y|` exceeds `g·w`.
#[must_use]
pub fn outcode<S: Scalar>(p: [S; 4], g: S) -> u8 {
    let [x, y, z, w] = p;
    let mut c = 0;
    if x < -w {
        c |= LEFT;
    }
    if x > w {
        c |= RIGHT;
    }
    if y < -w {
        c |= BOTTOM;
    }
    if y > w {
        c |= TOP;
    }
    if z < S::ZERO {
        c |= NEAR;
    }
    if z > w {
        c |= FAR;
    }
    // Inside the x/y planes (|x|, |y| ≤ w, so w ≥ 0) with g ≥ 1 is inside the band: the
    // product is needed only for points outside them (most vertices of a frame are not).
    if c & (LEFT | RIGHT | BOTTOM | TOP) != 0 || g < S::ONE {
        let gw = g * w;
        if x < -gw || x > gw || y < -gw || y > gw {
            c |= GUARD;
        }
    }
    c
}

/// A polygon vertex during clipping: clip-space position and colour (8.8 fixed point per
/// channel in the target's channel units, see [`crate::scene::color`]).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct ClipVertex<S> {
    /// Clip-space position (x, y, z, w).
    pub pos: [S; 4],
    /// Colour channels, unsigned 8.8 fixed point (range 0..=65280, step 1/256 channel unit).
    pub rgb: [u16; 3],
}

/// The most vertices a clipped triangle can have: 3 plus one per clipping plane (6).
pub const MAX_CLIPPED: usize = 9;

#[derive(Copy, Clone)]
enum Plane {
    Near,
    Far,
    Left,
    Right,
    Bottom,
    Top,
}

fn distance<S: Scalar>(plane: Plane, p: [S; 4], g: S) -> S {
    let [x, y, z, w] = p;
    match plane {
        Plane::Near => z,
        Plane::Far => w - z,
        Plane::Left => x + g * w,
        Plane::Right => g * w - x,
        Plane::Bottom => y + g * w,
        Plane::Top => g * w - y,
    }
}

fn intersect<S: Scalar>(
    inside: &ClipVertex<S>,
    outside: &ClipVertex<S>,
    di: S,
    d_o: S,
) -> ClipVertex<S> {
    // t in [0, 1] from the inside vertex; di ≥ 0 > d_o so the denominator is positive.
    let t = di / (di - d_o);
    let t = t.max(S::ZERO).min(S::ONE);
    let mut pos = inside.pos;
    for (k, p) in pos.iter_mut().enumerate() {
        *p = *p + t * (outside.pos[k] - *p);
    }
    let tq = t.to_fixed_i32(16) as i64;
    let mut rgb = inside.rgb;
    for (k, c) in rgb.iter_mut().enumerate() {
        let d = outside.rgb[k] as i64 - *c as i64;
        *c = (*c as i64 + ((d * tq + (1 << 15)) >> 16)).clamp(0, u16::MAX as i64) as u16;
    }
    ClipVertex { pos, rgb }
}

/// A convex polygon of at most [`MAX_CLIPPED`] vertices.
#[derive(Clone, Debug)]
pub struct Polygon<S> {
    /// The vertices, counter-clockwise as the input triangle was.
    pub v: heapless::Vec<ClipVertex<S>, MAX_CLIPPED>,
}

fn clip_plane<S: Scalar>(poly: &Polygon<S>, plane: Plane, g: S) -> Polygon<S> {
    let mut out = Polygon {
        v: heapless::Vec::new(),
    };
    let n = poly.v.len();
    for i in 0..n {
        let a = &poly.v[i];
        let b = &poly.v[(i + 1) % n];
        let da = distance(plane, a.pos, g);
        let db = distance(plane, b.pos, g);
        let (ina, inb) = (da >= S::ZERO, db >= S::ZERO);
        if ina {
            // Capacity: each plane adds at most one vertex to a convex polygon, and at most
            // six planes are applied to a triangle, so pushes cannot fail.
            let _ = out.v.push(*a);
        }
        if ina != inb {
            let p = if ina {
                intersect(a, b, da, db)
            } else {
                intersect(b, a, db, da)
            };
            let _ = out.v.push(p);
        }
    }
    out
}

/// Clips triangle `tri` against the planes its vertices' outcodes `codes` (OR-ed) call for:
/// near and far always when set, the guard band only when a vertex lies outside it.
/// Returns a convex polygon with 0 or 3..=9 vertices.
#[must_use]
pub fn clip_triangle<S: Scalar>(tri: [ClipVertex<S>; 3], codes: u8, g: S) -> Polygon<S> {
    let mut poly = Polygon {
        v: heapless::Vec::new(),
    };
    for v in tri {
        let _ = poly.v.push(v);
    }
    let mut planes: heapless::Vec<Plane, 6> = heapless::Vec::new();
    if codes & NEAR != 0 {
        let _ = planes.push(Plane::Near);
    }
    if codes & FAR != 0 {
        let _ = planes.push(Plane::Far);
    }
    if codes & GUARD != 0 {
        for p in [Plane::Left, Plane::Right, Plane::Bottom, Plane::Top] {
            let _ = planes.push(p);
        }
    }
    for p in planes {
        if poly.v.len() < 3 {
            break;
        }
        poly = clip_plane(&poly, p, g);
    }
    if poly.v.len() < 3 {
        poly.v.clear();
    }
    poly
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::scalar::Fx;
    use fixed::types::I16F16;

    fn cv<S: Scalar>(x: f64, y: f64, z: f64, w: f64) -> ClipVertex<S> {
        ClipVertex {
            pos: [
                S::from_f64(x),
                S::from_f64(y),
                S::from_f64(z),
                S::from_f64(w),
            ],
            rgb: [0, 100, 65280],
        }
    }

    #[test]
    fn outcodes_name_each_plane() {
        let g = 8.0f64;
        assert_eq!(outcode([0.0, 0.0, 0.5, 1.0], g), 0);
        assert_eq!(outcode([-2.0, 0.0, 0.5, 1.0], g), LEFT);
        assert_eq!(outcode([2.0, 3.0, 0.5, 1.0], g), RIGHT | TOP);
        assert_eq!(outcode([0.0, -2.0, -0.1, 1.0], g), BOTTOM | NEAR);
        assert_eq!(outcode([0.0, 0.0, 1.5, 1.0], g), FAR);
        assert_eq!(outcode([9.0, 0.0, 0.5, 1.0], g), RIGHT | GUARD);
        // Behind the eye: w < 0, z < 0.
        assert_ne!(outcode([0.0, 0.0, -1.2, -1.0], g) & NEAR, 0);
    }

    fn near_clip_one_and_two_behind<S: Scalar>() {
        let g = S::from_f64(8.0);
        // One vertex behind the near plane: quad.
        let t = [
            cv::<S>(-1.0, -1.0, 0.5, 1.0),
            cv(1.0, -1.0, 0.5, 1.0),
            cv(0.0, 1.0, -0.5, 0.5),
        ];
        let p = clip_triangle(t, NEAR, g);
        assert_eq!(p.v.len(), 4);
        for v in &p.v {
            assert!(v.pos[2] >= S::ZERO);
            assert!(v.pos[3] > S::ZERO);
        }
        // Two behind: triangle.
        let t = [
            cv::<S>(-1.0, -1.0, 0.5, 1.0),
            cv(1.0, -1.0, -0.5, 0.5),
            cv(0.0, 1.0, -0.5, 0.5),
        ];
        assert_eq!(clip_triangle(t, NEAR, g).v.len(), 3);
        // All behind: nothing.
        let t = [
            cv::<S>(-1.0, -1.0, -0.5, 0.5),
            cv(1.0, -1.0, -0.5, 0.5),
            cv(0.0, 1.0, -0.5, 0.5),
        ];
        assert_eq!(clip_triangle(t, NEAR, g).v.len(), 0);
    }

    #[test]
    fn near_plane_clipping_for_every_type() {
        near_clip_one_and_two_behind::<f64>();
        near_clip_one_and_two_behind::<f32>();
        near_clip_one_and_two_behind::<Fx<I16F16>>();
    }

    #[test]
    fn shared_edge_is_cut_at_identical_points() {
        let g = 8.0f32;
        let a = cv::<f32>(-0.3, 0.7, 0.9, 1.3);
        let b = cv::<f32>(0.4, -0.2, -0.7, 0.3);
        let c = cv::<f32>(0.8, 0.8, 0.5, 1.1);
        let d = cv::<f32>(-0.9, -0.9, 0.4, 1.0);
        let p1 = clip_triangle([a, b, c], NEAR, g);
        let p2 = clip_triangle([b, a, d], NEAR, g);
        let on_plane = |p: &Polygon<f32>| {
            p.v.iter()
                .filter(|v| v.pos != a.pos && v.pos != c.pos && v.pos != d.pos)
                .map(|v| v.pos)
                .collect::<heapless::Vec<_, 9>>()
        };
        let (e1, e2) = (on_plane(&p1), on_plane(&p2));
        assert!(e1.iter().any(|v| e2.contains(v)), "{e1:?} vs {e2:?}");
    }

    #[test]
    fn colour_is_interpolated_at_the_cut() {
        let g = 8.0f64;
        let mut a = cv::<f64>(0.0, 0.0, 1.0, 2.0);
        let mut b = cv::<f64>(0.0, 0.0, -1.0, 2.0);
        a.rgb = [0, 0, 0];
        b.rgb = [1000, 1000, 1000];
        let c = cv::<f64>(1.0, 0.0, 1.0, 2.0);
        let p = clip_triangle([a, b, c], NEAR, g);
        assert!(p.v.iter().any(|v| v.rgb == [500, 500, 500]), "{p:?}");
    }
}
