//! Bakes an OBJ mesh into Rust source for flash: `static` arrays ready for `include!` —
//! normalized Q16.16 positions with their scale and offset, triangle indices, unit vertex
//! normals in the format the pipeline reads, the bounding box and sphere. Prints the flash
//! size and the quantization error.
//!
//! `cargo run --release --example bake -- model.obj --out model_mesh.rs`

#[path = "../tests/common/mod.rs"]
mod common;

use std::path::PathBuf;

use clap::{Parser, ValueEnum};
use common::obj::{bake, load_obj};

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
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
    /// Vertex normals: averaged from the faces, or the OBJ's own vn [default: file when present]
    #[arg(long, value_enum)]
    normals: Option<NormalsArg>,
}

fn main() {
    let args = Args::parse();
    if let Err(e) = run(&args) {
        eprintln!("bake: {e}");
        std::process::exit(2);
    }
}

fn run(args: &Args) -> Result<(), String> {
    let mesh = load_obj(&args.obj)?;
    let use_file = match args.normals {
        Some(NormalsArg::File) if mesh.normals.is_none() => {
            return Err(format!(
                "{}: --normals file, but the OBJ has no vn for every vertex",
                args.obj.display()
            ));
        }
        Some(NormalsArg::File) => true,
        Some(NormalsArg::FaceAverage) => false,
        None => mesh.normals.is_some(),
    };
    let name = args.obj.file_name().map_or_else(
        || "the OBJ".to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let b = bake(&mesh, use_file, &name);
    let tmp = args.out.with_extension("partial");
    std::fs::write(&tmp, &b.source)
        .and_then(|_| std::fs::rename(&tmp, &args.out))
        .map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            format!("{}: {e}", args.out.display())
        })?;
    println!(
        "{}: {} vertices, {} triangles, {} bytes of flash, largest position error {:.3e} model units (scale {:.6}, offset {:?})",
        args.out.display(),
        mesh.positions.len(),
        mesh.indices.len(),
        b.flash_bytes,
        b.quantization_error,
        b.scale,
        b.offset
    );
    Ok(())
}
