//! `render --scene shadow`: the shadow benchmark scene (`demo::render_shadow_scene`) with the
//! shadow method, the shadow's plane, the torus's opacity, the outlines and edges (`--outline`,
//! `--edges`, `--shading wireframe`) from the command line.

use std::path::Path;

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use scanline3d::fixed::types::I16F16;
use scanline3d::shadow::{ShadowFilter, ShadowMethod};
use scanline3d::{probe::NoProbe, Fx, Scalar, TargetColor};
use scanline3d_support::demo::{render_shadow_scene, EdgeStyle, ShadowScene};

use super::common::Frame;
use super::edges::{self, EdgesArg};
use super::{write_image, Args, FormatArg, NumberArg, OnOff, ShadingArg, ShadowArg};

/// `--shadow-plane`: four finite numbers, the normal not zero.
pub fn plane(s: &str) -> Result<[f64; 4], String> {
    match super::numbers(s)?[..] {
        [a, b, c, d] if (a, b, c) != (0.0, 0.0, 0.0) => Ok([a, b, c, d]),
        _ => Err(format!(
            "{s:?}: expected four finite numbers a,b,c,d (the plane a·x + b·y + c·z + d = 0, (a, b, c) not zero)"
        )),
    }
}

/// Renders the shadow scene with the command line's options to `args.out` (atomically).
pub fn run(args: &Args) -> Result<(), (String, i32)> {
    if args.budget {
        return super::shadow_budget::report(args);
    }
    // The flags this scene does not use are refused by `rules::check`.
    if args.outline.is_some() && args.edge_color.is_some() {
        return Err((
            "--outline and --edge-color both set the lines' colour: give one".into(),
            2,
        ));
    }
    // A wireframe has no shadow unless asked for one.
    let shadow = args
        .shadow
        .unwrap_or(if args.shading == ShadingArg::Wireframe {
            ShadowArg::None
        } else {
            ShadowArg::Projected
        });
    let o = ShadowScene {
        shadow: match shadow {
            ShadowArg::None | ShadowArg::Volume | ShadowArg::Map(..) | ShadowArg::Image(..) => None,
            ShadowArg::Projected => Some(ShadowMethod::Projected),
            ShadowArg::Blob => Some(ShadowMethod::Blob),
        },
        volume: shadow == ShadowArg::Volume,
        outline: match (args.outline, edges::chosen(args)) {
            (Some(c), _) => Some(c),
            (None, EdgesArg::None) => None,
            (None, _) => Some(edges::color(args)),
        },
        edges: match edges::chosen(args) {
            EdgesArg::None | EdgesArg::Silhouette => EdgeStyle::Silhouette,
            EdgesArg::Crease => EdgeStyle::Crease,
            EdgesArg::All => EdgeStyle::All,
        },
        crease_angle: args.crease_angle,
        see_through: args.see_through,
        wireframe: args.shading == ShadingArg::Wireframe,
        plane: args.shadow_plane.unwrap_or([0.0, 1.0, 0.0, 0.0]),
        alpha: args.alpha.unwrap_or(255),
        spin_deg: 0.0,
        dither: args.dither == OnOff::On,
        map: match shadow {
            ShadowArg::Map(size, _) | ShadowArg::Image(size, _) => Some(size),
            _ => None,
        },
        map_filter: match shadow {
            ShadowArg::Map(_, filter) => filter,
            ShadowArg::Image(_, true) => ShadowFilter::Pcf3,
            _ => ShadowFilter::Nearest,
        },
        image: matches!(shadow, ShadowArg::Image(..)),
    };
    if o.map.is_some() && (o.outline.is_some() || o.alpha < 255 || o.wireframe) {
        return Err((
            "--shadow map or image draws a plain frame: it takes no --outline, --edges, --alpha \
             below 255 or --shading wireframe"
                .into(),
            2,
        ));
    }
    match args.format {
        FormatArg::Rgb565 => go::<Rgb565>(args, &o),
        FormatArg::Rgb888 => go::<Rgb888>(args, &o),
    }
}

fn go<C: TargetColor + Into<Rgb888>>(args: &Args, o: &ShadowScene) -> Result<(), (String, i32)> {
    match args.number {
        NumberArg::Fixed => frames::<Fx<I16F16>, C>(args, o),
        NumberArg::F32 => frames::<f32, C>(args, o),
        NumberArg::F64 => frames::<f64, C>(args, o),
    }
}

fn frames<S: Scalar, C: TargetColor + Into<Rgb888>>(
    args: &Args,
    o: &ShadowScene,
) -> Result<(), (String, i32)> {
    let mut out = Vec::new();
    for k in 0..args.frames {
        let mut f = Frame::new(240, 240, C::from_channels([0; 3]));
        let scene = ShadowScene {
            spin_deg: args.spin * k as f64,
            ..*o
        };
        let frame = render_shadow_scene::<S, C, _, _>(&scene, &mut f, &mut NoProbe)
            .map_err(|e| (format!("shadow scene in {}: {e}", S::NAME), 1))?;
        if let Some((_, s)) = super::rules::nothing_drawn(&[frame.stats]) {
            return Err((
                format!(
                    "shadow scene in {}: nothing drawn in frame {k}: all {} triangle(s) left \
                     after culling were invalid (out of the number type's range, NaN or \
                     infinite); no image written",
                    S::NAME,
                    s.invalid
                ),
                1,
            ));
        }
        if k == 0 {
            let s = frame.stats;
            println!(
                "shadow scene ({}, {}): {} triangles drawn of {}, {} fragments, {} pixels written, renderer and layers RAM {} bytes",
                S::NAME,
                match o.shadow {
                    None if o.map.is_some() && o.image => "shadow image",
                    None if o.map.is_some() => "shadow map",
                    None if o.volume => "shadow volumes",
                    None => "no shadow",
                    Some(ShadowMethod::Projected) => "projected shadow",
                    Some(ShadowMethod::Blob) => "blob shadow",
                    Some(_) => "shadow",
                },
                s.drawn,
                s.triangles_in,
                s.fragments,
                s.pixels_written,
                frame.renderer_ram_bytes
            );
        }
        out.push(f);
    }
    write_image(Path::new(&args.out), &out, 100).map_err(|e| (e, 1))?;
    println!("wrote {}", args.out.display());
    Ok(())
}
