//! `render --budget`: what a scene needs over every frame (capacities, fixed-point headroom,
//! RAM, the renderer type for firmware), and the capacities no renderer holds.

use super::*;

/// The capacities `needs` exceeds the library's limits in: (capacity, needed, limit, whether
/// `needed` is an upper bound). A frame drawn in passes (`multi_pass`) has an upper bound of
/// its active count (the passes' largest counts added up), named only when its vertices and
/// triangles are within the limits.
pub(crate) fn short_capacities(
    needs: &Needs,
    multi_pass: bool,
) -> Vec<(Capacity, usize, usize, bool)> {
    let mut out: Vec<_> = [Capacity::Vertices, Capacity::Triangles]
        .into_iter()
        .filter(|&c| needs.get(c) > LIMIT.get(c))
        .map(|c| (c, needs.get(c), LIMIT.get(c), false))
        .collect();
    let active = Capacity::ActiveTriangles;
    if (out.is_empty() || !multi_pass) && needs.active > LIMIT.active {
        out.push((active, needs.active, LIMIT.active, multi_pass));
    }
    out
}

/// A capacity no renderer has, with what to do about it.
pub(crate) fn capacity_message(
    m: &Model,
    what: Capacity,
    needed: usize,
    limit: usize,
    bound: bool,
) -> String {
    let name = &m.name;
    let n = suggest_triangles(m.indices.len(), needed, limit);
    format!(
        "{name}: one frame needs {}{needed} {}, more than any renderer holds ({limit}, the \
         library's limit): the preview draws it in passes, a device cannot; simplify the model, \
         e.g. preview and budget it with `--max-triangles {n}`, or bake a smaller mesh with \
         `cargo run --release -p scanline3d-tools --features simplify --bin bake -- {name} --max-triangles {n} --obj-out smaller.obj`",
        if bound { "up to " } else { "" },
        capacity_name(what),
    )
}

pub(crate) fn capacity_name(c: Capacity) -> &'static str {
    match c {
        Capacity::Vertices => "vertices",
        Capacity::Triangles => "triangles",
        Capacity::ActiveTriangles => "triangles active on one row",
        _ => "of a capacity",
    }
}

/// `--budget`: what the scene needs over every frame.
pub(crate) fn budget<C: TargetColor>(
    args: &Args,
    m: &Model,
    s: &Setup,
    run: &Run<C>,
    number: &str,
) -> Result<(), (String, i32)> {
    let (w, h) = args.size;
    let max = |f: fn(&Stats) -> u32| run.stats.iter().map(f).max().unwrap_or(0) as usize;
    // What one renderer needs for every frame (for a frame drawn in passes, its whole mesh's).
    let needs = run.needs.iter().fold(Needs::default(), |a, n| a.max(*n));
    let (verts, tris, active) = (needs.vertices, needs.triangles, needs.active);
    let passes = run.passes.iter().copied().max().unwrap_or(1);
    let invalid = max(|s| s.invalid);
    // Fixed-point headroom: the largest magnitudes each stage reaches, in f64, against Q16.16.
    let cam = Camera::look_at(s.eye, s.target, s.up, s.projection)
        .map_err(|e| (format!("camera: {e}"), 2))?;
    let pv = cam.projection.matrix(w as f64 / h as f64).mul(&cam.view);
    let (mut model_max, mut world_max, mut clip_max) = (0.0f64, 0.0f64, 0.0f64);
    for k in 0..args.frames {
        let t = transform::<f64>(args, s, k);
        let mvp = pv.mul(&t);
        for p in &m.positions {
            model_max = model_max.max(p.iter().fold(0.0, |a, v| a.max(v.abs())));
            world_max = world_max.max(
                t.transform_point(*p)
                    .iter()
                    .take(3)
                    .fold(0.0, |a, v| a.max(v.abs())),
            );
            clip_max = clip_max.max(
                mvp.transform_point(*p)
                    .iter()
                    .fold(0.0, |a, v| a.max(v.abs())),
            );
        }
    }
    let matrix_max = pv.m.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
    let range = 32768.0;
    let lines = args.strip;
    let color = if core::mem::size_of::<C>() == 2 {
        "Rgb565"
    } else {
        "Rgb888"
    };
    println!(
        "budget for {} over {} frame(s) at {w}x{h} ({number}):",
        m.name,
        run.stats.len()
    );
    if let Some(s) = &m.simplified {
        println!("  {s}");
    }
    println!("  vertices stored (mesh + clipping): {verts}");
    println!(
        "  triangles after culling and clipping: {tris} (of {} in the mesh)",
        m.indices.len()
    );
    if passes > 1 {
        println!(
            "  triangles active on one row (max): at most {active} (the preview drew a frame in \
             {passes} passes; this adds up their largest counts)"
        );
    } else {
        println!("  triangles active on one row (max): {active}");
    }
    println!("  invalid triangles skipped: {invalid}");
    println!("  fixed-point headroom (Q16.16 range ±32768; margin = range / largest magnitude):");
    for (stage, v) in [
        ("model positions", model_max),
        ("world positions", world_max),
        ("view-projection matrix", matrix_max),
        ("clip coordinates", clip_max),
    ] {
        println!(
            "    {stage:24} largest {v:>12.4}  margin {:>10.1}x",
            range / v.max(1e-30)
        );
    }
    tone::budget(args, args.ambient, args.diffuse, args.specular).map_err(|e| (e, 1))?;
    let short = short_capacities(&needs, passes > 1);
    if !short.is_empty() {
        // No renderer holds a frame: no RAM figure or renderer type, but what to do.
        return Err((
            short
                .iter()
                .map(|&(what, needed, limit, bound)| {
                    capacity_message(m, what, needed, limit, bound)
                })
                .collect::<Vec<_>>()
                .join("\n"),
            1,
        ));
    }
    let ram = ram_formula(w, h, core::mem::size_of::<C>(), lines, verts, tris, active);
    println!(
        "  renderer RAM: {ram} bytes = {lines}·{w}·({} + 2) + {}·{verts} + {}·{tris} + {}·{active} + 4·{h} (+ ≤ 128 state)",
        core::mem::size_of::<C>(),
        scanline3d::internals::VERTEX_BYTES,
        scanline3d::internals::TRIANGLE_BYTES,
        scanline3d::internals::ACTIVE_BYTES
    );
    if s.texture.is_some()
        || matches!(
            args.shading,
            ShadingArg::Phong | ShadingArg::FastPhong | ShadingArg::Toon
        )
    {
        // The attribute stores: every vertex, and every active triangle plus the Phong lights'
        // and material's entries.
        let reserved = if matches!(
            args.shading,
            ShadingArg::Phong | ShadingArg::FastPhong | ShadingArg::Toon
        ) {
            2
        } else {
            0
        };
        let (xv, xa) = (verts, active + reserved);
        println!(
            "  attribute stores (texture, Phong): XV = {xv}, XA = {xa}: + {} bytes on a 32-bit core \
             ({xv}·{} + {xa}·{})",
            xv * scanline3d::limits::VERTEX_EXTRA_BYTES_32 + xa * scanline3d::limits::ACTIVE_EXTRA_BYTES_32,
            scanline3d::limits::VERTEX_EXTRA_BYTES_32,
            scanline3d::limits::ACTIVE_EXTRA_BYTES_32
        );
        println!("  renderer type: Renderer<Fx<I16F16>, {color}, {w}, {h}, {verts}, {tris}, {active}, {lines}, {xv}, {xa}>");
    } else {
        println!("  renderer type: Renderer<Fx<I16F16>, {color}, {w}, {h}, {verts}, {tris}, {active}, {lines}>");
    }
    // Work the scene does not need.
    if let Some(d) = &run.depth {
        d.report(run.stats.len(), lines, w);
    }
    if is_closed_convex(m) {
        println!(
            "  (the mesh is one closed convex object: after back-face culling nothing overlaps)"
        );
    }
    if args.shading == ShadingArg::Flat {
        println!("  hint: flat shading lights faces, not vertices: the mesh needs no vertex normals (saves {} bytes of flash)", 12 * m.positions.len());
    }
    let overflow = [model_max, world_max, matrix_max, clip_max]
        .iter()
        .any(|&v| v >= range);
    if overflow || invalid > 0 {
        return Err((format!("{}: the scene overflows Q16.16 (see the margins above); scale it down or use Fx<I20F12>", m.name), 1));
    }
    Ok(())
}

/// Every edge shared by exactly two triangles (vertices welded by position, since OBJ corners
/// with different texture coordinates or normals are separate vertices), and every vertex on or
/// behind every face's plane.
fn is_closed_convex(m: &Model) -> bool {
    use std::collections::HashMap;
    let mut weld: HashMap<[u64; 3], u32> = HashMap::new();
    let id: Vec<u32> = m
        .positions
        .iter()
        .map(|p| {
            let n = weld.len() as u32;
            *weld.entry(p.map(f64::to_bits)).or_insert(n)
        })
        .collect();
    let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
    for t in &m.indices {
        for k in 0..3 {
            let (a, b) = (id[t[k] as usize], id[t[(k + 1) % 3] as usize]);
            *edges.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    if edges.values().any(|&n| n != 2) {
        return false;
    }
    let (_, _, _, r) = bounds(&m.positions);
    m.indices.iter().all(|t| {
        let [a, b, c] = t.map(|i| m.positions[i as usize]);
        let n = scanline3d::math::cross(scanline3d::math::sub(b, a), scanline3d::math::sub(c, a));
        let len = scanline3d::math::length(n);
        len == 0.0
            || m.positions.iter().all(|p| {
                scanline3d::math::dot(n, scanline3d::math::sub(*p, a)) / len <= 1e-9 * r.max(1.0)
            })
    })
}
