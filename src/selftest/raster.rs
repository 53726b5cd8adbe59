//! The raster kernels against their portable twins: the edge setup, the attribute setup, the
//! triangle setup, the dither check, the dithered span and the row routine.

use super::*;

/// For the benchmark firmware (compiled, and run by the host tests, on every target): the assembly edge setup against the portable
/// one on `n` pseudo-random edges (coordinates over the whole snapped range, rows at and past
/// the upper vertex). Returns the inputs `[xa, ya, xb, yb, row]` of the first mismatch.
#[doc(hidden)]
pub fn edge_setup_self_test(n: u32) -> Option<[i32; 5]> {
    let mut next = xorshift32(0x9e37_79b9u32);
    let lim = crate::geometry::project::COORD_LIMIT;
    for i in 0..n {
        let (r1, r2, r3) = (next(), next(), next());
        // Short and long edges, steep and flat, every sign.
        let span = [15, 255, 4095, 2 * lim][(r3 >> 30) as usize];
        let xa = (r1 % (2 * lim as u32 + 1)) as i32 - lim;
        let ya = ((r1 >> 16) % (2 * lim as u32 + 1)) as i32 - lim;
        let xb = (xa + (r2 % (2 * span as u32 + 1)) as i32 - span).clamp(-lim, lim);
        let yb = (ya + ((r2 >> 16) % (span as u32 + 1)) as i32).min(lim);
        // The row of the upper vertex's first sample or a later one of the edge (some
        // beyond it, which the assembly declines).
        let first = first_pixel(ya);
        let row = (first + (r3 % 8) as i32 * (i % 3) as i32).clamp(0, 1024);
        let want = Edge::new_portable(xa, ya, xb, yb, row);
        if let Some(got) = kernel::edge_new(xa, ya, xb, yb, row) {
            if got != want {
                return Some([xa, ya, xb, yb, row]);
            }
        }
    }
    None
}

/// For the benchmark firmware (compiled, and run by the host tests, on every target): the assembly Gouraud setup
/// (`kernel::gouraud_setup`) against the portable [`attribute_words`] for RGB565 on `n`
/// pseudo-random triangles (small and large, every orientation, any depths and colours,
/// first rows and left edges at and around the first vertex). Returns the first mismatching
/// triangle's vertices `[x, y, depth, colour]` (the colour's three 10-bit channels packed)
/// and `[row, left column, left step]`.
#[doc(hidden)]
#[allow(clippy::type_complexity)]
pub fn gouraud_setup_self_test(n: u32) -> Option<([[i32; 4]; 3], [i32; 3])> {
    use embedded_graphics_core::pixelcolor::Rgb565;
    let mut next = xorshift32(0x6a09_e667u32);
    let lim = crate::geometry::project::COORD_LIMIT;
    for i in 0..n {
        let size = [64u32, 512, 4096, 2 * lim as u32][(i % 4) as usize];
        let (ox, oy) = ((next() % 4096) as i32 - 2048, (next() % 4096) as i32 - 2048);
        let mut v = [ScreenVertex::default(); 3];
        for p in &mut v {
            let r = next();
            p.x = (ox + (r % (size + 1)) as i32 - size as i32 / 2).clamp(-lim, lim) as i16;
            p.y = (oy + ((r >> 16) % (size + 1)) as i32 - size as i32 / 2).clamp(-lim, lim) as i16;
            random_depth_and_colour(p, &mut next);
        }
        v.sort_unstable_by_key(|p| p.y);
        let [a, b, c] = &v;
        let det = (b.x as i32 - a.x as i32) * (c.y as i32 - a.y as i32)
            - (c.x as i32 - a.x as i32) * (b.y as i32 - a.y as i32);
        if det == 0 {
            continue;
        }
        let r = next();
        let row = first_pixel(a.y as i32) + (r % 16) as i32;
        let left_c = (a.x as i32 >> 4) + ((r >> 8) % 64) as i32 - 32;
        let left_sq = ((r >> 16) % 512) as i32 - 256;
        let tri = Sorted {
            v: [a, b, c],
            det,
            row,
            left_c,
            left_sq,
        };
        // The routine's precondition, which a first pixel of the left edge (within a pixel of
        // the triangle) meets: every colour plane at the first pixel within ±2³⁰ (20
        // fraction bits), so that its 32-bit value has not wrapped. Random first pixels far
        // from a small triangle can break it.
        let (dx, dy) = (16 * left_c + 8 - a.x as i32, 16 * row + 8 - a.y as i32);
        let (dx1, dy1) = (b.x as i32 - a.x as i32, b.y as i32 - a.y as i32);
        let (dx2, dy2) = (c.x as i32 - a.x as i32, c.y as i32 - a.y as i32);
        let l1 = dy2 as i64 * dx as i64 - dx2 as i64 * dy as i64;
        let l2 = dx1 as i64 * dy as i64 - dy1 as i64 * dx as i64;
        let in_range = (0..3).all(|k| {
            let c0 = a.color()[k] as i64;
            let (d1, d2) = (b.color()[k] as i64 - c0, c.color()[k] as i64 - c0);
            let n = (c0 * det as i64 + d1 * l1 + d2 * l2) << 16;
            n.unsigned_abs() < (det.unsigned_abs() as u64) << 30
        });
        if !in_range {
            continue;
        }
        let want = attribute_words::<Rgb565>(&tri, false, true, [0; 3]);
        let mut rec = ActiveTri::EMPTY;
        if kernel::gouraud_setup(&mut rec, &tri) && [rec.gx, rec.row, rec.inc] != want {
            let word = |p: &ScreenVertex| {
                let c = p.color();
                [
                    p.x as i32,
                    p.y as i32,
                    p.depth(),
                    c[0] as i32 | (c[1] as i32) << 10 | (c[2] as i32) << 20,
                ]
            };
            return Some(([word(a), word(b), word(c)], [row, left_c, left_sq]));
        }
    }
    None
}

/// For the triangle setup self-tests: case `i`'s three random vertices within a box of 48,
/// 400, 4000 or 16 000 subpixels (by `i mod 4`) around (120, 120) px, any depths and colours,
/// each then changed by `tweak`.
fn random_triangle(
    i: u32,
    next: &mut impl FnMut() -> u32,
    tweak: impl Fn(&mut ScreenVertex),
) -> [ScreenVertex; 3] {
    let size = [48u32, 400, 4000, 16000][(i % 4) as usize];
    let mut v = [ScreenVertex::default(); 3];
    for p in &mut v {
        let r = next();
        p.x = ((r % size) as i32 - size as i32 / 2 + 1920) as i16;
        p.y = (((r >> 16) % size) as i32 - size as i32 / 2 + 1920) as i16;
        random_depth_and_colour(p, next);
        tweak(p);
    }
    v
}

/// For the benchmark firmware (compiled, and run by the host tests, on every target): the
/// assembly triangle setup (`kernel::setup565`) against [`ActiveTri::setup_portable`] for RGB565 on `n`
/// pseudo-random Gouraud triangles (small, tall and wide ones, equal ys, first rows before,
/// at and after the middle vertex, short screens), without and with the dither check. Returns
/// the first mismatch's vertices `[x, y]` and `[row, height]` (height negated when the
/// mismatch is with the check).
#[doc(hidden)]
pub fn triangle_setup_self_test(n: u32) -> Option<([[i16; 2]; 3], [i32; 2])> {
    use embedded_graphics_core::pixelcolor::Rgb565;
    let mut next = xorshift32(0xbb67_ae85u32);
    let mode = SpanMode::new::<Rgb565>(crate::DepthTest::Less, false);
    let same = |a: &ActiveTri, b: &ActiveTri| {
        (a.flags, a.routine_rows, a.dy, a.row_mid, a.row_end)
            == (b.flags, b.routine_rows, b.dy, b.row_mid, b.row_end)
            && (a.bx, a.by, a.cx, a.cy) == (b.bx, b.by, b.cx, b.cy)
            && a.edges
                .iter()
                .zip(&b.edges)
                .all(|(p, q)| (p.w, p.s) == (q.w, q.s))
            && (a.gx, a.row, a.inc) == (b.gx, b.row, b.inc)
    };
    for i in 0..n {
        let v = random_triangle(i, &mut next, |p| {
            if i % 7 == 0 {
                // Equal ys.
                p.y &= !63;
            }
        });
        let t = TriRecord { v: [0, 1, 2] };
        let y_min = v.iter().map(|p| p.y as i32).min().unwrap_or(0);
        let r = next();
        let row = (first_pixel(y_min) + (r % 64) as i32 - 2).max(0);
        let height = [240, 60, 1024, 128][(r >> 8) as usize % 4];
        let mut want = ActiveTri::EMPTY;
        let kept = want.setup_portable::<Rgb565>(&t, &v, row, height, mode);
        let mut got = ActiveTri::EMPTY;
        if let Some(k) = kernel::setup565(&mut got, &t, &v, row, height, false) {
            let k = k == kernel::Setup565::Kept;
            if k != kept || (kept && !same(&got, &want)) {
                return Some((v.map(|p| [p.x, p.y]), [row, height]));
            }
            // With the dither check: `DITHER_OK` added to the same record, or the answer that
            // the triangle needs the slow path, as the portable check decides.
            use kernel::Setup565;
            let mut dithered = ActiveTri::EMPTY;
            let d = kernel::setup565(&mut dithered, &t, &v, row, height, true);
            let expect = if !kept {
                Setup565::Empty
            } else if want.dither_fits::<Rgb565>([&v[0], &v[1], &v[2]], row) {
                want.flags |= DITHER_OK;
                Setup565::Kept
            } else {
                Setup565::NotDitherable
            };
            if d != Some(expect) || (expect == Setup565::Kept && !same(&dithered, &want)) {
                return Some((v.map(|p| [p.x, p.y]), [row, -height]));
            }
        }
    }
    None
}

/// For the benchmark firmware (compiled, and run by the host tests, on every target): the assembly dither check
/// (`kernel::dither_fits565`) against the portable [`ActiveTri::dither_fits`] for RGB565
/// on `n` pseudo-random fast Gouraud triangles (small to the largest fast size, so that the
/// packed rows drift; colours anywhere in half the cases and inside the RGB565 range in the
/// other half, so that both answers occur; first rows at and below the first vertex). Returns
/// the first mismatching triangle's vertices `[x, y]` and `[row, portable answer]`.
#[doc(hidden)]
pub fn dither_fits_self_test(n: u32) -> Option<([[i16; 2]; 3], [i32; 2])> {
    use embedded_graphics_core::pixelcolor::Rgb565;
    let mut next = xorshift32(0x510e_527fu32);
    let mode = SpanMode::new::<Rgb565>(DepthTest::Less, true);
    let (mut tested, mut fits) = (0u32, 0u32);
    let mut i = 0u32;
    while tested < n && i < 8 * n {
        i += 1;
        let v = random_triangle(i, &mut next, |p| {
            if i % 2 == 0 {
                let c = p.color();
                p.set_color([c[0] % 993, c[1] % 1009, c[2] % 993]);
            }
        });
        let t = TriRecord { v: [0, 1, 2] };
        let y_min = v.iter().map(|p| p.y as i32).min().unwrap_or(0);
        let row = (first_pixel(y_min) + (next() % 16) as i32 - 2).max(0);
        let mut rec = ActiveTri::EMPTY;
        if !rec.setup_portable::<Rgb565>(&t, &v, row, 1024, mode)
            || rec.flags & (FAST | FLAT) != FAST
        {
            continue;
        }
        tested += 1;
        let p = [&v[0], &v[1], &v[2]];
        let want = rec.dither_fits::<Rgb565>(p, row);
        fits += want as u32;
        if kernel::dither_fits565(&rec, p, row).is_some_and(|got| got != want) {
            return Some((v.map(|p| [p.x, p.y]), [row, want as i32]));
        }
    }
    // Both answers must have been compared (and enough triangles found).
    if tested < n || fits == 0 || fits == tested {
        return Some(([[0; 2]; 3], [tested as i32, fits as i32]));
    }
    None
}

/// For the benchmark firmware (compiled, and run by the host tests, on every target): the assembly dithered span
/// (`kernel::span565_less_dither`) against [`span_packed_dither_portable`] (RGB565,
/// `DepthTest::Less`) on `n` pseudo-random spans: any start words and steps (small and large),
/// lengths 1 to 40, every column phase and Bayer row, depth lines that hide about half the
/// pixels. Returns the first mismatch's `[case, length, x0, row]`.
#[doc(hidden)]
pub fn dither_span_self_test(n: u32) -> Option<[u32; 4]> {
    use embedded_graphics_core::pixelcolor::Rgb565;
    let mut next = xorshift32(0x3c6e_f372u32);
    for case in 0..n {
        let len = 1 + (next() % 40) as usize;
        let x0 = (next() % 1024) as usize;
        let row = (next() % 1024) as i32;
        let RandomSpan {
            z,
            rb,
            g,
            mut za,
            mut ca,
        } = random_span(&mut next);
        let (mut zb, mut cb) = (za, ca);
        let words = rgb565_words_mut(&mut ca[..len])?;
        let Some(wa) = kernel::span565_less_dither(&mut za[..len], words, z, rb, g, x0, row) else {
            continue;
        };
        let wb = span_packed_dither_portable::<Rgb565, LESS>(
            &mut zb[..len],
            &mut cb[..len],
            z,
            rb,
            g,
            x0,
            row,
        );
        if wa != wb || za != zb || ca != cb {
            return Some([case, len as u32, x0 as u32, row as u32]);
        }
    }
    None
}

/// For the benchmark firmware (compiled, and run by the host tests, on every target): the dithered row routine
/// (`kernel::rows565` with dithering, the renderer's path) against `draw_row` alone on `n`
/// pseudo-random strips of four Gouraud triangles (RGB565, 96 × 48 px, some across the left
/// border, any depths and colours, set up while dithering as the renderer sets them up: on
/// their first row), row by row. Returns the first mismatching case.
#[doc(hidden)]
pub fn dither_rows_self_test(n: u32) -> Option<u32> {
    rows_case(n, true)
}

/// The row kernel without dithering (`kernel::rows565`, the renderer's path) against
/// `draw_row` alone, on `n` pseudo-random strips as in [`dither_rows_self_test`]. Returns the
/// first mismatching case.
pub fn rows_self_test(n: u32) -> Option<u32> {
    rows_case(n, false)
}

/// The strips of [`dither_rows_self_test`] and [`rows_self_test`].
fn rows_case(n: u32, dither: bool) -> Option<u32> {
    use embedded_graphics_core::pixelcolor::Rgb565;
    const W: usize = 96;
    const H: i32 = 48;
    let mut next = xorshift32(0xa54f_f53au32);
    let mode = SpanMode::new::<Rgb565>(DepthTest::Less, dither);
    for case in 0..n {
        let mut v = [ScreenVertex::default(); 12];
        for p in &mut v {
            let r = next();
            p.x = ((r % (W as u32 * 16 + 320)) as i32 - 160) as i16;
            p.y = ((r >> 16) % (H as u32 * 16)) as i16;
            random_depth_and_colour(p, &mut next);
            if case % 2 == 0 {
                // Colours inside the RGB565 range (most of these triangles are DITHER_OK).
                let c = p.color();
                p.set_color([c[0] % 993, c[1] % 1009, c[2] % 993]);
            }
        }
        let tris = [[0u16, 1, 2], [3, 4, 5], [6, 7, 8], [9, 10, 11]].map(|v| TriRecord { v });
        let first = |t: &TriRecord| {
            let [i0, i1, i2] = t.indices();
            first_pixel(v[i0].y.min(v[i1].y).min(v[i2].y) as i32).max(0)
        };
        let mut a = ActiveList::<4>::new();
        let mut b = ActiveList::<4>::new();
        for row in 0..H {
            for t in tris.iter().filter(|t| first(t) == row) {
                // One triangle in four is set up as a pool kind is (no fast path) and may
                // carry a pool kind's code in the routine's last and switch bits
                // (`raster::kind`): the routine must leave it to `draw_row`, which draws it
                // by its attribute layout alone.
                let r = next();
                let m = if r & 3 == 0 {
                    SpanMode::default()
                } else {
                    mode
                };
                let code = (r >> 8) as u8 & (LAST_IN_ROUTINE | SWITCH_IN_ROUTINE);
                for list in [&mut a, &mut b] {
                    let n = list.len();
                    list.push_with(|r| r.setup::<Rgb565>(t, &v, row, H, m));
                    if list.len() > n && list.get_mut(n).flags & FAST == 0 {
                        list.get_mut(n).flags |= code;
                    }
                }
            }
            let (mut ca, mut za) = ([Rgb565::new(0, 0, 0); W], [u16::MAX; W]);
            let (mut cb, mut zb) = (ca, za);
            let mut i = 0;
            loop {
                let words = rgb565_words_mut(&mut ca)?;
                if let Some((next_i, _, _)) =
                    kernel::rows565(&mut a, i, words, &mut za, row as usize, dither)
                {
                    i = next_i;
                }
                if i >= a.len() {
                    break;
                }
                let (_, _, done) =
                    a.get_mut(i)
                        .draw_row(row, &mut ca, &mut za, DepthTest::Less, dither);
                if done {
                    a.swap_remove(i);
                } else {
                    i += 1;
                }
            }
            let mut i = 0;
            while i < b.len() {
                let (_, _, done) =
                    b.get_mut(i)
                        .draw_row(row, &mut cb, &mut zb, DepthTest::Less, dither);
                if done {
                    b.swap_remove(i);
                } else {
                    i += 1;
                }
            }
            if ca != cb || za != zb || a.len() != b.len() {
                return Some(case);
            }
        }
    }
    None
}

/// The plain and flat RGB565 span kernels (`kernel::span565_less`, `kernel::span565_flat_less`)
/// and the line clear (`kernel::clear_line565`) against the span stage's portable loops, on `n`
/// pseudo-random spans: any packed start values and steps (steps of every magnitude), any
/// stored depths and colours, 1 to 40 pixels. Returns the first mismatching case and length.
pub fn span_self_test(n: u32) -> Option<[u32; 2]> {
    use embedded_graphics_core::pixelcolor::Rgb565;
    let mut next = xorshift32(0x9e37_79b9u32);
    for case in 0..n {
        let len = 1 + (next() % 40) as usize;
        let RandomSpan { z, rb, g, za, ca } = random_span(&mut next);
        let fail = Some([case, len as u32]);
        // Gouraud.
        let (mut zk, mut ck, mut zp, mut cp) = (za, ca, za, ca);
        let words = rgb565_words_mut(&mut ck[..len])?;
        if let Some(wk) = kernel::span565_less(&mut zk[..len], words, z, rb, g) {
            let wp = span_packed_portable::<Rgb565, LESS>(&mut zp[..len], &mut cp[..len], z, rb, g);
            if wk != wp || zk != zp || ck != cp {
                return fail;
            }
        }
        // Flat (16.12 depth with any bias, any colour), from the same random words.
        let (z0, gz, g0) = (z[0] as u32, z[1] as u32, g[0] as u32);
        let color = Rgb565::new(
            (g0 >> 3) as u8 & 31,
            (g0 >> 9) as u8 & 63,
            (g0 >> 17) as u8 & 31,
        );
        let (zf, gzf) = ((z0 >> 4) as i32, gz as i32 >> 4);
        let (mut zk, mut ck, mut zp, mut cp) = (za, ca, za, ca);
        let word = crate::scene::color::rgb565_word(color)?;
        let words = rgb565_words_mut(&mut ck[..len])?;
        if let Some(wk) = kernel::span565_flat_less(&mut zk[..len], words, zf, gzf, word) {
            let wp =
                span_flat_portable::<Rgb565, LESS>(&mut zp[..len], &mut cp[..len], zf, gzf, color);
            if wk != wp || zk != zp || ck != cp {
                return fail;
            }
        }
        // Clear.
        let (mut zk, mut ck) = (za, ca);
        let words = rgb565_words_mut(&mut ck[..len])?;
        kernel::clear_line565(words, &mut zk[..len], word);
        if zk[..len].iter().any(|&d| d != u16::MAX)
            || ck[..len].iter().any(|&c| c != color)
            || zk[len..] != za[len..]
            || ck[len..] != ca[len..]
        {
            return fail;
        }
    }
    None
}

/// A pseudo-random span for the span tests: packed start words and steps (depth, red-blue,
/// green; each step shifted right by 0 to 31 bits, so of every magnitude) and the stored depth
/// and colour lines (40 pixels; a test draws over the first 1 to 40).
struct RandomSpan {
    z: [i32; 2],
    rb: [u32; 2],
    g: [i32; 2],
    za: [u16; 40],
    ca: [embedded_graphics_core::pixelcolor::Rgb565; 40],
}

/// Draws a [`RandomSpan`] from `next`.
fn random_span(next: &mut impl FnMut() -> u32) -> RandomSpan {
    use embedded_graphics_core::pixelcolor::Rgb565;
    let mut word_and_step = || {
        let (v, s, k) = (next(), next(), next() % 32);
        [v, s >> k]
    };
    let [z0, gz] = word_and_step();
    let rb = word_and_step();
    let [g0, gg] = word_and_step();
    let mut za = [0u16; 40];
    let mut ca = [Rgb565::new(0, 0, 0); 40];
    for (zp, cp) in za.iter_mut().zip(ca.iter_mut()) {
        let r = next();
        *zp = r as u16;
        *cp = Rgb565::new((r >> 16) as u8 & 31, (r >> 21) as u8 & 63, (r >> 27) as u8);
    }
    RandomSpan {
        z: [z0 as i32, gz as i32],
        rb,
        g: [g0 as i32, gg as i32],
        za,
        ca,
    }
}
