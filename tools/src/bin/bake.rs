//! Bakes an OBJ mesh into Rust source for flash: `static` arrays ready for `include!` —
//! normalized Q16.16 positions with their scale and offset, triangle indices, unit vertex
//! normals in the format the pipeline reads, the bounding box and sphere, and texture
//! coordinates (`UVS`, `t = 1 − v`) when every face corner has a `vt` (vertices split at texture
//! seams). Prints the flash size and the quantization error.
//!
//! `--max-triangles N` / `--max-vertices N` first simplify the mesh to that budget with
//! meshoptimizer (and order it: see `common::obj::simplify`), and print the geometric error the
//! simplification introduced; `--obj-out FILE` writes the (simplified) mesh as OBJ, e.g. to
//! preview it with `tools/src/bin/render/main.rs`. Texture coordinates follow simplification where
//! meshoptimizer's topology-keeping simplifier reaches the budget; a textured mesh that would
//! need its vertex-clustering one is refused (it joins vertices across seams).
//!
//! `--csg FILE` bakes a CSG tree (tools/src/csg.rs) instead of an OBJ.
//!
//! `--texture FILE.png` bakes an image instead: RGB565 texels (rounded, not cut) and a `static`
//! `scanline3d::Texture` (power-of-two sizes up to 1024; `--wrap repeat|clamp` on both axes;
//! transparent pixels become a colour key, `NAME_KEY`). Prints the size, the flash bytes and
//! the quantization error.
//!
//! `cargo run --release -p scanline3d-tools --bin bake -- model.obj --out model_mesh.rs`
//! `cargo run --release -p scanline3d-tools --bin bake -- scan.obj --max-triangles 4000 --out scan_mesh.rs --obj-out scan_4k.obj`
//! `cargo run --release -p scanline3d-tools --bin bake -- --csg tests/data/part.csg --out part_mesh.rs`
//! `cargo run --release -p scanline3d-tools --bin bake -- --texture bricks.png --out bricks.rs --wrap repeat`

use scanline3d_tools as common;

use std::path::PathBuf;

use clap::{Parser, ValueEnum};
use common::atomic::write_atomic;
use common::csg::load_csg;
use common::obj::{bake_with_uvs, parse_obj, simplify, to_obj_with_uvs, NormalSource};
use common::texture_io::bake_texture;
use scanline3d::Wrap;

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
enum NormalsArg {
    FaceAverage,
    File,
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
enum WrapArg {
    Repeat,
    Clamp,
}

/// Bakes an OBJ mesh, or a PNG texture, into Rust source with static arrays for flash.
#[derive(Parser, Debug)]
#[command(name = "bake", version)]
struct Args {
    /// The OBJ file
    #[arg(required_unless_present_any = ["texture", "csg"], conflicts_with_all = ["texture", "csg"])]
    obj: Option<PathBuf>,
    /// Bake a CSG tree instead (format: tools/src/csg.rs): meshed with mesh booleans, normals
    /// split at edges sharper than 40°
    #[arg(long, value_name = "FILE", conflicts_with_all = ["texture", "normals"])]
    csg: Option<PathBuf>,
    /// Bake this PNG image into an RGB565 texture instead of an OBJ mesh
    #[arg(
        long,
        value_name = "FILE.png",
        conflicts_with_all = ["obj_out", "normals", "max_triangles", "max_vertices"]
    )]
    texture: Option<PathBuf>,
    /// The texture's Rust name, upper-cased [default: from the file name]
    #[arg(long, requires = "texture", conflicts_with = "obj")]
    name: Option<String>,
    /// How the texture wraps outside [0, 1), on both axes [default: repeat]
    #[arg(long, value_enum, requires = "texture", conflicts_with = "obj")]
    wrap: Option<WrapArg>,
    /// Output Rust source file
    #[arg(long, value_name = "FILE", required_unless_present = "obj_out")]
    out: Option<PathBuf>,
    /// Also (or only) write the mesh, simplified if asked, as an OBJ file
    #[arg(long, value_name = "FILE")]
    obj_out: Option<PathBuf>,
    /// Vertex normals: averaged from the faces, or the OBJ's own vn [default: file when present]
    #[arg(long, value_enum)]
    normals: Option<NormalsArg>,
    /// Simplify the mesh to at most this many triangles (meshoptimizer)
    #[arg(long, value_name = "N")]
    max_triangles: Option<usize>,
    /// Simplify the mesh to at most this many vertices (meshoptimizer)
    #[arg(long, value_name = "N")]
    max_vertices: Option<usize>,
}

fn main() {
    let args = Args::parse();
    if let Err(e) = run(&args) {
        eprintln!("bake: {e}");
        std::process::exit(2);
    }
}

fn run(args: &Args) -> Result<(), String> {
    if let Some(png) = &args.texture {
        let wrap = match args.wrap {
            Some(WrapArg::Clamp) => Wrap::Clamp,
            Some(WrapArg::Repeat) | None => Wrap::Repeat,
        };
        // clap requires --out without --obj-out, which --texture excludes.
        let out = args.out.as_ref().ok_or("--texture needs --out")?;
        println!("{}", bake_texture(png, out, args.name.as_deref(), wrap)?);
        return Ok(());
    }
    let (obj, file) = match (&args.obj, &args.csg) {
        (Some(obj), _) => (obj, parse_obj(obj)?),
        (_, Some(csg)) => (csg, load_csg(csg)?.to_obj_file(&csg.display().to_string())),
        _ => return Err("give an OBJ file, --csg FILE or --texture".into()),
    };
    let source = match args.normals {
        Some(NormalsArg::File) => NormalSource::File,
        Some(NormalsArg::FaceAverage) => NormalSource::FaceAverage,
        None => file.default_normals(),
    };
    let uvs = file.uvs_present()?;
    let mut big = file.mesh_with(source, uvs)?;
    let mut note = String::new();
    if args.max_triangles.is_some() || args.max_vertices.is_some() {
        let s = simplify(&big, args.max_triangles, args.max_vertices)
            .map_err(|e| format!("{}: {e}", file.name))?;
        note = s.summary(&big);
        println!("{}: {note}", file.name);
        big = s.mesh;
    }
    let mesh = big.to_u16(&file.name)?;
    let uvs = big.uvs.as_deref();
    if let Some(path) = &args.obj_out {
        write_atomic(
            path,
            &to_obj_with_uvs(&mesh.positions, mesh.normals.as_deref(), uvs, &mesh.indices),
        )?;
        println!(
            "{}: {} vertices, {} triangles",
            path.display(),
            mesh.positions.len(),
            mesh.indices.len()
        );
    }
    let Some(out) = &args.out else {
        return Ok(());
    };
    let name = obj.file_name().map_or_else(
        || "the OBJ".to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let mut b = bake_with_uvs(&mesh, uvs, source == NormalSource::File, &name);
    if !note.is_empty() {
        b.source = b
            .source
            .replacen("\n//\n", &format!("\n// {note}\n//\n"), 1);
    }
    write_atomic(out, &b.source)?;
    println!(
        "{}: {} vertices, {} triangles, {} bytes of flash, largest position error {:.3e} model units (scale {:.6}, offset {:?})",
        out.display(),
        mesh.positions.len(),
        mesh.indices.len(),
        b.flash_bytes,
        b.quantization_error,
        b.scale,
        b.offset
    );
    if let Some(uvs) = uvs {
        println!(
            "{}: {} texture coordinates (UVS, one per vertex: vertices split where faces meet with different vt)",
            out.display(),
            uvs.len()
        );
    }
    if mesh.positions.len() > 32768 || mesh.indices.len() > 32767 {
        println!(
            "note: more than 32768 vertices or 32767 triangles: no renderer holds this mesh in one frame; simplify it with --max-triangles"
        );
    }
    Ok(())
}
