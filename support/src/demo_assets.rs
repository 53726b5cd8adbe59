//! The benchmark scenes' shared parts: the scene list ([`Bench`]), what a frame produced or why
//! it failed, the camera helpers, and the textured scenes' assets (the checkerboard texture in
//! flash and the floor mesh).

use scanline3d::Scalar;
use scanline3d::{errors::CameraError, Camera, Projection};

/// Degrees to radians in `S`.
#[must_use]
pub fn deg<S: Scalar>(d: f64) -> S {
    S::from_f64(d * core::f64::consts::PI / 180.0)
}

/// What one benchmark frame produced.
#[derive(Copy, Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BenchFrame {
    /// The frame's statistics.
    pub stats: scanline3d::Stats,
    /// `size_of` the renderer the scene used.
    pub renderer_ram_bytes: usize,
}

/// Why a benchmark frame failed.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum BenchError<E> {
    /// Building the scene failed (a shape or camera).
    Scene,
    /// Rendering failed.
    Render(scanline3d::Error<E>),
    /// The frame needed more than the scene's capacities (on the host, whose renderers are
    /// larger: see `host_sizing`; a microcontroller's renderer fails such a frame with
    /// [`scanline3d::Error::Shortfall`] instead).
    Capacity {
        /// What the frame needed.
        needed: scanline3d::Needs,
        /// The scene's capacities.
        capacity: scanline3d::Needs,
    },
    /// The scene is not in this build ([`crate::demo::render_bench_cube`] draws only the cube
    /// scenes).
    NotCompiled(Bench),
}

impl<E: core::fmt::Display> core::fmt::Display for BenchError<E> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            BenchError::Scene => write!(f, "building the benchmark scene failed (shape or camera)"),
            BenchError::Render(e) => write!(f, "rendering the benchmark scene failed: {e}"),
            BenchError::Capacity { needed, capacity } => write!(
                f,
                "the benchmark frame needed {needed:?}, more than its scene's capacities {capacity:?}"
            ),
            BenchError::NotCompiled(b) => {
                write!(f, "the benchmark scene {} is not compiled into this build", b.name())
            }
        }
    }
}

impl<E: core::fmt::Debug + core::fmt::Display> core::error::Error for BenchError<E> {}

pub(crate) fn look<S: Scalar>(
    eye: [f64; 3],
    target: [f64; 3],
    projection: Projection<S>,
) -> Result<Camera<S>, CameraError> {
    Camera::look_at(
        eye.map(S::from_f64),
        target.map(S::from_f64),
        [S::ZERO, S::ONE, S::ZERO],
        projection,
    )
}

pub(crate) fn persp<S: Scalar>(fov_deg: f64, near: f64, far: f64) -> Projection<S> {
    Projection::Perspective {
        fov_y: deg(fov_deg),
        near: S::from_f64(near),
        far: S::from_f64(far),
    }
}

/// Renders `scene` with a fresh `W × H` renderer of capacities `V`, `T`, `A` and reports the
/// frame's statistics and the renderer's size.
pub(crate) fn render_with<
    S,
    C,
    D,
    P,
    const W: usize,
    const H: usize,
    const V: usize,
    const T: usize,
    const A: usize,
    const L: usize,
    const LINES: usize,
    const XV: usize,
    const XA: usize,
>(
    scene: &scanline3d::Scene<'_, S, L>,
    dither: bool,
    target: &mut D,
    probe: &mut P,
) -> Result<BenchFrame, BenchError<D::Error>>
where
    S: Scalar,
    C: scanline3d::TargetColor,
    D: embedded_graphics_core::draw_target::DrawTarget<Color = C>,
    P: scanline3d::probe::Probe,
{
    let order = scanline3d::DrawOrder::default();
    render_on::<S, C, D, P, W, H, V, T, A, L, LINES, XV, XA, LINES>(
        scene, dither, order, target, probe,
    )
}

/// [`render_with`] with `ZL` depth lines (`LINES`, or 0 for a renderer without them, which
/// draws in `order`).
///
/// On a microcontroller the frame is drawn by a renderer of exactly these capacities. On the
/// host (the `host` feature) by one of [`host_sizing`]'s: see there why.
pub(crate) fn render_on<
    S,
    C,
    D,
    P,
    const W: usize,
    const H: usize,
    const V: usize,
    const T: usize,
    const A: usize,
    const L: usize,
    const LINES: usize,
    const XV: usize,
    const XA: usize,
    const ZL: usize,
>(
    scene: &scanline3d::Scene<'_, S, L>,
    dither: bool,
    order: scanline3d::DrawOrder,
    target: &mut D,
    probe: &mut P,
) -> Result<BenchFrame, BenchError<D::Error>>
where
    S: Scalar,
    C: scanline3d::TargetColor,
    D: embedded_graphics_core::draw_target::DrawTarget<Color = C>,
    P: scanline3d::probe::Probe,
{
    #[cfg(not(feature = "host"))]
    {
        // Set in place: `with_dither` would move the renderer, which may take a second copy of
        // it on the stack.
        let mut r = scanline3d::Renderer::<S, C, W, H, V, T, A, LINES, XV, XA, ZL>::new();
        r.set_dither(dither);
        scanline3d::internals::set_order_any(&mut r, order);
        let stats = r
            .render_with(
                scene,
                scanline3d::FrameOptions::new().probe(&mut *probe),
                target,
            )
            .map_err(BenchError::Render)?;
        Ok(BenchFrame {
            stats,
            renderer_ram_bytes: core::mem::size_of_val(&r),
        })
    }
    #[cfg(feature = "host")]
    {
        use host_sizing::{ACTIVE, ATTR_ACTIVE, ATTR_VERTICES, TRIANGLES, VERTICES};
        const {
            assert!(
                V <= VERTICES
                    && T <= TRIANGLES
                    && A <= ACTIVE
                    && XV <= ATTR_VERTICES
                    && XA <= ATTR_ACTIVE,
                "a benchmark scene's capacities exceed the host's renderer (demo_assets::host_sizing)"
            )
        };
        fn draw<
            S,
            C,
            D,
            P,
            const W: usize,
            const H: usize,
            const L: usize,
            const LINES: usize,
            const XV: usize,
            const XA: usize,
            const ZL: usize,
        >(
            scene: &scanline3d::Scene<'_, S, L>,
            dither: bool,
            order: scanline3d::DrawOrder,
            target: &mut D,
            probe: &mut P,
        ) -> Result<scanline3d::Stats, scanline3d::Error<D::Error>>
        where
            S: Scalar,
            C: scanline3d::TargetColor,
            D: embedded_graphics_core::draw_target::DrawTarget<Color = C>,
            P: scanline3d::probe::Probe,
        {
            let mut r: std::boxed::Box<
                scanline3d::Renderer<S, C, W, H, VERTICES, TRIANGLES, ACTIVE, LINES, XV, XA, ZL>,
            > = std::boxed::Box::default();
            r.set_dither(dither);
            scanline3d::internals::set_order_any(&mut *r, order);
            r.render_with(scene, scanline3d::FrameOptions::new().probe(probe), target)
        }
        // A scene without attribute stores keeps a renderer without them: the pipeline
        // compiled without the stores' tests, which a microcontroller runs for it. Only the
        // taken branch is compiled (the conditions are constants of the instantiation), but
        // every branch's renderer type must be valid (its checks are evaluated): hence the
        // depth lines as `0` or `LINES` (what `ZL` is) rather than `ZL` itself.
        let stats = if ZL == 0 {
            draw::<S, C, D, P, W, H, L, LINES, 0, 0, 0>(scene, dither, order, target, probe)
        } else if XV == 0 && XA == 0 {
            draw::<S, C, D, P, W, H, L, LINES, 0, 0, LINES>(scene, dither, order, target, probe)
        } else {
            draw::<S, C, D, P, W, H, L, LINES, ATTR_VERTICES, ATTR_ACTIVE, LINES>(
                scene, dither, order, target, probe,
            )
        }
        .map_err(BenchError::Render)?;
        host_sizing::fits(&stats, scanline3d::Needs::new(V, T, A).with_stores(XV, XA))?;
        Ok(BenchFrame {
            stats,
            renderer_ram_bytes: core::mem::size_of::<
                scanline3d::Renderer<S, C, W, H, V, T, A, LINES, XV, XA, ZL>,
            >(),
        })
    }
}

/// The host's benchmark renderers. Each benchmark scene has its own capacities (what its
/// frames need, so that a microcontroller's RAM holds nothing unused), and each set of
/// capacities is a renderer type of its own, with its own compiled copy of the whole pipeline
/// for every number type, colour and target it is drawn in. On the host the scenes share one
/// renderer type per strip height, depth lines and attribute stores (with or without), large
/// enough for each, so that the tools and tests that draw every scene in six number types do
/// not compile some twenty copies of the renderer per number type (`scripts/mono-report`,
/// CHANGELOG). A frame's pixels do not depend on the capacities it fits, which the QEMU
/// benchmark checks (its frames' hashes against the host's); whether it fits its scene's own
/// capacities is checked after the frame ([`fits`]), so that a scene that outgrows them fails
/// on the host as it would on a microcontroller.
#[cfg(feature = "host")]
pub(crate) mod host_sizing {
    use super::BenchError;

    /// Vertex records: the most of any scene (the see-through wireframe with triangle ids).
    pub(crate) const VERTICES: usize = 7680;
    /// Triangles.
    pub(crate) const TRIANGLES: usize = 2560;
    /// Active triangles per row (at most the frame's height, 240: the painter's order then
    /// keeps its slot order in the renderer's own row table, as on a microcontroller).
    pub(crate) const ACTIVE: usize = 160;
    /// Texture and Phong attributes per vertex record.
    pub(crate) const ATTR_VERTICES: usize = 512;
    /// Texture and Phong attributes per active triangle.
    pub(crate) const ATTR_ACTIVE: usize = 40;

    /// [`BenchError::Capacity`] unless the frame of `stats` fits `capacity` (a scene's own).
    pub(crate) fn fits<E>(
        stats: &scanline3d::Stats,
        capacity: scanline3d::Needs,
    ) -> Result<(), BenchError<E>> {
        let needed = scanline3d::Needs::from_stats(stats);
        if needed.fits(&capacity) {
            Ok(())
        } else {
            Err(BenchError::Capacity { needed, capacity })
        }
    }
}

/// The textured benchmark's 64 × 64 texture: a two-tone checkerboard of 8 × 8-texel squares
/// with a dark line along each square's top and left edge (the lines show a perspective
/// error as bent or broken lines).
pub static CHECKER_TEXELS: [u16; 64 * 64] = {
    let mut t = [0u16; 64 * 64];
    let mut i = 0;
    while i < 64 * 64 {
        let (x, y) = (i % 64, i / 64);
        let light = ((x / 8) + (y / 8)) % 2 == 0;
        t[i] = if x % 8 == 0 || y % 8 == 0 {
            0x2104 // dark grey (4, 8, 4)
        } else if light {
            0xffff
        } else {
            0xc618 // grey (24, 48, 24)
        };
        i += 1;
    }
    t
};

/// [`CHECKER_TEXELS`] as a texture (repeating).
pub static CHECKER: scanline3d::Texture = match scanline3d::Texture::new(&CHECKER_TEXELS, 64, 64) {
    Ok(t) => t,
    Err(_) => panic!("the checkerboard is 64 x 64"),
};

/// The textured benchmark's floor: x ∈ [−3, 3], z ∈ [−10, 4] at y = 0 (reaching behind the
/// eye, so it is clipped at the near plane), facing up, the checkerboard repeated 3 × 7 times.
pub(crate) struct Floor<S> {
    pub(crate) positions: [[S; 3]; 4],
    pub(crate) normals: [[S; 3]; 4],
    pub(crate) uvs: [[S; 2]; 4],
    pub(crate) indices: [[u16; 3]; 2],
}

impl<S: Scalar> Floor<S> {
    pub(crate) fn new() -> Self {
        let p = |x: f64, z: f64| [S::from_f64(x), S::ZERO, S::from_f64(z)];
        let uv = |x: f64, z: f64| [S::from_f64((x + 3.0) * 0.5), S::from_f64((4.0 - z) * 0.5)];
        Floor {
            positions: [p(-3.0, 4.0), p(3.0, 4.0), p(3.0, -10.0), p(-3.0, -10.0)],
            normals: [[S::ZERO, S::ONE, S::ZERO]; 4],
            uvs: [uv(-3.0, 4.0), uv(3.0, 4.0), uv(3.0, -10.0), uv(-3.0, -10.0)],
            indices: [[0, 1, 2], [0, 2, 3]],
        }
    }
}

/// The benchmark scenes, shared by the examples, the host tests and the microcontroller
/// benchmark so that every figure is measured on the same frames.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Bench {
    /// A flat-shaded cube filling about a third of the screen.
    Cube,
    /// The default scene: the Gouraud torus.
    Torus,
    /// An icosphere (3 subdivisions, 642 vertices) with Gouraud shading and a specular term.
    Icosphere,
    /// A 16 × 16-cell height field seen from low above, whose near part crosses the near plane.
    Terrain,
    /// Eight large overlapping quads at close depths: every pixel tests up to eight layers, and
    /// most layers pass (heavy overdraw).
    Overdraw,
    /// Six cubes from 0.05 to 800 units away with near 0.01 and far 1000 (depth precision).
    Deep,
    /// A checkerboard floor receding to the far plane with a textured cube on it, lit
    /// (Gouraud), the floor crossing the near plane: perspective-correct texturing by
    /// 16-pixel segments ([`scanline3d::TextureMode::Subdivided16`]).
    Textured,
    /// [`Bench::Textured`] with [`scanline3d::TextureMode::Affine`] spans.
    TexturedAffine,
    /// [`Bench::Textured`] with [`scanline3d::TextureMode::PerPixel`] spans (the reference).
    TexturedExact,
    /// A coarse icosphere (2 subdivisions, 320 triangles) with a sharp specular highlight
    /// (specular 0.8, shininess 40), [`scanline3d::Shading::Phong`]: lit at every pixel.
    Phong,
    /// [`Bench::Phong`] with [`scanline3d::Shading::FastPhong`] (lit every 8 pixels).
    PhongFast,
    /// [`Bench::Phong`] with Gouraud shading, for comparison: the highlight falls inside
    /// triangles and mostly vanishes.
    PhongGouraud,
    /// [`Bench::Phong`] with an attenuated point light besides the directional one.
    PointPhong,
    /// [`Bench::PointPhong`] with [`scanline3d::Shading::FastPhong`].
    PointPhongFast,
    /// [`Bench::PointPhong`] with Gouraud shading (the point light per vertex).
    PointGouraud,
    /// [`Bench::PhongGouraud`] in fog (per vertex).
    FogGouraud,
    /// [`Bench::Textured`] in fog (per 16-pixel segment).
    TexturedFog,
    /// A torus and a cube above a ground square, without shadows (the figures the shadow
    /// methods are measured against).
    ShadowNone,
    /// [`Bench::ShadowNone`] with the projected planar shadow of both models on the ground
    /// ([`scanline3d::FrameOptions::layered`]; the two shadows overlap and darken once).
    Shadow,
    /// [`Bench::ShadowNone`] with a soft blob shadow under each model
    /// ([`scanline3d::shadow::ShadowMethod::Blob`]).
    ShadowBlob,
    /// [`Bench::ShadowNone`] with the torus translucent (drawn after the opaque triangles of
    /// each row, blended).
    Translucent,
    /// [`Bench::ShadowNone`] with shadow volumes of both models ([`scanline3d::shadow::VolumeShadow`]): on
    /// the ground, on each other and on themselves.
    ShadowVolume,
    /// [`Bench::ShadowNone`] with both models outlined ([`scanline3d::shadow::Outline`]).
    Outline,
    /// The shadow scene's torus and cube outlined with their creases (edges sharper than
    /// [`crate::demo::CREASE_ANGLE`]: the cube's) besides their contours.
    Edges,
    /// The shadow scene as a wireframe with its hidden lines removed: every edge of the ground,
    /// the torus and the cube, the surfaces unlit in the background colour.
    Wireframe,
    /// [`Bench::PointGouraud`] in HDR: both lights [`crate::demo::HDR_INTENSITY`] times as
    /// bright, exposure [`crate::demo::HDR_EXPOSURE`], the filmic tone curve.
    HdrGouraud,
    /// [`Bench::Cube`] on a renderer without depth lines ([`scanline3d::NoDepthRenderer`]) in the
    /// painter's order ([`scanline3d::DrawOrder::FarToNear`]): the same pixels (one convex object).
    CubePainter,
    /// [`Bench::Cube`] without depth lines in any order ([`scanline3d::DrawOrder::Any`]): back-face
    /// culling alone, as the seeds say suffices for one convex polyhedron.
    CubeNoDepth,
    /// [`Bench::Icosphere`] without depth lines in the painter's order.
    IcospherePainter,
    /// [`Bench::Icosphere`] without depth lines in any order.
    IcosphereNoDepth,
    /// [`Bench::PointPhong`] in HDR as [`Bench::HdrGouraud`]: tone-mapped per pixel.
    HdrPhong,
    /// The example CSG part (`tests/data/part.csg`: a block with a spherical pocket and a
    /// drilled hole, 210 triangles) baked into flash, Gouraud, one white light.
    Csg,
    /// [`Bench::Phong`] with [`scanline3d::Shading::Toon`] in [`crate::demo::TOON_BANDS`]
    /// bands: lit per pixel, hard edges between the tones and at the highlight.
    Toon,
    /// [`Bench::ShadowNone`] with a 64 × 64 shadow map of both models
    /// ([`scanline3d::FrameOptions::shadow_map`]): on the ground, on each other and on
    /// themselves.
    ShadowMap,
    /// [`Bench::ShadowMap`] with a map of 32 texels a side.
    ShadowMap32,
    /// [`Bench::ShadowMap`] with a map of 128 texels a side.
    ShadowMap128,
    /// [`Bench::ShadowMap`] read through 2 × 2 percentage-closer filtering (soft edges).
    ShadowMapPcf,
    /// [`Bench::ShadowMap`] read through 3 × 3 percentage-closer filtering.
    ShadowMapPcf3,
    /// [`Bench::ShadowNone`] with a 64 × 64 light-view image without depth
    /// ([`scanline3d::shadow::ShadowImage`]): the casters shadow the ground only.
    ShadowImage,
    /// [`Bench::ShadowImage`] pre-blurred (3 × 3): soft edges.
    ShadowImageBlur,
}

impl Bench {
    /// The order of a scene drawn without depth lines, or `None` for a Z-buffer scene.
    #[must_use]
    pub fn depth_order(self) -> Option<scanline3d::DrawOrder> {
        match self {
            Bench::CubePainter | Bench::IcospherePainter => Some(scanline3d::DrawOrder::FarToNear),
            Bench::CubeNoDepth | Bench::IcosphereNoDepth => Some(scanline3d::DrawOrder::Any),
            _ => None,
        }
    }

    /// Every benchmark scene.
    pub const ALL: [Bench; 40] = [
        Bench::Cube,
        Bench::Torus,
        Bench::Icosphere,
        Bench::Terrain,
        Bench::Overdraw,
        Bench::Deep,
        Bench::Textured,
        Bench::TexturedAffine,
        Bench::TexturedExact,
        Bench::Phong,
        Bench::PhongFast,
        Bench::PhongGouraud,
        Bench::PointPhong,
        Bench::PointPhongFast,
        Bench::PointGouraud,
        Bench::FogGouraud,
        Bench::TexturedFog,
        Bench::ShadowNone,
        Bench::Shadow,
        Bench::ShadowBlob,
        Bench::Translucent,
        Bench::ShadowVolume,
        Bench::Outline,
        Bench::Edges,
        Bench::Wireframe,
        Bench::HdrGouraud,
        Bench::CubePainter,
        Bench::CubeNoDepth,
        Bench::IcospherePainter,
        Bench::IcosphereNoDepth,
        Bench::HdrPhong,
        Bench::Csg,
        Bench::Toon,
        Bench::ShadowMap,
        Bench::ShadowMap32,
        Bench::ShadowMap128,
        Bench::ShadowMapPcf,
        Bench::ShadowMapPcf3,
        Bench::ShadowImage,
        Bench::ShadowImageBlur,
    ];

    /// Its name in reports.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Bench::Cube => "cube",
            Bench::Torus => "torus",
            Bench::Icosphere => "icosphere",
            Bench::Terrain => "terrain",
            Bench::Overdraw => "overdraw",
            Bench::Deep => "deep",
            Bench::Textured => "textured",
            Bench::TexturedAffine => "textured_affine",
            Bench::TexturedExact => "textured_exact",
            Bench::Phong => "phong",
            Bench::PhongFast => "phong_fast",
            Bench::Toon => "toon",
            Bench::PhongGouraud => "phong_gouraud",
            Bench::PointPhong => "point_phong",
            Bench::PointPhongFast => "point_phong_fast",
            Bench::PointGouraud => "point_gouraud",
            Bench::FogGouraud => "fog_gouraud",
            Bench::TexturedFog => "textured_fog",
            Bench::ShadowNone => "shadow_none",
            Bench::Shadow => "shadow",
            Bench::ShadowBlob => "shadow_blob",
            Bench::Translucent => "translucent",
            Bench::ShadowVolume => "shadow_volume",
            Bench::Outline => "outline",
            Bench::Edges => "edges",
            Bench::Wireframe => "wireframe",
            Bench::HdrGouraud => "hdr_gouraud",
            Bench::CubePainter => "cube_painter",
            Bench::CubeNoDepth => "cube_nodepth",
            Bench::IcospherePainter => "icosphere_painter",
            Bench::IcosphereNoDepth => "icosphere_nodepth",
            Bench::HdrPhong => "hdr_phong",
            Bench::Csg => "csg",
            Bench::ShadowMap => "shadow_map",
            Bench::ShadowMap32 => "shadow_map_32",
            Bench::ShadowMap128 => "shadow_map_128",
            Bench::ShadowMapPcf => "shadow_map_pcf",
            Bench::ShadowMapPcf3 => "shadow_map_pcf3",
            Bench::ShadowImage => "shadow_image",
            Bench::ShadowImageBlur => "shadow_image_blur",
        }
    }
}
