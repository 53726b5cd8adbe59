//! The shadow benchmark scenes (`demo::Bench::ShadowNone`, `Shadow`, `ShadowBlob`,
//! `ShadowVolume`, `Translucent`, `Outline`, `Edges`, `Wireframe`): a torus and a cube above a ground square, lit by
//! one directional light, drawn without a shadow, with the projected planar shadow of both on
//! the ground (their shadows overlap), with blobs, with shadow volumes, with the torus
//! translucent, outlined, with its edges and creases drawn (`Edges`) and as a wireframe with its
//! hidden lines removed (`Wireframe`).

use crate::demo_assets::{deg, look, persp, Bench, BenchError, BenchFrame};
use scanline3d::shadow::{ShadowFilter, ShadowImage, ShadowMap, ShadowMapping, ShadowStore};
use scanline3d::Mat4;
use scanline3d::Scalar;
use scanline3d::Shape;
use scanline3d::{
    shadow::Edges, shadow::Layering, shadow::Outline, shadow::PlanarShadow, shadow::ShadowLight,
    shadow::ShadowMethod, shadow::VolumeShadow,
};
use scanline3d::{FrameOptions, Layers, Renderer};
use scanline3d::{Light, Material};
use scanline3d::{Object, Scene};

/// The scene's capacities: vertices, triangles, active triangles, and the layers' receiver and
/// post lists (the shadow polygons of both casters, or the translucent torus).
pub const SHADOW_CAPACITY: (usize, usize, usize, usize, usize) = (1024, 1024, 64, 4, 64);

/// The shadow-volume scene's capacities (as [`SHADOW_CAPACITY`]): each caster's volume adds
/// two vertices per mesh vertex and its caps and silhouette quads.
pub const VOLUME_CAPACITY: (usize, usize, usize, usize, usize) = (1280, 1536, 64, 4, 192);

/// The capacities (as [`SHADOW_CAPACITY`]) of the scene with every edge drawn
/// ([`EdgeStyle::All`], [`Bench::Wireframe`]): each edge is a quad of four vertices and two
/// triangles.
pub const WIRE_CAPACITY: (usize, usize, usize, usize, usize) = (2560, 2048, 64, 4, 160);

/// The capacities (as [`SHADOW_CAPACITY`]) of the scene with hidden edges drawn too
/// ([`ShadowScene::see_through`]): every edge of every face.
pub const SEE_THROUGH_CAPACITY: (usize, usize, usize, usize, usize) = (5120, 2560, 160, 4, 256);

/// The angle between two faces above which their edge is a crease ([`EdgeStyle::Crease`]),
/// degrees: the cube's edges (90°), not the torus's facets (15° and 30°).
pub const CREASE_ANGLE: f64 = 40.0;

/// The wireframe's lines' colour.
pub const WIRE_COLOR: [u8; 3] = [120, 230, 170];

/// How far the shadow volumes reach from the casters (world units): past the ground.
pub const VOLUME_REACH: f64 = 6.0;

/// The outlines' colour.
pub const OUTLINE_COLOR: [u8; 3] = [20, 20, 20];

/// The direction toward the scene's light (also the shadow's).
pub const SHADOW_LIGHT: [f64; 3] = [-1.6, 1.5, 0.8];

/// The shadow's opacity (black at 140/255).
pub const SHADOW_ALPHA: u8 = 140;

/// The translucent torus's opacity.
pub const TRANSLUCENT_ALPHA: u8 = 150;

/// The shadow scene's options ([`render_shadow_scene`]); the benchmark scenes are
/// [`ShadowScene::bench`].
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct ShadowScene {
    /// The planar shadow of the torus and the cube (`None`: no planar shadow).
    pub shadow: Option<ShadowMethod>,
    /// Shadow volumes of the torus and the cube instead (with `shadow` `None`).
    pub volume: bool,
    /// Outlines of the torus and the cube (of the ground too with `wireframe`), in this colour.
    pub outline: Option<[u8; 3]>,
    /// Which edges the outlines draw.
    pub edges: EdgeStyle,
    /// The crease angle of [`EdgeStyle::Crease`], degrees (0..=180; the benchmark's is
    /// [`CREASE_ANGLE`]).
    pub crease_angle: f64,
    /// Hidden edges drawn too ([`Outline::see_through`]).
    pub see_through: bool,
    /// Every model unlit in the background colour ([`Material::unlit`]): with `outline`, a
    /// wireframe.
    pub wireframe: bool,
    /// The plane the shadow falls on, `a·x + b·y + c·z + d = 0`: the ground square is placed
    /// in it (centred at the plane's point nearest the origin; `0, 1, 0, 0` is the level
    /// ground).
    pub plane: [f64; 4],
    /// The torus's opacity (255: opaque).
    pub alpha: u8,
    /// The models' turn about the vertical axis, degrees.
    pub spin_deg: f64,
    /// 4 × 4 ordered dithering.
    pub dither: bool,
    /// A shadow map of the torus and the cube instead of a planar shadow or volumes, this many
    /// texels a side (32, 64 or 128): every model receives.
    pub map: Option<usize>,
    /// How the map is read (nearest or percentage-closer filtering; an image is pre-blurred
    /// by either filter).
    pub map_filter: ShadowFilter,
    /// The map is a light-view image without depth ([`ShadowImage`]) rather than a depth map:
    /// the ground alone receives.
    pub image: bool,
}

/// Which edges [`ShadowScene::outline`] draws ([`Edges`]).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum EdgeStyle {
    /// The contours.
    Silhouette,
    /// The contours and the creases sharper than [`CREASE_ANGLE`].
    Crease,
    /// Every edge.
    All,
}

impl ShadowScene {
    /// Benchmark scene `bench` ([`Bench::ShadowNone`], [`Bench::Shadow`],
    /// [`Bench::ShadowBlob`], [`Bench::ShadowVolume`], [`Bench::Translucent`], [`Bench::Outline`],
    /// [`Bench::Edges`] or [`Bench::Wireframe`]) turned by `spin_deg`.
    #[must_use]
    pub fn bench(bench: Bench, spin_deg: f64, dither: bool) -> Self {
        ShadowScene {
            shadow: match bench {
                Bench::Shadow => Some(ShadowMethod::Projected),
                Bench::ShadowBlob => Some(ShadowMethod::Blob),
                _ => None,
            },
            volume: bench == Bench::ShadowVolume,
            outline: match bench {
                Bench::Outline | Bench::Edges => Some(OUTLINE_COLOR),
                Bench::Wireframe => Some(WIRE_COLOR),
                _ => None,
            },
            edges: match bench {
                Bench::Edges => EdgeStyle::Crease,
                Bench::Wireframe => EdgeStyle::All,
                _ => EdgeStyle::Silhouette,
            },
            crease_angle: CREASE_ANGLE,
            see_through: false,
            wireframe: bench == Bench::Wireframe,
            plane: [0.0, 1.0, 0.0, 0.0],
            alpha: if bench == Bench::Translucent {
                TRANSLUCENT_ALPHA
            } else {
                255
            },
            spin_deg,
            dither,
            map: match bench {
                Bench::ShadowMap
                | Bench::ShadowMapPcf
                | Bench::ShadowMapPcf3
                | Bench::ShadowImage
                | Bench::ShadowImageBlur => Some(64),
                Bench::ShadowMap32 => Some(32),
                Bench::ShadowMap128 => Some(128),
                _ => None,
            },
            map_filter: match bench {
                Bench::ShadowMapPcf => ShadowFilter::Pcf2,
                Bench::ShadowMapPcf3 | Bench::ShadowImageBlur => ShadowFilter::Pcf3,
                _ => ShadowFilter::Nearest,
            },
            image: matches!(bench, Bench::ShadowImage | Bench::ShadowImageBlur),
        }
    }
}

/// Renders the shadow scene — a torus and a cube above a ground square, one directional light —
/// at 240 × 240 with options `o`: drawn by [`scanline3d::Renderer::render`] when it needs no layers
/// (no shadow, an opaque torus), else by [`scanline3d::FrameOptions::layered`].
/// [`BenchFrame::renderer_ram_bytes`] counts the [`Layers`] too.
pub fn render_shadow_scene<S, C, D, P>(
    o: &ShadowScene,
    target: &mut D,
    probe: &mut P,
) -> Result<BenchFrame, BenchError<D::Error>>
where
    S: Scalar,
    C: scanline3d::TargetColor,
    D: embedded_graphics_core::draw_target::DrawTarget<Color = C>,
    P: scanline3d::probe::Probe,
{
    let ground = Shape::<S, 4, 2>::plane(5.0, 5.0, 1, 1).map_err(|_| BenchError::Scene)?;
    let torus = Shape::<S, 288, 576>::torus(0.7, 0.25, 24, 12).map_err(|_| BenchError::Scene)?;
    let cube = Shape::<S, 24, 12>::cube(0.35).map_err(|_| BenchError::Scene)?;
    let spin = Mat4::rotate_y(deg(o.spin_deg));
    let background = [24, 28, 40];
    let m = |c: [u8; 3]| {
        if o.wireframe {
            Material::unlit(background)
        } else {
            Material::matte(c, S::from_f64(0.25), S::from_f64(0.75))
        }
    };
    let objects = [
        Object {
            mesh: ground.mesh(),
            transform: onto_plane(o.plane),
            material: m([200, 190, 160]).flat(),
        },
        Object {
            mesh: torus.mesh(),
            transform: Mat4::rotate_x(deg(35.0))
                .then(&spin)
                .then(&Mat4::translate([
                    S::from_f64(-0.4),
                    S::from_f64(1.2),
                    S::from_f64(-0.2),
                ])),
            material: m([90, 160, 255]).translucent(o.alpha),
        },
        Object {
            mesh: cube.mesh(),
            transform: Mat4::rotate_y(deg(30.0)).then(&Mat4::translate([
                S::from_f64(0.55),
                S::from_f64(0.5),
                S::from_f64(0.7),
            ])),
            material: m([230, 110, 80]).flat(),
        },
    ];
    let camera = look([0.0, 3.8, 4.6], [0.0, 0.3, 0.0], persp(45.0, 0.5, 20.0))
        .map_err(|_| BenchError::Scene)?;
    let l = SHADOW_LIGHT.map(S::from_f64);
    let scene = Scene::new(&objects, camera, [Light::white(l)]).with_background(background);
    // The models' adjacency (for volumes and outlines): built here, outside the frame (a
    // mesh's setup; an application keeps it with the mesh).
    let mut ground_adj = [[0u16; 3]; 2];
    let mut torus_adj = [[0u16; 3]; 576];
    let mut cube_adj = [[0u16; 3]; 12];
    // And their creases (3 bits per triangle).
    let mut ground_creases = [0u8; 1];
    let mut torus_creases = [0u8; 216];
    let mut cube_creases = [0u8; 5];
    if o.volume || o.outline.is_some() {
        let bad = |_| BenchError::Scene;
        scanline3d::mesh::mesh_adjacency(&ground.mesh(), &mut ground_adj).map_err(bad)?;
        scanline3d::mesh::mesh_adjacency(&torus.mesh(), &mut torus_adj).map_err(bad)?;
        scanline3d::mesh::mesh_adjacency(&cube.mesh(), &mut cube_adj).map_err(bad)?;
        if o.edges == EdgeStyle::Crease {
            let a = o.crease_angle;
            scanline3d::mesh::mesh_creases(&ground.mesh(), &ground_adj, a, &mut ground_creases)
                .map_err(bad)?;
            scanline3d::mesh::mesh_creases(&torus.mesh(), &torus_adj, a, &mut torus_creases)
                .map_err(bad)?;
            scanline3d::mesh::mesh_creases(&cube.mesh(), &cube_adj, a, &mut cube_creases)
                .map_err(bad)?;
        }
    }
    // Each table checked against its mesh once (Adjacency::new): the frame then only checks
    // that each object's mesh is that mesh.
    let checked = if o.volume || o.outline.is_some() {
        let bad = |_| BenchError::Scene;
        Some([
            scanline3d::mesh::Adjacency::new(&ground.mesh(), &ground_adj).map_err(bad)?,
            scanline3d::mesh::Adjacency::new(&torus.mesh(), &torus_adj).map_err(bad)?,
            scanline3d::mesh::Adjacency::new(&cube.mesh(), &cube_adj).map_err(bad)?,
        ])
    } else {
        None
    };
    let every = checked.as_ref().map_or(&[][..], |c| &c[..]);
    let creases: [&[u8]; 3] = [&ground_creases, &torus_creases, &cube_creases];
    // The casters' (and the outlined models') tables; a wireframe outlines the ground too.
    let (adjacency, creases, outlined) = if o.wireframe {
        (every, &creases[..], &[0, 1, 2][..])
    } else {
        (every.get(1..).unwrap_or(&[]), &creases[1..], &[1, 2][..])
    };
    let mut layering = match o.shadow {
        Some(method) => Layering::projected(
            &[0],
            &[1, 2],
            PlanarShadow {
                method,
                ..PlanarShadow::new(
                    o.plane.map(S::from_f64),
                    ShadowLight::Directional(l),
                    SHADOW_ALPHA,
                )
            },
        ),
        None if o.volume => Layering::volumes(
            &[1, 2],
            VolumeShadow {
                light: ShadowLight::Directional(l),
                reach: S::from_f64(VOLUME_REACH),
                adjacency,
                color: [0; 3],
                alpha: SHADOW_ALPHA,
            },
        ),
        None => Layering::none(),
    };
    if let Some(color) = o.outline {
        let edges = match o.edges {
            EdgeStyle::Silhouette => Edges::Silhouette,
            EdgeStyle::Crease => Edges::Crease(creases),
            EdgeStyle::All => Edges::All,
        };
        layering = layering.with_outline(
            Outline::silhouette(outlined, adjacency, color)
                .with_edges(edges)
                .see_through(o.see_through),
        );
    }
    if let Some(size) = o.map {
        let mapping = ShadowMapping::new(ShadowLight::Directional(l), &[1, 2], &[])
            .with_shadow([0; 3], SHADOW_ALPHA)
            .with_filter(o.map_filter);
        const V: usize = SHADOW_CAPACITY.0;
        const T: usize = SHADOW_CAPACITY.1;
        const A: usize = SHADOW_CAPACITY.2;
        // The 128-texel map's pass sees the casters four times finer than the 32 one: more of
        // their triangles cross a map row at once (65 at 315° of the turn).
        const A128: usize = A + 16;
        let (s, d) = (&scene, o.dither);
        return match (size, o.image) {
            (32, false) => {
                draw_mapped::<S, C, D, P, V, T, A, ShadowMap<32>>(s, &mapping, d, target, probe)
            }
            (64, false) => {
                draw_mapped::<S, C, D, P, V, T, A, ShadowMap<64>>(s, &mapping, d, target, probe)
            }
            (128, false) => {
                draw_mapped::<S, C, D, P, V, T, A128, ShadowMap<128>>(s, &mapping, d, target, probe)
            }
            #[cfg(feature = "host")]
            (32, true) => {
                draw_mapped::<S, C, D, P, V, T, A, ShadowImage<32>>(s, &mapping, d, target, probe)
            }
            (64, true) => {
                draw_mapped::<S, C, D, P, V, T, A, ShadowImage<64>>(s, &mapping, d, target, probe)
            }
            #[cfg(feature = "host")]
            (128, true) => draw_mapped::<S, C, D, P, V, T, A128, ShadowImage<128>>(
                s, &mapping, d, target, probe,
            ),
            _ => Err(BenchError::Scene),
        };
    }
    let plain = o.shadow.is_none() && !o.volume && o.outline.is_none() && o.alpha == 255;
    // Rendering triangle ids makes every triangle flat (one more vertex record per drawn
    // triangle): those renders get a larger vertex store.
    // Each set of capacities: vertices, triangles, active triangles, post list.
    macro_rules! go {
        ($cap:expr) => {{
            const V: usize = $cap.0;
            const T: usize = $cap.1;
            const A: usize = $cap.2;
            const PA: usize = $cap.4;
            let (s, l, d) = (&scene, &layering, o.dither);
            if C::triangle_id(0).is_some() {
                draw::<S, C, D, P, { V + T }, T, A, PA>(plain, s, l, d, target, probe)
            } else {
                draw::<S, C, D, P, V, T, A, PA>(plain, s, l, d, target, probe)
            }
        }};
    }
    // Hidden edges take the largest stores, every edge the next, then volumes.
    let lines = o.outline.is_some();
    if lines && o.see_through {
        go!(SEE_THROUGH_CAPACITY)
    } else if lines && o.edges == EdgeStyle::All {
        go!(WIRE_CAPACITY)
    } else if o.volume {
        go!(VOLUME_CAPACITY)
    } else {
        go!(SHADOW_CAPACITY)
    }
}

/// Draws `scene` plainly (`plain`) or in layers, with a vertex store of `V`, a triangle store of
/// `T`, an active list of `A` and a post list of `PA`.
fn draw<S, C, D, P, const V: usize, const T: usize, const A: usize, const PA: usize>(
    plain: bool,
    scene: &Scene<'_, S, 1>,
    layering: &Layering<'_, S>,
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
    const RA: usize = SHADOW_CAPACITY.3;
    // On the host one renderer and one set of layer lists for every capacity set
    // (`demo_assets::host_sizing`), the frame's needs checked against the scene's own after it.
    #[cfg(feature = "host")]
    {
        use crate::demo_assets::host_sizing::{self, ACTIVE, TRIANGLES, VERTICES};
        const HOST_PA: usize = SEE_THROUGH_CAPACITY.4;
        const { assert!(V <= VERTICES && T <= TRIANGLES && A <= ACTIVE && PA <= HOST_PA) };
        let mut r: std::boxed::Box<Renderer<S, C, 240, 240, VERTICES, TRIANGLES, ACTIVE>> =
            std::boxed::Box::default();
        r.set_dither(dither);
        let options = FrameOptions::new().probe(probe);
        let stats = if plain {
            r.render_with(scene, options, target)
        } else {
            let mut layers: std::boxed::Box<Layers<240, 1, RA, HOST_PA>> =
                std::boxed::Box::default();
            r.render_with(scene, options.layered(layering, &mut layers), target)
        }
        .map_err(BenchError::Render)?;
        let capacity = scanline3d::Needs::new(V, T, A);
        let capacity = if plain {
            capacity
        } else {
            capacity.with_layers(RA, PA)
        };
        host_sizing::fits(&stats, capacity)?;
        let ram = core::mem::size_of::<Renderer<S, C, 240, 240, V, T, A>>();
        let layers = core::mem::size_of::<Layers<240, 1, RA, PA>>();
        Ok(BenchFrame {
            stats,
            renderer_ram_bytes: if plain { ram } else { ram + layers },
        })
    }
    #[cfg(not(feature = "host"))]
    {
        let mut r = Renderer::<S, C, 240, 240, V, T, A>::new();
        r.set_dither(dither);
        if plain {
            let stats = r
                .render_with(scene, FrameOptions::new().probe(&mut *probe), target)
                .map_err(BenchError::Render)?;
            return Ok(BenchFrame {
                stats,
                renderer_ram_bytes: core::mem::size_of_val(&r),
            });
        }
        let mut layers = Layers::<240, 1, RA, PA>::new();
        let stats = r
            .render_with(
                scene,
                FrameOptions::new()
                    .probe(&mut *probe)
                    .layered(layering, &mut layers),
                target,
            )
            .map_err(BenchError::Render)?;
        Ok(BenchFrame {
            stats,
            renderer_ram_bytes: core::mem::size_of_val(&r) + core::mem::size_of_val(&layers),
        })
    }
}

/// Draws `scene` with a shadow map or image `M` from `mapping`, on a renderer with a vertex
/// store of `V`, a triangle store of `T`, an active list of `A` and as many pool entries (each
/// receiver's triangle takes one while active). [`BenchFrame::renderer_ram_bytes`] counts the
/// map too.
fn draw_mapped<S, C, D, P, const V: usize, const T: usize, const A: usize, M>(
    scene: &Scene<'_, S, 1>,
    mapping: &ShadowMapping<'_, S>,
    dither: bool,
    target: &mut D,
    probe: &mut P,
) -> Result<BenchFrame, BenchError<D::Error>>
where
    S: Scalar,
    C: scanline3d::TargetColor,
    D: embedded_graphics_core::draw_target::DrawTarget<Color = C>,
    P: scanline3d::probe::Probe,
    M: ShadowStore + Default,
{
    #[cfg(feature = "host")]
    let (mut r, mut map) = (
        std::boxed::Box::new(Renderer::<S, C, 240, 240, V, T, A, 1, 0, A>::new()),
        std::boxed::Box::new(M::default()),
    );
    #[cfg(not(feature = "host"))]
    let (mut r, mut map) = (
        Renderer::<S, C, 240, 240, V, T, A, 1, 0, A>::new(),
        M::default(),
    );
    // (A `Box` on the host, the value on a device's stack.)
    let map: &mut M = &mut map;
    r.set_dither(dither);
    let stats = r
        .render_with(
            scene,
            FrameOptions::new()
                .probe(&mut *probe)
                .shadow_map(mapping, map),
            target,
        )
        .map_err(BenchError::Render)?;
    Ok(BenchFrame {
        stats,
        renderer_ram_bytes: core::mem::size_of::<Renderer<S, C, 240, 240, V, T, A, 1, 0, A>>()
            + core::mem::size_of::<M>(),
    })
}

/// The transform that places the level ground square (y = 0, facing +y) in plane
/// `a·x + b·y + c·z + d = 0`: +y to the plane's unit normal, the origin to the plane's point
/// nearest it. (The identity for the level ground.)
fn onto_plane<S: Scalar>(p: [f64; 4]) -> Mat4<S> {
    let (u, n, w) = scanline3d::internals::plane_basis(p);
    let len = libm::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).max(1e-300);
    let o = n.map(|c| -c * p[3] / len);
    let mut m = Mat4::identity();
    for i in 0..3 {
        m.m[i] = [u[i], n[i], w[i], o[i]].map(S::from_f64);
    }
    m
}
