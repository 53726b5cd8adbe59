//! The renderer's errors and capacity reports: what a frame needs, what was short, and what
//! to do when a frame does not fit.

use embedded_graphics_core::geometry::Size;
use embedded_graphics_core::primitives::Rectangle;

use crate::stats::Stats;

/// One of the compile-time capacities a frame needs (see [`Needs`]): the renderer's, its
/// attribute stores' and a layered frame's [`crate::Layers`] lists.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Capacity {
    /// `VERTS`: mesh vertices of all objects plus vertices made by clipping.
    Vertices,
    /// `TRIS`: triangles that survive culling and clipping (a clipped triangle may become up
    /// to seven).
    Triangles,
    /// `ACTIVE`: triangles crossing one pixel row.
    ActiveTriangles,
    /// `XV`: the texture and normal attribute store's vertices.
    AttributeVertices,
    /// `XA`: the attribute pool's entries (the frame's fog, Phong lights and materials, and
    /// the textured and Phong triangles of one row).
    AttributeActive,
    /// `RA` of [`crate::Layers`]: receiver triangles crossing one row.
    Receivers,
    /// `PA` of [`crate::Layers`]: shadow, outline and translucent triangles crossing one row.
    Overlays,
}

impl Capacity {
    /// Every capacity, in the order [`Shortfall::iter`] reports them.
    pub const ALL: [Capacity; 7] = [
        Capacity::Vertices,
        Capacity::Triangles,
        Capacity::ActiveTriangles,
        Capacity::AttributeVertices,
        Capacity::AttributeActive,
        Capacity::Receivers,
        Capacity::Overlays,
    ];

    /// What it counts and the parameter that holds it, e.g. `"vertices (VERTS)"`.
    #[must_use]
    pub const fn describe(self) -> &'static str {
        match self {
            Capacity::Vertices => "vertices (VERTS)",
            Capacity::Triangles => "triangles (TRIS)",
            Capacity::ActiveTriangles => "triangles active on one row (ACTIVE)",
            Capacity::AttributeVertices => "attribute-store vertices (XV)",
            Capacity::AttributeActive => "attribute pool entries (XA)",
            Capacity::Receivers => "receiver triangles on one row (Layers RA)",
            Capacity::Overlays => {
                "shadow, outline and translucent triangles on one row (Layers PA)"
            }
        }
    }
}

/// Why a frame was not (completely) drawn.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Error<E> {
    /// The draw target returned an error; the frame is drawn up to the failing strip.
    Target(E),
    /// Object `object` asks for Gouraud shading but its mesh has no vertex normals. Nothing
    /// was drawn.
    MissingNormals {
        /// Index of the object in the scene.
        object: usize,
    },
    /// Object `object` has a textured material but its mesh has no texture coordinates
    /// ([`crate::Mesh::with_uvs`]). Nothing was drawn.
    MissingUvs {
        /// Index of the object in the scene.
        object: usize,
    },
    /// Object `object` is textured or Phong-shaded (it needs the attribute stores) and the
    /// renderer's stores cannot hold the frame: its vertices end at store index
    /// `vertices_needed`, beyond the renderer's `XV`; or (under [`OverflowPolicy::Error`]) the
    /// frame needs `active_needed` pool entries, more than the renderer's `XA` — the frame's
    /// fog, Phong lights and materials, and [`crate::Stats::max_active`] triangles (a bound of
    /// the textured and Phong ones on a row); [`crate::Stats::attr_active`] and
    /// [`Needs::attr_active`] give that figure. A part that fits has its figure at or below
    /// its capacity (0 when it was not reached). Nothing was drawn.
    AttributeStore {
        /// Index of the (first) textured object in the scene.
        object: usize,
        /// The `XV` the frame needs (at least).
        vertices_needed: usize,
        /// The renderer's `XV`.
        vertex_capacity: usize,
        /// The most triangles active on one row (an upper bound of the textured ones).
        active_needed: usize,
        /// The renderer's `XA`.
        active_capacity: usize,
    },
    /// Object `object` has a translucent material ([`crate::Material::alpha`] below 255),
    /// which only [`FrameOptions::layered`](crate::FrameOptions::layered) draws (after
    /// the opaque triangles of each row, back to front). Nothing was drawn.
    NeedsLayers {
        /// Index of the object in the scene.
        object: usize,
    },
    /// A layered frame ([`FrameOptions::layered`](crate::FrameOptions::layered)) that
    /// cannot be drawn: the [`crate::errors::LayerError`] says why. Nothing was drawn.
    Layers(LayerError),
    /// The scene's fog ([`crate::Scene::fog`]) has `near ≥ far`, or a number that is NaN,
    /// infinite or at a fixed-point rail. Nothing was drawn.
    Fog,
    /// Light `index` of the scene has a number that is NaN, infinite or at a fixed-point
    /// rail (where [`crate::Scalar::from_f64`] puts those and out-of-range values): a
    /// directional light's direction ([`crate::Scene::lights`], `point` false) or a point
    /// light's position or attenuation ([`crate::Effects::point_lights`], `point` true).
    /// Nothing was drawn.
    Light {
        /// Index of the light in its list.
        index: usize,
        /// Whether it is a point light.
        point: bool,
    },
    /// The scene's tone map ([`crate::ToneMap`]) has an intensity or exposure that is not a
    /// valid number within `0..=MAX_TONE_SCALE` (exposure above 0). Nothing was drawn.
    /// (`object` is always `None`: Phong objects, once refused here, are tone-mapped per pixel.)
    Tone {
        /// `None` (no longer names an object).
        object: Option<usize>,
    },
    /// A layered frame ([`crate::FrameOptions::layered`]: shadows, outlines, translucency)
    /// on a renderer without depth lines ([`crate::NoDepthRenderer`]): the layers are tested
    /// against the depth lines. Nothing was drawn.
    NoDepthLines,
    /// The scene's camera fails [`crate::Camera::validate`] (its fields are public and may
    /// have been changed after [`crate::Camera::look_at`]). Nothing was drawn.
    Camera(crate::scene::camera::CameraError),
    /// The frame needs more room than the renderer has, in one or more of its capacities:
    /// every capacity that is short, with what the frame needed, is in the [`Shortfall`]
    /// ([`Shortfall::iter`]). Returned under [`OverflowPolicy::Error`] (the default); nothing
    /// was drawn.
    Shortfall(Shortfall),
    /// The draw target does not contain the viewport: the renderer draws `viewport` pixels at
    /// the target's origin (`W × H` unless changed by [`Renderer::set_viewport`](crate::Renderer::set_viewport)) and the
    /// target's bounding box is `target`. Checked before anything is drawn (by
    /// [`Renderer::render`](crate::Renderer::render) and [`Frame::draw_to`](crate::frame::Frame::draw_to) once per frame, by [`Frame::strip_to`](crate::frame::Frame::strip_to) at
    /// each call); a larger target is fine (the rest of it is left as it was). Set the
    /// viewport to the target's size to draw into a smaller one.
    TargetTooSmall {
        /// The viewport, in pixels.
        viewport: Size,
        /// The target's bounding box.
        target: Rectangle,
    },
    /// [`Renderer::render_passes`](crate::Renderer::render_passes) needs one strip over the whole viewport (the colour and
    /// depth lines keep every pass's pixels until the frame is sent): `LINES` is `lines`, the
    /// viewport is `height` rows high. Nothing was drawn.
    StripTooShort {
        /// The renderer's `LINES`.
        lines: usize,
        /// The viewport's height.
        height: usize,
    },
    /// A [`StripPass`](crate::StripPass) was begun on a renderer that holds no frame a strip
    /// pass can draw: none was prepared, the last geometry stage failed, or the frame is
    /// layered (a layered frame is drawn only by
    /// [`FrameOptions::layered`](crate::FrameOptions::layered)). Nothing was drawn.
    NoFrame,
    /// The renderer began another frame after the [`StripPass`](crate::StripPass) began
    /// (or the pass never began one): begin the pass again on the renderer's frame. Nothing
    /// was drawn.
    FrameChanged,
}

impl<E> Error<E> {
    /// The same error with its target error mapped by `f` (every other variant as it is).
    pub fn map_target<F, T: FnOnce(E) -> F>(self, f: T) -> Error<F> {
        match self {
            Error::Target(e) => Error::Target(f(e)),
            Error::MissingNormals { object } => Error::MissingNormals { object },
            Error::MissingUvs { object } => Error::MissingUvs { object },
            Error::AttributeStore {
                object,
                vertices_needed,
                vertex_capacity,
                active_needed,
                active_capacity,
            } => Error::AttributeStore {
                object,
                vertices_needed,
                vertex_capacity,
                active_needed,
                active_capacity,
            },
            Error::NeedsLayers { object } => Error::NeedsLayers { object },
            Error::Layers(e) => Error::Layers(e),
            Error::Fog => Error::Fog,
            Error::Light { index, point } => Error::Light { index, point },
            Error::Tone { object } => Error::Tone { object },
            Error::NoDepthLines => Error::NoDepthLines,
            Error::Camera(e) => Error::Camera(e),
            Error::Shortfall(s) => Error::Shortfall(s),
            Error::TargetTooSmall { viewport, target } => {
                Error::TargetTooSmall { viewport, target }
            }
            Error::StripTooShort { lines, height } => Error::StripTooShort { lines, height },
            Error::NoFrame => Error::NoFrame,
            Error::FrameChanged => Error::FrameChanged,
        }
    }
}

impl Error<core::convert::Infallible> {
    /// The same error for any target error type: a [`crate::Renderer::prepare`] error (which
    /// has no target) in a function whose errors carry a target's
    /// (`renderer.prepare(&scene, options).map_err(Error::widen)?`).
    pub fn widen<E>(self) -> Error<E> {
        self.map_target(|e| match e {})
    }
}

impl<E: core::fmt::Display> core::fmt::Display for Error<E> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Error::Target(e) => write!(f, "draw target error: {e}"),
            Error::MissingNormals { object } => write!(
                f,
                "object {object} is Gouraud-shaded but its mesh has no vertex normals; nothing \
                 was drawn"
            ),
            Error::MissingUvs { object } => write!(
                f,
                "object {object} is textured but its mesh has no texture coordinates; nothing \
                 was drawn"
            ),
            Error::AttributeStore {
                object,
                vertices_needed,
                vertex_capacity,
                active_needed,
                active_capacity,
            } => {
                write!(
                    f,
                    "object {object} is textured or Phong-shaded and the attribute stores are \
                     short:"
                )?;
                let xv = vertices_needed > vertex_capacity;
                let xa = active_needed > active_capacity;
                if xv || !xa {
                    write!(
                        f,
                        " XV needs {vertices_needed}, has {vertex_capacity} (the vertex-store \
                         index where its vertices end);"
                    )?;
                }
                if xa || !xv {
                    write!(
                        f,
                        " XA needs {active_needed}, has {active_capacity} (the frame's fog, \
                         Phong lights and materials, and the triangles active on one row);"
                    )?;
                }
                write!(f, " nothing was drawn")
            }
            Error::NeedsLayers { object } => write!(
                f,
                "object {object} is translucent: draw the scene as a layered frame (FrameOptions::layered); nothing was drawn"
            ),
            Error::Layers(e) => write!(f, "{e}; nothing was drawn"),
            Error::Fog => write!(
                f,
                "the scene's fog needs finite numbers with near < far; nothing was drawn"
            ),
            Error::Light { index, point } => write!(
                f,
                "{} {index} has a number that is NaN, infinite or out of the number type's \
                 range; nothing was drawn",
                if *point { "point light" } else { "light" }
            ),
            Error::Tone { object: None } => write!(
                f,
                "the tone map's intensity and exposure must be finite, within 0 to 16 (exposure above 0); nothing was drawn"
            ),
            Error::Tone { object: Some(i) } => write!(
                f,
                "object {i} is lit per pixel (Phong), which the tone map does not reach: use flat or Gouraud shading; nothing was drawn"
            ),
            Error::NoDepthLines => write!(
                f,
                "shadows, outlines and translucency test against the depth lines, which this renderer does not have (ZL = 0): use a renderer with depth lines; nothing was drawn"
            ),
            Error::Camera(e) => write!(f, "{e}; nothing was drawn"),
            Error::Shortfall(s) => {
                write!(f, "frame does not fit the renderer: {s}; nothing was drawn")
            }
            Error::TargetTooSmall { viewport, target } => write!(
                f,
                "the draw target ({} × {} px at ({}, {})) does not contain the {} × {} px \
                 viewport; nothing was drawn",
                target.size.width,
                target.size.height,
                target.top_left.x,
                target.top_left.y,
                viewport.width,
                viewport.height
            ),
            Error::StripTooShort { lines, height } => write!(
                f,
                "drawing in passes needs one strip over the whole viewport, but the renderer's \
                 strip has {lines} lines for a viewport {height} rows high (LINES must be at \
                 least the viewport's height); nothing was drawn"
            ),
            Error::NoFrame => write!(
                f,
                "the renderer holds no frame a strip pass can draw (none prepared, the last one \
                 failed, or it is layered); nothing was drawn"
            ),
            Error::FrameChanged => write!(
                f,
                "the renderer began another frame since the strip pass began; begin the pass \
                 again; nothing was drawn"
            ),
        }
    }
}

/// What a frame needs of each capacity, or (as [`Renderer::CAPACITY`](crate::Renderer::CAPACITY)) what
/// a renderer has.
///
/// | field | capacity | [`Stats`] field of a frame that fit |
/// |---|---|---|
/// | `vertices` | `VERTS` | [`Stats::vertices`] |
/// | `triangles` | `TRIS` | [`Stats::drawn`] |
/// | `active` | `ACTIVE` | [`Stats::max_active`] |
/// | `attr_vertices` | `XV` | [`Stats::attr_vertices`] |
/// | `attr_active` | `XA` | [`Stats::attr_active`] |
/// | `receivers` | `RA` of [`crate::Layers`] | [`Stats::max_receivers`] |
/// | `overlays` | `PA` of [`crate::Layers`] | [`Stats::max_overlays`] |
///
/// To size a renderer for an animation built in code, measure every frame on the host with a
/// renderer of generous capacities ([`Renderer::needs`](crate::Renderer::needs), or
/// [`Renderer::needs_layered`](crate::Renderer::needs_layered) for a layered frame, with
/// `XV = VERTS` and a generous `XA` for textured or Phong objects) and keep the largest
/// figures ([`Needs::max`]); then check the device's renderer with [`Needs::fits`]:
///
/// ```
/// # use embedded_graphics::pixelcolor::Rgb565;
/// # use scanline3d::prelude::*;
/// # use scanline3d::Needs;
/// # type Q = Fx<scanline3d::fixed::types::I16F16>;
/// let torus = Shape::<Q, 512, 1024>::torus(1.0, 0.4, 32, 16).unwrap();
/// let perspective =
///     Projection::Perspective { fov_y: Q::lit(0.785), near: Q::lit(0.1), far: Q::lit(10.0) };
/// let eye = [Q::ZERO, Q::lit(1.2), Q::lit(3.0)];
/// let camera = Camera::look_at(eye, [Q::ZERO; 3], [Q::ZERO, Q::ONE, Q::ZERO], perspective).unwrap();
/// // The host's measuring renderer: the device's size, large capacities (in a `Box` or a
/// // `static`, see `Renderer::const_new`, when they are large).
/// let mut measure = Box::new(Renderer::<Q, Rgb565, 240, 240, 2048, 2048, 256>::new());
/// let mut worst = Needs::default();
/// for frame in 0..12 {
///     let objects = [Object {
///         mesh: torus.mesh(),
///         transform: Mat4::rotate_y(Q::lit(0.5 * frame as f64)),
///         material: Material::matte([255, 160, 64], Q::lit(0.15), Q::lit(0.85)),
///     }];
///     let scene = Scene::new(&objects, camera, [Light::white([-Q::ONE, Q::ONE, Q::ONE])]);
///     worst = worst.max(measure.needs(&scene).unwrap());
/// }
/// type Device = Renderer<Q, Rgb565, 240, 240, 512, 480, 64>;
/// assert!(worst.fits(&Device::CAPACITY), "{worst:?}");
/// ```
///
/// `Needs`, [`Stats`] and [`Shortfall`] are `#[non_exhaustive]`: they may gain fields, so
/// outside this crate they are read, and built only by their functions ([`Needs::new`],
/// `Default`), not by struct expressions:
///
/// ```compile_fail
/// let n = scanline3d::Needs { vertices: 512, triangles: 480, active: 64 };
/// ```
///
/// ```compile_fail
/// let s = scanline3d::Stats { drawn: 1, ..Default::default() };
/// ```
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub struct Needs {
    /// Vertices (`VERTS`): mesh vertices of every object, vertices made by clipping, and one
    /// face-colour vertex per drawn flat-shaded triangle.
    pub vertices: usize,
    /// Triangles stored for the row pass (`TRIS`): those that survive culling and clipping
    /// and cover a pixel (a clipped triangle may become up to seven).
    pub triangles: usize,
    /// Triangles crossing one pixel row at once, at the busiest row (`ACTIVE`).
    pub active: usize,
    /// The attribute store's vertices (`XV`): where the last textured or Phong object's
    /// vertices end in the vertex store ([`Stats::attr_vertices`]); 0 without such objects.
    /// (This and the three figures below are `u16`, as every capacity they count is at most
    /// 32 768: it keeps [`Error`] small on a microcontroller's stack.)
    pub attr_vertices: u16,
    /// The attribute pool's entries (`XA`, [`Stats::attr_active`]); 0 without textured or
    /// Phong objects.
    pub attr_active: u16,
    /// A layered frame's receiver triangles on one row ([`crate::Layers`]' `RA`,
    /// [`Stats::max_receivers`]).
    pub receivers: u16,
    /// A layered frame's shadow, outline and translucent triangles on one row
    /// ([`crate::Layers`]' `PA`, [`Stats::max_overlays`]).
    pub overlays: u16,
}

/// `v` as a `u16`, at most `u16::MAX`.
const fn narrow(v: usize) -> u16 {
    if v > u16::MAX as usize {
        u16::MAX
    } else {
        v as u16
    }
}

impl Needs {
    /// Needs (or capacities) of `vertices`, `triangles` and `active` triangles.
    #[must_use]
    /// (no attribute stores, no layers: add them with [`Needs::with_stores`] and
    /// [`Needs::with_layers`]).
    pub const fn new(vertices: usize, triangles: usize, active: usize) -> Self {
        Needs {
            vertices,
            triangles,
            active,
            attr_vertices: 0,
            attr_active: 0,
            receivers: 0,
            overlays: 0,
        }
    }

    /// These needs with the attribute stores' figures (`XV`, `XA`).
    #[must_use]
    pub const fn with_stores(mut self, attr_vertices: usize, attr_active: usize) -> Self {
        self.attr_vertices = narrow(attr_vertices);
        self.attr_active = narrow(attr_active);
        self
    }

    /// These needs with a layered frame's list figures ([`crate::Layers`]' `RA` and `PA`):
    /// e.g. `Device::CAPACITY.with_layers(RA, PA)` for the capacity a layered frame is
    /// checked against.
    #[must_use]
    pub const fn with_layers(mut self, receivers: usize, overlays: usize) -> Self {
        self.receivers = narrow(receivers);
        self.overlays = narrow(overlays);
        self
    }

    /// The needs of a frame that fit, from its statistics ([`Stats::vertices`],
    /// [`Stats::drawn`], [`Stats::max_active`], [`Stats::attr_vertices`],
    /// [`Stats::attr_active`], [`Stats::max_receivers`], [`Stats::max_overlays`]).
    #[must_use]
    pub const fn from_stats(stats: &Stats) -> Self {
        Needs {
            vertices: stats.vertices as usize,
            triangles: stats.drawn as usize,
            active: stats.max_active as usize,
            attr_vertices: narrow(stats.attr_vertices as usize),
            attr_active: narrow(stats.attr_active as usize),
            receivers: narrow(stats.max_receivers as usize),
            overlays: narrow(stats.max_overlays as usize),
        }
    }

    /// The larger of each figure: accumulates the needs of an animation's frames.
    #[must_use]
    pub const fn max(self, other: Needs) -> Self {
        const fn m(a: usize, b: usize) -> usize {
            if a > b {
                a
            } else {
                b
            }
        }
        const fn m16(a: u16, b: u16) -> u16 {
            if a > b {
                a
            } else {
                b
            }
        }
        Needs {
            vertices: m(self.vertices, other.vertices),
            triangles: m(self.triangles, other.triangles),
            active: m(self.active, other.active),
            attr_vertices: m16(self.attr_vertices, other.attr_vertices),
            attr_active: m16(self.attr_active, other.attr_active),
            receivers: m16(self.receivers, other.receivers),
            overlays: m16(self.overlays, other.overlays),
        }
    }

    /// Whether these needs fit `capacity` in every figure (e.g. a renderer's
    /// [`Renderer::CAPACITY`](crate::Renderer::CAPACITY), which includes its `XV` and `XA`;
    /// for a layered frame add the [`crate::Layers`]' lists with [`Needs::with_layers`]).
    #[must_use]
    pub const fn fits(&self, capacity: &Needs) -> bool {
        self.vertices <= capacity.vertices
            && self.triangles <= capacity.triangles
            && self.active <= capacity.active
            && self.attr_vertices <= capacity.attr_vertices
            && self.attr_active <= capacity.attr_active
            && self.receivers <= capacity.receivers
            && self.overlays <= capacity.overlays
    }

    /// The figure for one capacity.
    #[must_use]
    pub const fn get(&self, what: Capacity) -> usize {
        match what {
            Capacity::Vertices => self.vertices,
            Capacity::Triangles => self.triangles,
            Capacity::ActiveTriangles => self.active,
            Capacity::AttributeVertices => self.attr_vertices as usize,
            Capacity::AttributeActive => self.attr_active as usize,
            Capacity::Receivers => self.receivers as usize,
            Capacity::Overlays => self.overlays as usize,
        }
    }
}

impl<E: core::fmt::Debug + core::fmt::Display> core::error::Error for Error<E> {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            Error::Camera(e) => Some(e),
            _ => None,
        }
    }
}

/// A frame that did not fit the renderer: what it needed against what the renderer has, for
/// every capacity at once ([`Error::Shortfall`], or [`Renderer::shortfall`](crate::Renderer::shortfall) under
/// [`OverflowPolicy::DrawWhatFits`]).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub struct Shortfall {
    /// What the frame needed (see `exact`).
    pub needed: Needs,
    /// The renderer's capacities ([`Renderer::CAPACITY`](crate::Renderer::CAPACITY)).
    pub capacity: Needs,
    /// Whether `needed` is exact. It is not when the vertex or the triangle store overflowed:
    /// the objects whose vertices did not fit are neither culled nor clipped, so all of their
    /// triangles count as needed and none of them toward `active`, and the triangles that did
    /// not fit the store do not count toward `active` either. Measure with larger capacities
    /// ([`Renderer::needs`](crate::Renderer::needs)) for exact figures.
    pub exact: bool,
    /// Under [`OverflowPolicy::DrawWhatFits`], the triangles left out of the frame for lack of
    /// room (complete once the frame is drawn): the triangles counted in `needed.triangles`
    /// that were not stored (for an object whose vertices did not fit: all of its triangles),
    /// and each stored triangle dropped because the active list was full on its first row.
    /// 0 in an [`Error::Shortfall`] (nothing is drawn).
    pub skipped: usize,
}

impl Shortfall {
    /// Whether the frame needed more than `what`'s capacity.
    #[must_use]
    pub const fn is_short(&self, what: Capacity) -> bool {
        self.needed.get(what) > self.capacity.get(what)
    }

    /// Every capacity that is short: `(capacity, needed, available)`, in the order of
    /// [`Capacity::ALL`] (vertices, triangles, active triangles, attribute stores, layers).
    pub fn iter(&self) -> impl Iterator<Item = (Capacity, usize, usize)> + '_ {
        Capacity::ALL
            .into_iter()
            .filter(|&c| self.is_short(c))
            .map(|c| (c, self.needed.get(c), self.capacity.get(c)))
    }
}

impl core::fmt::Display for Shortfall {
    /// `vertices: needs 530, has 512; triangles active on one row: needs 66, has 64`, with
    /// `at least` before figures that are not exact.
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        for (k, (what, needed, capacity)) in self.iter().enumerate() {
            let name = what.describe();
            let sep = if k > 0 { "; " } else { "" };
            let about = if self.exact { "" } else { "about " };
            write!(f, "{sep}{name}: needs {about}{needed}, has {capacity}")?;
        }
        if self.skipped > 0 {
            write!(f, "; {} triangles skipped", self.skipped)?;
        }
        Ok(())
    }
}

/// What the renderer does with a frame that does not fit its capacities
/// ([`Renderer::with_overflow`](crate::Renderer::with_overflow)).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum OverflowPolicy {
    /// The frame fails with [`Error::Shortfall`] before anything is drawn (the default): on a
    /// display without a framebuffer the previous image stays on the panel.
    #[default]
    Error,
    /// The frame is drawn without what does not fit, and [`Renderer::shortfall`](crate::Renderer::shortfall) says what was
    /// needed and how many triangles were left out: objects whose vertices do not fit the
    /// vertex store (in scene order, the later ones), triangles that do not fit the triangle
    /// store (the later ones), and triangles that start on a row where the active list is
    /// full (each dropped as a whole, never drawn in part). The frame is never an error for
    /// its capacities and never panics; the image has holes where triangles were left out.
    DrawWhatFits,
}

/// [`Frame::strip_be`](crate::frame::Frame::strip_be)'s error: the buffer cannot hold one row of the viewport.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StripBufferTooSmall {
    /// Bytes one row needs.
    pub needed: usize,
    /// Bytes given.
    pub given: usize,
}

/// The most translucent objects one layered frame draws (the [`crate::Layers`]' table of them).
pub const MAX_TRANSLUCENT: usize = 16;

/// Why a layered frame was refused (inside [`crate::Error::Layers`]). Nothing was drawn.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum LayerError {
    /// A receiver or caster index is not an object of the scene.
    NoSuchObject {
        /// The index given.
        index: usize,
    },
    /// The shadow's plane or light has an invalid number, the plane's normal is zero, or the
    /// light is in the plane (point) or parallel to it (directional).
    Shadow,
    /// Object `object` is translucent and textured or Phong-shaded: translucent triangles are
    /// drawn with flat or Gouraud colours only.
    Translucent {
        /// Index of the object in the scene.
        object: usize,
    },
    /// Receiver `object` does not lie in the shadow's plane (a vertex is farther from it than
    /// 2⁻¹⁰ of its distance from the origin, or of one unit): the shadow would float off it.
    OffPlane {
        /// Index of the object in the scene.
        object: usize,
    },
    /// More translucent objects than [`MAX_TRANSLUCENT`].
    TooManyTranslucent,
    /// The target colour cannot report its channels ([`crate::TargetColor::channels`]), so
    /// nothing can be blended onto it.
    Blending,
    /// Both a planar shadow and shadow volumes: the stencil serves one of them per frame.
    TwoShadows,
    /// Object `object` (a volume caster or an outlined object) has no adjacency table, or one
    /// checked against another mesh ([`crate::mesh::Adjacency::is_for`]: not the same index and
    /// position slices).
    Adjacency {
        /// Index of the object in the scene.
        object: usize,
    },
    /// Outlined object `object` has no crease table ([`crate::shadow::Edges::Crease`]), or one shorter than
    /// its mesh's `3·T` bits ([`crate::mesh::mesh_creases`]).
    Creases {
        /// Index of the object in the scene.
        object: usize,
    },
    /// Object `object` has more triangles than the stencil lines have bits
    /// (`8·W·LINES`): a volume caster's or outlined object's faces are marked there while
    /// its silhouette is found.
    TooManyTriangles {
        /// Index of the object in the scene.
        object: usize,
        /// Its triangles.
        triangles: usize,
        /// The bits of the stencil lines.
        capacity: usize,
    },
    /// The volumes' `reach` is not a valid positive number.
    Reach,
    /// A shadow map of `size` texels a side on a renderer of `width × height`: the map's rows
    /// are drawn as strips of the renderer, so `size` ≤ `W` and ≤ `H`
    /// ([`crate::shadow::ShadowMap`]).
    MapLargerThanViewport {
        /// The map's side.
        size: usize,
        /// The renderer's `W`.
        width: usize,
        /// The renderer's `H`.
        height: usize,
    },
    /// The point light of a shadow map is inside receiver `object`'s bounding sphere, or its
    /// receivers are spread over more than [`crate::shadow::MAX_MAP_FOV`] as seen from it:
    /// one map (one perspective view from the light) cannot see them all.
    LightInside {
        /// Index of the object in the scene.
        object: usize,
    },
    /// A shadow map's receivers (or, with none given, the scene's opaque objects) have no
    /// extent to fit the light's view to: no object, or only empty or degenerate meshes.
    EmptyBounds,
    /// Object `object` of a mapped frame ([`crate::FrameOptions::shadow_map`]) is textured or
    /// lit per pixel: a mapped frame draws flat and Gouraud objects (such an object can be
    /// drawn with the map in a frame of its own, or cast into the map).
    MapShading {
        /// Index of the object in the scene.
        object: usize,
    },
}

impl core::fmt::Display for LayerError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            LayerError::NoSuchObject { index } => {
                write!(f, "receiver or caster {index} is not an object of the scene")
            }
            LayerError::Translucent { object } => write!(
                f,
                "object {object} is translucent and textured or Phong: translucency is flat or Gouraud only"
            ),
            LayerError::OffPlane { object } => {
                write!(f, "receiver {object} does not lie in the shadow's plane")
            }
            LayerError::Shadow => write!(
                f,
                "the shadow's plane or light is invalid (a NaN, a zero normal, or a light in or parallel to the plane)"
            ),
            LayerError::TooManyTranslucent => write!(
                f,
                "more than {} translucent objects",
                MAX_TRANSLUCENT
            ),
            LayerError::TwoShadows => {
                write!(f, "a planar shadow and shadow volumes in one frame")
            }
            LayerError::Adjacency { object } => write!(
                f,
                "object {object} has no adjacency table checked against its mesh (Adjacency::new)"
            ),
            LayerError::Creases { object } => write!(
                f,
                "outlined object {object} has no crease table of 3 bits per triangle (mesh_creases)"
            ),
            LayerError::TooManyTriangles {
                object,
                triangles,
                capacity,
            } => write!(
                f,
                "object {object} has {triangles} triangles, the stencil lines mark at most {capacity}"
            ),
            LayerError::Reach => write!(f, "the shadow volumes' reach is not a positive number"),
            LayerError::MapLargerThanViewport {
                size,
                width,
                height,
            } => write!(
                f,
                "a shadow map of {size} texels a side needs a renderer at least that wide and tall ({width} x {height})"
            ),
            LayerError::LightInside { object } => write!(
                f,
                "the shadow map's point light is inside receiver {object}, or its receivers are too widely spread around it for one map"
            ),
            LayerError::MapShading { object } => write!(
                f,
                "object {object} of a shadow-mapped frame is textured or lit per pixel: a mapped frame draws flat and Gouraud objects"
            ),
            LayerError::EmptyBounds => write!(
                f,
                "the shadow map's receivers have no extent to fit the light's view to"
            ),
            LayerError::Blending => {
                write!(f, "the target colour cannot report its channels for blending")
            }
        }
    }
}
