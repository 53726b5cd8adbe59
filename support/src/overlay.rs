//! Text composed into strips: glyphs rasterized once from an embedded-graphics [`MonoFont`],
//! then copied into the lines of whichever strips a label crosses.
//!
//! [`FrameOptions::overlay`](scanline3d::FrameOptions::overlay) draws any embedded-graphics
//! [`Drawable`] into every strip, which runs the drawable's
//! text layout once per strip: with a one-line strip that is 240 layouts a frame for a label
//! that covers ten rows. [`Glyphs`] does the font work once, when it is built, and
//! [`Glyphs::draw`] then touches only the rows of a strip that the text covers: a strip the text
//! does not reach costs one comparison.
//!
//! ```
//! use embedded_graphics::mono_font::ascii::FONT_6X10;
//! use embedded_graphics::pixelcolor::Rgb565;
//! use embedded_graphics::prelude::*;
//! use scanline3d_support::overlay::Glyphs;
//!
//! let glyphs = Glyphs::<16>::new(&FONT_6X10, "0123456789. fps").unwrap();
//! let mut lines = [[Rgb565::BLACK; 64]; 4]; // a strip of rows 8..12
//! let unknown = glyphs.draw("12.5 fps", (2, 5), Rgb565::WHITE, 8, &mut lines);
//! assert_eq!(unknown, 0);
//! assert!(lines.iter().flatten().any(|&c| c == Rgb565::WHITE));
//! ```

use embedded_graphics::mono_font::{MonoFont, MonoTextStyle};
use embedded_graphics::text::{Baseline, Text};
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{OriginDimensions, Point, Size};
use embedded_graphics_core::pixelcolor::BinaryColor;
use embedded_graphics_core::{Drawable, Pixel};

/// Largest glyph [`Glyphs`] stores, in pixels (width and height).
pub const MAX_GLYPH: u32 = 16;

/// Why a [`Glyphs`] set could not be built.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum GlyphError {
    /// The font's characters are wider or taller than [`MAX_GLYPH`] pixels.
    FontTooLarge {
        /// The font's character size in pixels.
        width: u32,
        /// The font's character height in pixels.
        height: u32,
    },
    /// More distinct characters than the set's capacity `N`.
    TooManyChars {
        /// The capacity.
        capacity: usize,
    },
}

impl core::fmt::Display for GlyphError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            GlyphError::FontTooLarge { width, height } => write!(
                f,
                "font characters are {width} × {height} px; at most {MAX_GLYPH} × {MAX_GLYPH} \
                 are supported"
            ),
            GlyphError::TooManyChars { capacity } => write!(
                f,
                "more distinct characters than the glyph set's capacity {capacity}"
            ),
        }
    }
}

impl core::error::Error for GlyphError {}

/// Up to `N` characters of a monospaced font, each rasterized once into a 1-bit mask.
///
/// Stored per glyph: the character, and one `u16` per glyph row whose bit `i` is set where
/// column `i` of the glyph is ink (width and height ≤ [`MAX_GLYPH`]): `N · 36` bytes.
#[derive(Clone, Debug)]
pub struct Glyphs<const N: usize> {
    chars: [char; N],
    masks: [[u16; MAX_GLYPH as usize]; N],
    len: usize,
    /// Glyph width and height in pixels (≤ 16), and the advance from one character to the
    /// next (width plus the font's spacing).
    width: u8,
    height: u8,
    advance: u8,
}

/// A draw target that records the ink of one glyph cell.
struct Cell {
    mask: [u16; MAX_GLYPH as usize],
}

impl OriginDimensions for Cell {
    fn size(&self) -> Size {
        Size::new(MAX_GLYPH, MAX_GLYPH)
    }
}

impl DrawTarget for Cell {
    type Color = BinaryColor;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<BinaryColor>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in pixels {
            let inside =
                (0..MAX_GLYPH as i32).contains(&p.x) && (0..MAX_GLYPH as i32).contains(&p.y);
            if inside && c == BinaryColor::On {
                self.mask[p.y as usize] |= 1 << p.x;
            }
        }
        Ok(())
    }
}

impl<const N: usize> Glyphs<N> {
    /// Rasterizes each distinct character of `chars` in `font` (top-left of the character cell
    /// at the glyph's origin). Characters the font lacks get the font's replacement glyph.
    ///
    /// # Errors
    ///
    /// [`GlyphError::FontTooLarge`] for a font wider or taller than [`MAX_GLYPH`];
    /// [`GlyphError::TooManyChars`] when `chars` has more than `N` distinct characters.
    pub fn new(font: &MonoFont<'_>, chars: &str) -> Result<Self, GlyphError> {
        let size = font.character_size;
        if size.width > MAX_GLYPH || size.height > MAX_GLYPH || size.width == 0 {
            return Err(GlyphError::FontTooLarge {
                width: size.width,
                height: size.height,
            });
        }
        let mut glyphs = Glyphs {
            chars: ['\0'; N],
            masks: [[0; MAX_GLYPH as usize]; N],
            len: 0,
            width: size.width as u8,
            height: size.height as u8,
            advance: (size.width + font.character_spacing).min(255) as u8,
        };
        let style = MonoTextStyle::new(font, BinaryColor::On);
        for ch in chars.chars() {
            if glyphs.index(ch).is_some() {
                continue;
            }
            if glyphs.len == N {
                return Err(GlyphError::TooManyChars { capacity: N });
            }
            let mut cell = Cell {
                mask: [0; MAX_GLYPH as usize],
            };
            let mut utf8 = [0u8; 4];
            let text = ch.encode_utf8(&mut utf8);
            let _ = Text::with_baseline(text, Point::zero(), style, Baseline::Top).draw(&mut cell);
            glyphs.chars[glyphs.len] = ch;
            glyphs.masks[glyphs.len] = cell.mask;
            glyphs.len += 1;
        }
        Ok(glyphs)
    }

    /// Index of `ch` in the set.
    fn index(&self, ch: char) -> Option<usize> {
        self.chars[..self.len].iter().position(|&c| c == ch)
    }

    /// Glyph width, height and advance (width plus spacing) in pixels.
    #[must_use]
    pub fn metrics(&self) -> (u32, u32, u32) {
        (self.width as u32, self.height as u32, self.advance as u32)
    }

    /// The rows `text` covers when drawn with its top-left corner at row `y`.
    #[must_use]
    pub fn rows(&self, y: i32) -> core::ops::Range<i32> {
        y..y + self.height as i32
    }

    /// Draws the ink of `text`, top-left corner at `(x, y)` in screen pixels, in `color`, into
    /// the strip whose first row is `y0` (`lines[i]` is screen row `y0 + i`); pixels outside
    /// the lines are skipped, the background is left as it is. Characters not in the set are
    /// left blank (their cell still advances) and counted: the return value, for a strip the
    /// text crosses (0 for one it does not).
    ///
    /// Costs nothing but one range test for a strip the text does not cross; otherwise a few
    /// operations per glyph row it crosses.
    pub fn draw<C: Copy, const W: usize>(
        &self,
        text: &str,
        (x, y): (i32, i32),
        color: C,
        y0: usize,
        lines: &mut [[C; W]],
    ) -> usize {
        let start = i64::try_from(y0).unwrap_or(i64::MAX);
        let first = (y as i64).max(start);
        let end = (y as i64 + self.height as i64).min(start.saturating_add(lines.len() as i64));
        let mut unknown = 0;
        if first >= end {
            return 0;
        }
        let w = self.width as i64;
        for (k, ch) in text.chars().enumerate() {
            let Some(g) = self.index(ch) else {
                unknown += 1;
                continue;
            };
            // The glyph's columns that fall on the line, as bit positions lo..hi.
            let gx = x as i64 + k as i64 * self.advance as i64;
            let lo = (-gx).clamp(0, w) as u32;
            let hi = (W as i64 - gx).clamp(0, w) as u32;
            if lo >= hi {
                continue;
            }
            // Screen columns of bits lo..hi, within 0..W.
            let base = (gx + lo as i64) as usize;
            let mask = &self.masks[g];
            for row in first..end {
                let bits = (mask[(row - y as i64) as usize] as u32) >> lo;
                if bits == 0 {
                    continue;
                }
                let line = &mut lines[(row - start) as usize][base..base + (hi - lo) as usize];
                for (i, px) in line.iter_mut().enumerate() {
                    if bits & (1 << i) != 0 {
                        *px = color;
                    }
                }
            }
        }
        unknown
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics::mock_display::MockDisplay;
    use embedded_graphics::mono_font::ascii::{FONT_10X20, FONT_6X10, FONT_9X15};
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_graphics::prelude::*;

    /// The composed glyphs are exactly what embedded-graphics draws for the same text, however
    /// the screen is cut into strips.
    #[test]
    fn matches_embedded_graphics_in_any_strip_height() {
        for font in [&FONT_6X10, &FONT_9X15] {
            let glyphs = Glyphs::<24>::new(font, "0123456789. fpsx").unwrap();
            let text = "59.9 fps";
            let (x, y) = (3, 5);
            let mut reference = MockDisplay::<Rgb565>::new();
            reference.set_allow_out_of_bounds_drawing(true);
            Text::with_baseline(
                text,
                Point::new(x, y),
                MonoTextStyle::new(font, Rgb565::WHITE),
                Baseline::Top,
            )
            .draw(&mut reference)
            .unwrap();
            for strip in [1usize, 3, 4, 7, 64] {
                let mut screen = [[Rgb565::BLACK; 64]; 64];
                for y0 in (0..64).step_by(strip) {
                    let n = strip.min(64 - y0);
                    let mut lines = [[Rgb565::BLACK; 64]; 64];
                    assert_eq!(
                        glyphs.draw(text, (x, y), Rgb565::WHITE, y0, &mut lines[..n]),
                        0
                    );
                    screen[y0..y0 + n].copy_from_slice(&lines[..n]);
                }
                for py in 0..64 {
                    for px in 0..64 {
                        let want = reference
                            .get_pixel(Point::new(px, py))
                            .unwrap_or(Rgb565::BLACK);
                        assert_eq!(
                            screen[py as usize][px as usize], want,
                            "strip {strip} at {px},{py}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn unknown_chars_are_counted_and_clipping_is_safe() {
        let glyphs = Glyphs::<4>::new(&FONT_6X10, "01").unwrap();
        let mut lines = [[0u8; 8]; 2];
        assert_eq!(glyphs.draw("0a1b", (-5, -3), 1, 0, &mut lines), 2);
        assert_eq!(glyphs.draw("0a1b", (1000, 0), 1, 0, &mut lines), 2);
        assert_eq!(glyphs.draw("0a1b", (0, 1000), 1, 0, &mut lines), 0);
        assert_eq!(
            glyphs.draw("01", (i32::MIN, i32::MAX), 1, usize::MAX / 2, &mut lines),
            0
        );
        assert_eq!(
            Glyphs::<2>::new(&FONT_6X10, "012").unwrap_err(),
            GlyphError::TooManyChars { capacity: 2 }
        );
        assert_eq!(
            Glyphs::<2>::new(&FONT_10X20, "0").unwrap_err(),
            GlyphError::FontTooLarge {
                width: 10,
                height: 20
            }
        );
    }
}
