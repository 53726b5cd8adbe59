//! The `render` example's command line (issue 40): every flag it accepts is applied or refused
//! with a message naming the flag (exit status 2, no image written); a frame in which every
//! triangle is invalid is an error (exit status 1, no image); negative and out-of-range numbers
//! get a range message, not clap's "unexpected argument"; `--help` states units and defaults.
//!
//! Each case runs the built example as a process (cargo builds the examples before the
//! integration tests).

use scanline3d_tools as common;
mod shared;

use std::path::PathBuf;

fn tmp(name: &str) -> PathBuf {
    shared::tmp("render_cli", name)
}

fn run(args: &[&str]) -> (i32, String, String) {
    shared::run("render", args)
}

/// Runs `args` writing to a fresh file `name`: exit status, stderr, and the image if written.
fn image(args: &[&str], name: &str) -> (i32, String, Option<Vec<u8>>) {
    let out = tmp(name);
    let _ = std::fs::remove_file(&out);
    let mut all = args.to_vec();
    all.extend(["--out", out.to_str().unwrap()]);
    let (code, stdout, stderr) = run(&all);
    assert!(
        !stderr.contains("panicked") && code != 101 && code != 3,
        "render {args:?}: {stdout}{stderr}"
    );
    (code, stderr, std::fs::read(&out).ok())
}

/// `args` is refused as a usage error (exit status 2) naming every string of `expect`, with
/// nothing written.
fn refused(args: &[&str], expect: &[&str]) {
    let (code, stderr, png) = image(args, "refused.png");
    assert_eq!(code, 2, "render {args:?} should be refused: {stderr}");
    for e in expect {
        assert!(
            stderr.contains(e),
            "render {args:?}: {stderr:?} lacks {e:?}"
        );
    }
    assert!(
        !stderr.contains("unexpected argument"),
        "render {args:?}: {stderr}"
    );
    assert!(png.is_none(), "render {args:?}: an image was written");
}

/// The file's path as a string.
fn data(name: &str) -> String {
    shared::data(name).display().to_string()
}

#[test]
fn shadow_scene_refuses_the_model_flags_it_ignored() {
    // Main: exit 0 and a PNG byte-identical to the default for each of these.
    let texture = data("checker8.png");
    for flag in [
        &["--light", "1,1,1"][..],
        &["--texture", &texture],
        &["--fog", "1,5,255,0,0"],
        &["--point-light", "1,1,1"],
        &["--background", "0,0,255"],
        &["--eye", "0,2,3"],
        &["--target", "0.2,0,0"],
        &["--up", "1,1,0"],
        &["--fov-y", "30"],
        &["--near", "1"],
        &["--far", "5"],
        &["--ortho", "3"],
        &["--fit"],
        &["--rotate-x", "0"],
        &["--rotate-z", "30"],
        &["--ambient", "0.5"],
        &["--diffuse", "0.3"],
        &["--specular", "0.8"],
        &["--normals", "face-average"],
        &["--strip", "4"],
        &["--exposure", "0.5"],
    ] {
        let args = [&["--scene", "shadow"][..], flag].concat();
        refused(&args, &[flag[0], "not --scene shadow"]);
    }
    refused(
        &["--scene", "shadow", "--shading", "phong"],
        &["--shading", "phong", "--scene shadow"],
    );
    refused(
        &["--scene", "shadow", "--shading", "flat"],
        &["--shading", "--scene shadow"],
    );
    refused(
        &["--scene", "shadow", "--color", "1,2,3"],
        &["--color", "--scene shadow"],
    );
    refused(
        &["--scene", "shadow", "--size", "120x120"],
        &["--size", "240x240"],
    );
    refused(
        &["--scene", "shadow", "--shadow", "map,48"],
        &["map[,SIZE[,FILTER]]", "32, 64 or 128"],
    );
    for bad in [
        "map,64,pcf4",
        "map,64,pcf,1",
        "image,64,pcf",
        "image,16",
        "maps",
    ] {
        refused(
            &["--scene", "shadow", "--shadow", bad],
            &["image[,SIZE[,blur]]", "pcf3"],
        );
    }
    refused(
        &["--scene", "shadow", "--shadow", "map", "--alpha", "100"],
        &["--shadow map or image draws a plain frame"],
    );
    // --ram is --scene shadow --budget's only; the scene's drawing flags are not taken there.
    refused(
        &["--scene", "shadow", "--ram", "1000"],
        &["--ram", "--budget only"],
    );
    refused(
        &["--scene", "shadow", "--budget", "--shadow", "map"],
        &["--shadow", "every shadow method"],
    );
    // What the scene takes is applied: a different image from the default.
    let (code, stderr, base) = image(&["--scene", "shadow"], "shadow_base.png");
    assert_eq!(code, 0, "{stderr}");
    for args in [
        &["--shadow", "blob"][..],
        &["--shadow", "map"],
        &["--shadow", "map,32"],
        &["--shadow", "map,64,pcf"],
        &["--shadow", "map,128,pcf3"],
        &["--shadow", "image"],
        &["--shadow", "image,32,blur"],
        &["--shadow-plane", "0.3,1,0,0.3"],
        &["--alpha", "150"],
        &["--shadow", "none", "--outline", "255,0,0"],
        &["--shadow", "none", "--edges", "all"],
        &["--dither", "on"],
        &["--shading", "wireframe"],
        &["--format", "rgb888"],
    ] {
        let all = [&["--scene", "shadow"][..], args].concat();
        let (code, stderr, png) = image(&all, "shadow_applied.png");
        assert_eq!(code, 0, "{all:?}: {stderr}");
        assert_ne!(png, base, "{all:?}: the same image as the default");
    }
    // The soft and depth-less variants differ from the nearest map and from each other.
    let map = |a: &str| image(&["--scene", "shadow", "--shadow", a], &format!("{a}.png")).2;
    let variants = ["map", "map,64,pcf", "map,64,pcf3", "image", "image,64,blur"].map(map);
    for i in 0..variants.len() {
        for j in i + 1..variants.len() {
            assert_ne!(variants[i], variants[j], "variants {i} and {j}");
        }
    }
    // --budget: every method with its measured RAM and instructions, the cheapest that fits.
    let (code, stdout, stderr) = run(&["--scene", "shadow", "--budget"]);
    assert_eq!(code, 0, "{stderr}");
    for s in [
        "shadow_map_pcf3",
        "shadow_image_blur",
        "cheapest that fits: --shadow ",
        "270336",
    ] {
        assert!(stdout.contains(s), "{stdout} lacks {s:?}");
    }
    // Nothing fits in 1000 bytes: exit 1, naming the smallest method.
    let (code, _, stderr) = run(&["--scene", "shadow", "--budget", "--ram", "1000"]);
    assert_eq!(code, 1, "{stderr}");
    assert!(
        stderr.contains("no shadow method fits in 1000 bytes: the smallest"),
        "{stderr}"
    );
    let (code, _, stderr) = run(&["--scene", "shadow", "--budget", "--number", "f64"]);
    assert_eq!(code, 2, "{stderr}");
    // --color is the lines' colour of the wireframe; --edge-color replaces it.
    let wire = ["--scene", "shadow", "--shading", "wireframe"];
    let (_, _, plain) = image(&wire, "shadow_wire.png");
    let (code, stderr, colored) = image(&[&wire[..], &["--color", "255,0,0"]].concat(), "w.png");
    assert_eq!(code, 0, "{stderr}");
    assert_ne!(plain, colored);
    refused(
        &[&wire[..], &["--edge-color", "1,1,1", "--color", "255,0,0"]].concat(),
        &["--color", "--edge-color"],
    );
}

#[test]
fn flags_without_effect_in_the_chosen_mode_are_refused() {
    // Main: each accepted with exit 0 and an image byte-identical to the one without it.
    let texture = data("checker8.png");
    let cases: &[(&[&str], &[&str])] = &[
        // A wireframe's surfaces are unlit.
        (
            &["--shading", "wireframe", "--light", "1,1,1"],
            &["--light", "--shading wireframe"],
        ),
        (
            &["--shading", "wireframe", "--point-light", "1,1,1"],
            &["--point-light", "--shading wireframe"],
        ),
        (
            &["--shading", "wireframe", "--ambient", "0.5"],
            &["--ambient", "--shading wireframe"],
        ),
        (
            &["--shading", "wireframe", "--specular", "0.5"],
            &["--specular", "--shading wireframe"],
        ),
        (
            &["--shading", "wireframe", "--tone", "filmic"],
            &["--tone", "--shading wireframe"],
        ),
        (
            &["--shading", "wireframe", "--light-intensity", "2"],
            &["--light-intensity", "--shading wireframe"],
        ),
        (
            &[
                "--shading",
                "wireframe",
                "--edge-color",
                "1,1,1",
                "--color",
                "1,2,3",
            ],
            &["--color", "--edge-color"],
        ),
        // Flat shading lights faces.
        (
            &["--shading", "flat", "--normals", "face-average"],
            &["--normals", "--shading flat"],
        ),
        // The highlights' exponent without highlights.
        (&["--shininess", "40"], &["--shininess", "--specular"]),
        // Phong takes two point lights.
        (
            &[
                "--shading",
                "phong",
                "--point-light",
                "1,1,1",
                "--point-light",
                "0,1,2",
                "--point-light",
                "-1,1,1",
            ],
            &["--point-light", "first 2"],
        ),
        // Dithering is of Gouraud gradients in RGB565.
        (
            &["--dither", "on", "--format", "rgb888"],
            &["--dither", "rgb888"],
        ),
        (
            &["--dither", "on", "--shading", "flat"],
            &["--dither", "Gouraud"],
        ),
        (
            &["--dither", "on", "--shading", "phong"],
            &["--dither", "Gouraud"],
        ),
        (
            &["--dither", "on", "--texture", &texture],
            &["--dither", "--texture"],
        ),
        (
            &[
                "--scene",
                "shadow",
                "--shading",
                "wireframe",
                "--dither",
                "on",
            ],
            &["--dither", "wireframe"],
        ),
        // The crease angle without crease edges.
        (
            &["--crease-angle", "10"],
            &["--crease-angle", "--edges crease"],
        ),
        (
            &["--edges", "all", "--crease-angle", "10"],
            &["--crease-angle", "--edges crease"],
        ),
        (
            &["--scene", "shadow", "--crease-angle", "10"],
            &["--crease-angle", "--edges crease"],
        ),
        // The spin of one frame.
        (&["--spin", "45"], &["--spin", "--frames 2"]),
        (
            &["--scene", "shadow", "--spin", "45"],
            &["--spin", "--frames 2"],
        ),
        // --fit places the near and far planes.
        (&["--fit", "--near", "1"], &["--near", "--fit"]),
        (&["--fit", "--far", "5"], &["--far", "--fit"]),
        // The shadow scene's flags on a model.
        (&["--alpha", "100"], &["--alpha", "--scene shadow only"]),
        (&["--shadow", "blob"], &["--shadow", "--scene shadow only"]),
    ];
    for (args, expect) in cases {
        refused(args, expect);
    }
    // --budget writes no image.
    let out = tmp("budget.png");
    let (code, _, stderr) = run(&["--budget", "--out", out.to_str().unwrap()]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("--out") && stderr.contains("--budget"),
        "{stderr}"
    );
    // The same flags where they apply: accepted, and the image changes.
    let applied: &[(&[&str], &[&str])] = &[
        (&["--shading", "flat"], &["--specular", "0.8"]),
        (&["--specular", "0.8"], &["--shininess", "40"]),
        (
            &["--shading", "flat", "--specular", "0.8"],
            &["--shininess", "40"],
        ),
        (&[], &["--normals", "face-average"]),
        (&["--edges", "crease"], &["--crease-angle", "10"]),
        (&["--frames", "2"], &["--spin", "45"]),
        (&["--shading", "wireframe"], &["--color", "1,200,3"]),
        (&["--shading", "wireframe"], &["--fog", "2,3.3,255,0,0"]),
        (&[], &["--dither", "on"]),
        (&["--fit"], &["--eye", "3,0,0"]),
        (
            &["--shading", "phong", "--point-light", "1,1,1"],
            &["--point-light", "0,1,2"],
        ),
    ];
    for (base, flag) in applied {
        let (code, stderr, a) = image(base, "base.png");
        assert_eq!(code, 0, "{base:?}: {stderr}");
        let all = [*base, *flag].concat();
        let (code, stderr, b) = image(&all, "with_flag.png");
        assert_eq!(code, 0, "{all:?}: {stderr}");
        assert_ne!(a, b, "{all:?}: {flag:?} changed nothing");
    }
}

#[test]
fn ortho_refuses_fov_y_and_scales_the_fitted_view() {
    // Main: --fov-y silently ignored.
    refused(&["--ortho", "3", "--fov-y", "10"], &["--ortho", "--fov-y"]);
    // With --fit, --ortho is a factor on the fitted height (main: ignored, the same image for
    // any height).
    let obj = data("torus.obj");
    let fitted = |h: &str| {
        let (code, stderr, png) = image(
            &["--obj", &obj, "--fit", "--ortho", h, "--format", "rgb888"],
            &format!("ortho_{h}.png"),
        );
        assert_eq!(code, 0, "{stderr}");
        assert!(png.is_some());
        let (_, _, rgb) = common::read_png(&tmp(&format!("ortho_{h}.png"))).expect("a PNG");
        rgb.chunks_exact(3).filter(|p| p != &[0, 0, 0]).count()
    };
    let (one, double) = (fitted("1"), fitted("2"));
    // Twice the view height: the model covers about a quarter of the pixels.
    assert!(one > 3 * double && double > 0, "{one} vs {double}");
}

#[test]
fn a_frame_with_every_triangle_invalid_is_an_error() {
    // Main: exit 0, a blank image and only "invalid 1" on the summary line.
    let obj = tmp("far_vertex.obj");
    std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1e30 0\nf 1 2 3\n").unwrap();
    let o = obj.to_str().unwrap();
    let (code, stderr, png) = image(&["--obj", o], "far_vertex.png");
    assert_eq!(code, 1, "{stderr}");
    for part in ["nothing drawn", "invalid", "I16F16", "no image written"] {
        assert!(stderr.contains(part), "{stderr:?} lacks {part:?}");
    }
    assert!(png.is_none(), "an image was written");
    // The same triangle is drawn in f32.
    let (code, stderr, png) = image(&["--obj", o, "--number", "f32"], "far_vertex_f32.png");
    assert_eq!(code, 0, "{stderr}");
    assert!(png.is_some());
    // Main: `--point-light 1e30,1,1` drew nothing (every triangle invalid) with exit 0. Refused
    // up front now, naming the flag and the number type's range.
    refused(
        &["--point-light", "1e30,1,1"],
        &["--point-light", "1e30", "I16F16", "±32768"],
    );
    refused(
        &["--point-light", "40000,0,1"],
        &["--point-light", "40000", "I16F16"],
    );
    refused(
        &["--point-light", "1e39,0,0", "--number", "f32"],
        &["--point-light", "f32"],
    );
    let (code, stderr, _) = image(&["--point-light", "1e30,1,1", "--number", "f64"], "pl.png");
    assert_eq!(code, 0, "{stderr}");
    refused(&["--fog", "1,40000,255,0,0"], &["--fog", "40000", "I16F16"]);
    refused(
        &["--fog", "1,1.000001,255,0,0"],
        &["--fog", "the same depth", "I16F16"],
    );
    refused(&["--point-light", "nan,1,1"], &["--point-light", "finite"]);
    refused(&["--light", "inf,1,1"], &["--light", "finite"]);
    refused(&["--fog", "1,inf,0,0,0"], &["--fog", "finite"]);
    // A light direction is any length: a very long or very short one is the same direction
    // (main: 1e-30,0,0 rounded to zero in Q16.16 and lit nothing; 1e30,1,1 saturated).
    let (_, _, unit) = image(&["--light", "1,0,0"], "light_unit.png");
    for d in ["1e-30,0,0", "1e30,0,0", "0.001,0,0", "40000,0,0"] {
        let (code, stderr, png) = image(&["--light", d], "light_scaled.png");
        assert_eq!(code, 0, "--light {d}: {stderr}");
        assert_eq!(png, unit, "--light {d}: not the image of --light 1,0,0");
    }
}

#[test]
fn negative_and_out_of_range_numbers_get_a_range_message() {
    // Main: clap's "unexpected argument '-1' found" for most of these.
    let obj = data("torus.obj");
    let cases: &[(&[&str], &[&str])] = &[
        (&["--size", "-1x5"], &["--size", "integers 1-1024", "-1"]),
        (&["--size", "240x-5"], &["--size", "integers 1-1024"]),
        (&["--size", "2000x240"], &["--size", "integers 1-1024"]),
        (&["--color", "-1,2,3"], &["--color", "0-255", "-1"]),
        (&["--color", "1,2,300"], &["--color", "0-255", "300"]),
        (&["--background", "-1,0,0"], &["--background", "0-255"]),
        (
            &["--edges", "all", "--edge-color", "-5,0,0"],
            &["--edge-color", "0-255"],
        ),
        (
            &["--scene", "shadow", "--outline", "-5,0,0"],
            &["--outline", "0-255"],
        ),
        (
            &["--shininess", "-1"],
            &["--shininess must be in [1, 255], got -1"],
        ),
        (
            &["--shininess", "300"],
            &["--shininess must be in [1, 255], got 300"],
        ),
        (
            &["--scene", "shadow", "--alpha", "-1"],
            &["--alpha must be in [0, 255], got -1"],
        ),
        (
            &["--frames", "-1"],
            &["--frames must be in [1, 1000], got -1"],
        ),
        (
            &["--frames", "2.5"],
            &["--frames must be in [1, 1000], got 2.5"],
        ),
        (&["--exposure", "-1"], &["--exposure must be", "got -1"]),
        (
            &["--edges", "crease", "--crease-angle", "-1"],
            &["--crease-angle must be in [0, 180] degrees, got -1"],
        ),
        (
            &["--light-intensity", "-1"],
            &["--light-intensity must be in [0, 16], got -1"],
        ),
        (&["--strip", "-1"], &["--strip must be in [1, ", "got -1"]),
        (
            &["--obj", &obj, "--max-triangles", "-5"],
            &["--max-triangles must be an integer ≥ 1, got -5"],
        ),
        (
            &["--obj", &obj, "--max-vertices", "-5"],
            &["--max-vertices must be an integer ≥ 3, got -5"],
        ),
        (
            &["--pass-triangles", "-5"],
            &["--pass-triangles must be an integer ≥ 1, got -5"],
        ),
        (
            &["--fov-y", "-10"],
            &["--fov-y must be in (0, 180) degrees"],
        ),
        (&["--near", "-1"], &["--near must be greater than 0"]),
        (&["--far", "-1"], &["--far must be greater than --near"]),
        (&["--ortho", "-1"], &["--ortho", "greater than 0"]),
        (
            &["--ambient", "-1"],
            &["--ambient must be in [0, 255], got -1"],
        ),
        (
            &["--diffuse", "-1"],
            &["--diffuse must be in [0, 255], got -1"],
        ),
        (
            &["--specular", "-1"],
            &["--specular must be in [0, 255], got -1"],
        ),
        (
            &["--point-light", "1,1,1,255,255,255,-1,0,0"],
            &["--point-light", "attenuation"],
        ),
        (
            &["--point-light", "1,1,1,-1,0,0"],
            &["--point-light", "0-255"],
        ),
        (&["--fog", "-1,-5,0,0,0"], &["--fog", "near depth"]),
        (
            &["--scene", "shadow", "--shadow-plane", "0,0,0,-1"],
            &["--shadow-plane", "not zero"],
        ),
    ];
    for (args, expect) in cases {
        refused(args, expect);
    }
    // Negative values where they are valid.
    for args in [
        &["--rotate-x", "-30"][..],
        &["--frames", "2", "--spin", "-10"],
        &["--eye", "-1,1.2,3"],
        &["--light", "-1,-1,-1"],
        &["--point-light", "-1,1,1"],
        &["--fog", "-5,4,0,0,0"],
        &["--scene", "shadow", "--shadow-plane", "0,1,0,-0.2"],
    ] {
        let (code, stderr, png) = image(args, "negative_ok.png");
        assert_eq!(code, 0, "{args:?}: {stderr}");
        assert!(png.is_some(), "{args:?}");
    }
}

/// The `--help` entry of each flag: (flag, its text).
fn help_entries() -> Vec<(String, String)> {
    let (code, help, stderr) = run(&["--help"]);
    assert_eq!(code, 0, "{stderr}");
    let mut out: Vec<(String, String)> = Vec::new();
    for line in help.lines() {
        let t = line.trim_start();
        if t.starts_with("--") && line.starts_with("      --") {
            let flag = t.split([' ', '=']).next().unwrap().to_string();
            out.push((flag, t.to_string()));
        } else if t.starts_with("-h, --help") || t.starts_with("-V, --version") {
            out.push((t.to_string(), String::new()));
        } else if let Some(last) = out.last_mut() {
            last.1.push(' ');
            last.1.push_str(t);
        }
    }
    out
}

#[test]
fn help_states_units_and_defaults() {
    let entries = help_entries();
    assert!(entries.len() > 40, "{entries:?}");
    let entry = |flag: &str| {
        entries
            .iter()
            .find(|(f, _)| f == flag)
            .unwrap_or_else(|| panic!("no {flag} in --help"))
            .1
            .clone()
    };
    // Main: "Ambient coefficient, 0-255" (a coefficient, with 1 the full colour).
    for flag in ["--ambient", "--diffuse", "--specular"] {
        let e = entry(flag);
        assert!(!e.contains("0-255"), "{flag}: {e}");
        assert!(e.contains("0 to 255") && e.contains("1 = "), "{flag}: {e}");
    }
    // Every flag that takes a value states its default.
    for (flag, text) in &entries {
        if text.contains(&format!("{flag} <")) {
            assert!(text.contains("[default"), "{flag}: no default in {text:?}");
        }
    }
    // Units.
    for (flag, unit) in [
        ("--size", "pixels"),
        ("--eye", "world units"),
        ("--fov-y", "degrees"),
        ("--near", "world units"),
        ("--far", "world units"),
        ("--ortho", "world units"),
        ("--rotate-x", "degrees"),
        ("--spin", "degrees"),
        ("--crease-angle", "degrees"),
        ("--strip", "Lines"),
        ("--point-light", "world units"),
        ("--fog", "world units"),
        ("--color", "0-255"),
        ("--shininess", "1-255"),
        ("--alpha", "0-255"),
        ("--frames", "1-1000"),
        ("--exposure", "16"),
        ("--light-intensity", "0 to 16"),
    ] {
        let e = entry(flag);
        assert!(e.contains(unit), "{flag}: {unit:?} not in {e:?}");
    }
}
