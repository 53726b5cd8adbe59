//! What a layered frame ([`crate::FrameOptions::layered`]) does beyond the opaque pass:
//! which objects receive and cast a projected planar shadow, the plane, the light and the
//! shadow's colour. The projection is the seeds' shadow matrix, generalised to any plane and to
//! point lights.

use crate::num::math::{Mat4, Vec3};
use crate::num::scalar::Scalar;

/// A sphere around `object` in world units, `(centre, radius)`: its transform's origin, and
/// the mesh's largest distance from its own origin times the transform's largest column length
/// (its largest scale). Loose for a mesh far from its origin, never too small for an affine
/// transform. In f64 from the number type's values; a few products per vertex in the number
/// type (no f64 per vertex, which is soft float on a Cortex-M0; a square that does not fit the
/// type counts as three times its largest coordinate's square).
pub(crate) fn object_sphere<S: Scalar>(object: &crate::Object<'_, S>) -> ([f64; 3], f64) {
    let t = object.transform.m.map(|r| r.map(|v| v.to_f64()));
    let mut r2 = 0.0f64;
    for &q in object.mesh.positions() {
        let d = crate::num::math::dot(q, q);
        let v = if d.is_valid() {
            d.to_f64()
        } else {
            let m = q.iter().fold(0.0f64, |m, c| m.max(c.to_f64().abs()));
            3.0 * m * m
        };
        r2 = r2.max(v);
    }
    let scale = (0..3).fold(0.0f64, |m, j| {
        m.max(libm::sqrt(
            t[0][j] * t[0][j] + t[1][j] * t[1][j] + t[2][j] * t[2][j],
        ))
    });
    ([t[0][3], t[1][3], t[2][3]], libm::sqrt(r2) * scale)
}

/// How a planar shadow is drawn.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ShadowMethod {
    /// The casters' triangles projected onto the plane from the light: the exact shadow
    /// shape on the plane, stencilled so that overlaps darken once.
    Projected,
    /// The seeds' cheapest method: a soft round blob on the plane under each caster (where the
    /// light projects the caster's origin), as wide as the caster, darkest (`alpha`) at its
    /// centre: [`BLOB_RINGS`] nested discs of [`BLOB_SIDES`] sides, each darkening what the
    /// discs inside it leave, so the darkness falls off in steps toward the rim. Its cost does
    /// not grow with the caster's triangles. Overlapping blobs of two casters darken twice.
    Blob,
}

/// The blob shadow's nested discs.
pub const BLOB_RINGS: usize = 4;
/// Sides of each blob disc.
pub const BLOB_SIDES: usize = 16;

/// The light a planar shadow is cast along.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum ShadowLight<S> {
    /// A directional light: the direction toward the light (as [`crate::Light::direction`];
    /// any length but zero).
    Directional(Vec3<S>),
    /// A point light at this world position.
    Point(Vec3<S>),
}

/// A projected planar shadow: every caster's triangles projected from the light onto the
/// plane `a·x + b·y + c·z + d = 0` (world space) darken the receivers' pixels they cover,
/// once whatever the overlap (a per-line stencil), blended toward `color` by `alpha`:
/// `C = color·α + C·(1 − α)`, `α = alpha/255`.
///
/// The receivers are the objects that lie in the plane (a ground, a wall): the shadow falls on
/// their visible pixels and nowhere else (not outside their polygons, not on objects in front
/// of them), and is not depth-tested against them, so it cannot z-fight with them. A caster
/// part on the far side of the plane from the light is projected too (the matrix's
/// behaviour); keep casters on the light's side.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct PlanarShadow<S> {
    /// The plane `[a, b, c, d]`, `a·x + b·y + c·z + d = 0`, in world units; `(a, b, c)` not
    /// zero. Its scale does not matter.
    pub plane: [S; 4],
    /// The light.
    pub light: ShadowLight<S>,
    /// The shadow's colour, 8 bits per channel (black for a plain darkening).
    pub color: [u8; 3],
    /// The shadow's opacity, 0..=255.
    pub alpha: u8,
    /// Projected polygons or blobs.
    pub method: ShadowMethod,
}

impl<S: Scalar> PlanarShadow<S> {
    /// A black shadow of opacity `alpha` on `plane` from `light`.
    #[must_use]
    pub const fn new(plane: [S; 4], light: ShadowLight<S>, alpha: u8) -> Self {
        PlanarShadow {
            plane,
            light,
            color: [0; 3],
            alpha,
            method: ShadowMethod::Projected,
        }
    }

    /// This shadow drawn as blobs ([`ShadowMethod::Blob`]).
    #[must_use]
    pub const fn blob(self) -> Self {
        PlanarShadow {
            method: ShadowMethod::Blob,
            ..self
        }
    }

    /// The blob under `caster` ([`ShadowMethod::Blob`]), with shadow matrix `m`: the
    /// transforms of its [`BLOB_RINGS`] discs (the unit disc of [`blob_disc`], largest first),
    /// or `None` when the caster's origin projects to no point. Its centre is the caster's
    /// origin projected onto the plane, its radius the largest distance of the caster's mesh from
    /// its origin times the transform's largest scale. Once per caster and frame.
    pub(crate) fn blob_rings(
        &self,
        m: &Mat4<S>,
        caster: &crate::Object<'_, S>,
    ) -> Option<[Mat4<S>; BLOB_RINGS]> {
        let (origin, radius) = object_sphere(caster);
        let c = m.m.map(|r| r.map(|v| v.to_f64()));
        let h: [f64; 4] = core::array::from_fn(|i| {
            c[i][0] * origin[0] + c[i][1] * origin[1] + c[i][2] * origin[2] + c[i][3]
        });
        if h[3].abs() < 1e-12 || !h.iter().all(|v| v.is_finite()) {
            return None;
        }
        let centre = [h[0] / h[3], h[1] / h[3], h[2] / h[3]];
        let (u, n, w) = plane_basis(self.plane.map(|v| v.to_f64()));
        Some(core::array::from_fn(|k| {
            let r = radius * (BLOB_RINGS - k) as f64 / BLOB_RINGS as f64;
            let mut t = Mat4::identity();
            for i in 0..3 {
                t.m[i] = [u[i] * r, n[i], w[i] * r, centre[i]].map(S::from_f64);
            }
            t
        }))
    }

    /// Each blob disc's opacity: [`BLOB_RINGS`] of them over the centre make `alpha`,
    /// `1 − (1 − α)^(1/BLOB_RINGS)` in 0..=255.
    pub(crate) fn blob_ring_alpha(&self) -> u8 {
        let a = self.alpha as f64 / 255.0;
        let step = 1.0 - libm::pow(1.0 - a, 1.0 / BLOB_RINGS as f64);
        libm::round(step * 255.0).clamp(0.0, 255.0) as u8
    }

    /// Whether every vertex of `object` lies in the plane, within 2⁻¹⁰ of its distance from
    /// the origin or of one unit (the shadow polygons are drawn on the receivers' pixels without
    /// a depth test, so a receiver must be in the plane). Computed in f64, one transform per
    /// vertex: meant for a ground or a wall, a few vertices.
    #[must_use]
    pub fn holds(&self, object: &crate::Object<'_, S>) -> bool {
        let p = self.plane.map(|v| v.to_f64());
        let n = libm::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        object.mesh.positions().iter().all(|&q| {
            let w = object.transform.transform_point(q).map(|v| v.to_f64());
            let x = [w[0] / w[3], w[1] / w[3], w[2] / w[3]];
            let dist = (p[0] * x[0] + p[1] * x[1] + p[2] * x[2] + p[3]).abs() / n;
            let size = x.iter().fold(1.0f64, |m, c| m.max(c.abs()));
            dist <= size / 1024.0
        })
    }

    /// The world → world projection onto the plane from the light, scaled so that its
    /// largest entry is 1 (a homogeneous matrix's scale does not change the point it maps to;
    /// for a directional light the bottom row is then `[0, 0, 0, s]`, an affine map). `None`
    /// when the plane or the light has an invalid number, the plane's normal is zero, or the
    /// light lies in the plane (a point light) or parallel to it (a directional light), where
    /// no projection exists.
    ///
    /// With `p = (a, b, c, d)` and the light `l = (x, y, z, w)` (`w = 0` for a direction), the
    /// matrix is `(p·l)·I − l·pᵀ`: a point `q` on the plane (`p·q = 0`) maps to itself, and
    /// any point maps to where the line from the light through it meets the plane. Computed in
    /// f64 once per frame.
    #[must_use]
    pub fn matrix(&self) -> Option<Mat4<S>> {
        let p = self.plane.map(|v| v.to_f64());
        let (l, w) = match self.light {
            ShadowLight::Directional(d) => (d, 0.0),
            ShadowLight::Point(q) => (q, 1.0),
        };
        let l = [l[0].to_f64(), l[1].to_f64(), l[2].to_f64(), w];
        let valid = self.plane.iter().all(|v| v.is_valid())
            && match self.light {
                ShadowLight::Directional(d) | ShadowLight::Point(d) => {
                    d.iter().all(|v| v.is_valid())
                }
            };
        let n2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
        if !valid || n2 <= 0.0 {
            return None;
        }
        let dot = p[0] * l[0] + p[1] * l[1] + p[2] * l[2] + p[3] * l[3];
        // Parallel (directional) or in the plane (point): within a relative 2⁻²⁰.
        let l2 = l[0] * l[0] + l[1] * l[1] + l[2] * l[2];
        if dot.abs() <= 1e-6 * libm::sqrt(n2 * l2.max(1e-300)) {
            return None;
        }
        let mut m = [[0.0f64; 4]; 4];
        let mut big = 0.0f64;
        for (i, row) in m.iter_mut().enumerate() {
            for (j, e) in row.iter_mut().enumerate() {
                *e = if i == j { dot } else { 0.0 } - l[i] * p[j];
                big = big.max(e.abs());
            }
        }
        let s = 1.0 / big;
        Some(Mat4 {
            m: m.map(|r| r.map(|e| S::from_f64(e * s))),
        })
    }
}

/// A right-handed orthonormal basis `(u, n, w)` of plane `a·x + b·y + c·z + d = 0`: `n` its unit
/// normal, `u` and `w` in it (`(x, y, z)` for the level plane `0, 1, 0, d`).
pub fn plane_basis(p: [f64; 4]) -> ([f64; 3], [f64; 3], [f64; 3]) {
    let len = libm::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).max(1e-300);
    let n = [p[0] / len, p[1] / len, p[2] / len];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let unit = |v: [f64; 3]| {
        let l = libm::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        v.map(|c| c / l)
    };
    let u = if n[2].abs() < 0.9 {
        unit(cross(n, [0.0, 0.0, 1.0]))
    } else {
        unit(cross([1.0, 0.0, 0.0], n)).map(|c| -c)
    };
    (u, n, cross(u, n))
}

/// The unit blob disc in the plane y = 0, facing +y: its centre and [`BLOB_SIDES`] rim points
/// (positions) and its fan of triangles.
pub(crate) fn blob_disc<S: Scalar>() -> [[S; 3]; BLOB_SIDES + 1] {
    core::array::from_fn(|i| {
        if i == 0 {
            [S::ZERO; 3]
        } else {
            let a = core::f64::consts::TAU * (i - 1) as f64 / BLOB_SIDES as f64;
            [libm::cos(a), 0.0, libm::sin(a)].map(S::from_f64)
        }
    })
}

/// [`blob_disc`]'s triangles: `(centre, rim i + 1, rim i)`, counter-clockwise seen from +y.
pub(crate) const BLOB_FAN: [[u16; 3]; BLOB_SIDES] = {
    let mut t = [[0u16; 3]; BLOB_SIDES];
    let mut i = 0;
    while i < BLOB_SIDES {
        t[i] = [0, ((i + 1) % BLOB_SIDES) as u16 + 1, i as u16 + 1];
        i += 1;
    }
    t
};

/// A shadow volume per caster ([`Layering::volume`]): the silhouette of each caster as seen
/// from the light (found with its [`crate::mesh::mesh_adjacency`]) extruded away from the light by
/// `reach`, closed by caps, and counted per pixel in the stencil lines (z-fail: the volume
/// faces behind the visible surface, so a camera inside a volume needs nothing special).
/// Every visible pixel inside a volume is blended toward `color` by `alpha`, whichever object
/// it belongs to: casters shadow the ground, each other and themselves.
///
/// The near cap is each caster's faces turned away from the light, so those faces (already
/// unlit: ambient only) are not darkened a second time by their own volume; the far cap is
/// the same faces moved by `reach`. A volume part beyond the camera's far plane is flattened
/// onto it (still counted: the volume stays closed). A caster should be a closed mesh whose
/// triangles are counter-clockwise from outside; an open mesh casts from its faces turned
/// away from the light.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct VolumeShadow<'a, S> {
    /// The light (usually the scene's own light).
    pub light: ShadowLight<S>,
    /// How far each silhouette is extruded, in world units (> 0): past every surface the
    /// shadow should reach (for a point light, from each caster vertex along the light's ray).
    pub reach: S,
    /// One adjacency table per caster, in the order of [`Layering::casters`]
    /// ([`crate::mesh::mesh_adjacency`] of its mesh, checked once by [`crate::mesh::Adjacency::new`]).
    pub adjacency: &'a [crate::scene::adjacency::Adjacency<'a, S>],
    /// The shadow's colour, 8 bits per channel.
    pub color: [u8; 3],
    /// The shadow's opacity, 0..=255.
    pub alpha: u8,
}

/// Which edges of an object an [`Outline`] draws.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Edges<'a> {
    /// The contour as seen from the eye: the edges between a face turned toward the eye and
    /// one turned away, and the open edges of faces turned toward it.
    Silhouette,
    /// The contour and the creases: besides the silhouette, every edge whose two faces meet at
    /// more than a crease angle (and every open edge). One crease table per outlined object,
    /// in the order of [`Outline::objects`], from [`crate::mesh::mesh_creases`] (a mesh's setup: the
    /// angle is fixed there).
    Crease(&'a [&'a [u8]]),
    /// Every edge: with the depth test, a wireframe with its hidden lines removed.
    All,
}

/// Outlines and wireframes ([`Layering::outline`]): the chosen [`Edges`] of each listed object
/// (found with its [`crate::mesh::mesh_adjacency`]) drawn as lines of `color`, 1 px wide: each edge
/// is a quad one pixel across its minor axis, so every column (or row) it crosses takes exactly
/// one pixel by the top-left rule and joined edges leave no gap. With `see_through` off an edge
/// is drawn only where it is not behind a nearer surface (within a small bias, so an edge on a
/// surface shows) and only the edges of faces turned toward the eye are considered; with it on,
/// every chosen edge shows, hidden or not.
///
/// A wireframe with hidden lines removed: [`Edges::All`] over objects whose material is
/// [`crate::Material::unlit`] in the background colour (they fill the depth lines and hide what
/// is behind them, but show only their edges).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Outline<'a, S> {
    /// The outlined objects (indices into [`crate::Scene::objects`]).
    pub objects: &'a [usize],
    /// One adjacency table per outlined object, in the order of `objects` (checked once by
    /// [`crate::mesh::Adjacency::new`]).
    pub adjacency: &'a [crate::scene::adjacency::Adjacency<'a, S>],
    /// The lines' colour, 8 bits per channel.
    pub color: [u8; 3],
    /// Which edges are drawn.
    pub edges: Edges<'a>,
    /// Whether hidden edges are drawn too (no depth test, the faces turned away included).
    pub see_through: bool,
}

impl<'a, S> Outline<'a, S> {
    /// The silhouettes of `objects` in `color`, depth-tested.
    #[must_use]
    pub const fn silhouette(
        objects: &'a [usize],
        adjacency: &'a [crate::scene::adjacency::Adjacency<'a, S>],
        color: [u8; 3],
    ) -> Self {
        Outline {
            objects,
            adjacency,
            color,
            edges: Edges::Silhouette,
            see_through: false,
        }
    }

    /// This outline with `edges`.
    #[must_use]
    pub const fn with_edges(self, edges: Edges<'a>) -> Self {
        Outline { edges, ..self }
    }

    /// This outline with hidden edges shown (`true`) or removed.
    #[must_use]
    pub const fn see_through(self, on: bool) -> Self {
        Outline {
            see_through: on,
            ..self
        }
    }
}

/// What a layered frame draws beyond the opaque pass: the objects (indices into
/// [`crate::Scene::objects`]) that receive and cast a shadow, the shadow (planar or volumes)
/// and the outlines. Translucent materials ([`crate::Material::alpha`]) need nothing here.
#[derive(Copy, Clone, Debug)]
pub struct Layering<'a, S> {
    /// The objects a planar shadow falls on (drawn first on each row; opaque ones only).
    pub receivers: &'a [usize],
    /// The objects that cast the planar shadow or the shadow volumes.
    pub casters: &'a [usize],
    /// The planar shadow (`None`: receivers and casters are drawn as ordinary objects).
    pub shadow: Option<PlanarShadow<S>>,
    /// Shadow volumes of the casters (not with a planar `shadow`: one stencil serves one).
    pub volume: Option<VolumeShadow<'a, S>>,
    /// Outlines.
    pub outline: Option<Outline<'a, S>>,
}

impl<'a, S> Layering<'a, S> {
    /// No shadow: a layered frame only for its translucent materials.
    #[must_use]
    pub const fn none() -> Self {
        Layering {
            receivers: &[],
            casters: &[],
            shadow: None,
            volume: None,
            outline: None,
        }
    }

    /// A projected shadow of `casters` on `receivers`.
    #[must_use]
    pub const fn projected(
        receivers: &'a [usize],
        casters: &'a [usize],
        shadow: PlanarShadow<S>,
    ) -> Self {
        Layering {
            receivers,
            casters,
            shadow: Some(shadow),
            volume: None,
            outline: None,
        }
    }

    /// Shadow volumes of `casters` on everything.
    #[must_use]
    pub const fn volumes(casters: &'a [usize], volume: VolumeShadow<'a, S>) -> Self {
        Layering {
            receivers: &[],
            casters,
            shadow: None,
            volume: Some(volume),
            outline: None,
        }
    }

    /// This layering with `outline`.
    #[must_use]
    pub fn with_outline(self, outline: Outline<'a, S>) -> Self {
        Layering {
            outline: Some(outline),
            ..self
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn apply(m: &Mat4<f64>, q: [f64; 3]) -> [f64; 3] {
        let h = m.transform_point(q);
        [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
    }

    #[test]
    fn points_land_on_the_plane_along_the_light() {
        let plane = [0.3, 1.0, -0.2, 0.5];
        for light in [
            ShadowLight::Directional([0.4, 1.0, 0.3]),
            ShadowLight::Point([1.0, 6.0, -2.0]),
        ] {
            let m = PlanarShadow::new(plane, light, 128).matrix().unwrap();
            for q in [[0.0, 2.0, 0.0], [1.5, 1.0, -0.7], [-2.0, 3.0, 1.0]] {
                let s = apply(&m, q);
                let on = plane[0] * s[0] + plane[1] * s[1] + plane[2] * s[2] + plane[3];
                assert!(on.abs() < 1e-9, "{on}");
                // On the line from the light through q.
                let dir = match light {
                    ShadowLight::Directional(d) => d,
                    ShadowLight::Point(p) => [p[0] - q[0], p[1] - q[1], p[2] - q[2]],
                };
                let d = [s[0] - q[0], s[1] - q[1], s[2] - q[2]];
                let cross = [
                    d[1] * dir[2] - d[2] * dir[1],
                    d[2] * dir[0] - d[0] * dir[2],
                    d[0] * dir[1] - d[1] * dir[0],
                ];
                assert!(cross.iter().all(|c| c.abs() < 1e-9), "{cross:?}");
            }
        }
    }

    #[test]
    fn no_projection_for_a_light_parallel_to_or_in_the_plane() {
        let ground = [0.0, 1.0, 0.0, 0.0];
        let flat = ShadowLight::Directional([1.0, 0.0, 0.0]);
        assert!(PlanarShadow::new(ground, flat, 1).matrix().is_none());
        let inside = ShadowLight::Point([3.0, 0.0, 1.0]);
        assert!(PlanarShadow::new(ground, inside, 1).matrix().is_none());
        let zero = [0.0, 0.0, 0.0, 1.0];
        let up = ShadowLight::Directional([0.0, 1.0, 0.0]);
        assert!(PlanarShadow::new(zero, up, 1).matrix().is_none());
        let nan = [f64::NAN, 1.0, 0.0, 0.0];
        assert!(PlanarShadow::new(nan, up, 1).matrix().is_none());
    }
}
