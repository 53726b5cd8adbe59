//! # scanline3d
//!
//! A `no_std`, allocation-free renderer for shaded 3D triangle meshes on microcontroller
//! displays, drawing through embedded-graphics' [`DrawTarget`] without a framebuffer: a
//! **scanline Z-buffer** keeps only a strip of `LINES` lines (one by default) of colour and
//! 16-bit depth, and hands each finished strip to the target with one `fill_contiguous`.
//!
//! The pipeline — model/view/projection transforms, lighting, near-plane clipping in clip
//! space, perspective division, back-face culling, exact integer rasterization with the
//! top-left fill rule, flat or Gouraud shading — is written once, generic over its number type
//! ([`Scalar`]): [`Fx`]`<I16F16>` fixed point for the device, `f32` and `f64` as twins to
//! measure the fixed-point error against. Everything after the perspective divide is integer
//! code shared by all of them.
//!
//! ```
//! use embedded_graphics::mock_display::MockDisplay;
//! use embedded_graphics::pixelcolor::Rgb565;
//! use scanline3d::prelude::*;
//! use scanline3d::fixed::types::I16F16;
//!
//! type Q = Fx<I16F16>;
//! let cube = Shape::<Q, 24, 12>::cube(1.0).unwrap();
//! let mut material = Material::matte([255, 160, 64], Q::lit(0.15), Q::lit(0.85));
//! material.shading = Shading::Flat;
//! let objects = [Object {
//!     mesh: cube.mesh(),
//!     transform: Mat4::rotate_y(Q::lit(0.5)).then(&Mat4::rotate_x(Q::lit(0.4))),
//!     material,
//! }];
//! let camera = Camera::look_at(
//!     [Q::ZERO, Q::ZERO, Q::lit(5.0)],
//!     [Q::ZERO; 3],
//!     [Q::ZERO, Q::ONE, Q::ZERO],
//!     Projection::Perspective { fov_y: Q::lit(0.8), near: Q::lit(0.1), far: Q::lit(10.0) },
//! )
//! .unwrap();
//! let scene = Scene::new(&objects, camera, [Light::white([-Q::ONE, Q::ONE, Q::ONE])]);
//!
//! // 64×64 pixels, up to 32 vertices (24 + one face-colour vertex per drawn flat triangle),
//! // 12 triangles, 12 active per row, one-line strip (`lines`, default 1).
//! type Small = renderer_type!(Q, Rgb565,
//!     width: 64, height: 64, vertices: 32, triangles: 12, active: 12);
//! let mut renderer = Small::new();
//! let mut display = MockDisplay::<Rgb565>::new(); // panics if a pixel is drawn twice
//! let stats = renderer.render(&scene, &mut display).unwrap();
//! assert_eq!(stats.culled, 6); // the back half of the cube
//! ```
//!
//! ## Memory
//!
//! Renderer RAM in bytes ([`Renderer::RAM_BYTES`] gives the exact value):
//!
//! `LINES·W·(size_of::<C>() + 2) + 12·VERTS + 6·TRIS + 84·ACTIVE + 4·H` (+ at most 160 bytes of
//! state and padding; a unit test checks the formula against `size_of`).
//!
//! The lines hold colour and 16-bit depth; `VERTS` projected vertices of 12 bytes, `TRIS`
//! triangles of 6 bytes (three vertex indices, sorted by first row after the geometry stage)
//! and `ACTIVE` triangles being scanned of 84 bytes are the capacities a scene needs; `4·H` is
//! the per-row bucket starts and the active-count sweep. A flat-shaded triangle takes one more
//! vertex (a copy of a corner that carries the face colour). For the default torus scene at
//! 240 × 240 RGB565, `cargo run --release -p scanline3d-tools --bin render` prints the value for the
//! capacities that frame needs — under 16 KB, against 230 KB for a 240 × 240 RGB565
//! framebuffer plus a 16-bit depth buffer.
//!
//! ## Capacities and placement
//!
//! The renderer's size and capacities are const generic parameters,
//! `Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES = 1>`: write the type with names instead,
//! [`renderer_type!`]`(S, C, width: …, height: …, vertices: …, triangles: …, active: …)`
//! (any order, each name required but `lines`; a missing, repeated or unknown name is a compile
//! error that says which), or from a [`Capacities`] constant (a struct with named fields),
//! `renderer_type!(S, C, CAPS)`. Both expand to the positional type and check each value's
//! range by name where the type is written ([`Capacities`] has the details).
//!
//! A frame that needs more than `VERTS`, `TRIS` or `ACTIVE` fails with [`Error::Shortfall`],
//! which names every capacity that is short, before anything is drawn; or, with
//! [`OverflowPolicy::DrawWhatFits`], is drawn without what does not fit
//! ([`Renderer::shortfall`] counts it). [`Renderer::needs`] measures a frame on the host and
//! [`Needs::max`] accumulates an animation's frames, to size the device's renderer. A renderer
//! can be a `static` ([`Renderer::const_new`] is a `const fn`); the target must contain the
//! `W × H` viewport ([`Error::TargetTooSmall`]).
//!
//! ## Number formats per stage
//!
//! | stage | format | why |
//! |---|---|---|
//! | positions, matrices, normals, lighting, clip coordinates | `S` (e.g. Q16.16) | one type keeps the pipeline generic; 2⁻¹⁶ is far below the 1/255 colour step and 1/16 px |
//! | 1/w | `S::Recip` (Q16.16: 31-bit normalized mantissa + shift) | Q16.16 would leave 1/w with ~6 significant bits at w = 1000 |
//! | x/w, y/w, z/w | signed Q31.32 in `i64` | exact enough for any `S`; shared integer viewport |
//! | screen x, y | signed 12.4 in `i16` (1/16 px), ±16 383 (guard band G = 7 at 240 px) | 4 subpixel bits; edge and area setup in 32-bit integers |
//! | depth | 16.8 at vertices, 16.12 interpolated, `u16` stored (0 = near) | |
//! | colour | channel units, 10-bit at vertices (RGB565: 5.5 / 6.4), 20 fraction bits in spans | rounding to RGB565 happens once, per pixel, by a shift |
//!
//! ## Textures and Phong shading
//!
//! A material can carry an RGB565 texture in flash ([`Material::textured`], [`Texture`]) and
//! be lit per pixel ([`Shading::Phong`], [`Shading::FastPhong`]). Both need the renderer's
//! attribute stores, its last two capacities `XV` and `XA` ([`Renderer`], "Textures"); a
//! renderer without them (the default, 0 and 0) has the size and the code it had before.
//!
//! ```
//! # use embedded_graphics::mock_display::MockDisplay;
//! # use embedded_graphics::pixelcolor::Rgb565;
//! use scanline3d::prelude::*;
//! use scanline3d::{Texture, TexturedShape};
//!
//! static TEXELS: [u16; 4] = [0xf800, 0x07e0, 0x001f, 0xffff];
//! static TEX: Texture = match Texture::new(&TEXELS, 2, 2) {
//!     Ok(t) => t,
//!     Err(_) => panic!("2 x 2"),
//! };
//! let cube = TexturedShape::<f32, 24, 12>::cube(1.0).unwrap();
//! let objects = [Object {
//!     mesh: cube.mesh(),
//!     transform: Mat4::rotate_y(0.6),
//!     material: Material::matte([255; 3], 0.3, 0.7).textured(&TEX),
//! }];
//! let camera = Camera::look_at([0.0, 1.5, 4.0], [0.0; 3], [0.0, 1.0, 0.0],
//!     Projection::Perspective { fov_y: 0.8, near: 0.1, far: 10.0 }).unwrap();
//! let scene = Scene::new(&objects, camera, [Light::white([-1.0, 1.0, 1.0])]);
//! // 64 × 64; 24 vertices, 12 triangles, 8 active; 1 line; stores for 24 vertices and
//! // 8 triangles on a row.
//! let mut r = Renderer::<f32, Rgb565, 64, 64, 24, 12, 8, 1, 24, 8>::new();
//! let mut display = MockDisplay::<Rgb565>::new();
//! assert!(r.render(&scene, &mut display).unwrap().pixels_written > 0);
//! ```
//!
//! ## Cortex-M kernels
//!
//! On Cortex-M targets (`target_os = "none"`) the hot path runs **hand-written Thumb
//! assembly**: on every core the RGB565 span and row loops, the strip-line clear, the cull
//! loop, the triangle and Gouraud attribute setup and the dither check; on ARMv6-M
//! (Cortex-M0/M0+: Thumb-1 routines) and on Thumb-2 cores (Cortex-M3/M4/M7/M33: Thumb-2 forms
//! with the long multiplies, `clz` and the divide) also the vertex run, the projection and the
//! lighting run; on ARMv6-M only, the edge setup and the single Q16.16 transforms. It lives in
//! one module (`src/kernel`, one file per kernel), behind entry points that each do a prefix
//! of their work and leave the rest to portable Rust, so every other stage is portable code and
//! a case a kernel does not handle (another colour type, another depth test, a new shading mode)
//! simply takes the portable path. `build.rs` chooses the kernels from the target; no other
//! module names an architecture.
//!
//! **How they are tested.** Each kernel computes exactly what its portable twin computes (the
//! same roundings and wrap-arounds), so the image is bit-identical on every target: the QEMU
//! benchmark (`scripts/mcu-bench`) compares every scene's frame hash on Cortex-M0, M4F and M33
//! with the host's, and before measuring compares each kernel with its twin on thousands of
//! pseudo-random inputs ([`selftest`]; the generators and oracles also run on the host in
//! `cargo test`). The Pico firmware's frames are compared with the host's in an RP2040
//! emulator (`scripts/pico-emu`).
//!
//! **Opting out.** The `portable` feature turns every kernel off: portable Rust on every
//! target, with the same pixels (and more instructions).
//!
//! ## Crate features
//!
//! The number type is a type parameter, not a feature, so fixed and float render side by side
//! in one build. Two features:
//!
//! - `portable` (off by default): no assembly on any target (see "Cortex-M kernels").
//! - `rp2040` (off by default): on a Raspberry Pi Pico's RP2040 (`thumbv6m-none-eabi`), the
//!   dithered RGB565 row routine uses the SIO interpolators of the core that renders (24
//!   cycles per written pixel instead of 28). Only for an RP2040: other Cortex-M0 chips have
//!   no SIO. The renderer sets both interpolators up whenever it draws a row and leaves them
//!   changed; an interrupt handler that uses them must save and restore them. No effect on
//!   other targets.

#![no_std]
#![deny(missing_docs)]
#![deny(unsafe_code)]
#![deny(missing_debug_implementations)]
#![deny(rustdoc::broken_intra_doc_links)]
// Matrix, vector and colour-channel code indexes several arrays in lockstep; index loops say
// that more plainly than zipped iterators.
#![allow(clippy::needless_range_loop)]

// Every module is private; what users name is re-exported below (tiny-skia's layout). The
// built-in scenes, hashes, metrics and overlays live in the repository's support crate
// (support/), not here. One folder per stage, in pipeline order: `scene` (what the user
// describes) → `geometry` (vertices, lighting, clipping, projection, culling, binning) →
// `raster` (the strip pass: setup, spans, layers) → the target; `num` (the number types) on
// `kernel` (every architecture-specific routine and the capability-chosen integer arithmetic,
// see "Cortex-M kernels" above), which imports nothing of the crate. `scripts/module-graph`
// checks these layers.
mod config;
mod error;
pub mod frame;
mod geometry;
mod kernel;
mod num;
mod raster;
mod renderer;
mod scene;
#[doc(hidden)]
pub mod selftest;
mod stats;

pub use fixed;

// The baked CSG part (support/src/demo_csg_mesh.rs) names the crate as its users do.
extern crate self as scanline3d;

#[doc(hidden)]
pub use config::__macro as __renderer_type;
pub use config::Capacities;
pub use frame::FrameOptions;
pub use num::math::Mat4;
pub use num::scalar::{Fx, Scalar};
pub use raster::depth_mode::DrawOrder;
pub use raster::layers::Layers;
pub use raster::pass::StripPass;
pub use raster::strip::StripCanvas;
pub use raster::DepthTest;
pub use renderer::no_depth::NoDepthRenderer;
pub use renderer::{Error, Needs, OverflowPolicy, Renderer, Shortfall, Stats};
pub use scene::camera::{Camera, Projection};
pub use scene::color::TargetColor;
pub use scene::effects::{Effects, Fog, PointLight};
pub use scene::mesh::Mesh;
pub use scene::shade::{Light, Material, Shading};
pub use scene::shapes::Shape;
pub use scene::texture::{Texture, TextureMode, Texturing, Wrap};
pub use scene::textured_shapes::TexturedShape;
pub use scene::tone::ToneMap;
pub use scene::{Object, Scene};

// The crate root holds what a frame needs; the rest is grouped by subject in the modules
// below (each only re-exports: the code stays in its stage's folder).

/// Vector and matrix helpers over any [`Scalar`] (`[S; 3]` vectors, column-vector
/// [`Mat4`]s), and the fixed-point reciprocal the projection uses.
pub mod math {
    pub use crate::num::math::{add, cross, dot, length, normalize, scale, sub, Mat4, Vec3};
    pub use crate::num::scalar::FxRecip;
}

/// The library's numeric limits and formats: largest screen, coordinates, textures and light
/// counts, the fixed-point formats of screen coordinates, depth and colour, and the sizes of
/// the per-vertex and per-triangle attribute records (for RAM budgets).
pub mod limits {
    pub use crate::error::MAX_TRANSLUCENT;
    pub use crate::geometry::phong_entries::MAX_PHONG_LIGHTS;
    pub use crate::geometry::project::{COORD_LIMIT, DEPTH_FRAC_BITS, MAX_SCREEN, SUBPIXEL_BITS};
    pub use crate::num::scalar::NDC_FRAC_BITS;
    pub use crate::raster::shadow::{BLOB_RINGS, BLOB_SIDES};
    pub use crate::raster::COLOR_FRAC_BITS;
    pub use crate::renderer::{
        ACTIVE_EXTRA_BYTES, ACTIVE_EXTRA_BYTES_32, VERTEX_EXTRA_BYTES, VERTEX_EXTRA_BYTES_32,
    };
    pub use crate::scene::camera::MAX_DEPTH_RATIO;
    pub use crate::scene::effects::MAX_PHONG_POINT_LIGHTS;
    pub use crate::scene::mesh::UV_LIMIT;
    pub use crate::scene::texture::MAX_TEXTURE_SIZE;
    pub use crate::scene::tone::MAX_TONE_SCALE;
}

/// Screen space: the projected vertex record, the view-volume outcode bits (clipping) and
/// the facing test of a screen triangle (culling).
pub mod screen {
    pub use crate::geometry::clip::{BOTTOM, FAR, GUARD, LEFT, NEAR, NEEDS_CLIP, RIGHT, TOP};
    pub use crate::geometry::cull::{facing, signed_area2, Facing};
    pub use crate::geometry::project::ScreenVertex;
}

/// Mesh helpers: normals, the edge adjacency that outlines and shadow volumes read, and the
/// parameters of the built-in [`Shape`]s.
pub mod mesh {
    pub use crate::scene::adjacency::{
        check_adjacency, mesh_adjacency, mesh_creases, Adjacency, NO_NEIGHBOUR,
    };
    pub use crate::scene::mesh::{face_normal, vertex_normals};
    pub use crate::scene::shapes::ParamValue;
}

/// Colour helpers: 8-bit channels to a target colour (rounded, optionally dithered with the
/// [`BAYER`](color::BAYER) matrix), luma, and the triangle-index "colour" for picking.
pub mod color {
    pub use crate::scene::color::{luma, quantize, scale_channels, TriangleId, BAYER};
}

/// Shadows and edges: planar (projected) and volume shadows, blob shadows, outlines and
/// wireframe edges, how translucent layers are ordered, and shadow maps.
pub mod shadow {
    pub use crate::raster::shadow::{
        Edges, Layering, Outline, PlanarShadow, ShadowLight, ShadowMethod, VolumeShadow,
    };
    pub use crate::raster::shadow_map::{
        ShadowFilter, ShadowImage, ShadowMap, ShadowMapping, ShadowStore, DEFAULT_BIAS, MAP_MARGIN,
        MAX_MAP_FOV,
    };
    pub use crate::raster::span_map::MAX_BIAS;
}

/// HDR tone mapping: the curves and the automatic exposure ([`ToneMap`] is
/// at the crate root).
pub mod tone {
    pub use crate::scene::tone::{AutoExposure, Metered, ToneCurve};
}

/// Profiling hooks: a [`Probe`](probe::Probe) sees every stage change of a frame (the
/// benchmarks time stages with one); [`NoProbe`](probe::NoProbe) costs nothing.
pub mod probe {
    pub use crate::renderer::{NoProbe, Probe, Stage};
}

/// The error types besides [`Error`]: the scene's parts' own errors (camera,
/// mesh, texture, shape, adjacency), the layered frame's, the strip buffer's, and which
/// capacity a [`Shortfall`] names.
pub mod errors {
    pub use crate::error::LayerError;
    pub use crate::renderer::{Capacity, StripBufferTooSmall};
    pub use crate::scene::adjacency::AdjacencyError;
    pub use crate::scene::camera::CameraError;
    pub use crate::scene::mesh::MeshError;
    pub use crate::scene::shapes::ShapeError;
    pub use crate::scene::texture::TextureError;
}

#[doc(inline)]
pub use embedded_graphics_core::draw_target::DrawTarget;

/// Internals the crate's own integration tests and tools check directly (the RAM formula, the
/// vertex colour packing, the normalized reciprocal). Not API: no stability promise.
#[doc(hidden)]
pub mod internals {
    pub use crate::geometry::project::{pack_channels, Viewport};
    pub use crate::kernel::wide::recip_norm;
    pub use crate::raster::shadow::plane_basis;
    pub use crate::renderer::no_depth::set_order_any;
    pub use crate::renderer::{ram_formula, ACTIVE_BYTES, TRIANGLE_BYTES, VERTEX_BYTES};
}

/// The types and traits a typical user needs.
pub mod prelude {
    pub use crate::mesh::vertex_normals;
    pub use crate::{
        renderer_type, Camera, Capacities, DepthTest, Effects, Fog, FrameOptions, Fx, Light, Mat4,
        Material, Mesh, Needs, Object, OverflowPolicy, PointLight, Projection, Renderer, Scalar,
        Scene, Shading, Shape, TargetColor,
    };
}

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
