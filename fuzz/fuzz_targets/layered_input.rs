//! Decodes fuzzer bytes into a layered frame and renders it with every number type: a ground
//! (a planar shadow's receiver), a caster (a built-in shape, textured or not, with hostile
//! parameters, or a box) and an optional third object (any mesh: positions, normals and texture
//! coordinates of any value, indices in or out of range), each with any material (flat,
//! Gouraud, Phong, fast Phong, textured with any mode and colour key, translucent); two
//! directional lights; effects (point lights, fog, a tone map, all with any numbers); and a
//! layering (projected or blob planar shadow from a directional or point light, shadow volumes,
//! both at once, outlines of every kind; adjacency and crease tables right, garbage, too short,
//! too long, missing or another mesh's; receiver, caster and outline indices in or out of
//! range). The frame is drawn as a layered frame (`FrameOptions::layered`) and, for the same scene, `render`.
//!
//! Shared by the fuzz target (`fuzz_targets/layered.rs`) and the host regression test
//! (`tests/fuzz_regressions.rs`), which replays the committed corpus (`fuzz/corpus/layered`)
//! and crash inputs (`fuzz/regressions/layered`).
//!
//! The contract checked: no panic (overflow checks are on), no hang; `Err` is a defined
//! result. Besides, what the library documents:
//! - an `Ok` frame under `OverflowPolicy::Error` fits every capacity its `Stats` report
//!   (`VERTS`, `ACTIVE`, `XV`, `XA`, the layers' `RA` and `PA`) and has no shortfall, and its
//!   face-colour vertices are among its vertices;
//! - a table made by `mesh_adjacency` passes `check_adjacency`, and `mesh_creases` accepts it
//!   (with an angle in 0..=180 and a table of `3·T` bits).

use embedded_graphics_core::pixelcolor::Rgb565;
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;
use scanline3d::{
    mesh::check_adjacency, mesh::mesh_adjacency, mesh::mesh_creases, mesh::Adjacency,
    mesh::NO_NEIGHBOUR, shadow::Edges, shadow::Layering, shadow::Outline, shadow::PlanarShadow,
    shadow::ShadowLight, shadow::VolumeShadow, tone::ToneCurve, Layers, Stats, Texture,
    TextureMode, TexturedShape, ToneMap, Wrap,
};
use scanline3d_support::hash::HashTarget;

// The renderer's and the layers' capacities.
const W: usize = 40;
const H: usize = 32;
const VERTS: usize = 256;
const TRIS: usize = 384;
const ACTIVE: usize = 64;
const LINES: usize = 4;
const XV: usize = 256;
const XA: usize = 64;
const RA: usize = 64;
const PA: usize = 128;
// The caster shapes' capacities.
const SV: usize = 128;
const ST: usize = 200;

type R<S> = Renderer<S, Rgb565, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA>;
type L = Layers<W, LINES, RA, PA>;

static T1: [u16; 1] = [0xf800];
static T4: [u16; 4] = [0xffff, 0x0000, 0x001f, 0x07e0];
static T16: [u16; 16] = [
    0xffff, 0x0000, 0xffff, 0x0000, 0x0000, 0xffff, 0x0000, 0xffff, 0xf800, 0x07e0, 0x001f, 0x0000,
    0x1234, 0xabcd, 0x0001, 0xfffe,
];
static T1024: [u16; 1024] = {
    let mut t = [0u16; 1024];
    let mut i = 0;
    while i < 1024 {
        t[i] = (i as u16).wrapping_mul(0x9e37);
        i += 1;
    }
    t
};

const fn tex(texels: &'static [u16], w: u32, h: u32, s: Wrap, t: Wrap) -> Texture {
    match Texture::new(texels, w, h) {
        Ok(x) => x.with_wrap(s, t),
        Err(_) => panic!("bad texture"),
    }
}

/// Textures of every shape (1 × 1, square, 1024 × 1, 1 × 1024) and wrap mode.
static TEXTURES: [Texture; 8] = [
    tex(&T1, 1, 1, Wrap::Repeat, Wrap::Repeat),
    tex(&T4, 2, 2, Wrap::Repeat, Wrap::Clamp),
    tex(&T16, 4, 4, Wrap::Clamp, Wrap::Repeat),
    tex(&T16, 4, 4, Wrap::Clamp, Wrap::Clamp),
    tex(&T1024, 1024, 1, Wrap::Repeat, Wrap::Repeat),
    tex(&T1024, 1, 1024, Wrap::Clamp, Wrap::Repeat),
    tex(&T1024, 32, 32, Wrap::Repeat, Wrap::Repeat),
    tex(&T16, 16, 1, Wrap::Repeat, Wrap::Clamp),
];

struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn u8(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }
    fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.u8(), self.u8()])
    }
    /// A number: mode 0 a small value (step 1/16, |v| ≤ 8), 1 a signed value of step 1/256
    /// (|v| < 128), 2 any f32 bit pattern (NaN and infinities included), 3 a special value
    /// (zeros, NaN, infinities, the Q16.16 rails, values just past what Q16.16 squares hold,
    /// the reaches the issue names, tiny and huge).
    fn real(&mut self) -> f64 {
        match self.u8() % 4 {
            0 => f64::from(self.u8() as i8) / 16.0,
            1 => f64::from(self.u16() as i16) / 256.0,
            2 => f64::from(f32::from_bits(u32::from_le_bytes([
                self.u8(),
                self.u8(),
                self.u8(),
                self.u8(),
            ]))),
            _ => SPECIAL[usize::from(self.u8()) % SPECIAL.len()],
        }
    }
    fn v3(&mut self) -> [f64; 3] {
        [self.real(), self.real(), self.real()]
    }
    fn rgb(&mut self) -> [u8; 3] {
        [self.u8(), self.u8(), self.u8()]
    }
}

const SPECIAL: [f64; 20] = [
    0.0,
    -0.0,
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    1e30,
    -1e30,
    19_000.0,
    24_000.0,
    32_767.99,
    -32_768.0,
    181.0,
    1e-6,
    1.0,
    0.5,
    65_536.0,
    f64::MAX,
    f64::MIN_POSITIVE,
    16.0,
    255.0,
];

fn s3<S: Scalar>(v: [f64; 3]) -> [S; 3] {
    v.map(S::from_f64)
}

/// A material: any coefficients, shading, texture (mode, colour key) and opacity.
fn material<S: Scalar>(b: &mut Bytes) -> Material<S> {
    let f = b.u8();
    let mut m = Material::matte(b.rgb(), S::from_f64(b.real()), S::from_f64(b.real()));
    m.specular = S::from_f64(b.real());
    m.shininess = b.u8();
    m.shading = match f & 3 {
        0 => Shading::Flat,
        1 => Shading::Gouraud,
        2 => Shading::Phong,
        _ => Shading::FastPhong,
    };
    let t = b.u8();
    let key = b.u16();
    let alpha = b.u8();
    if f & 4 != 0 {
        m = m
            .textured(&TEXTURES[usize::from(t) % TEXTURES.len()])
            .texture_mode(match (f >> 3) & 3 {
                0 => TextureMode::PerPixel,
                1 => TextureMode::Subdivided16,
                2 => TextureMode::Subdivided8,
                _ => TextureMode::Affine,
            });
        if f & 0x20 != 0 {
            m = m.color_key(key);
        }
    }
    if f & 0x40 != 0 {
        m = m.translucent(alpha);
    }
    m
}

/// An object's own data (the scene borrows it).
struct Part<S> {
    pos: Vec<[S; 3]>,
    nor: Option<Vec<[S; 3]>>,
    uvs: Option<Vec<[S; 2]>>,
    idx: Vec<[u16; 3]>,
    transform: Mat4<S>,
    material: Material<S>,
}

impl<S: Scalar> Part<S> {
    fn mesh(&self) -> Mesh<'_, S> {
        // `Mesh::new` only refuses more than 65 536 positions; normals and coordinates that are
        // refused are left out (the frame then reports what it misses).
        let mut m = Mesh::new(&self.pos, &self.idx).expect("at most a few hundred positions");
        if let Some(n) = &self.nor {
            m = m.with_normals(n).unwrap_or(m);
        }
        if let Some(uv) = &self.uvs {
            m = m.with_uvs(uv).unwrap_or(m);
        }
        m
    }
}

fn transform<S: Scalar>(b: &mut Bytes) -> Mat4<S> {
    let t = s3::<S>(b.v3());
    let rot = S::from_f64(b.real());
    let k = S::from_f64(b.real());
    Mat4::rotate_y(rot)
        .then(&Mat4::scale([k; 3]))
        .then(&Mat4::translate(t))
}

/// A square ground of half-size `g` at height `y` (in the plane y = 0 when `y` is 0).
fn ground<S: Scalar>(b: &mut Bytes) -> Part<S> {
    let g = b.real();
    let y = b.real();
    let pos = [[-g, y, g], [g, y, g], [g, y, -g], [-g, y, -g]]
        .map(s3::<S>)
        .to_vec();
    let nor = Some(vec![s3::<S>([0.0, 1.0, 0.0]); 4]);
    let uvs = Some(
        [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]]
            .map(|v| v.map(S::from_f64))
            .to_vec(),
    );
    Part {
        pos,
        nor,
        uvs,
        idx: vec![[0, 1, 2], [0, 2, 3]],
        transform: Mat4::identity(),
        material: material(b),
    }
}

/// A closed box of half-size `h` (8 corners, 12 counter-clockwise triangles from outside).
fn boxed(h: f64) -> (Vec<[f64; 3]>, Vec<[u16; 3]>) {
    let p = (0..8)
        .map(|k| {
            let s = |bit: usize| if k & (1 << bit) != 0 { h } else { -h };
            [s(0), s(1), s(2)]
        })
        .collect();
    let mut t = Vec::new();
    for q in [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
    ] {
        t.push([q[0], q[1], q[2]]);
        t.push([q[0], q[2], q[3]]);
    }
    (p, t)
}

/// The caster: a built-in shape (plain or textured) with any parameters, or a closed box.
/// `None` when the shape is refused (a `ShapeError` is its constructor's defined result).
fn caster<S: Scalar>(b: &mut Bytes) -> Option<Part<S>> {
    let kind = b.u8();
    let (x, y) = (b.real(), b.real());
    let (c, d) = (usize::from(b.u8()), usize::from(b.u8()));
    let transform = transform(b);
    let material = material(b);
    let part = |sh: &scanline3d::Shape<S, SV, ST>, uvs: Option<Vec<[S; 2]>>| Part {
        pos: sh.positions.to_vec(),
        nor: Some(sh.normals.to_vec()),
        uvs,
        idx: sh.indices.to_vec(),
        transform,
        material,
    };
    let textured = |t: TexturedShape<S, SV, ST>| part(&t.shape, Some(t.uvs.to_vec()));
    Some(match kind % 8 {
        0 => part(&scanline3d::Shape::cube(x).ok()?, None),
        1 => part(&scanline3d::Shape::icosphere(x, (c % 3) as u32).ok()?, None),
        2 => part(&scanline3d::Shape::torus(x, y, c % 12, d % 12).ok()?, None),
        3 => textured(TexturedShape::cube(x).ok()?),
        4 => textured(TexturedShape::torus(x, y, c % 12, d % 12).ok()?),
        5 => textured(TexturedShape::icosphere(x, (c % 3) as u32).ok()?),
        6 => textured(TexturedShape::terrain(x, c % 11, y).ok()?),
        _ => {
            let (p, idx) = boxed(x);
            // Corner normals (the diagonals), for Gouraud and Phong.
            let k = 1.0 / 3f64.sqrt();
            let nor = p
                .iter()
                .map(|v| s3::<S>(v.map(|c| if c > 0.0 { k } else { -k })))
                .collect();
            Part {
                pos: p.into_iter().map(s3::<S>).collect(),
                nor: Some(nor),
                uvs: None,
                idx,
                transform,
                material,
            }
        }
    })
}

/// Any mesh: up to 12 positions, normals and texture coordinates of any value, up to 16
/// triangles whose indices may be out of range.
fn free_mesh<S: Scalar>(b: &mut Bytes) -> Part<S> {
    let f = b.u8();
    let n = usize::from(b.u8() % 12) + 1;
    let t = usize::from(b.u8() % 16) + 1;
    let pos = (0..n).map(|_| s3::<S>(b.v3())).collect();
    let nor = (f & 1 != 0).then(|| (0..n).map(|_| s3::<S>(b.v3())).collect());
    let uvs = (f & 2 != 0).then(|| {
        (0..n)
            .map(|_| [S::from_f64(b.real()), S::from_f64(b.real())])
            .collect()
    });
    // Mostly in range: `n + 2` possible values, two of them out of range.
    let m = n as u16 + 2;
    let idx = (0..t)
        .map(|_| [b.u8(), b.u8(), b.u8()].map(|i| u16::from(i) % m))
        .collect();
    Part {
        pos,
        nor,
        uvs,
        idx,
        transform: transform(b),
        material: material(b),
    }
}

/// A table of `len` entries from a small generator: neighbours mostly below `t + 2` (some out
/// of range), some open edges.
fn garbage(len: usize, t: usize, seed: u16) -> Vec<[u16; 3]> {
    let mut x = u32::from(seed) | 1;
    let mut next = || {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        if x % 7 == 0 {
            NO_NEIGHBOUR
        } else {
            (x % (t as u32 + 2)) as u16
        }
    };
    (0..len).map(|_| [next(), next(), next()]).collect()
}

/// Object `i`'s adjacency table as layering byte `mode` says: its own (from `mesh_adjacency`,
/// or garbage when it has none), garbage of the right length, one too short or too long,
/// another object's, or every edge open.
fn table(
    mode: u8,
    i: usize,
    seed: u16,
    proper: &[Option<Vec<[u16; 3]>>],
    tris: &[usize],
) -> Vec<[u16; 3]> {
    let t = tris[i];
    match mode % 8 {
        0..=2 => proper[i].clone().unwrap_or_else(|| garbage(t, t, seed)),
        3 => garbage(t, t, seed),
        4 => garbage(t.saturating_sub(1), t, seed),
        5 => garbage(t + 1, t, seed),
        6 => proper[(i + 1) % proper.len()]
            .clone()
            .unwrap_or_else(|| garbage(t, t, seed)),
        _ => vec![[NO_NEIGHBOUR; 3]; t],
    }
}

/// Decodes and draws the frame with number type `S`; returns what each call gave (`Err` and its
/// error, or `Ok` and the frame's counts), or why no frame was drawn.
fn layered<S: Scalar>(data: &[u8]) -> String {
    let mut b = Bytes(data);
    let opts = b.u8();
    let (vw, vh) = (usize::from(b.u8()), usize::from(b.u8()));
    let background = b.rgb();

    // Camera.
    let eye = s3::<S>(b.v3());
    let target = s3::<S>(b.v3());
    let up = s3::<S>(b.v3());
    let (a, near, far) = (b.real(), b.real(), b.real());
    let projection = if opts & 1 == 0 {
        Projection::Perspective {
            fov_y: S::from_f64(a),
            near: S::from_f64(near),
            far: S::from_f64(far),
        }
    } else {
        Projection::Orthographic {
            height: S::from_f64(a),
            near: S::from_f64(near),
            far: S::from_f64(far),
        }
    };
    let lights = [
        Light {
            direction: s3::<S>(b.v3()),
            color: b.rgb(),
        },
        Light {
            direction: s3::<S>(b.v3()),
            color: b.rgb(),
        },
    ];

    // Objects: the ground (0), the caster (1, when its shape is accepted) and a free mesh.
    let mut parts = vec![ground::<S>(&mut b)];
    let caster = caster::<S>(&mut b);
    let has_caster = caster.is_some();
    parts.extend(caster);
    if opts & 0x20 != 0 {
        parts.push(free_mesh::<S>(&mut b));
    }

    // Effects.
    let ef = b.u8();
    let points: Vec<PointLight<S>> = (0..ef % 4)
        .map(|_| {
            PointLight::new(s3::<S>(b.v3()), b.rgb()).attenuation(
                S::from_f64(b.real()),
                S::from_f64(b.real()),
                S::from_f64(b.real()),
            )
        })
        .collect();
    let fog = Fog::linear(S::from_f64(b.real()), S::from_f64(b.real()), b.rgb());
    let curve = match b.u8() % 3 {
        0 => ToneCurve::Clamp,
        1 => ToneCurve::Reinhard,
        _ => ToneCurve::Filmic,
    };
    let tone = ToneMap::new(curve)
        .with_exposure(S::from_f64(b.real()))
        .with_intensity(S::from_f64(b.real()));
    // Two panics this target found, fixed in the library (phong.rs `point_dir`: a point
    // light's large attenuation at a Phong pixel; effects.rs `FogSpan::factor`: orthographic
    // fog with a huge far distance); their inputs are in fuzz/regressions/layered.
    let fog_on = ef & 4 != 0;
    let effects = Effects {
        point_lights: &points,
        fog: fog_on.then_some(fog),
        tone: (ef & 8 != 0).then_some(tone),
    };

    // Layering.
    let lm = b.u8();
    let lists = b.u8();
    let bad_index = usize::from(b.u8());
    let plane_mode = b.u8();
    let plane_v = [b.real(), b.real(), b.real(), b.real()];
    let shadow_light = s3::<S>(b.v3());
    let (shadow_color, shadow_alpha) = (b.rgb(), b.u8());
    let reach = S::from_f64(b.real());
    let (volume_color, volume_alpha) = (b.rgb(), b.u8());
    let adj_modes = [b.u8(), b.u8(), b.u8()];
    let seed = b.u16();
    let crease_angle = b.real();
    let crease_short = b.u8();
    let outline_color = b.rgb();

    let meshes: Vec<Mesh<'_, S>> = parts.iter().map(Part::mesh).collect();
    let tris: Vec<usize> = meshes.iter().map(|m| m.indices().len()).collect();

    // Adjacency and creases of each mesh, through the public functions, with their
    // documented agreement: a table `mesh_adjacency` makes passes `check_adjacency`, and
    // `mesh_creases` accepts it.
    let proper: Vec<Option<Vec<[u16; 3]>>> = meshes
        .iter()
        .map(|m| {
            let mut out = vec![[0u16; 3]; m.indices().len()];
            let open = mesh_adjacency(m, &mut out).ok()?;
            assert_eq!(
                open,
                out.iter().flatten().filter(|&&v| v == NO_NEIGHBOUR).count()
            );
            if let Err(e) = check_adjacency(m, &out) {
                panic!("check_adjacency refuses mesh_adjacency's own table: {e:?}");
            }
            Some(out)
        })
        .collect();
    let ids: Vec<usize> = (0..parts.len()).collect();
    let adjacency: Vec<Vec<[u16; 3]>> = ids
        .iter()
        .map(|&i| table(adj_modes[i], i, seed, &proper, &tris))
        .collect();
    // Each object's table checked once (`Adjacency::new`, documented as `check_adjacency`:
    // they agree on any table, right or wrong; an error is fine, a panic is not).
    let checked: Vec<Option<Adjacency<'_, S>>> = meshes
        .iter()
        .zip(&adjacency)
        .map(|(m, t)| {
            let a = Adjacency::new(m, t);
            assert_eq!(
                a.is_ok(),
                check_adjacency(m, t).is_ok(),
                "Adjacency::new and check_adjacency disagree"
            );
            a.ok()
        })
        .collect();
    let creases: Vec<Vec<u8>> = ids
        .iter()
        .map(|&i| {
            let bytes = (3 * tris[i]).div_ceil(8);
            let mut out = vec![0u8; bytes.saturating_sub(usize::from(crease_short % 2))];
            let r = mesh_creases(&meshes[i], &adjacency[i], crease_angle, &mut out);
            if proper[i].is_some()
                && adj_modes[i] % 8 <= 2
                && (0.0..=180.0).contains(&crease_angle)
                && crease_short % 2 == 0
            {
                if let Err(e) = r {
                    panic!("mesh_creases refuses a right table at {crease_angle}°: {e:?}");
                }
            }
            out
        })
        .collect();

    let objects: Vec<Object<'_, S>> = parts
        .iter()
        .zip(&meshes)
        .map(|(p, &mesh)| Object {
            mesh,
            transform: p.transform,
            material: p.material,
        })
        .collect();
    let Ok(camera) = Camera::look_at(eye, target, up, projection) else {
        return format!("{}: camera refused", S::NAME);
    };
    let mut scene = Scene::new(&objects, camera, lights);
    if ef & 0x10 != 0 {
        scene = scene.with_effects(&effects);
    }
    if opts & 0x80 != 0 {
        scene = scene.with_background(background);
    }

    // Receivers, casters and outlined objects: the intended ones, or with an index out of
    // range, or empty.
    let n = parts.len();
    let mut receivers = vec![0usize];
    let mut casters: Vec<usize> = if has_caster { vec![1] } else { vec![] };
    if lists & 1 != 0 && n > 2 {
        casters.push(2);
    }
    let mut outlined: Vec<usize> = casters.clone();
    match (lists >> 1) % 8 {
        0 => receivers.push(bad_index),
        1 => casters.push(bad_index),
        2 => receivers.clear(),
        3 => outlined.insert(0, 0),
        4 => outlined.push(bad_index),
        5 => casters.clear(),
        _ => {}
    }
    // A checked table per volume caster and per outlined object: its own, or where its own
    // was refused (or the mode asks for another mesh's), the next object's that was accepted
    // (checked against another mesh); one fewer when `lists` says so (an object without its
    // table), or where none was accepted.
    let pick = |list: &[usize]| -> Vec<Adjacency<'_, S>> {
        let mut v: Vec<Adjacency<'_, S>> = list
            .iter()
            .filter_map(|&i| {
                let n = checked.len();
                let other = (1..=n).find_map(|k| checked[(i + k) % n]);
                match checked.get(i).copied().flatten() {
                    Some(own) if adj_modes.get(i).is_none_or(|m| m % 8 != 6) => Some(own),
                    _ => other,
                }
            })
            .collect();
        if lists & 0x40 != 0 {
            v.pop();
        }
        v
    };
    let caster_tables = pick(&casters);
    let outline_tables = pick(&outlined);
    let crease_tables: Vec<&[u8]> = outlined
        .iter()
        .map(|&i| creases.get(i).map_or(&[][..], |c| &c[..]))
        .collect();

    let plane = if plane_mode % 4 == 0 {
        plane_v.map(S::from_f64)
    } else {
        // The ground's plane (y = its height).
        [0.0, 1.0, 0.0, -parts_height(&parts[0])].map(S::from_f64)
    };
    let light = if lm & 8 == 0 {
        ShadowLight::Directional(shadow_light)
    } else {
        ShadowLight::Point(shadow_light)
    };
    let planar = PlanarShadow {
        color: shadow_color,
        ..PlanarShadow::new(plane, light, shadow_alpha)
    };
    let volume = VolumeShadow {
        light,
        reach,
        adjacency: &caster_tables,
        color: volume_color,
        alpha: volume_alpha,
    };
    let mut layering = match lm % 8 {
        0 => Layering::none(),
        1 | 2 => Layering::projected(&receivers, &casters, planar),
        3 => Layering::projected(&receivers, &casters, planar.blob()),
        4..=6 => Layering::volumes(&casters, volume),
        _ => Layering {
            receivers: &receivers,
            ..Layering::volumes(&casters, volume)
        },
    };
    if lm % 8 == 7 {
        layering.shadow = Some(planar);
    }
    if lm & 0x10 != 0 {
        let edges = match (lm >> 5) & 3 {
            0 => Edges::Silhouette,
            1 => Edges::Crease(&crease_tables),
            2 => Edges::All,
            _ => Edges::Crease(&crease_tables[..crease_tables.len().saturating_sub(1)]),
        };
        layering = layering.with_outline(
            Outline::silhouette(&outlined, &outline_tables, outline_color)
                .with_edges(edges)
                .see_through(lm & 0x80 != 0),
        );
    }

    let mut r = Box::new(R::<S>::new());
    r.set_dither(opts & 2 != 0);
    r.set_depth_test(match (opts >> 2) & 3 {
        0 => DepthTest::Less,
        1 => DepthTest::LessEqual,
        2 => DepthTest::Equal,
        _ => DepthTest::Always,
    });
    let strict = opts & 0x10 == 0;
    if !strict {
        r.set_overflow(OverflowPolicy::DrawWhatFits);
    }
    if opts & 0x40 != 0 {
        r.set_viewport(vw, vh);
    }
    let mut layers = Box::new(L::new());
    let mut h = HashTarget::<Rgb565>::new(W as u32, H as u32);
    let result = r.render_with(
        &scene,
        scanline3d::FrameOptions::new().layered(&layering, &mut layers),
        &mut h,
    );
    if let (true, Ok(s)) = (strict, &result) {
        check_stats(s, true, &r);
    }
    let first = outcome(&result);
    // The same scene without layers (translucent objects make it an error).
    let result = r.render(&scene, &mut h);
    if let (true, Ok(s)) = (strict, &result) {
        check_stats(s, false, &r);
    }
    format!(
        "{}: {} objects; layered {first}; render {}",
        S::NAME,
        n,
        outcome(&result)
    )
}

fn outcome<E: core::fmt::Debug>(r: &Result<Stats, scanline3d::Error<E>>) -> String {
    match r {
        Ok(s) => format!(
            "Ok(drawn {}, invalid {}, written {}, receivers {}, overlays {}, attr {}/{})",
            s.drawn,
            s.invalid,
            s.pixels_written,
            s.max_receivers,
            s.max_overlays,
            s.attr_vertices,
            s.attr_active
        ),
        Err(e) => format!("Err({e:?})"),
    }
}

/// The ground's height (its first vertex's y), as given.
fn parts_height<S: Scalar>(p: &Part<S>) -> f64 {
    p.pos[0][1].to_f64()
}

/// What an `Ok` frame under `OverflowPolicy::Error` promises: it fit every capacity it
/// reports a need for, and the renderer reports no shortfall.
fn check_stats<S: Scalar>(s: &Stats, layered: bool, r: &R<S>) {
    let fits = [
        ("vertices", s.vertices as usize, VERTS),
        ("max_active", s.max_active as usize, ACTIVE),
        ("attr_vertices", s.attr_vertices as usize, XV),
        ("attr_active", s.attr_active as usize, XA),
        ("max_receivers", s.max_receivers as usize, RA),
        ("max_overlays", s.max_overlays as usize, PA),
    ];
    for (name, need, cap) in fits {
        assert!(
            need <= cap,
            "an Ok frame (layered {layered}) needs {name} {need}, capacity {cap}: {s:?}"
        );
    }
    assert!(s.color_vertices <= s.vertices, "{s:?}");
    assert!(
        r.shortfall().is_none(),
        "an Ok frame under OverflowPolicy::Error reports a shortfall: {:?}",
        r.shortfall()
    );
}

/// Renders the layered frame encoded in `data` with I16F16, f32 and f64.
pub fn layered_all(data: &[u8]) {
    outcomes(data);
}

/// [`layered_all`], saying what each number type's frames gave.
pub fn outcomes(data: &[u8]) -> [String; 3] {
    [
        layered::<Fx<I16F16>>(data),
        layered::<f32>(data),
        layered::<f64>(data),
    ]
}
