//! The built-in scenes used by the examples, tests and benchmarks.
//!
//! The **default scene** is the torus peers are measured on: R = 1.0, r = 0.4, 32 × 16
//! segments (512 vertices, 1024 triangles), rotated 30° about X then 20° about Y; eye
//! (0, 1.2, 3) looking at the origin, up +Y, vertical field of view 45°, near 0.1, far 10;
//! one white light toward (−1, 1, 1); ambient 0.15, diffuse 0.85, no specular; colour
//! (255, 160, 64) on black; Gouraud; 240 × 240.

use crate::demo_assets::Floor;
pub use crate::demo_assets::{deg, Bench, BenchError, BenchFrame, CHECKER, CHECKER_TEXELS};
pub(crate) use crate::demo_assets::{look, persp};
use crate::demo_assets::{render_on, render_with};
pub use crate::demo_csg::{CSG_ACTIVE, CSG_TRIS};
pub use crate::demo_shadow::{
    render_shadow_scene, EdgeStyle, ShadowScene, CREASE_ANGLE, SHADOW_LIGHT, WIRE_COLOR,
};
use scanline3d::Mat4;
use scanline3d::Object;
use scanline3d::Scalar;
use scanline3d::{errors::CameraError, Camera, Projection};
use scanline3d::{errors::ShapeError, Shape};
use scanline3d::{Light, Material};

/// The default torus mesh.
pub type TorusShape<S> = Shape<S, 512, 1024>;

/// The default torus: R = 1.0, r = 0.4, 32 × 16 segments.
pub fn torus<S: Scalar>() -> Result<TorusShape<S>, ShapeError> {
    let mut shape = Shape::new();
    build_torus(&mut shape)?;
    Ok(shape)
}

/// Makes `shape` the default torus ([`torus`]) in place, with no copy of it on the stack.
///
/// # Errors
///
/// Never for the built-in parameters (the shape is then left as it was).
pub fn build_torus<S: Scalar>(shape: &mut TorusShape<S>) -> Result<(), ShapeError> {
    shape.set_torus(1.0, 0.4, 32, 16)
}

/// The default model transform: 30° about X, then 20° about Y ([`torus_tilt`]), then
/// `spin_deg` about Y.
#[must_use]
pub fn torus_transform<S: Scalar>(spin_deg: f64) -> Mat4<S> {
    torus_tilt().then(&Mat4::rotate_y(deg(spin_deg)))
}

/// The fixed part of [`torus_transform`]: 30° about X, then 20° about Y.
#[must_use]
pub fn torus_tilt<S: Scalar>() -> Mat4<S> {
    Mat4::rotate_x(deg(30.0)).then(&Mat4::rotate_y(deg(20.0)))
}

/// The default material: colour (255, 160, 64), ambient 0.15, diffuse 0.85, Gouraud.
#[must_use]
pub fn torus_material<S: Scalar>() -> Material<S> {
    Material::matte([255, 160, 64], S::from_f64(0.15), S::from_f64(0.85))
}

/// The default torus placed in the world.
#[must_use]
pub fn torus_object<S: Scalar>(shape: &TorusShape<S>) -> Object<'_, S> {
    Object {
        mesh: shape.mesh(),
        transform: torus_transform(0.0),
        material: torus_material(),
    }
}

/// The default camera: eye (0, 1.2, 3), target origin, up +Y, 45° vertical field of view,
/// near 0.1, far 10.
pub fn camera<S: Scalar>() -> Result<Camera<S>, CameraError> {
    let f = S::from_f64;
    Camera::look_at(
        [f(0.0), f(1.2), f(3.0)],
        [S::ZERO; 3],
        [S::ZERO, S::ONE, S::ZERO],
        Projection::Perspective {
            fov_y: deg(45.0),
            near: f(0.1),
            far: f(10.0),
        },
    )
}

/// The default light: white, toward (−1, 1, 1).
#[must_use]
pub fn lights<S: Scalar>() -> [Light<S>; 1] {
    [Light::white([-S::ONE, S::ONE, S::ONE])]
}

/// A renderer sized for the default scene at 240 × 240 with a one-line strip, with a margin
/// for any angle: 512 vertices, 480 triangles and 64 active triangles per row (a full turn
/// about Y in 1° steps keeps at most 466 triangles after culling, with at most 61 on one row:
/// `cargo run --release -p scanline3d-tools --bin render -- --budget --frames 360 --spin 1`).
pub type TorusRenderer<S, C> = scanline3d::Renderer<S, C, 240, 240, 512, 480, 64>;

/// Capacities of the benchmark torus renderer: exactly what a full turn in 1° steps needs
/// (see [`TorusRenderer`] for one with a margin).
pub const TORUS_CAPACITY: (usize, usize, usize) = (512, 466, 61);

/// The 16 KB part's torus frame: side in pixels, triangle and active capacities, for QEMU's
/// `microbit` (nRF51, 16 KB RAM) with the mesh in flash. The renderer's vertex store, triangle
/// list and active list do not shrink with the frame, so the frame side is what the stack has
/// left: `scripts/mcu-bench` measures the stack's high-water mark at this size and says what
/// the next multiple of 8 would need (BENCHMARKS.md, "Smallest part"; it was 120 until the
/// layered frames' geometry grew the deepest frame by 32 bytes, more than the 120 × 120
/// frame had left). The capacities are exactly what this frame needs (`render --budget --size
/// 112x112`: 446 triangles, 57 active; one less fails the render with
/// [`scanline3d::Error::Shortfall`], which `tests/bench_scenes.rs` checks).
pub const SMALL_PART_TORUS: (usize, usize, usize) = (112, 446, 57);

/// The default torus frame (spin 0) at `W × W` pixels from a given copy of the torus mesh
/// (for example one baked into flash), with a renderer of capacities `(512, T, A)` — what the
/// smallest parts use, where neither the 18 KB mesh nor a 240 × 240 renderer fits in RAM. The
/// frame (viewport) is square, so the image is the benchmark frame scaled.
pub fn render_torus_sized<S, C, D, P, const W: usize, const T: usize, const A: usize>(
    mesh: scanline3d::Mesh<'_, S>,
    target: &mut D,
    probe: &mut P,
) -> Result<BenchFrame, BenchError<D::Error>>
where
    S: Scalar,
    C: scanline3d::TargetColor,
    D: embedded_graphics_core::draw_target::DrawTarget<Color = C>,
    P: scanline3d::probe::Probe,
{
    let objects = [Object {
        mesh,
        transform: torus_transform(0.0),
        material: torus_material(),
    }];
    let scene =
        scanline3d::Scene::new(&objects, camera().map_err(|_| BenchError::Scene)?, lights());
    render_with::<S, C, D, P, W, W, 512, T, A, 1, 1, 0, 0>(&scene, false, target, probe)
}

/// The triangle capacity of the 240 × 240 torus benchmark frame.
const TORUS_TRIS: usize = 466;
/// The active-list capacity of the 240 × 240 torus benchmark frame.
const TORUS_ACTIVE: usize = 61;

/// The [`Bench::Torus`] frame with a strip of `LINES` lines ([`render_bench`] renders it with
/// one): the same image for every `LINES` (the strip height changes when lines are handed to
/// the target, not what they hold), a larger renderer. For measuring what a taller strip buys.
pub fn render_torus_strip<S, C, D, P, const LINES: usize>(
    spin_deg: f64,
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
    let shape = torus::<S>().map_err(|_| BenchError::Scene)?;
    let objects = [Object {
        mesh: shape.mesh(),
        transform: torus_transform(spin_deg),
        material: torus_material(),
    }];
    let camera = camera().map_err(|_| BenchError::Scene)?;
    let scene = scanline3d::Scene::new(&objects, camera, lights());
    if C::triangle_id(0).is_some() {
        // One more vertex record per drawn triangle, as in `render_bench`.
        render_with::<
            S,
            C,
            D,
            P,
            240,
            240,
            { 512 + TORUS_TRIS },
            TORUS_TRIS,
            TORUS_ACTIVE,
            1,
            LINES,
            0,
            0,
        >(&scene, dither, target, probe)
    } else {
        render_with::<S, C, D, P, 240, 240, 512, TORUS_TRIS, TORUS_ACTIVE, 1, LINES, 0, 0>(
            &scene, dither, target, probe,
        )
    }
}

/// The toon benchmark scene's bands ([`Bench::Toon`]).
pub const TOON_BANDS: core::num::NonZeroU8 = match core::num::NonZeroU8::new(4) {
    Some(b) => b,
    None => panic!("bands are at least 1"),
};

/// The lights' intensity in the HDR benchmark scene ([`Bench::HdrGouraud`]).
pub const HDR_INTENSITY: f64 = 2.0;
/// The exposure of the HDR benchmark scene.
pub const HDR_EXPOSURE: f64 = 0.6;

/// Renders one frame of benchmark scene `bench` at 240 × 240 into `target`, with `dither`,
/// reporting stages to `probe`. Meshes are generated on the stack; each scene has its own
/// renderer sized for it (see [`BenchFrame::renderer_ram_bytes`]).
pub fn render_bench<S, C, D, P>(
    bench: Bench,
    spin_deg: f64,
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
    render_bench_of::<S, C, D, P, false>(bench, spin_deg, dither, target, probe)
}

/// [`render_bench`] compiled for the cube scenes only ([`Bench::Cube`], [`Bench::CubePainter`],
/// [`Bench::CubeNoDepth`]); any other scene is [`BenchError::NotCompiled`]. For a firmware that
/// runs only those (the 16 KB parts' benchmark): `render_bench` holds a copy of every scene's
/// renderer, which such a firmware's build would compile and optimize for nothing.
pub fn render_bench_cube<S, C, D, P>(
    bench: Bench,
    spin_deg: f64,
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
    render_bench_of::<S, C, D, P, true>(bench, spin_deg, dither, target, probe)
}

/// [`render_bench`], or [`render_bench_cube`] with `CUBE_ONLY`: the other scenes' arms are then
/// behind a constant condition of the instantiation (`const { CUBE_ONLY }`), which the compiler
/// leaves out of the build.
fn render_bench_of<S, C, D, P, const CUBE_ONLY: bool>(
    bench: Bench,
    spin_deg: f64,
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
    use scanline3d::Shading;
    macro_rules! go_with {
        ($objects:expr, $camera:expr, $lights:expr, $v:expr, $t:expr, $a:expr) => {{
            let camera = $camera.map_err(|_| BenchError::Scene)?;
            let scene = scanline3d::Scene::new(&$objects, camera, $lights);
            match bench.depth_order() {
                None => render_with::<S, C, D, P, 240, 240, { $v }, $t, $a, 1, 1, 0, 0>(
                    &scene, dither, target, probe,
                ),
                Some(order) => render_on::<S, C, D, P, 240, 240, { $v }, $t, $a, 1, 1, 0, 0, 0>(
                    &scene, dither, order, target, probe,
                ),
            }
        }};
    }
    // Rendering triangle ids makes every triangle flat, which takes one more vertex record
    // per drawn triangle (see [`scanline3d::Renderer`]): those renders get a larger vertex store.
    macro_rules! go {
        ($objects:expr, $camera:expr, $lights:expr, $v:expr, $t:expr, $a:expr) => {{
            if C::triangle_id(0).is_some() {
                go_with!($objects, $camera, $lights, { $v + $t }, $t, $a)
            } else {
                go_with!($objects, $camera, $lights, $v, $t, $a)
            }
        }};
    }
    let spin = Mat4::rotate_y(deg(spin_deg));
    let fog = |near, far| scanline3d::Effects {
        point_lights: &[],
        fog: Some(scanline3d::Fog::linear(
            S::from_f64(near),
            S::from_f64(far),
            [150, 170, 200],
        )),
        tone: None,
    };
    match bench {
        Bench::Cube | Bench::CubePainter | Bench::CubeNoDepth => {
            let shape = Shape::<S, 24, 12>::cube(1.0).map_err(|_| BenchError::Scene)?;
            let mut m = Material::matte([90, 160, 255], S::from_f64(0.2), S::from_f64(0.8));
            m.shading = Shading::Flat;
            let objects = [Object {
                mesh: shape.mesh(),
                transform: Mat4::rotate_y(deg(35.0))
                    .then(&Mat4::rotate_x(deg(25.0)))
                    .then(&spin),
                material: m,
            }];
            let cam = look([0.0, 0.0, 4.5], [0.0; 3], persp(45.0, 0.1, 10.0));
            go!(
                objects,
                cam,
                [Light::white([-S::ONE, S::from_f64(2.0), S::from_f64(3.0)])],
                32,
                16,
                8
            )
        }
        _ if const { CUBE_ONLY } => Err(BenchError::NotCompiled(bench)),
        Bench::Torus => render_torus_strip::<S, C, D, P, 1>(spin_deg, dither, target, probe),
        Bench::Csg => crate::demo_csg::render_csg::<S, C, D, P>(spin_deg, dither, target, probe),
        Bench::ShadowNone
        | Bench::Shadow
        | Bench::ShadowBlob
        | Bench::Translucent
        | Bench::ShadowVolume
        | Bench::Outline
        | Bench::Edges
        | Bench::Wireframe
        | Bench::ShadowMap
        | Bench::ShadowMap32
        | Bench::ShadowMap128
        | Bench::ShadowMapPcf
        | Bench::ShadowMapPcf3
        | Bench::ShadowImage
        | Bench::ShadowImageBlur => render_shadow_scene::<S, C, D, P>(
            &ShadowScene::bench(bench, spin_deg, dither),
            target,
            probe,
        ),
        Bench::Icosphere | Bench::IcospherePainter | Bench::IcosphereNoDepth => {
            let shape = Shape::<S, 642, 1280>::icosphere(1.0, 3).map_err(|_| BenchError::Scene)?;
            let mut m = Material::matte([200, 60, 60], S::from_f64(0.1), S::from_f64(0.8));
            m.specular = S::from_f64(0.6);
            m.shininess = 20;
            let objects = [Object {
                mesh: shape.mesh(),
                transform: spin,
                material: m,
            }];
            let cam = look([0.0, 0.5, 3.0], [0.0; 3], persp(45.0, 0.1, 10.0));
            go!(
                objects,
                cam,
                [Light::white([-S::ONE, S::ONE, S::ONE])],
                642,
                704,
                96
            )
        }
        Bench::Terrain => {
            let shape =
                Shape::<S, 289, 512>::terrain(8.0, 16, 0.5).map_err(|_| BenchError::Scene)?;
            let m = Material::matte([110, 180, 90], S::from_f64(0.25), S::from_f64(0.75));
            let objects = [Object {
                mesh: shape.mesh(),
                transform: spin,
                material: m,
            }];
            // The ground under the eye (a grid vertex at x = 0, z = 2.5) is at y = −0.163; the
            // eye is 3 cm above it, less than the near plane's half-height (0.1·tan 30° =
            // 5.8 cm), so the ground in front of the eye crosses the near plane.
            let cam = look(
                [0.0, -0.133, 2.5],
                [0.0, -0.35, -2.0],
                persp(60.0, 0.1, 20.0),
            );
            go!(
                objects,
                cam,
                [Light::white([S::ONE, S::from_f64(2.0), S::ONE])],
                400,
                600,
                96
            )
        }
        Bench::Overdraw => {
            const QUAD: [[u16; 3]; 2] = [[0, 1, 2], [0, 2, 3]];
            let p = |x: f64, y: f64| [S::from_f64(x), S::from_f64(y), S::ZERO];
            let quad = [p(-1.0, -1.0), p(1.0, -1.0), p(1.0, 1.0), p(-1.0, 1.0)];
            let mesh = scanline3d::Mesh::new(&quad, &QUAD).map_err(|_| BenchError::Scene)?;
            let mut objects = [Object {
                mesh,
                transform: Mat4::identity(),
                material: Material::matte([0; 3], S::ONE, S::ZERO),
            }; 8];
            for (k, o) in objects.iter_mut().enumerate() {
                let t = k as f64;
                // 0.01 apart, the first object nearest. Triangles starting on the same row
                // are drawn in an unspecified (deterministic) order; in this frame most
                // layers still pass the depth test.
                o.transform = Mat4::rotate_z(deg(7.0 * t))
                    .then(&Mat4::translate([
                        S::from_f64(0.05 * t - 0.2),
                        S::from_f64(0.03 * t - 0.1),
                        S::from_f64(-0.01 * t),
                    ]))
                    .then(&spin);
                o.material = Material::matte(
                    [(40 + 25 * k) as u8, (200 - 20 * k) as u8, 128],
                    S::ONE,
                    S::ZERO,
                );
                o.material.shading = Shading::Flat;
            }
            let cam = look([0.0, 0.0, 2.2], [0.0; 3], persp(45.0, 0.1, 10.0));
            go!(
                objects,
                cam,
                [Light::white([S::ZERO, S::ZERO, S::ONE])],
                48,
                16,
                16
            )
        }
        Bench::Textured | Bench::TexturedAffine | Bench::TexturedExact | Bench::TexturedFog => {
            let mode = match bench {
                Bench::TexturedAffine => scanline3d::TextureMode::Affine,
                Bench::TexturedExact => scanline3d::TextureMode::PerPixel,
                _ => scanline3d::TextureMode::Subdivided16,
            };
            let cube =
                scanline3d::TexturedShape::<S, 24, 12>::cube(1.0).map_err(|_| BenchError::Scene)?;
            let floor = Floor::<S>::new();
            let floor_mesh = scanline3d::Mesh::new(&floor.positions, &floor.indices)
                .and_then(|m| m.with_normals(&floor.normals))
                .and_then(|m| m.with_uvs(&floor.uvs))
                .map_err(|_| BenchError::Scene)?;
            let lit = |c: [u8; 3]| {
                Material::matte(c, S::from_f64(0.3), S::from_f64(0.7))
                    .textured(&CHECKER)
                    .texture_mode(mode)
            };
            let objects = [
                Object {
                    mesh: floor_mesh,
                    transform: Mat4::identity(),
                    material: lit([255, 255, 255]),
                },
                Object {
                    mesh: cube.mesh(),
                    transform: Mat4::scale([S::from_f64(0.6); 3])
                        .then(&Mat4::rotate_y(deg(30.0)))
                        .then(&Mat4::translate([
                            S::ZERO,
                            S::from_f64(0.6),
                            S::from_f64(-1.0),
                        ]))
                        .then(&spin),
                    material: lit([255, 220, 160]),
                },
            ];
            let cam = look([-0.8, 1.0, 2.2], [0.3, 0.2, -1.5], persp(60.0, 0.1, 12.0));
            let camera = cam.map_err(|_| BenchError::Scene)?;
            let haze = fog(2.0, 9.0);
            let mut scene = scanline3d::Scene::new(
                &objects,
                camera,
                [Light::white([-S::ONE, S::from_f64(2.0), S::ONE])],
            );
            if bench == Bench::TexturedFog {
                scene = scene.with_effects(&haze);
            }
            // Room for the clipped floor and, with triangle ids (every triangle flat), one more
            // vertex record per triangle.
            render_with::<S, C, D, P, 240, 240, 96, 24, 16, 1, 1, 96, 16>(
                &scene, dither, target, probe,
            )
        }
        Bench::Phong
        | Bench::PhongFast
        | Bench::Toon
        | Bench::PhongGouraud
        | Bench::PointPhong
        | Bench::PointPhongFast
        | Bench::PointGouraud
        | Bench::FogGouraud
        | Bench::HdrGouraud
        | Bench::HdrPhong => {
            let shape = Shape::<S, 162, 320>::icosphere(1.0, 2).map_err(|_| BenchError::Scene)?;
            let shading = match bench {
                Bench::Phong | Bench::PointPhong | Bench::HdrPhong => Shading::Phong,
                Bench::PhongFast | Bench::PointPhongFast => Shading::FastPhong,
                Bench::Toon => Shading::Toon { bands: TOON_BANDS },
                _ => Shading::Gouraud,
            };
            let m = Material::matte([60, 110, 210], S::from_f64(0.1), S::from_f64(0.8))
                .specular(S::from_f64(0.8), 40)
                .shading(shading);
            let objects = [Object {
                mesh: shape.mesh(),
                transform: Mat4::rotate_y(deg(20.0)).then(&spin),
                material: m,
            }];
            let cam = look([0.0, 0.3, 3.0], [0.0; 3], persp(45.0, 0.1, 10.0));
            let camera = cam.map_err(|_| BenchError::Scene)?;
            let light = [Light::white([-S::from_f64(0.6), S::from_f64(0.8), S::ONE])];
            let v = |x: f64, y: f64, z: f64| [S::from_f64(x), S::from_f64(y), S::from_f64(z)];
            let lamp = [
                scanline3d::PointLight::new(v(1.3, -0.4, 1.6), [255, 200, 140]).attenuation(
                    S::from_f64(0.5),
                    S::from_f64(0.3),
                    S::from_f64(0.2),
                ),
            ];
            let lamps = scanline3d::Effects {
                point_lights: &lamp,
                fog: None,
                tone: None,
            };
            let haze = fog(2.2, 3.6);
            let hdr = scanline3d::Effects {
                tone: Some(
                    scanline3d::ToneMap::new(scanline3d::tone::ToneCurve::Filmic)
                        .with_intensity(S::from_f64(HDR_INTENSITY))
                        .with_exposure(S::from_f64(HDR_EXPOSURE)),
                ),
                ..lamps
            };
            let mut scene = scanline3d::Scene::new(&objects, camera, light);
            if matches!(
                bench,
                Bench::PointPhong | Bench::PointPhongFast | Bench::PointGouraud
            ) {
                scene = scene.with_effects(&lamps);
            } else if bench == Bench::FogGouraud {
                scene = scene.with_effects(&haze);
            } else if matches!(bench, Bench::HdrGouraud | Bench::HdrPhong) {
                scene = scene.with_effects(&hdr);
            }
            // Room for triangle ids (one more vertex record per triangle).
            render_with::<S, C, D, P, 240, 240, 512, 192, 32, 1, 1, 512, 40>(
                &scene, dither, target, probe,
            )
        }
        Bench::Deep => {
            let shape = Shape::<S, 24, 12>::cube(1.0).map_err(|_| BenchError::Scene)?;
            let mut objects = [Object {
                mesh: shape.mesh(),
                transform: Mat4::identity(),
                material: Material::matte([0; 3], S::ONE, S::ZERO),
            }; 6];
            for (k, (dist, x)) in [
                (0.05, -0.03),
                (0.5, 0.1),
                (5.0, -0.6),
                (40.0, 4.0),
                (200.0, -30.0),
                (800.0, 80.0),
            ]
            .iter()
            .enumerate()
            {
                let size = dist * 0.12;
                o_set(&mut objects[k], *dist, *x, size, k, &spin);
            }
            let cam = look([0.0, 0.0, 0.0], [0.0, 0.0, -1.0], persp(60.0, 0.01, 1000.0));
            go!(
                objects,
                cam,
                [Light::white([S::ONE, S::ONE, S::ONE])],
                192,
                80,
                40
            )
        }
    }
}

fn o_set<S: Scalar>(o: &mut Object<'_, S>, dist: f64, x: f64, size: f64, k: usize, spin: &Mat4<S>) {
    let s = S::from_f64(size);
    o.transform = Mat4::scale([s, s, s])
        .then(spin)
        .then(&Mat4::rotate_x(deg(20.0 + 10.0 * k as f64)))
        .then(&Mat4::translate([
            S::from_f64(x),
            S::from_f64(-0.1 * dist),
            S::from_f64(-dist),
        ]));
    o.material = Material::matte(
        [(60 + 30 * k) as u8, 120, (230 - 30 * k) as u8],
        S::from_f64(0.3),
        S::from_f64(0.7),
    );
    o.material.shading = scanline3d::Shading::Flat;
}

/// The Raspberry Pi Pico firmware's frames (`examples/pico_st7789.rs`), shared with the host
/// tool that renders the same frames for the emulator check (`tools/src/bin/board_frames.rs`): the
/// default torus spinning about Y, Gouraud-shaded with dithering, and the frame rate of the
/// previous frame as a label, drawn strip by strip into buffers the caller owns.
pub mod board {
    use core::fmt::Write as _;
    use core::ops::Range;

    use embedded_graphics::mono_font::ascii::FONT_6X10;
    use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};

    use crate::overlay::{GlyphError, Glyphs};
    use scanline3d::Scalar;
    use scanline3d::{Object, Scene};

    /// Panel width and height in pixels.
    pub const SIZE: usize = 240;
    /// Rows per strip: the depth lines of [`BoardRenderer`] and the height of each of the
    /// firmware's two strip buffers (2 × 8 × 240 × 2 B = 7.5 KB).
    pub const STRIP_LINES: usize = 8;
    /// Degrees the torus turns per frame.
    pub const SPIN_DEG_PER_FRAME: u32 = 3;
    /// Frames per turn (the animation repeats after them).
    pub const TURN_FRAMES: usize = (360 / SPIN_DEG_PER_FRAME) as usize;
    const _: () = assert!(360 % SPIN_DEG_PER_FRAME == 0);
    /// Top-left corner of the frame-rate label, in pixels.
    pub const LABEL_AT: (i32, i32) = (4, 4);
    /// The characters the label uses (its glyphs are rasterized once, from `FONT_6X10`).
    pub const LABEL_CHARS: &str = "0123456789. fps";

    /// The firmware's renderer: the default torus's capacities ([`super::TorusRenderer`]) with
    /// a strip of [`STRIP_LINES`] lines.
    pub type BoardRenderer<S> =
        scanline3d::Renderer<S, Rgb565, 240, 240, 512, 480, 64, STRIP_LINES>;

    /// The firmware's renderer, dithering on.
    #[must_use]
    pub fn renderer<S: Scalar>() -> BoardRenderer<S> {
        BoardRenderer::new().with_dither(true)
    }

    /// One strip buffer: [`STRIP_LINES`] lines of native RGB565 words.
    pub type StripBuffer = [[Rgb565; SIZE]; STRIP_LINES];

    /// The spin of frame `frame` in degrees (0 ≤ spin < 360, whole degrees).
    #[must_use]
    pub fn spin(frame: u32) -> f64 {
        ((frame as u64 * SPIN_DEG_PER_FRAME as u64) % 360) as f64
    }

    /// The label for a previous frame that took `frame_us` microseconds: frames per second
    /// with one decimal, truncated (`"35.7 fps"`); empty for 0 (no previous frame).
    #[must_use]
    pub fn fps_label(frame_us: u64) -> heapless::String<16> {
        let mut label = heapless::String::new();
        if let Some(tenths) = 10_000_000u64.checked_div(frame_us) {
            // At most 20 characters for u64::MAX tenths; a 1 µs frame gives "1000000.0 fps".
            let _ = write!(label, "{}.{} fps", tenths / 10, tenths % 10);
        }
        label
    }

    /// The label's glyphs, rasterized once.
    ///
    /// # Errors
    ///
    /// Never for the built-in font and characters (a [`GlyphError`] would mean a change to
    /// them broke the set's capacity).
    pub fn glyphs() -> Result<Glyphs<16>, GlyphError> {
        Glyphs::new(&FONT_6X10, LABEL_CHARS)
    }

    /// The firmware's scene, built once: the default torus mesh ([`super::torus`], 18 KB for
    /// `Fx<I16F16>`, borrowed: the caller keeps it where it fits, e.g. a `static` built in place
    /// with [`super::build_torus`] on a part whose stack cannot hold it twice), the
    /// camera, the material and light, the fixed part of the model transform and the sine and
    /// cosine of every frame's spin ([`TURN_FRAMES`] pairs, 960 B for `Fx<I16F16>`: a frame then
    /// computes no sine, cosine or `f64` conversion).
    #[derive(Debug)]
    pub struct BoardScene<'a, S: Scalar> {
        shape: &'a super::TorusShape<S>,
        camera: scanline3d::Camera<S>,
        tilt: scanline3d::Mat4<S>,
        material: scanline3d::Material<S>,
        lights: [scanline3d::Light<S>; 1],
        spins: [(S, S); TURN_FRAMES],
    }

    impl<'a, S: Scalar> BoardScene<'a, S> {
        /// The scene around `shape`, the board's torus ([`super::torus`] or [`super::build_torus`]).
        ///
        /// # Errors
        ///
        /// Never for the built-in parameters; a message naming the part that failed otherwise.
        pub fn new(shape: &'a super::TorusShape<S>) -> Result<Self, &'static str> {
            let mut spins = [(S::ZERO, S::ZERO); TURN_FRAMES];
            for (k, sc) in spins.iter_mut().enumerate() {
                *sc = super::deg::<S>(spin(k as u32)).sin_cos();
            }
            Ok(BoardScene {
                shape,
                camera: super::camera().map_err(|_| "camera")?,
                tilt: super::torus_tilt(),
                material: super::torus_material(),
                lights: super::lights(),
                spins,
            })
        }

        /// The model transform of frame `frame`: exactly [`super::torus_transform`] of its
        /// [`spin`] (the same operations on the same values), with the fixed part computed once.
        #[must_use]
        pub fn transform(&self, frame: u32) -> scanline3d::Mat4<S> {
            // spin(frame) = SPIN_DEG_PER_FRAME · (frame mod TURN_FRAMES).
            let (s, c) = self.spins[frame as usize % TURN_FRAMES];
            self.tilt.then(&scanline3d::Mat4::rotate_y_sin_cos(s, c))
        }

        /// Prepares frame `frame` of the animation in `renderer` (geometry only) and returns
        /// it: its strips follow with [`draw_strip`], or with the strip passes
        /// ([`BoardPass`]) after [`scanline3d::frame::Frame::share`]. `renderer` is a
        /// [`BoardRenderer`] or the same renderer with other strip lines `L` of its own (the
        /// two-core firmware's renderers keep one line: their rows are drawn by the cores'
        /// passes, whose strips are [`STRIP_LINES`] rows whatever `L` is).
        ///
        /// # Errors
        ///
        /// The renderer's error when the frame does not fit its capacities (it always does: the
        /// capacities hold for a full turn).
        pub fn prepare<'r, const L: usize>(
            &self,
            renderer: &'r mut scanline3d::Renderer<S, Rgb565, 240, 240, 512, 480, 64, L>,
            frame: u32,
        ) -> Result<
            scanline3d::frame::Frame<
                'r,
                scanline3d::Renderer<S, Rgb565, 240, 240, 512, 480, 64, L>,
            >,
            scanline3d::Error<core::convert::Infallible>,
        > {
            let objects = [Object {
                mesh: self.shape.mesh(),
                transform: self.transform(frame),
                material: self.material,
            }];
            renderer.prepare(
                &Scene::new(&objects, self.camera, self.lights),
                scanline3d::FrameOptions::new(),
            )
        }
    }

    /// Draws the next strip of the prepared `frame` into `buffer` with the label `label`
    /// composed into it (white, at [`LABEL_AT`]); returns its rows, or `None` when the frame
    /// is done.
    pub fn draw_strip<S: Scalar>(
        frame: &mut scanline3d::frame::Frame<'_, BoardRenderer<S>>,
        glyphs: &Glyphs<16>,
        label: &str,
        buffer: &mut StripBuffer,
    ) -> Option<Range<usize>> {
        let rows = frame.strip_into(buffer)?;
        let n = rows.len();
        glyphs.draw(label, LABEL_AT, Rgb565::WHITE, rows.start, &mut buffer[..n]);
        Some(rows)
    }

    /// A strip pass of the board's renderer ([`scanline3d::StripPass`]), one per core: its
    /// active list and [`STRIP_LINES`] depth lines (the strips go to the caller's buffers).
    pub type BoardPass = scanline3d::StripPass<Rgb565, SIZE, 64, STRIP_LINES>;

    /// The parts of a frame split between two cores at row `split` ([`split_frame`]).
    #[derive(Copy, Clone, Debug, PartialEq, Eq)]
    pub enum SplitPart {
        /// Geometry (shared: one core prepares it for both).
        Geometry,
        /// Rows `0..split`, the first core's strips (its pass begun at row 0).
        Top,
        /// Rows `split..240`, the second core's strips (its pass begun at `split`: the
        /// triangles crossing it set up and stepped down to it).
        Bottom,
    }

    /// Renders frame `frame` as two cores share it: the geometry once, then rows `0..split`
    /// through the first core's pass `top` and rows `split..240` through the second core's
    /// pass `bottom`, both reading the same prepared frame ([`scanline3d::StripPass`]). Here
    /// the parts run one after the other on one core, and `mark` is called at the end of
    /// each, so a benchmark can time them; `split` is rounded down to a multiple of
    /// [`STRIP_LINES`]. Returns the strips drawn; the frame is the whole frame's, bit for bit.
    ///
    /// # Errors
    ///
    /// The renderer's error when the frame does not fit its capacities.
    #[allow(clippy::too_many_arguments)]
    pub fn split_frame<S: Scalar>(
        scene: &BoardScene<'_, S>,
        renderer: &mut BoardRenderer<S>,
        passes: [&mut BoardPass; 2],
        frame: u32,
        split: usize,
        buffer: &mut StripBuffer,
        mut mark: impl FnMut(SplitPart),
    ) -> Result<usize, scanline3d::Error<core::convert::Infallible>> {
        let split = split.min(SIZE) / STRIP_LINES * STRIP_LINES;
        let shared = scene.prepare(renderer, frame)?.share();
        mark(SplitPart::Geometry);
        let [top, bottom] = passes;
        let mut strips = 0;
        top.begin(shared, 0..split)?;
        while top.render_strip_into(shared, buffer)?.is_some() {
            strips += 1;
        }
        mark(SplitPart::Top);
        bottom.begin(shared, split..SIZE)?;
        while bottom.render_strip_into(shared, buffer)?.is_some() {
            strips += 1;
        }
        mark(SplitPart::Bottom);
        Ok(strips)
    }

    #[cfg(test)]
    mod tests {
        use super::*;

        #[test]
        fn labels() {
            assert_eq!(fps_label(0).as_str(), "");
            assert_eq!(fps_label(28_000).as_str(), "35.7 fps");
            assert_eq!(fps_label(1).as_str(), "1000000.0 fps");
            assert_eq!(fps_label(u64::MAX).as_str(), "0.0 fps");
            assert_eq!(spin(0), 0.0);
            assert_eq!(spin(121), 3.0);
            assert!(glyphs().is_ok());
        }

        #[test]
        fn cached_tilt_gives_the_same_transform() {
            type Q = scanline3d::Fx<scanline3d::fixed::types::I16F16>;
            let shape = super::super::torus::<Q>().unwrap();
            let scene = BoardScene::new(&shape).unwrap();
            for frame in [0, 1, 7, 119, 120, 1000, u32::MAX] {
                let a = scene.transform(frame);
                let b = super::super::torus_transform::<Q>(spin(frame));
                assert!(a == b, "frame {frame}");
            }
        }

        #[test]
        fn split_frame_draws_every_strip_once() {
            type Q = scanline3d::Fx<scanline3d::fixed::types::I16F16>;
            let shape = super::super::torus::<Q>().unwrap();
            let scene = BoardScene::new(&shape).unwrap();
            let mut r = renderer::<Q>();
            let mut buffer = [[Rgb565::BLACK; SIZE]; STRIP_LINES];
            let (mut top, mut bottom) = (BoardPass::new(), BoardPass::new());
            for split in [0, 8, 100, 120, 240, 999] {
                let mut parts = heapless::Vec::<SplitPart, 3>::new();
                let strips = split_frame(
                    &scene,
                    &mut r,
                    [&mut top, &mut bottom],
                    5,
                    split,
                    &mut buffer,
                    |p| parts.push(p).unwrap(),
                )
                .unwrap();
                assert_eq!(strips, SIZE / STRIP_LINES, "split {split}");
                assert_eq!(
                    parts.as_slice(),
                    [SplitPart::Geometry, SplitPart::Top, SplitPart::Bottom]
                );
            }
        }
    }
}

#[cfg(test)]
mod capacity_tests {
    use super::*;
    use embedded_graphics_core::pixelcolor::Rgb565;
    use scanline3d::fixed::types::I16F16;
    use scanline3d::Fx;

    #[test]
    fn the_torus_renderers_meet_the_ram_budget() {
        // The benchmark torus renderer meets the 16 KB budget; the demo one, with a margin for
        // any angle, is the figure the README quotes.
        let (v, t, a) = TORUS_CAPACITY;
        assert_eq!((v, t, a), (512, 466, 61));
        type Q = Fx<I16F16>;
        let bench = core::mem::size_of::<scanline3d::Renderer<Q, Rgb565, 240, 240, 512, 466, 61>>();
        assert!(bench <= 16 * 1024, "{bench}");
        let demo = core::mem::size_of::<TorusRenderer<Q, Rgb565>>();
        assert!(demo > bench && demo < 17 * 1024, "{demo}");
    }
}
