//! Edges and wireframes (`Outline` with `Edges`): crease tables, 1 px lines with one pixel per
//! column or row and no gap where they join, hidden lines removed by the depth test (or shown
//! with `see_through`), silhouettes ⊂ creases ⊂ all edges, and bad tables named.

use crate::common;

use common::Frame;
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use scanline3d::prelude::*;
use scanline3d::{
    errors::AdjacencyError, errors::LayerError, mesh::mesh_adjacency, mesh::mesh_creases,
    mesh::Adjacency, shadow::Edges, shadow::Layering, shadow::Outline, Error, Layers, Shape,
};

type Q = Fx<scanline3d::fixed::types::I16F16>;

const N: u32 = 96;
const INK: [u8; 3] = [250, 240, 40];
const BACKGROUND: [u8; 3] = [10, 20, 30];

fn ink() -> Rgb888 {
    Rgb888::new(INK[0], INK[1], INK[2])
}

/// An orthographic camera on the +z axis looking at the origin: pixel centre `(i + 0.5,
/// j + 0.5)` is at `x = (i + 0.5 − 48)/8`, `y = (48 − j − 0.5)/8`.
fn ortho<S: Scalar>(eye: [f64; 3]) -> Camera<S> {
    common::ortho8(eye, [0.0, 1.0, 0.0], N, 30.0)
}

/// `mesh` (unlit in the background colour, turned by `transform`) seen from `eye`, with the
/// outline `edges` (crease table `creases`) in ink.
fn draw<S: Scalar>(
    mesh: Mesh<'_, S>,
    transform: Mat4<S>,
    eye: [f64; 3],
    edges: Edges<'_>,
    see_through: bool,
) -> Frame<Rgb888> {
    let objects = [Object {
        mesh,
        transform,
        material: Material::unlit(BACKGROUND),
    }];
    let scene = Scene::new(
        &objects,
        ortho(eye),
        [Light::white([S::ZERO, S::ZERO, S::ONE])],
    )
    .with_background(BACKGROUND);
    let mut adjacency = vec![[0u16; 3]; mesh.indices().len()];
    mesh_adjacency(&mesh, &mut adjacency).unwrap();
    let adj = [Adjacency::new(&mesh, &adjacency).unwrap()];
    let layering = Layering::<S>::none().with_outline(
        Outline::silhouette(&[0], &adj, INK)
            .with_edges(edges)
            .see_through(see_through),
    );
    let mut r = Renderer::<S, Rgb888, { N as usize }, { N as usize }, 256, 256, 64>::new();
    let mut layers = Layers::<{ N as usize }, 1, 4, 64>::new();
    let mut f = Frame::new(N, N, Rgb888::BLACK);
    r.render_with(
        &scene,
        scanline3d::FrameOptions::new().layered(&layering, &mut layers),
        &mut f,
    )
    .unwrap();
    f.assert_each_written_once();
    f
}

fn ink_pixels(f: &Frame<Rgb888>) -> Vec<(u32, u32)> {
    (0..N)
        .flat_map(|y| (0..N).map(move |x| (x, y)))
        .filter(|&(x, y)| f.get(x, y) == ink())
        .collect()
}

/// The 8-connected groups of ink pixels.
fn components(f: &Frame<Rgb888>) -> usize {
    let mut seen = vec![false; (N * N) as usize];
    let mut groups = 0;
    for (x, y) in ink_pixels(f) {
        if seen[(y * N + x) as usize] {
            continue;
        }
        groups += 1;
        let mut stack = vec![(x as i32, y as i32)];
        while let Some((x, y)) = stack.pop() {
            if x < 0 || y < 0 || x >= N as i32 || y >= N as i32 {
                continue;
            }
            let k = (y as u32 * N + x as u32) as usize;
            if seen[k] || f.get(x as u32, y as u32) != ink() {
                continue;
            }
            seen[k] = true;
            for (dx, dy) in [
                (-1, -1),
                (0, -1),
                (1, -1),
                (-1, 0),
                (1, 0),
                (-1, 1),
                (0, 1),
                (1, 1),
            ] {
                stack.push((x + dx, y + dy));
            }
        }
    }
    groups
}

/// A triangle facing the camera, its corners off the pixel grid, edges of three slopes.
const TRI: [[f64; 3]; 3] = [[-4.3, -3.1, 0.0], [4.7, -1.2, 0.0], [0.6, 4.4, 0.0]];

fn one_pixel_lines<S: Scalar>() {
    let p: Vec<[S; 3]> = TRI.iter().map(|v| v.map(S::from_f64)).collect();
    let tris = [[0u16, 1, 2]];
    let f = draw(
        Mesh::new(&p, &tris).unwrap(),
        Mat4::identity(),
        [0.0, 0.0, 10.0],
        Edges::All,
        false,
    );
    // Only the background and the lines: the unlit surface shows nothing of itself.
    let bg = Rgb888::new(BACKGROUND[0], BACKGROUND[1], BACKGROUND[2]);
    for y in 0..N {
        for x in 0..N {
            assert!(f.get(x, y) == bg || f.get(x, y) == ink(), "({x}, {y})");
        }
    }
    let screen = |v: [f64; 3]| (48.0 + 8.0 * v[0], 48.0 - 8.0 * v[1]);
    for e in 0..3 {
        let (a, b) = (screen(TRI[e]), screen(TRI[(e + 1) % 3]));
        let x_major = (b.0 - a.0).abs() >= (b.1 - a.1).abs();
        // Along the major axis, away from the corners (where the other edges are).
        let (s0, s1) = if x_major { (a.0, b.0) } else { (a.1, b.1) };
        let (lo, hi) = (s0.min(s1) + 3.0, s0.max(s1) - 3.0);
        for i in lo.ceil() as u32..hi.floor() as u32 {
            let c = i as f64 + 0.5;
            let t = (c - s0) / (s1 - s0);
            // The line's position across the minor axis at this pixel centre.
            let across = if x_major {
                a.1 + t * (b.1 - a.1)
            } else {
                a.0 + t * (b.0 - a.0)
            };
            let hits: Vec<f64> = (0..N)
                .filter(|&j| {
                    let (x, y) = if x_major { (i, j) } else { (j, i) };
                    f.get(x, y) == ink() && (j as f64 + 0.5 - across).abs() < 1.5
                })
                .map(|j| j as f64 + 0.5 - across)
                .collect();
            assert_eq!(hits.len(), 1, "{} edge {e}, step {i}: {hits:?}", S::NAME);
            // The pixel whose centre is nearest the line (within the 1/16 px snap).
            assert!(
                hits[0].abs() <= 0.5 + 1.0 / 16.0,
                "edge {e}, step {i}: {hits:?}"
            );
        }
    }
    // The three lines join with no gap: one 8-connected loop.
    assert_eq!(components(&f), 1, "{}", S::NAME);
}

#[test]
fn lines_are_one_pixel_wide_and_join_without_gaps() {
    one_pixel_lines::<Q>();
    one_pixel_lines::<f32>();
    one_pixel_lines::<f64>();
}

/// A cube (half-size 2) turned so that three faces show, with its silhouette, its creases,
/// all its edges and all its edges seen through.
fn cube_frames<S: Scalar>() -> [Frame<Rgb888>; 4] {
    let cube = Shape::<S, 24, 12>::cube(2.0).unwrap();
    let mut adjacency = [[0u16; 3]; 12];
    mesh_adjacency(&cube.mesh(), &mut adjacency).unwrap();
    let mut creases = [0u8; 5];
    assert_eq!(
        mesh_creases(&cube.mesh(), &adjacency, 40.0, &mut creases),
        Ok(12)
    );
    let tables: [&[u8]; 1] = [&creases];
    let turn = Mat4::rotate_y(S::from_f64(0.6)).then(&Mat4::rotate_x(S::from_f64(0.45)));
    let eye = [0.0, 0.0, 10.0];
    [
        draw(cube.mesh(), turn, eye, Edges::Silhouette, false),
        draw(cube.mesh(), turn, eye, Edges::Crease(&tables), false),
        draw(cube.mesh(), turn, eye, Edges::All, false),
        draw(cube.mesh(), turn, eye, Edges::All, true),
    ]
}

fn subsets<S: Scalar>() {
    let [silhouette, crease, all, through] = cube_frames::<S>();
    let sets = [&silhouette, &crease, &all, &through].map(ink_pixels);
    // Each set of edges contains the last, hidden edges add to the visible ones.
    for k in 1..4 {
        for p in &sets[k - 1] {
            assert!(sets[k].contains(p), "{} {k}: {p:?}", S::NAME);
        }
        assert!(sets[k].len() > sets[k - 1].len(), "{} {k}", S::NAME);
    }
    // The creases are the cube's 9 visible edges (6 on the contour, 3 inside it): the
    // contour and the inner edges each form one connected figure.
    assert_eq!(components(&silhouette), 1);
    assert_eq!(components(&crease), 1);
}

#[test]
fn silhouettes_creases_all_and_hidden_edges_nest() {
    subsets::<Q>();
    subsets::<f32>();
    subsets::<f64>();
}

#[test]
fn crease_tables_follow_the_angle() {
    let cube = Shape::<f64, 24, 12>::cube(1.0).unwrap();
    let mut adjacency = [[0u16; 3]; 12];
    mesh_adjacency(&cube.mesh(), &mut adjacency).unwrap();
    let mut bits = [0u8; 5];
    // The cube's faces meet at 90°; its faces' diagonals are flat (not creases even at 0°).
    assert_eq!(
        mesh_creases(&cube.mesh(), &adjacency, 0.0, &mut bits),
        Ok(12)
    );
    assert_eq!(
        mesh_creases(&cube.mesh(), &adjacency, 89.0, &mut bits),
        Ok(12)
    );
    assert_eq!(
        mesh_creases(&cube.mesh(), &adjacency, 91.0, &mut bits),
        Ok(0)
    );
    assert_eq!(bits, [0; 5]);
    // An open square: its four border edges are creases at any angle.
    let sq = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    let tris = [[0u16, 1, 2], [0, 2, 3]];
    let mesh = Mesh::new(&sq, &tris).unwrap();
    let mut adj = [[0u16; 3]; 2];
    mesh_adjacency(&mesh, &mut adj).unwrap();
    let mut b = [0u8; 1];
    assert_eq!(mesh_creases(&mesh, &adj, 180.0, &mut b), Ok(4));
    assert_eq!(
        mesh_creases(&mesh, &adj, 181.0, &mut b),
        Err(AdjacencyError::Angle)
    );
    assert_eq!(
        mesh_creases(&mesh, &adj, f64::NAN, &mut b),
        Err(AdjacencyError::Angle)
    );
    assert_eq!(
        mesh_creases(&mesh, &adj[..1], 30.0, &mut b),
        Err(AdjacencyError::BufferTooSmall { needed: 2 })
    );
    assert_eq!(
        mesh_creases(&cube.mesh(), &adjacency, 30.0, &mut bits[..4]),
        Err(AdjacencyError::CreaseTableTooSmall { bytes: 5 })
    );
}

#[test]
fn missing_or_short_crease_tables_are_named() {
    let cube = Shape::<f32, 24, 12>::cube(1.0).unwrap();
    let objects = [Object {
        mesh: cube.mesh(),
        transform: Mat4::identity(),
        material: Material::unlit(BACKGROUND),
    }];
    let scene = Scene::new(
        &objects,
        ortho([0.0, 0.0, 10.0]),
        [Light::white([0.0, 0.0, 1.0])],
    );
    let mut adjacency = [[0u16; 3]; 12];
    mesh_adjacency(&cube.mesh(), &mut adjacency).unwrap();
    let adj = [Adjacency::new(&cube.mesh(), &adjacency).unwrap()];
    let short = [0u8; 4];
    let short: [&[u8]; 1] = [&short];
    let run = |edges| {
        let layering = Layering::<f32>::none()
            .with_outline(Outline::silhouette(&[0], &adj, INK).with_edges(edges));
        let mut r = Renderer::<f32, Rgb888, 32, 32, 256, 256, 64>::new();
        let mut layers = Layers::<32, 1, 4, 64>::new();
        let mut f = Frame::new(32, 32, Rgb888::BLACK);
        r.render_with(
            &scene,
            scanline3d::FrameOptions::new().layered(&layering, &mut layers),
            &mut f,
        )
        .err()
    };
    let missing = Some(Error::Layers(LayerError::Creases { object: 0 }));
    assert_eq!(run(Edges::Crease(&[])), missing);
    assert_eq!(run(Edges::Crease(&short)), missing);
    assert_eq!(run(Edges::All), None);
}
