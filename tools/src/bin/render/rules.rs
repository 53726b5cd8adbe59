//! Every flag given is applied or refused: which flags each scene and mode honours ([`UNUSED`],
//! checked once after parsing against the flags the user gave, [`Args::given`]), the values the
//! number type cannot hold ([`check_numbers`]), and frames in which nothing could be drawn
//! ([`nothing_drawn`]).

use scanline3d::{limits::MAX_PHONG_POINT_LIGHTS, Scalar, Stats};

use super::edges::{self, EdgesArg};
use super::{Args, FormatArg, OnOff, SceneArg, ShadingArg};

/// Flags that have no effect in some scene or mode: given there, they are refused.
struct Unused {
    /// The flags' long names.
    flags: &'static [&'static str],
    /// Whether the command line chose the scene or mode in which they have no effect.
    when: fn(&Args) -> bool,
    /// Why, after the flag's name.
    why: &'static str,
}

fn shadow(a: &Args) -> bool {
    a.scene == Some(SceneArg::Shadow)
}

fn wireframe(a: &Args) -> bool {
    a.shading == ShadingArg::Wireframe
}

fn phong(a: &Args) -> bool {
    matches!(
        a.shading,
        ShadingArg::Phong | ShadingArg::FastPhong | ShadingArg::Toon
    )
}

/// The table: for each flag, the scenes and modes that do not use it.
const UNUSED: &[Unused] = &[
    Unused {
        flags: &[
            "--fit",
            "--eye",
            "--target",
            "--up",
            "--fov-y",
            "--near",
            "--far",
            "--ortho",
            "--rotate-x",
            "--rotate-y",
            "--rotate-z",
            "--light",
            "--point-light",
            "--fog",
            "--ambient",
            "--diffuse",
            "--specular",
            "--shininess",
            "--background",
            "--texture",
            "--texture-mode",
            "--normals",
            "--strip",
            "--tone",
            "--exposure",
            "--light-intensity",
            "--pass-triangles",
        ],
        when: shadow,
        why: "applies to a model (--obj, --csg or another --scene), not --scene shadow: a fixed \
              scene (a torus, a cube and a ground square with their own camera, light, colours \
              and materials, at 240x240), which takes --shadow, --shadow-plane, --alpha, \
              --outline, --edges, --edge-color, --crease-angle, --see-through, --shading \
              gouraud|wireframe, --frames, --spin, --number, --format, --dither and --out",
    },
    Unused {
        flags: &["--ram"],
        when: |a| !(shadow(a) && a.budget),
        why: "applies to --scene shadow --budget only (the RAM its shadow methods must fit in)",
    },
    Unused {
        flags: &[
            "--shadow",
            "--shadow-plane",
            "--alpha",
            "--outline",
            "--edges",
            "--edge-color",
            "--crease-angle",
            "--see-through",
            "--shading",
            "--frames",
            "--spin",
            "--format",
            "--dither",
        ],
        when: |a| shadow(a) && a.budget,
        why: "has no effect with --scene shadow --budget, which reports every shadow method of \
              the benchmark scene as scripts/mcu-bench measured it",
    },
    Unused {
        flags: &["--size"],
        when: |a| shadow(a) && a.size != (240, 240),
        why: "other than 240x240: --scene shadow is drawn at 240x240 (the benchmark scene's \
              renderer)",
    },
    Unused {
        flags: &["--shading"],
        when: |a| {
            shadow(a)
                && matches!(
                    a.shading,
                    ShadingArg::Flat | ShadingArg::Phong | ShadingArg::FastPhong | ShadingArg::Toon
                )
        },
        why:
            "flat, phong, fast-phong or toon is not applied to --scene shadow: it draws its torus \
              Gouraud shaded and its ground and cube flat, or everything as a wireframe \
              (--shading gouraud or wireframe)",
    },
    Unused {
        flags: &["--color"],
        when: |a| shadow(a) && !wireframe(a),
        why: "has no effect on --scene shadow: its models keep their own colours (--color is \
              the lines' colour of --shading wireframe)",
    },
    Unused {
        flags: &["--color"],
        when: |a| wireframe(a) && (a.edge_color.is_some() || a.outline.is_some()),
        why: "has no effect here: with --shading wireframe the surfaces are unlit in the \
              background colour and --color is the lines' colour, which --edge-color (or \
              --outline) sets",
    },
    Unused {
        flags: &["--shadow", "--shadow-plane", "--alpha", "--outline"],
        when: |a| !shadow(a),
        why: "applies to --scene shadow only",
    },
    Unused {
        flags: &[
            "--light",
            "--point-light",
            "--ambient",
            "--diffuse",
            "--specular",
            "--shininess",
            "--normals",
            "--tone",
            "--exposure",
            "--light-intensity",
        ],
        when: wireframe,
        why: "has no effect with --shading wireframe: its surfaces are unlit, in the background \
              colour, and its lines are in one colour",
    },
    Unused {
        flags: &["--normals"],
        when: |a| a.shading == ShadingArg::Flat,
        why: "has no effect with --shading flat, which lights faces (vertex normals are not used)",
    },
    Unused {
        flags: &["--shininess"],
        when: |a| a.specular == 0.0,
        why: "is the highlights' exponent: it has no effect without --specular above 0",
    },
    Unused {
        flags: &["--point-light"],
        when: |a| phong(a) && a.point_light.len() > MAX_PHONG_POINT_LIGHTS,
        why: "given more than twice: Phong shading (phong, fast-phong) is lit by the first 2 \
              point lights only",
    },
    Unused {
        flags: &["--dither"],
        when: |a| a.dither == OnOff::On && a.format == FormatArg::Rgb888,
        why: "on has no effect with --format rgb888, which shows every colour (dithering is for \
              rgb565)",
    },
    Unused {
        flags: &["--dither"],
        when: |a| {
            a.dither == OnOff::On
                && !shadow(a)
                && (!matches!(a.shading, ShadingArg::Gouraud | ShadingArg::Toon)
                    || a.texture.is_some())
        },
        why: "on dithers Gouraud gradients and toon tones: it has no effect with --shading \
              flat, phong, fast-phong or wireframe, or with --texture",
    },
    Unused {
        flags: &["--bands"],
        when: |a| a.shading != ShadingArg::Toon,
        why: "sets the tones of --shading toon only",
    },
    Unused {
        flags: &["--dither"],
        when: |a| a.dither == OnOff::On && shadow(a) && wireframe(a),
        why: "on dithers Gouraud gradients: --scene shadow as a wireframe has none",
    },
    Unused {
        flags: &["--crease-angle"],
        when: |a| edges::chosen(a) != EdgesArg::Crease,
        why: "applies to --edges crease only",
    },
    Unused {
        flags: &["--spin"],
        when: |a| a.frames == 1,
        why: "turns the model between frames: it needs --frames 2 or more",
    },
    Unused {
        flags: &["--near", "--far"],
        when: |a| a.fit,
        why: "has no effect with --fit, which places the near and far planes around the model",
    },
    Unused {
        flags: &["--out"],
        when: |a| a.budget,
        why: "has no effect with --budget, which writes no image",
    },
];

/// Refuses every flag the user gave that the chosen scene and modes do not use (a usage error).
pub fn check(args: &Args) -> Result<(), String> {
    for rule in UNUSED {
        if !(rule.when)(args) {
            continue;
        }
        if let Some(flag) = rule.flags.iter().find(|f| args.given(f)) {
            return Err(format!("{flag} {}", rule.why));
        }
    }
    Ok(())
}

/// The values given on the command line that number type `S` cannot hold (usage errors), named
/// by flag, before anything is drawn: a point light's position, the fog's depths.
pub fn check_numbers<S: Scalar>(args: &Args) -> Result<(), String> {
    let hint = |flag: &str, v: f64| {
        let (name, range, other) = match S::NAME {
            "f64" => ("f64", "±1.8e308", ""),
            "f32" => ("f32", "±3.4e38", ", or --number f64"),
            _ => ("fixed", "±32768", ", or --number f32 or f64"),
        };
        let v = if v.abs() >= 1e6 {
            format!("{v:e}")
        } else {
            v.to_string()
        };
        format!(
            "{flag}: {v} is out of the range of {} ({range}) for --number {name}: give a smaller \
             value{other}",
            S::NAME
        )
    };
    let holds = |v: f64| S::from_f64(v).is_valid();
    for p in &args.point_light {
        if let Some(&v) = p.position.iter().find(|&&v| !holds(v)) {
            return Err(hint("--point-light", v));
        }
    }
    if let Some(f) = args.fog {
        for v in [f.near, f.far] {
            if !holds(v) {
                return Err(hint("--fog", v));
            }
        }
        if S::from_f64(f.near) >= S::from_f64(f.far) {
            return Err(format!(
                "--fog: near {} and far {} are the same depth in {}: give depths further apart",
                f.near,
                f.far,
                S::NAME
            ));
        }
    }
    Ok(())
}

/// A light direction given on the command line, scaled by a power of two (exact: the same
/// direction) so that its largest component is within [1/256, 16384) when it is not: a
/// direction is any length, and Q16.16 would saturate a longer one or round a shorter one.
pub fn light_direction(d: [f64; 3]) -> [f64; 3] {
    let m = d.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    if m == 0.0 || (1.0 / 256.0..16384.0).contains(&m) {
        return d;
    }
    let scale = 2f64.powi(-m.log2().floor() as i32);
    d.map(|v| v * scale)
}

/// The first frame in which nothing was drawn because every triangle left after culling and
/// clipping was invalid: (frame, its statistics).
pub fn nothing_drawn(stats: &[Stats]) -> Option<(usize, Stats)> {
    stats
        .iter()
        .position(|s| s.drawn == 0 && s.invalid > 0)
        .map(|k| (k, stats[k]))
}
