//! The shadow benchmark scenes (`demo::Bench::ShadowNone`, `Shadow`, `Translucent`): a torus
//! and a cube above a ground square, lit by one directional light, drawn without a shadow, with
//! the projected planar shadow of both on the ground (their shadows overlap), and with the torus
//! translucent.

use crate::demo::{deg, look, persp, Bench, BenchError, BenchFrame};
use crate::math::Mat4;
use crate::scalar::Scalar;
use crate::scene::{Object, Scene};
use crate::shade::{Light, Material};
use crate::shadow::{Layering, PlanarShadow, ShadowLight};
use crate::shapes::Shape;
use crate::{Layers, Renderer};

/// The scene's capacities: vertices, triangles, active triangles, and the layers' receiver and
/// post lists (the shadow polygons of both casters, or the translucent torus).
pub const SHADOW_CAPACITY: (usize, usize, usize, usize, usize) = (1024, 1024, 64, 4, 64);

/// The direction toward the scene's light (also the shadow's).
pub const SHADOW_LIGHT: [f64; 3] = [-1.5, 2.5, -0.2];

/// The shadow's opacity (black at 140/255).
pub const SHADOW_ALPHA: u8 = 140;

/// The translucent torus's opacity.
pub const TRANSLUCENT_ALPHA: u8 = 150;

/// Renders shadow benchmark scene `bench` (one of [`Bench::ShadowNone`], [`Bench::Shadow`],
/// [`Bench::Translucent`]) at 240 × 240, the models turned by `spin_deg`.
pub(crate) fn render_shadow_bench<S, C, D, P>(
    bench: Bench,
    spin_deg: f64,
    dither: bool,
    target: &mut D,
    probe: &mut P,
) -> Result<BenchFrame, BenchError<D::Error>>
where
    S: Scalar,
    C: crate::TargetColor,
    D: embedded_graphics_core::draw_target::DrawTarget<Color = C>,
    P: crate::Probe,
{
    const V: usize = SHADOW_CAPACITY.0;
    const T: usize = SHADOW_CAPACITY.1;
    let ground = Shape::<S, 4, 2>::plane(5.0, 5.0, 1, 1).map_err(|_| BenchError::Scene)?;
    let torus = Shape::<S, 288, 576>::torus(0.7, 0.25, 24, 12).map_err(|_| BenchError::Scene)?;
    let cube = Shape::<S, 24, 12>::cube(0.35).map_err(|_| BenchError::Scene)?;
    let spin = Mat4::rotate_y(deg(spin_deg));
    let m = |c: [u8; 3]| Material::matte(c, S::from_f64(0.25), S::from_f64(0.75));
    let alpha = if bench == Bench::Translucent {
        TRANSLUCENT_ALPHA
    } else {
        255
    };
    let objects = [
        Object {
            mesh: ground.mesh(),
            transform: Mat4::identity(),
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
            material: m([90, 160, 255]).translucent(alpha),
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
    let scene = Scene::new(&objects, camera, [Light::white(l)]).with_background([24, 28, 40]);
    let layering = if bench == Bench::Shadow {
        Layering::projected(
            &[0],
            &[1, 2],
            PlanarShadow::new(
                [S::ZERO, S::ONE, S::ZERO, S::ZERO],
                ShadowLight::Directional(l),
                SHADOW_ALPHA,
            ),
        )
    } else {
        Layering::none()
    };
    // Rendering triangle ids makes every triangle flat (one more vertex record per drawn
    // triangle): those renders get a larger vertex store.
    if C::triangle_id(0).is_some() {
        draw::<S, C, D, P, { V + T }>(bench, &scene, &layering, dither, target, probe)
    } else {
        draw::<S, C, D, P, V>(bench, &scene, &layering, dither, target, probe)
    }
}

/// Draws `scene` plainly ([`Bench::ShadowNone`]) or in layers, with a vertex store of `V`.
fn draw<S, C, D, P, const V: usize>(
    bench: Bench,
    scene: &Scene<'_, S, 1>,
    layering: &Layering<'_, S>,
    dither: bool,
    target: &mut D,
    probe: &mut P,
) -> Result<BenchFrame, BenchError<D::Error>>
where
    S: Scalar,
    C: crate::TargetColor,
    D: embedded_graphics_core::draw_target::DrawTarget<Color = C>,
    P: crate::Probe,
{
    const T: usize = SHADOW_CAPACITY.1;
    const A: usize = SHADOW_CAPACITY.2;
    const RA: usize = SHADOW_CAPACITY.3;
    const PA: usize = SHADOW_CAPACITY.4;
    let mut r = Renderer::<S, C, 240, 240, V, T, A>::new();
    r.set_dither(dither);
    if bench == Bench::ShadowNone {
        let stats = r
            .render_probed(scene, target, probe)
            .map_err(BenchError::Render)?;
        return Ok(BenchFrame {
            stats,
            renderer_ram_bytes: core::mem::size_of_val(&r),
        });
    }
    let mut layers = Layers::<240, 1, RA, PA>::new();
    let stats = r
        .render_layered_probed(scene, layering, &mut layers, target, probe)
        .map_err(BenchError::Render)?;
    Ok(BenchFrame {
        stats,
        renderer_ram_bytes: core::mem::size_of_val(&r) + core::mem::size_of_val(&layers),
    })
}
