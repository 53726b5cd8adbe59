//! The images `render` writes (atomically) and their comparison with the f64 reference; the
//! pieces a frame too large for one renderer is drawn in.

use super::*;

/// Writes PNG, animated PNG or GIF to a temporary name, then renames: never a half-written file.
pub(crate) fn write_image<C: PixelColor + Into<Rgb888>>(
    path: &Path,
    frames: &[Frame<C>],
    delay_ms: u16,
) -> Result<(), String> {
    let name = path.display();
    let tmp = path.with_extension("partial");
    let result = (|| -> Result<(), String> {
        let file = std::fs::File::create(&tmp).map_err(|e| format!("{name}: {e}"))?;
        let (w, h) = (frames[0].w, frames[0].h);
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or("")
            .to_ascii_lowercase();
        match ext.as_str() {
            "gif" => {
                let mut enc = gif::Encoder::new(file, w as u16, h as u16, &[])
                    .map_err(|e| format!("{name}: {e}"))?;
                enc.set_repeat(gif::Repeat::Infinite)
                    .map_err(|e| format!("{name}: {e}"))?;
                for f in frames {
                    let mut fr =
                        gif::Frame::from_rgb_speed(w as u16, h as u16, &f.rgb888_bytes(), 10);
                    fr.delay = delay_ms / 10;
                    enc.write_frame(&fr).map_err(|e| format!("{name}: {e}"))?;
                }
            }
            "png" => {
                let mut enc = png::Encoder::new(std::io::BufWriter::new(file), w, h);
                enc.set_color(png::ColorType::Rgb);
                enc.set_depth(png::BitDepth::Eight);
                if frames.len() > 1 {
                    enc.set_animated(frames.len() as u32, 0)
                        .map_err(|e| format!("{name}: {e}"))?;
                    enc.set_frame_delay(delay_ms, 1000)
                        .map_err(|e| format!("{name}: {e}"))?;
                }
                let mut wr = enc.write_header().map_err(|e| format!("{name}: {e}"))?;
                for f in frames {
                    wr.write_image_data(&f.rgb888_bytes())
                        .map_err(|e| format!("{name}: {e}"))?;
                }
                wr.finish().map_err(|e| format!("{name}: {e}"))?;
            }
            _ => return Err(format!("{name}: the output must end in .png or .gif")),
        }
        Ok(())
    })();
    match result {
        Ok(()) => std::fs::rename(&tmp, path).map_err(|e| format!("{name}: {e}")),
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(e)
        }
    }
}

pub(crate) fn compare<C: RgbColor>(a: &[Frame<C>], b: &[Frame<C>], background: C) -> Metrics {
    let mut m = Metrics::new([C::MAX_R, C::MAX_G, C::MAX_B]);
    for (fa, fb) in a.iter().zip(b.iter()) {
        for y in 0..fa.h as usize {
            let r = y * fa.w as usize..(y + 1) * fa.w as usize;
            m.add_line(&fa.px[r.clone()], &fb.px[r], background);
        }
    }
    m
}

/// A piece of the mesh for one pass: consecutive triangles, with their own vertex arrays.
pub(crate) struct Piece<S> {
    pub(crate) positions: Vec<[S; 3]>,
    pub(crate) normals: Vec<[S; 3]>,
    pub(crate) indices: Vec<[u16; 3]>,
}

/// The triangles `tris` with only the vertices they use, renumbered in order of first use.
/// `map` (one entry per mesh vertex, all `u32::MAX`) is left as it was found.
pub(crate) fn piece<S: Copy>(
    positions: &[[S; 3]],
    normals: &[[S; 3]],
    tris: &[[u16; 3]],
    map: &mut [u32],
) -> Piece<S> {
    let mut p = Piece {
        positions: Vec::new(),
        normals: Vec::new(),
        indices: Vec::with_capacity(tris.len()),
    };
    for t in tris {
        p.indices.push(t.map(|i| {
            let slot = &mut map[i as usize];
            if *slot == u32::MAX {
                *slot = p.positions.len() as u32;
                p.positions.push(positions[i as usize]);
                p.normals.push(normals[i as usize]);
            }
            *slot as u16
        }));
    }
    for t in tris {
        for &i in t {
            map[i as usize] = u32::MAX;
        }
    }
    p
}

pub(crate) fn piece_mesh<'a, S: Scalar>(m: &Model, p: &'a Piece<S>) -> Result<Mesh<'a, S>, String> {
    Mesh::new(&p.positions, &p.indices)
        .and_then(|mesh| mesh.with_normals(&p.normals))
        .map_err(|e| format!("{}: {e}", m.name))
}

/// Splits the mesh into pieces of consecutive triangles that each fit one renderer in this
/// frame (pieces of `first_pieces` triangles, each halved until it fits), in mesh order, with
/// each piece's needs.
pub(crate) fn plan<S: Scalar, C: TargetColor>(
    r: &mut Layered<S, C>,
    m: &Model,
    pos: &[[S; 3]],
    nor: &[[S; 3]],
    fs: &FrameSetup<'_, S>,
    first_pieces: usize,
) -> Result<Vec<(Piece<S>, Needs)>, String> {
    let mut map = vec![u32::MAX; pos.len()];
    let n = m.indices.len();
    let step = first_pieces.clamp(1, n.max(1));
    // Pieces of `step` triangles, the first on top of the stack.
    let mut todo: Vec<_> = (0..n.div_ceil(step))
        .rev()
        .map(|k| k * step..n.min((k + 1) * step))
        .collect();
    let mut out = Vec::new();
    while let Some(range) = todo.pop() {
        let p = piece(pos, nor, &m.indices[range.clone()], &mut map);
        let objects = fs.object(piece_mesh(m, &p)?);
        let measured = match r.needs(&fs.scene(&objects)) {
            Ok(n) => n,
            // Not measured exactly: the piece is too large, and is split.
            Err(Error::Shortfall(_)) => Needs::new(usize::MAX, usize::MAX, usize::MAX),
            Err(e) => return Err(format!("{}: {e}", m.name)),
        };
        if measured.fits(&LIMIT) {
            out.push((p, measured));
        } else if range.len() > 1 {
            let mid = range.start + range.len() / 2;
            // A stack: the first half is taken next, so the pieces stay in mesh order.
            todo.push(mid..range.end);
            todo.push(range.start..mid);
        } else {
            return Err(format!(
                "{}: triangle {} alone does not fit a renderer ({measured:?})",
                m.name, range.start
            ));
        }
    }
    Ok(out)
}
