//! Bakes an OBJ mesh into Rust source for flash: `static` arrays ready for `include!` —
//! normalized Q16.16 positions with their scale and offset, triangle indices, unit vertex
//! normals in the format the pipeline reads, the bounding box and sphere. Prints the flash
//! size and the quantization error.
//!
//! `--max-triangles N` / `--max-vertices N` first simplify the mesh to that budget with
//! meshoptimizer (and order it: see `common::obj::simplify`), and print the geometric error the
//! simplification introduced; `--obj-out FILE` writes the (simplified) mesh as OBJ, e.g. to
//! preview it with `examples/render.rs`.
//!
//! `cargo run --release --example bake -- model.obj --out model_mesh.rs`
//! `cargo run --release --example bake -- scan.obj --max-triangles 4000 --out scan_mesh.rs --obj-out scan_4k.obj`

#[path = "../tests/common/mod.rs"]
mod common;

use std::path::PathBuf;

use clap::{Parser, ValueEnum};
use common::obj::{bake, parse_obj, simplify, to_obj, write_atomic, NormalSource};

#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
enum NormalsArg {
    FaceAverage,
    File,
}

/// Bakes an OBJ mesh into Rust source with static arrays for flash.
#[derive(Parser, Debug)]
#[command(name = "bake", version)]
struct Args {
    /// The OBJ file
    obj: PathBuf,
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
    let file = parse_obj(&args.obj)?;
    let source = match args.normals {
        Some(NormalsArg::File) => NormalSource::File,
        Some(NormalsArg::FaceAverage) => NormalSource::FaceAverage,
        None => file.default_normals(),
    };
    let mut big = file.mesh(source)?;
    let mut note = String::new();
    if args.max_triangles.is_some() || args.max_vertices.is_some() {
        let s = simplify(&big, args.max_triangles, args.max_vertices)
            .map_err(|e| format!("{}: {e}", file.name))?;
        note = s.summary(&big);
        println!("{}: {note}", file.name);
        big = s.mesh;
    }
    let mesh = big.to_u16(&file.name)?;
    if let Some(path) = &args.obj_out {
        write_atomic(
            path,
            &to_obj(&mesh.positions, mesh.normals.as_deref(), &mesh.indices),
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
    let name = args.obj.file_name().map_or_else(
        || "the OBJ".to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let mut b = bake(&mesh, source == NormalSource::File, &name);
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
    if mesh.positions.len() > 32768 || mesh.indices.len() > 32767 {
        println!(
            "note: more than 32768 vertices or 32767 triangles: no renderer holds this mesh in one frame; simplify it with --max-triangles"
        );
    }
    Ok(())
}
