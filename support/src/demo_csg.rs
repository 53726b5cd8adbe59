//! The `csg` benchmark scene ([`crate::demo::Bench::Csg`]): the example CSG part
//! (`tests/data/part.csg`, a block with a spherical pocket and a drilled hole, meshed on the
//! host by mesh booleans) baked into flash by `bake` as `support/src/demo_csg_mesh.rs`, lit by one
//! white light and shaded per vertex (Gouraud).
//!
//! The baked data is Q16.16 in flash (positions normalized to ±1, scaled back by the object's
//! transform; unit normals). Every number type, Q16.16 included, converts the stored values
//! into arrays on the stack (169 positions and normals: 4 KB in Q16.16, 8 KB in f64), so every
//! type draws the same geometry and the twins' error is arithmetic, not a different mesh. (The
//! Q16.16 copy is not needed; rendering from flash directly would take a Q16.16-only path.)

use crate::demo_assets::{deg, look, persp, render_with, BenchError, BenchFrame};
use crate::demo_csg_mesh as baked;
use scanline3d::Mat4;
use scanline3d::Object;
use scanline3d::Scalar;
use scanline3d::{Light, Material};

/// Vertices of the baked part (corners split where the crease-angle normals differ).
const VERTICES: usize = 169;
/// Triangle capacity of the frame: what it draws (`Renderer::needs`, measured by
/// `tests/bench_scenes.rs`), every triangle facing the camera.
pub const CSG_TRIS: usize = 152;
/// Active-list capacity of the frame (measured the same way).
pub const CSG_ACTIVE: usize = 57;

/// The part's transform at `spin_deg`: the stored positions scaled back to model units, turned
/// as `render --csg tests/data/part.csg --fit` shows it (30° about x, 20° about y, so the
/// pocket opens towards the camera and the hole shows on the right), then spun about y.
fn transform<S: Scalar>(spin_deg: f64) -> Mat4<S> {
    Mat4::scale([S::from_f64(baked::SCALE); 3])
        .then(&Mat4::rotate_x(deg(30.0)))
        .then(&Mat4::rotate_y(deg(20.0)))
        .then(&Mat4::rotate_y(deg(spin_deg)))
}

/// Renders the `csg` frame (240 × 240) at `spin_deg`, with `dither`, reporting stages to `probe`.
pub(crate) fn render_csg<S, C, D, P>(
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
    let convert = |v: &[scanline3d::Fx<scanline3d::fixed::types::I16F16>; 3]| {
        v.map(|c| S::from_f64(c.to_f64()))
    };
    let mut positions = [[S::ZERO; 3]; VERTICES];
    let mut normals = [[S::ZERO; 3]; VERTICES];
    for (i, (p, n)) in baked::POSITIONS
        .iter()
        .zip(baked::NORMALS.iter())
        .enumerate()
    {
        positions[i] = convert(p);
        normals[i] = convert(n);
    }
    let mesh = scanline3d::Mesh::new(&positions, &baked::INDICES)
        .and_then(|m| m.with_normals(&normals))
        .map_err(|_| BenchError::Scene)?;
    let objects = [Object {
        mesh,
        transform: transform(spin_deg),
        material: Material::matte([230, 150, 70], S::from_f64(0.15), S::from_f64(0.85)),
    }];
    // `render --fit`'s eye: along (0, 1.2, 3) at the distance where the bounding sphere (radius
    // SCALE) fills the 45° view, 3.45 units.
    let camera =
        look([0.0, 1.28, 3.2], [0.0; 3], persp(45.0, 0.1, 10.0)).map_err(|_| BenchError::Scene)?;
    let lights = [Light::white([
        S::from_f64(-1.0),
        S::from_f64(1.5),
        S::from_f64(2.0),
    ])];
    let scene = scanline3d::Scene::new(&objects, camera, lights);
    if C::triangle_id(0).is_some() {
        // One more vertex record per drawn triangle, as in `render_bench`.
        render_with::<S, C, D, P, 240, 240, { VERTICES + CSG_TRIS }, CSG_TRIS, CSG_ACTIVE, 1, 1, 0, 0>(
            &scene, dither, target, probe,
        )
    } else {
        render_with::<S, C, D, P, 240, 240, VERTICES, CSG_TRIS, CSG_ACTIVE, 1, 1, 0, 0>(
            &scene, dither, target, probe,
        )
    }
}

#[cfg(test)]
mod tests {
    /// The baked arrays are what [`super::VERTICES`] says.
    #[test]
    fn the_baked_part_has_the_declared_size() {
        assert_eq!(crate::demo_csg_mesh::POSITIONS.len(), super::VERTICES);
        assert_eq!(crate::demo_csg_mesh::NORMALS.len(), super::VERTICES);
    }
}
