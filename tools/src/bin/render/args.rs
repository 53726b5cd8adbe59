//! `render`'s command line: the flags ([`Args`]), their parsers (each value checked against its
//! range and named as the user typed it) and the checks of the flags together
//! ([`check_flags`]; which flags each scene and mode honours is [`super::rules`]).

use std::collections::BTreeSet;
use std::path::PathBuf;

use clap::{ArgMatches, CommandFactory, FromArgMatches, Parser, ValueEnum};
use scanline3d::shadow::ShadowFilter;

use super::{depth, edges, shadow, tone, LIGHTS, MAX_H, MAX_W};

/// Most frames one run renders. Every frame is kept in memory twice (the tested number type
/// and the f64 reference) until the animated image is written, and each is rendered up to
/// three times (timing): 1 000 frames is 40 s of animation at the image's 25 frames/s, a full
/// turn even at a 0.36° `--spin`, and about 230 MB and a few seconds (release) at 240x240.
pub(crate) const MAX_FRAMES: usize = 1000;
/// Most pixels over all frames (frames × width × height, 64 Mi): bounds the memory of a large
/// animation (about 400 MB in Rgb888 for both copies) — 1 000 frames at 240x240, 64 at 1024x1024.
pub(crate) const MAX_FRAME_PIXELS: usize = 1 << 26;
/// Largest material coefficient: with a material channel ≥ 1 (of 255), a coefficient of 255
/// already saturates the channel, so larger ones change nothing but the fixed-point headroom.
pub(crate) const MAX_COEFFICIENT: f64 = 255.0;

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum SceneArg {
    Torus,
    Cube,
    Icosphere,
    Terrain,
    /// A torus and a cube above a ground square, with their own camera, light and colours, at
    /// 240x240 (the `shadow` benchmark scene): takes --shadow, --shadow-plane, --alpha,
    /// --outline, --edges, --edge-color, --crease-angle, --see-through, --shading
    /// gouraud|wireframe, --frames, --spin, --number, --format, --dither and --out; other
    /// model flags are refused
    Shadow,
}

/// How `--scene shadow` draws its shadow (`--shadow`, parsed by [`shadow_arg`]).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum ShadowArg {
    /// No shadow
    None,
    /// The models' triangles projected onto the shadow plane along the light, stencilled (each
    /// ground pixel darkened once)
    Projected,
    /// A soft round blob under each model (nested discs; the seeds' cheapest method)
    Blob,
    /// Shadow volumes of the models (stencil counting, z-fail): on the ground, on each other
    /// and on themselves
    Volume,
    /// A shadow map of the models, this many texels a side, read as the filter says: on the
    /// ground, on each other and on themselves
    Map(usize, ShadowFilter),
    /// A light-view image without depth, this many texels a side, pre-blurred or not: on the
    /// ground only (the models cast and receive nothing)
    Image(usize, bool),
}

/// `--shadow`: none, projected, blob, volume, map[,SIZE[,FILTER]] or image[,SIZE[,blur]] (SIZE
/// 32, 64 or 128, default 64; FILTER nearest, pcf or pcf3, default nearest).
fn shadow_arg(s: &str) -> Result<ShadowArg, String> {
    let bad = || {
        format!(
            "{s:?}: expected none, projected, blob, volume, map[,SIZE[,FILTER]] or \
             image[,SIZE[,blur]] with SIZE 32, 64 or 128 and FILTER nearest, pcf (2 × 2) or pcf3 \
             (3 × 3)"
        )
    };
    let mut parts = s.split(',');
    let arg = match parts.next() {
        Some("none") => ShadowArg::None,
        Some("projected") => ShadowArg::Projected,
        Some("blob") => ShadowArg::Blob,
        Some("volume") => ShadowArg::Volume,
        Some(kind @ ("map" | "image")) => {
            let size = match parts.next() {
                None | Some("64") => 64,
                Some("32") => 32,
                Some("128") => 128,
                Some(_) => return Err(bad()),
            };
            if kind == "image" {
                let blur = match parts.next() {
                    None => false,
                    Some("blur") => true,
                    Some(_) => return Err(bad()),
                };
                return match parts.next() {
                    None => Ok(ShadowArg::Image(size, blur)),
                    Some(_) => Err(bad()),
                };
            }
            let filter = match parts.next() {
                None | Some("nearest") => ShadowFilter::Nearest,
                Some("pcf") => ShadowFilter::Pcf2,
                Some("pcf3") => ShadowFilter::Pcf3,
                Some(_) => return Err(bad()),
            };
            ShadowArg::Map(size, filter)
        }
        _ => return Err(bad()),
    };
    match parts.next() {
        None => Ok(arg),
        Some(_) => Err(bad()),
    }
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum ShadingArg {
    Flat,
    Gouraud,
    /// Lit at every pixel
    Phong,
    /// Phong lit every 8 pixels, linear between
    FastPhong,
    /// Phong with hard edges, per pixel: --bands tones on the lit side, an all-or-nothing
    /// highlight
    Toon,
    /// Lines along the edges (--edges, default all) over surfaces unlit in the background
    /// colour, which hide the lines behind them (unless --see-through)
    Wireframe,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum TexModeArg {
    /// Perspective-correct every 16 pixels (TextureMode::Subdivided16)
    Perspective,
    /// Perspective-correct every 8 pixels (TextureMode::Subdivided8)
    Perspective8,
    /// Perspective-correct at every pixel (TextureMode::PerPixel)
    Exact,
    /// Linear in screen space (TextureMode::Affine)
    Affine,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum NormalsArg {
    FaceAverage,
    File,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum NumberArg {
    Fixed,
    F32,
    F64,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum FormatArg {
    Rgb565,
    Rgb888,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum OnOff {
    On,
    Off,
}

pub(crate) fn v3(s: &str) -> Result<[f64; 3], String> {
    match numbers(s)?[..] {
        [x, y, z] => Ok([x, y, z]),
        _ => Err(format!("{s:?}: expected three finite numbers x,y,z")),
    }
}

/// `--point-light`: position, colour, attenuation.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) struct PointArg {
    pub(crate) position: [f64; 3],
    pub(crate) color: [u8; 3],
    pub(crate) attenuation: [f64; 3],
}

/// `--fog`: view depths and colour.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) struct FogArg {
    pub(crate) near: f64,
    pub(crate) far: f64,
    pub(crate) color: [u8; 3],
}

/// Comma-separated finite numbers.
pub(crate) fn numbers(s: &str) -> Result<Vec<f64>, String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|e| format!("{s:?}: {e}"))?;
    if let Some(x) = v.iter().find(|x| !x.is_finite()) {
        return Err(format!("{s:?}: {x} is not a finite number"));
    }
    Ok(v)
}

/// A colour channel 0-255 given as a number.
pub(crate) fn channel(s: &str, v: f64) -> Result<u8, String> {
    if v.fract() != 0.0 || !(0.0..=255.0).contains(&v) {
        return Err(format!(
            "{s:?}: colour channels are integers 0-255, got {v}"
        ));
    }
    Ok(v as u8)
}

pub(crate) fn point_light(s: &str) -> Result<PointArg, String> {
    let v = numbers(s)?;
    if ![3, 6, 9].contains(&v.len()) {
        return Err(format!(
            "{s:?}: expected x,y,z or x,y,z,r,g,b or x,y,z,r,g,b,c,l,q ({} numbers given)",
            v.len()
        ));
    }
    let color = if v.len() >= 6 {
        [channel(s, v[3])?, channel(s, v[4])?, channel(s, v[5])?]
    } else {
        [255; 3]
    };
    let attenuation = if v.len() == 9 {
        [v[6], v[7], v[8]]
    } else {
        [1.0, 0.0, 0.0]
    };
    if attenuation
        .iter()
        .any(|&a| !(0.0..=MAX_ATTENUATION).contains(&a))
    {
        return Err(format!(
            "{s:?}: attenuation coefficients must be in [0, {MAX_ATTENUATION}]"
        ));
    }
    Ok(PointArg {
        position: [v[0], v[1], v[2]],
        color,
        attenuation,
    })
}

pub(crate) fn fog(s: &str) -> Result<FogArg, String> {
    let v = numbers(s)?;
    let [near, far, r, g, b] = v[..] else {
        return Err(format!(
            "{s:?}: expected near,far,r,g,b ({} numbers given)",
            v.len()
        ));
    };
    if near >= far {
        return Err(format!(
            "{s:?}: the fog's near depth must be below its far depth"
        ));
    }
    Ok(FogArg {
        near,
        far,
        color: [channel(s, r)?, channel(s, g)?, channel(s, b)?],
    })
}

/// The largest attenuation coefficient (what Phong spans store, Q5.16).
pub(crate) const MAX_ATTENUATION: f64 = 31.0;

/// `r,g,b`, each an integer 0-255 (a negative, fractional or larger channel named).
pub(crate) fn rgb(s: &str) -> Result<[u8; 3], String> {
    let v: Vec<u8> = s
        .split(',')
        .map(|x| match x.trim().parse::<i128>() {
            Ok(c) if (0..=255).contains(&c) => Ok(c as u8),
            _ => Err(format!(
                "{s:?}: colour channels are integers 0-255, got {:?}",
                x.trim()
            )),
        })
        .collect::<Result<_, _>>()?;
    match v[..] {
        [r, g, b] => Ok([r, g, b]),
        _ => Err(format!(
            "{s:?}: expected r,g,b (three channels 0-255), got {} channel(s)",
            v.len()
        )),
    }
}

/// `--size`: `WxH`, each an integer 1-1024.
pub(crate) fn size(s: &str) -> Result<(usize, usize), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("{s:?}: expected WxH, e.g. 240x240"))?;
    let side = |v: &str| match v.trim().parse::<i128>() {
        Ok(n) if (1..=MAX_W as i128).contains(&n) => Ok(n as usize),
        _ => Err(format!(
            "{s:?}: width and height must be integers 1-{MAX_W} (pixels), got {:?}",
            v.trim()
        )),
    };
    let (w, h) = (side(w)?, side(h)?);
    if h > MAX_H {
        return Err(format!("{s:?}: the height must be 1-{MAX_H}"));
    }
    Ok((w, h))
}

/// An integer flag's value in `lo..=hi`: a negative, fractional, too large or non-numeric value
/// is refused with the flag's name and range (`hi` `None`: no upper bound; `what` names the
/// upper bound when it is not a number known here).
fn integer(s: &str, flag: &str, lo: u64, hi: Option<u64>, what: &str) -> Result<u64, String> {
    match (s.trim().parse::<i128>(), hi) {
        (Ok(v), Some(hi)) if (lo as i128..=hi as i128).contains(&v) => Ok(v as u64),
        (Ok(v), None) if v >= lo as i128 && v <= u64::MAX as i128 => Ok(v as u64),
        _ => Err(match (hi, what) {
            (Some(hi), _) => format!("{flag} must be in [{lo}, {hi}]{what}, got {s}"),
            (None, "") => format!("{flag} must be an integer ≥ {lo}, got {s}"),
            (None, _) => format!("{flag} must be in [{lo}, {what}], got {s}"),
        }),
    }
}

fn bands(s: &str) -> Result<u8, String> {
    integer(s, "--bands", 1, Some(255), "").map(|v| v as u8)
}

fn shininess(s: &str) -> Result<u8, String> {
    integer(s, "--shininess", 1, Some(255), "").map(|v| v as u8)
}

fn alpha(s: &str) -> Result<u8, String> {
    integer(s, "--alpha", 0, Some(255), "").map(|v| v as u8)
}

fn frames(s: &str) -> Result<usize, String> {
    integer(s, "--frames", 1, Some(MAX_FRAMES as u64), "").map(|v| v as usize)
}

fn strip(s: &str) -> Result<usize, String> {
    integer(s, "--strip", 1, None, "the image height").map(|v| v as usize)
}

fn max_triangles(s: &str) -> Result<usize, String> {
    integer(s, "--max-triangles", 1, None, "").map(|v| v as usize)
}

fn max_vertices(s: &str) -> Result<usize, String> {
    integer(s, "--max-vertices", 3, None, "").map(|v| v as usize)
}

fn pass_triangles(s: &str) -> Result<usize, String> {
    integer(s, "--pass-triangles", 1, None, "").map(|v| v as usize)
}

/// Renders an OBJ file, a CSG part or a built-in scene as a 240×240 RGB565 LCD would show it
/// (through the library's own pipeline), and reports what the scene costs. Every flag given is
/// applied or refused: a flag the chosen scene or mode does not use is an error.
#[derive(Parser, Debug, Clone)]
#[command(name = "render", version)]
pub(crate) struct Args {
    /// OBJ file to render (triangulated; v/vt/vn and negative indices accepted) [default:
    /// none, the built-in --scene]
    #[arg(long, value_name = "FILE", conflicts_with = "scene")]
    pub(crate) obj: Option<PathBuf>,
    /// CSG tree to mesh and render (format: tools/src/csg.rs; e.g. tests/data/part.csg);
    /// corners get crease-angle normals (edges sharper than 40° stay hard) [default: none]
    #[arg(long, value_name = "FILE", conflicts_with_all = ["scene", "obj"])]
    pub(crate) csg: Option<PathBuf>,
    /// Built-in scene [default: torus]
    #[arg(long, value_enum)]
    pub(crate) scene: Option<SceneArg>,
    /// Centre the model and place the camera along --eye − --target so that the model's
    /// bounding sphere fills the view (the near and far planes, and with --ortho the view
    /// height, follow from it)
    #[arg(long)]
    pub(crate) fit: bool,
    /// Image size in pixels, WxH, each 1-1024
    #[arg(long, value_name = "WxH", allow_hyphen_values = true, value_parser = size, default_value = "240x240")]
    pub(crate) size: (usize, usize),
    /// Camera position x,y,z, world units
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = v3, default_value = "0,1.2,3")]
    pub(crate) eye: [f64; 3],
    /// Point the camera looks at x,y,z, world units
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = v3, default_value = "0,0,0")]
    pub(crate) target: [f64; 3],
    /// Camera up direction x,y,z (any length, not along the view)
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = v3, default_value = "0,1,0")]
    pub(crate) up: [f64; 3],
    /// Vertical field of view of the perspective projection, degrees, in (0, 180) (not with
    /// --ortho)
    #[arg(
        long = "fov-y",
        value_name = "DEG",
        allow_hyphen_values = true,
        default_value_t = 45.0,
        conflicts_with = "ortho"
    )]
    pub(crate) fov_y: f64,
    /// Near plane distance, world units, > 0 (not with --fit, which chooses it)
    #[arg(
        long,
        value_name = "DIST",
        allow_hyphen_values = true,
        default_value_t = 0.1
    )]
    pub(crate) near: f64,
    /// Far plane distance, world units, > --near (not with --fit, which chooses it)
    #[arg(
        long,
        value_name = "DIST",
        allow_hyphen_values = true,
        default_value_t = 10.0
    )]
    pub(crate) far: f64,
    /// Parallel projection with this view height (world units, > 0) instead of perspective
    /// [default: perspective]; with --fit, a factor on the fitted height (1: the bounding
    /// sphere fills the view)
    #[arg(long, value_name = "HEIGHT", allow_hyphen_values = true)]
    pub(crate) ortho: Option<f64>,
    /// Model rotation about X, degrees (applied first)
    #[arg(
        long = "rotate-x",
        value_name = "DEG",
        allow_hyphen_values = true,
        default_value_t = 30.0
    )]
    pub(crate) rotate_x: f64,
    /// Model rotation about Y, degrees (applied second)
    #[arg(
        long = "rotate-y",
        value_name = "DEG",
        allow_hyphen_values = true,
        default_value_t = 20.0
    )]
    pub(crate) rotate_y: f64,
    /// Model rotation about Z, degrees (applied third)
    #[arg(
        long = "rotate-z",
        value_name = "DEG",
        allow_hyphen_values = true,
        default_value_t = 0.0
    )]
    pub(crate) rotate_z: f64,
    /// Direction toward a white directional light x,y,z, world space (any length, not
    /// 0,0,0); repeat for up to 4 lights [default: -1,1,1]
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = v3)]
    pub(crate) light: Vec<[f64; 3]>,
    /// A point light: position x,y,z (world units), then optionally its colour r,g,b (0-255,
    /// default 255,255,255) and attenuation constant,linear,quadratic (each 0-31, default
    /// 1,0,0): the light is scaled by 1/max(1, c + l·d + q·d²) at distance d; repeat for more
    /// (Phong shading takes at most 2) [default: none]
    #[arg(long = "point-light", value_name = "X,Y,Z[,R,G,B[,C,L,Q]]", allow_hyphen_values = true, value_parser = point_light)]
    pub(crate) point_light: Vec<PointArg>,
    /// Linear depth fog: none before view depth NEAR, only fog colour r,g,b (0-255) beyond FAR
    /// (world units, NEAR < FAR) [default: no fog]
    #[arg(long, value_name = "NEAR,FAR,R,G,B", allow_hyphen_values = true, value_parser = fog)]
    pub(crate) fog: Option<FogArg>,
    /// Ambient coefficient: the factor on the model colour lit without a light, 0 to 255
    /// (1 = the full colour)
    #[arg(
        long,
        value_name = "K",
        allow_hyphen_values = true,
        default_value_t = 0.15
    )]
    pub(crate) ambient: f64,
    /// Diffuse coefficient: the factor on the model colour × the lights' colour facing a
    /// light, 0 to 255 (1 = the full colour)
    #[arg(
        long,
        value_name = "K",
        allow_hyphen_values = true,
        default_value_t = 0.85
    )]
    pub(crate) diffuse: f64,
    /// Specular coefficient: the factor on the lights' colour in the highlights, 0 to 255
    /// (0 = no highlights, 1 = the full light colour)
    #[arg(
        long,
        value_name = "K",
        allow_hyphen_values = true,
        default_value_t = 0.0
    )]
    pub(crate) specular: f64,
    /// Specular (Phong) exponent, an integer 1-255: higher is a smaller, sharper highlight
    /// (needs --specular above 0)
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = shininess, default_value = "16")]
    pub(crate) shininess: u8,
    /// Model colour r,g,b, each 0-255 (with --shading wireframe: the lines' colour)
    #[arg(long, value_name = "R,G,B", allow_hyphen_values = true, value_parser = rgb, default_value = "255,160,64")]
    pub(crate) color: [u8; 3],
    /// Background colour r,g,b, each 0-255
    #[arg(long, value_name = "R,G,B", allow_hyphen_values = true, value_parser = rgb, default_value = "0,0,0")]
    pub(crate) background: [u8; 3],
    /// Shading mode
    #[arg(long, value_enum, default_value = "gouraud")]
    pub(crate) shading: ShadingArg,
    /// Tones on the lit side with --shading toon, 1-255
    #[arg(long, value_name = "N", value_parser = bands, default_value = "4")]
    pub(crate) bands: u8,
    /// Texture image (PNG, power-of-two sides up to 1024): multiplies the lit colour (use
    /// --color 255,255,255 for the image's own colours); the OBJ needs vt, the built-in scenes
    /// have texture coordinates; transparent pixels are not drawn [default: none]
    #[arg(long, value_name = "FILE.png")]
    pub(crate) texture: Option<PathBuf>,
    /// How textured spans find their texture coordinates
    #[arg(long, value_enum, default_value = "perspective", requires = "texture")]
    pub(crate) texture_mode: TexModeArg,
    /// Vertex normals: averaged from the faces, or the OBJ's (or built-in scene's) own
    /// [default: file when the OBJ has vn for every vertex]; not with --shading flat or
    /// wireframe, which use none
    #[arg(long, value_enum)]
    pub(crate) normals: Option<NormalsArg>,
    /// Number type of the geometry pipeline (fixed: Q16.16, values within ±32768)
    #[arg(long, value_enum, default_value = "fixed")]
    pub(crate) number: NumberArg,
    /// Pixel format of the simulated display
    #[arg(long, value_enum, default_value = "rgb565")]
    pub(crate) format: FormatArg,
    /// 4×4 ordered dithering of Gouraud gradients (Gouraud shading, untextured, --format
    /// rgb565)
    #[arg(long, value_enum, default_value = "off")]
    pub(crate) dither: OnOff,
    /// Lines per strip for the RAM figures, an integer from 1 to the image height (the image
    /// is the same for every strip height)
    #[arg(long, value_name = "LINES", allow_hyphen_values = true, value_parser = strip, default_value = "1")]
    pub(crate) strip: usize,
    /// The shadow of `--scene shadow`: none, projected (the models' triangles projected onto
    /// the plane, stencilled), blob (a soft disc under each model), volume (shadow volumes: on
    /// the ground, on each other and on themselves) or map[,SIZE[,FILTER]] (a shadow map of
    /// SIZE 32, 64 or 128 texels a side, default 64: the same receivers as volumes; FILTER
    /// nearest, pcf for 2×2 or pcf3 for 3×3 percentage-closer soft edges, default nearest) or
    /// image[,SIZE[,blur]] (a light-view image without depth: the ground only, half a map's
    /// RAM; blur: pre-blurred 3×3) [default: projected; none with --shading wireframe]
    #[arg(long, value_name = "METHOD", value_parser = shadow_arg)]
    pub(crate) shadow: Option<ShadowArg>,
    /// The plane `--scene shadow`'s shadow falls on, a·x + b·y + c·z + d = 0 (world units;
    /// the ground square is placed in it) [default: 0,1,0,0, the level ground]
    #[arg(long = "shadow-plane", value_name = "A,B,C,D", allow_hyphen_values = true, value_parser = shadow::plane)]
    pub(crate) shadow_plane: Option<[f64; 4]>,
    /// Opacity of `--scene shadow`'s torus, an integer 0-255: below 255 it is blended over
    /// what is behind it [default: 255, opaque]
    #[arg(long, value_name = "A", allow_hyphen_values = true, value_parser = alpha)]
    pub(crate) alpha: Option<u8>,
    /// Outlines of `--scene shadow`'s models (their contour edges from the eye), 1 px, in
    /// this colour r,g,b (0-255) [default: none]
    #[arg(long, value_name = "R,G,B", allow_hyphen_values = true, value_parser = rgb)]
    pub(crate) outline: Option<[u8; 3]>,
    /// How depth is resolved: the Z-buffer, or without depth lines in the painter's order or in
    /// any order (flat and Gouraud models without edges; `--budget` says which one a scene
    /// needs)
    #[arg(long, value_enum, default_value = "zbuffer")]
    pub(crate) depth: depth::DepthArg,
    /// Edges drawn over the model (1 px, hidden behind nearer surfaces unless --see-through)
    /// [default: none; all with --shading wireframe]
    #[arg(long, value_enum)]
    pub(crate) edges: Option<edges::EdgesArg>,
    /// The edges' colour r,g,b, each 0-255 [default: 0,0,0; the model's --color with
    /// --shading wireframe]
    #[arg(long = "edge-color", value_name = "R,G,B", allow_hyphen_values = true, value_parser = rgb)]
    pub(crate) edge_color: Option<[u8; 3]>,
    /// `--edges crease`: an edge whose two faces meet at more than this angle is drawn,
    /// degrees, 0 to 180
    #[arg(
        long = "crease-angle",
        value_name = "DEG",
        allow_hyphen_values = true,
        default_value_t = 40.0
    )]
    pub(crate) crease_angle: f64,
    /// Edges hidden behind surfaces are drawn too (and those of faces turned away)
    #[arg(long = "see-through")]
    pub(crate) see_through: bool,
    /// HDR: the tone curve mapping the lit radiance to the display [default: none; clamp when
    /// --exposure or --light-intensity is given]
    #[arg(long, value_enum)]
    pub(crate) tone: Option<tone::ToneArg>,
    /// HDR: the radiance's factor before the tone curve, above 0 and at most 16, or `auto`:
    /// adapted frame by frame toward a mean luma of 96 from the previous frame's pixels (first
    /// over 16 frames at the first frame's pose) [default: 1]
    #[arg(long, value_name = "E|auto", allow_hyphen_values = true, value_parser = tone::exposure)]
    pub(crate) exposure: Option<tone::ExposureArg>,
    /// HDR: every light's brightness factor, 0 to 16 (1 = as its colour says) [default: 1]
    #[arg(long = "light-intensity", value_name = "X", allow_hyphen_values = true)]
    pub(crate) light_intensity: Option<f64>,
    /// Output image (.png; with --frames > 1 an animated .png or .gif); not with --budget,
    /// which writes none
    #[arg(long, value_name = "FILE", default_value = "scanline3d.png")]
    pub(crate) out: PathBuf,
    /// Number of frames (an animation about the Y axis, 25 frames/s), an integer 1-1000, and
    /// at most 64 Mi pixels over all frames (e.g. 64 frames at 1024x1024)
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = frames, default_value = "1")]
    pub(crate) frames: usize,
    /// Rotation about Y between frames, degrees (needs --frames 2 or more)
    #[arg(
        long,
        value_name = "DEG",
        allow_hyphen_values = true,
        default_value_t = 10.0
    )]
    pub(crate) spin: f64,
    /// Report what the scene needs (capacities, fixed-point headroom, RAM) over every frame,
    /// print the renderer type for firmware, and fail if a format or capacity overflows (no
    /// image is written)
    #[arg(long)]
    pub(crate) budget: bool,
    /// With --scene shadow --budget: the RAM the renderer may take, bytes (an integer ≥ 1), to
    /// name the cheapest shadow method that fits [default: 270336, the RP2040's 264 KB]
    #[arg(long, value_name = "BYTES", value_parser = clap::value_parser!(u32).range(1..))]
    pub(crate) ram: Option<u32>,
    /// Simplify the OBJ to at most this many triangles first, an integer ≥ 1 (meshoptimizer;
    /// as `bake --max-triangles`), e.g. to see a model too large for one renderer (drawn in
    /// passes here) as a device can hold it [default: no limit]
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = max_triangles, requires = "obj")]
    pub(crate) max_triangles: Option<usize>,
    /// Simplify the OBJ to at most this many vertices first, an integer ≥ 3 (meshoptimizer)
    /// [default: no limit]
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = max_vertices, requires = "obj")]
    pub(crate) max_vertices: Option<usize>,
    /// Testing: draw every frame in passes of at most N triangles (an integer ≥ 1) of the
    /// mesh, as a frame too large for one renderer is drawn (the image must be the same as in
    /// one pass). The active count of `--budget` and of the RAM figure is then an upper bound.
    #[arg(long, value_name = "N", hide = true, allow_hyphen_values = true, value_parser = pass_triangles)]
    pub(crate) pass_triangles: Option<usize>,
    /// The flags given on the command line (`--fov-y`, …), as opposed to their defaults.
    #[arg(skip)]
    pub(crate) given: BTreeSet<String>,
}

impl Args {
    /// The command line, parsed (clap's usage errors exit with status 2), with the flags the
    /// user gave.
    pub(crate) fn from_command_line() -> Self {
        let matches = Args::command().get_matches();
        let mut args = Args::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
        args.given = given(&matches);
        args
    }

    /// Whether `flag` (`--fov-y`) was given on the command line.
    pub(crate) fn given(&self, flag: &str) -> bool {
        self.given.contains(flag)
    }
}

/// The long names (`--fov-y`) of the flags the user gave ([`clap::parser::ValueSource`]).
fn given(m: &ArgMatches) -> BTreeSet<String> {
    Args::command()
        .get_arguments()
        .filter(|a| {
            m.value_source(a.get_id().as_str()) == Some(clap::parser::ValueSource::CommandLine)
        })
        .filter_map(|a| a.get_long().map(|l| format!("--{l}")))
        .collect()
}

/// Every numeric flag against its valid range, named as the user typed it (usage errors: exit
/// status 2, like clap's). The flags with a parser of their own (`--size`, `--eye`, `--target`,
/// `--up`, `--light`, `--point-light`, `--fog`, the colours, `--shininess`, `--alpha`,
/// `--frames`, `--strip`, `--exposure`, `--max-*`) are checked there (finite, in range, negative
/// values named rather than taken for flags); the camera as a whole (eye at the target, up along
/// the view, depth precision) by `Camera::look_at` in `setup`; what the number type holds by
/// `rules::check_numbers`; the flags the chosen scene or mode does not use by `rules::check`.
pub(crate) fn check_flags(args: &Args) -> Result<(), String> {
    let (w, h) = args.size;
    let finite = |flag: &str, v: f64| {
        if v.is_finite() {
            Ok(())
        } else {
            Err(format!("{flag} must be a finite number, got {v}"))
        }
    };
    finite("--fov-y", args.fov_y)?;
    if !(args.fov_y > 0.0 && args.fov_y < 180.0) {
        return Err(format!(
            "--fov-y must be in (0, 180) degrees, got {}",
            args.fov_y
        ));
    }
    finite("--near", args.near)?;
    if args.near <= 0.0 {
        return Err(format!(
            "--near must be greater than 0 (world units), got {}",
            args.near
        ));
    }
    finite("--far", args.far)?;
    if args.far <= args.near {
        return Err(format!(
            "--far must be greater than --near ({}), got {}",
            args.near, args.far
        ));
    }
    finite("--crease-angle", args.crease_angle)?;
    edges::check(args)?;
    tone::check(args)?;
    depth::check(args)?;
    if let Some(height) = args.ortho {
        finite("--ortho", height)?;
        if height <= 0.0 {
            return Err(format!(
                "--ortho (the view height) must be greater than 0 (world units), got {height}"
            ));
        }
    }
    for (flag, v) in [
        ("--rotate-x", args.rotate_x),
        ("--rotate-y", args.rotate_y),
        ("--rotate-z", args.rotate_z),
        ("--spin", args.spin),
    ] {
        finite(flag, v)?;
    }
    if args.light.len() > LIGHTS {
        return Err(format!(
            "at most {LIGHTS} --light flags, got {}",
            args.light.len()
        ));
    }
    if let Some(l) = args.light.iter().find(|l| **l == [0.0; 3]) {
        return Err(format!(
            "--light {},{},{} is a zero vector: a light needs a direction",
            l[0], l[1], l[2]
        ));
    }
    for (flag, v) in [
        ("--ambient", args.ambient),
        ("--diffuse", args.diffuse),
        ("--specular", args.specular),
    ] {
        finite(flag, v)?;
        if !(0.0..=MAX_COEFFICIENT).contains(&v) {
            return Err(format!("{flag} must be in [0, {MAX_COEFFICIENT}], got {v}"));
        }
    }
    if !(1..=h).contains(&args.strip) {
        return Err(format!(
            "--strip must be in [1, {h}] lines (the image height), got {}",
            args.strip
        ));
    }
    if !(1..=MAX_FRAMES).contains(&args.frames) {
        return Err(format!(
            "--frames must be in [1, {MAX_FRAMES}], got {} (every frame is kept in memory \
             until the animation is written)",
            args.frames
        ));
    }
    let pixels = args.frames.saturating_mul(w * h);
    if pixels > MAX_FRAME_PIXELS {
        return Err(format!(
            "--frames {} at {w}x{h} is {pixels} pixels, more than the {MAX_FRAME_PIXELS} \
             (frames × width × height) kept in memory: at most {} frames at this --size",
            args.frames,
            MAX_FRAME_PIXELS / (w * h)
        ));
    }
    Ok(())
}
