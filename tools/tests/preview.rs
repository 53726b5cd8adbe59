//! The preview tools end to end: the `render` binary on the default scene, on an OBJ and on
//! bad inputs (exit status, message, no half-written output), and bake → include → render.

use scanline3d_tools as common;
mod shared;

#[allow(dead_code)]
mod baked {
    include!("../../tests/data/torus_mesh.rs");
}

use std::path::PathBuf;

use common::obj::{bake, load_obj, to_obj, vertex_normals};
use common::Frame;
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d_support::demo;
use scanline3d_support::metrics::Metrics;

type Q = Fx<I16F16>;

fn tmp(name: &str) -> PathBuf {
    shared::tmp("preview", name)
}

fn run(args: &[&str]) -> (i32, String, String) {
    shared::run("render", args)
}

#[test]
fn default_scene_renders_and_summarizes() {
    let out = tmp("default.png");
    let (code, stdout, stderr) = run(&["--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{stderr}");
    for part in [
        "240x240 I16F16 torus",
        "triangles in 1024",
        "pixels written",
        "ms/frame",
        "vs f64: max LSB",
        "PSNR",
    ] {
        assert!(stdout.contains(part), "summary lacks {part:?}: {stdout}");
    }
    let (w, h, _) = common::read_png(&out).expect("a PNG");
    assert_eq!((w, h), (240, 240));
}

#[test]
fn an_obj_file_renders_with_fit_and_animation() {
    let torus = demo::torus::<f64>().unwrap();
    let obj = tmp("torus.obj");
    std::fs::write(
        &obj,
        to_obj(&torus.positions, Some(&torus.normals), &torus.indices),
    )
    .unwrap();
    let png = tmp("obj.png");
    let (code, stdout, stderr) = run(&[
        "--obj",
        obj.to_str().unwrap(),
        "--fit",
        "--size",
        "160x120",
        "--out",
        png.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("160x120"), "{stdout}");
    assert_eq!(common::read_png(&png).map(|p| (p.0, p.1)), Some((160, 120)));
    let gif = tmp("anim.gif");
    let (code, _, stderr) = run(&[
        "--frames",
        "3",
        "--spin",
        "30",
        "--out",
        gif.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(std::fs::read(&gif).unwrap().starts_with(b"GIF89a"));
    let (code, stdout, _) = run(&["--budget", "--frames", "4", "--spin", "90"]);
    assert_eq!(code, 0);
    assert!(
        stdout.contains("renderer type: Renderer<Fx<I16F16>, Rgb565, 240, 240,"),
        "{stdout}"
    );
    assert!(stdout.contains("margin"), "{stdout}");
}

fn bad(name: &str, obj_text: Option<&str>, expect: &[&str]) {
    let obj = tmp(&format!("{name}.obj"));
    match obj_text {
        Some(t) => std::fs::write(&obj, t).unwrap(),
        None => {
            let _ = std::fs::remove_file(&obj);
        }
    }
    let out = tmp(&format!("{name}.png"));
    let _ = std::fs::remove_file(&out);
    let (code, _, stderr) = run(&[
        "--obj",
        obj.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_ne!(code, 0, "{name}: exit status 0");
    assert!(!stderr.contains("panicked"), "{name}: {stderr}");
    for e in expect {
        assert!(stderr.contains(e), "{name}: message {stderr:?} lacks {e:?}");
    }
    assert!(
        stderr.contains(&format!("{name}.obj")),
        "{name}: message does not name the file: {stderr}"
    );
    assert!(
        !out.exists() && !out.with_extension("partial").exists(),
        "{name}: an output file was written"
    );
}

#[test]
fn bad_inputs_give_clear_messages_and_no_output() {
    bad("missing", None, &["cannot read"]);
    bad(
        "malformed",
        Some("v 0 0 0\nv 1 0 0\nv 0 1 zero\nf 1 2 3\n"),
        &[":3:", "three numbers"],
    );
    bad(
        "out_of_range",
        Some("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"),
        &[":4:", "vertex 4"],
    );
    bad(
        "no_triangles",
        Some("v 0 0 0\nv 1 0 0\n"),
        &["no triangles"],
    );
    // More vertices than u16 indices can address.
    let mut many = String::new();
    for k in 0..65_540 {
        many.push_str(&format!("v {} {} 0\n", k % 256, k / 256));
    }
    for k in 0..65_537 {
        let a = k + 1;
        many.push_str(&format!(
            "f {a} {} {}\n",
            (k + 1) % 65_540 + 1,
            (k + 2) % 65_540 + 1
        ));
    }
    bad("too_many_vertices", Some(&many), &["65536"]);
}

#[test]
fn baked_file_is_what_bake_produces_now() {
    let path = shared::data("torus.obj");
    let mesh = load_obj(&path).unwrap();
    let b = bake(&mesh, true, "torus.obj");
    assert_eq!(
        b.source,
        include_str!("../../tests/data/torus_mesh.rs"),
        "tests/data/torus_mesh.rs is stale: rerun the bake tool"
    );
}

fn frame_of(mesh: Mesh<'_, Q>, transform: Mat4<Q>) -> Frame<Rgb565> {
    let objects = [Object {
        mesh,
        transform,
        material: demo::torus_material(),
    }];
    let scene = Scene::new(&objects, demo::camera().unwrap(), demo::lights());
    let mut r: Box<demo::TorusRenderer<Q, Rgb565>> = Box::default();
    let mut f = Frame::new(240, 240, Rgb565::BLACK);
    r.render(&scene, &mut f).unwrap();
    f
}

#[test]
fn baked_mesh_renders_like_the_direct_mesh_within_its_quantization() {
    // Direct: the OBJ loaded and converted to Q16.16 at run time.
    let path = shared::data("torus.obj");
    let mesh = load_obj(&path).unwrap();
    let pos: Vec<[Q; 3]> = mesh.positions.iter().map(|p| p.map(Q::from_f64)).collect();
    let nor: Vec<[Q; 3]> = vertex_normals(&mesh, true)
        .iter()
        .map(|n| n.map(Q::from_f64))
        .collect();
    let direct = frame_of(
        Mesh::new(&pos, &mesh.indices)
            .unwrap()
            .with_normals(&nor)
            .unwrap(),
        demo::torus_transform(0.0),
    );
    // Baked: the included static arrays, with their scale and offset in the model transform.
    let s = Q::from_f64(baked::SCALE);
    let place = Mat4::scale([s, s, s]).then(&Mat4::translate(baked::OFFSET.map(Q::from_f64)));
    let baked_mesh = Mesh::new(&baked::POSITIONS, &baked::INDICES)
        .unwrap()
        .with_normals(&baked::NORMALS)
        .unwrap();
    let from_flash = frame_of(baked_mesh, place.then(&demo::torus_transform(0.0)));
    let mut m = Metrics::new([31, 63, 31]);
    for y in 0..240 {
        m.add_line(
            &from_flash.px[y * 240..(y + 1) * 240],
            &direct.px[y * 240..(y + 1) * 240],
            Rgb565::BLACK,
        );
    }
    // The baked positions are within 1.6e-5 model units of the file's (about 1.5e-3 px here):
    // only pixel centres that close to an edge may change coverage, and shading by 1 LSB.
    println!(
        "baked vs direct: coverage mismatches {}, max LSB {:?}, differing {}",
        m.coverage_mismatch, m.max_lsb, m.differing
    );
    assert!(m.coverage_mismatch <= 10, "{m:?}");
    assert!(m.max_lsb.iter().all(|&v| v <= 1), "{m:?}");
    assert!(direct.px.iter().filter(|&&c| c != Rgb565::BLACK).count() > 30_000);
}
