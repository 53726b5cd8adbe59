//! Error metrics between two renderings of the same scene, computed line by line in O(width)
//! memory, so that they also run on a device: prepare two renderers (say, fixed point and f32),
//! draw them strip by strip ([`scanline3d::frame::Frame::strip_to`]) into two [`StripCapture`]s, and
//! feed the strips to [`Metrics::add_line`]. Depth-order mismatches come from rendering
//! [`scanline3d::color::TriangleId`]s the same way and feeding them to [`Metrics::add_ids`].

use core::ops::Range;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{OriginDimensions, Size};
use embedded_graphics_core::pixelcolor::{PixelColor, RgbColor};
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;

use scanline3d::color::TriangleId;

/// Accumulated differences between a tested image and a reference image.
#[derive(Copy, Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct Metrics {
    /// Largest per-channel absolute difference, in the colour type's own units (LSB).
    pub max_lsb: [u8; 3],
    sum_abs: [u64; 3],
    /// Sum of squared differences, each channel normalized to its range (scaled by 2³²).
    sum_sq: u64,
    /// Pixels compared.
    pub pixels: u64,
    /// Pixels whose colours differ at all.
    pub differing: u64,
    /// Pixels drawn in one image and background in the other.
    pub coverage_mismatch: u64,
    /// Pixels where both images drew a triangle but not the same one.
    pub depth_mismatch: u64,
    /// Channel ranges.
    max: [u8; 3],
}

impl Metrics {
    /// Empty metrics for a colour type with these channel maxima (e.g. `[31, 63, 31]`).
    #[must_use]
    pub fn new(channel_max: [u8; 3]) -> Self {
        Metrics {
            max: channel_max,
            ..Default::default()
        }
    }

    /// Adds one line (or strip) of the tested image `a` and the reference `b`. Pixels equal to
    /// `background` count as not drawn; such pixels are compared for coverage only.
    pub fn add_line<C: RgbColor>(&mut self, a: &[C], b: &[C], background: C) {
        for (&x, &y) in a.iter().zip(b.iter()) {
            self.pixels += 1;
            if x == y {
                continue;
            }
            self.differing += 1;
            if (x == background) != (y == background) {
                self.coverage_mismatch += 1;
                continue;
            }
            self.add_color(x, y);
        }
    }

    /// Adds one line of the tested image `a` and the reference `b` together with the triangle
    /// ids both drew there (0 = background): coverage and depth order come from the ids
    /// (exact, whatever the colours), and colour error is measured only where both images drew
    /// the same triangle, so that it is arithmetic error, not a different surface.
    pub fn add_line_ids<C: RgbColor>(
        &mut self,
        a: &[C],
        b: &[C],
        ida: &[TriangleId],
        idb: &[TriangleId],
    ) {
        for (((&x, &y), &i), &j) in a.iter().zip(b.iter()).zip(ida.iter()).zip(idb.iter()) {
            self.pixels += 1;
            if x != y {
                self.differing += 1;
            }
            if (i.0 == 0) != (j.0 == 0) {
                self.coverage_mismatch += 1;
                continue;
            }
            if i != j {
                self.depth_mismatch += 1;
                continue;
            }
            self.add_color(x, y);
        }
    }

    fn add_color<C: RgbColor>(&mut self, x: C, y: C) {
        let d = [
            x.r().abs_diff(y.r()),
            x.g().abs_diff(y.g()),
            x.b().abs_diff(y.b()),
        ];
        for k in 0..3 {
            self.max_lsb[k] = self.max_lsb[k].max(d[k]);
            self.sum_abs[k] += d[k] as u64;
            if self.max[k] > 0 {
                // (d/max)² · 2³², exact enough in integers: d, max ≤ 255.
                let m = self.max[k] as u64;
                self.sum_sq += ((d[k] as u64 * d[k] as u64) << 32) / (m * m);
            }
        }
    }

    /// Adds one line of triangle ids (0 = background) of the tested and the reference image.
    pub fn add_ids(&mut self, a: &[TriangleId], b: &[TriangleId]) {
        for (x, y) in a.iter().zip(b.iter()) {
            if x.0 != 0 && y.0 != 0 && x.0 != y.0 {
                self.depth_mismatch += 1;
            }
        }
    }

    /// Mean absolute difference per channel sample, in LSB (coverage mismatches excluded).
    #[must_use]
    pub fn mean_abs(&self) -> f64 {
        let n = 3 * self.pixels.max(1);
        (self.sum_abs[0] + self.sum_abs[1] + self.sum_abs[2]) as f64 / n as f64
    }

    /// Peak signal-to-noise ratio in dB over all channel samples, each normalized to its range;
    /// infinite for identical images (coverage mismatches excluded).
    #[must_use]
    pub fn psnr_db(&self) -> f64 {
        let mse = self.sum_sq as f64 / (4294967296.0 * 3.0 * self.pixels.max(1) as f64);
        if mse == 0.0 {
            f64::INFINITY
        } else {
            10.0 * libm::log10(1.0 / mse)
        }
    }
}

/// A draw target that keeps the last strip drawn into it (`LINES` rows of `W` pixels): the
/// O(width) buffer for comparing two renderers strip by strip.
#[derive(Clone, Debug)]
pub struct StripCapture<C, const W: usize, const LINES: usize> {
    height: u32,
    rows: Range<usize>,
    buf: [[C; W]; LINES],
}

impl<C: PixelColor, const W: usize, const LINES: usize> StripCapture<C, W, LINES> {
    /// A capture for a `W × height` screen, initially filled with `fill`.
    #[must_use]
    pub fn new(height: u32, fill: C) -> Self {
        StripCapture {
            height,
            rows: 0..0,
            buf: [[fill; W]; LINES],
        }
    }

    /// The rows of the last strip.
    #[must_use]
    pub fn rows(&self) -> Range<usize> {
        self.rows.clone()
    }

    /// Line `k` of the last strip.
    #[must_use]
    pub fn line(&self, k: usize) -> &[C] {
        &self.buf[k.min(LINES - 1)]
    }
}

impl<C, const W: usize, const LINES: usize> OriginDimensions for StripCapture<C, W, LINES> {
    fn size(&self) -> Size {
        Size::new(W as u32, self.height)
    }
}

impl<C: PixelColor, const W: usize, const LINES: usize> DrawTarget for StripCapture<C, W, LINES> {
    type Color = C;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in pixels {
            let y = p.y as usize;
            if p.x >= 0 && (p.x as usize) < W && self.rows.contains(&y) {
                self.buf[y - self.rows.start][p.x as usize] = c;
            }
        }
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = C>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        let y0 = area.top_left.y.max(0) as usize;
        let lines = (area.size.height as usize).min(LINES);
        self.rows = y0..y0 + lines;
        let w = (area.size.width as usize).min(W);
        let mut it = colors.into_iter();
        for l in 0..lines {
            for x in 0..area.size.width as usize {
                match it.next() {
                    Some(c) if x < w => self.buf[l][x] = c,
                    Some(_) => {}
                    None => return Ok(()),
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics_core::pixelcolor::Rgb565;

    #[test]
    fn metrics_count_what_they_say() {
        let bg = Rgb565::BLACK;
        let a = [
            Rgb565::new(10, 20, 30),
            Rgb565::new(1, 1, 1),
            bg,
            Rgb565::new(5, 5, 5),
        ];
        let b = [
            Rgb565::new(10, 20, 30),
            Rgb565::new(2, 4, 1),
            Rgb565::new(3, 3, 3),
            Rgb565::new(5, 5, 5),
        ];
        let mut m = Metrics::new([31, 63, 31]);
        m.add_line(&a, &b, bg);
        assert_eq!(m.pixels, 4);
        assert_eq!(m.differing, 2);
        assert_eq!(m.coverage_mismatch, 1);
        assert_eq!(m.max_lsb, [1, 3, 0]);
        assert!((m.mean_abs() - 4.0 / 12.0).abs() < 1e-12);
        // MSE = ((1/31)² + (3/63)²) / 12.
        let mse = ((1.0f64 / 31.0).powi(2) + (3.0f64 / 63.0).powi(2)) / 12.0;
        assert!((m.psnr_db() - 10.0 * (1.0 / mse).log10()).abs() < 1e-6);
        let same = Metrics::new([31, 63, 31]);
        assert_eq!(same.psnr_db(), f64::INFINITY);
        m.add_ids(
            &[TriangleId(0), TriangleId(3), TriangleId(4)],
            &[TriangleId(2), TriangleId(3), TriangleId(5)],
        );
        assert_eq!(m.depth_mismatch, 1);
    }
}
