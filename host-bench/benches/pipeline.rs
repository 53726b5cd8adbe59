//! Host benchmarks per pipeline stage and number type, on the default torus scene:
//! vertex transform, geometry (transform, lighting, clipping, projection, culling, bucketing),
//! rasterization (triangle setup, spans, output to a null target) and the whole frame.
//!
//! `cargo bench --manifest-path host-bench/Cargo.toml` (from the repository root)

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use embedded_graphics::pixelcolor::Rgb565;
use scanline3d::fixed::types::I16F16;
use scanline3d::{Fx, Scalar, Scene};
use scanline3d_support::demo::{self, TorusRenderer};
use scanline3d_support::hash::NullTarget;

fn stages<S: Scalar>(c: &mut Criterion) {
    let shape = demo::torus::<S>().expect("torus");
    let objects = [demo::torus_object(&shape)];
    let camera = demo::camera::<S>().expect("camera");
    let scene = Scene::new(&objects, camera, demo::lights());
    let mvp = camera
        .projection
        .matrix(S::ONE)
        .mul(&camera.view)
        .mul(&objects[0].transform);
    let mut r: Box<TorusRenderer<S, Rgb565>> = Box::default();
    let mut target = NullTarget::<Rgb565>::new(240, 240);
    let name = S::NAME;
    c.bench_function(&format!("{name}/vertex transform"), |b| {
        b.iter(|| {
            for &p in shape.positions.iter() {
                black_box(mvp.transform_point(black_box(p)));
            }
        })
    });
    c.bench_function(&format!("{name}/geometry"), |b| {
        b.iter(|| {
            black_box(
                r.prepare(&scene, scanline3d::FrameOptions::new())
                    .expect("prepare")
                    .stats(),
            )
        })
    });
    c.bench_function(&format!("{name}/rasterization"), |b| {
        b.iter_batched(
            || {
                let mut r2: Box<TorusRenderer<S, Rgb565>> = Box::default();
                let _ = r2
                    .prepare(&scene, scanline3d::FrameOptions::new())
                    .expect("prepare");
                r2
            },
            |mut r2| {
                let mut frame = r2.prepared().expect("a prepared frame");
                while frame.strip_to(&mut target).expect("strip").is_some() {}
            },
            criterion::BatchSize::LargeInput,
        )
    });
    c.bench_function(&format!("{name}/frame"), |b| {
        b.iter(|| black_box(r.render(&scene, &mut target).expect("render")))
    });
}

fn all(c: &mut Criterion) {
    stages::<Fx<I16F16>>(c);
    stages::<f32>(c);
    stages::<f64>(c);
}

criterion_group!(benches, all);
criterion_main!(benches);
