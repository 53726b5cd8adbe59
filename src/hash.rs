//! A draw target that keeps no pixels, only a hash of everything drawn into it: the way to
//! compare a frame rendered on a microcontroller with the same frame rendered on the host.
//!
//! The hash is 64-bit FNV-1a over, for each pixel in drawing order, its position's row-major
//! index (only for [`DrawTarget::draw_iter`]) and its colour as 8-bit R, G, B (through
//! [`Rgb888`], which is exact for every embedded-graphics RGB type). The renderer only uses
//! `fill_contiguous`, so a frame's hash depends on nothing but its pixels.

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{OriginDimensions, Size};
use embedded_graphics_core::pixelcolor::{PixelColor, Rgb888, RgbColor};
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;

const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

/// A `width × height` target that hashes what is drawn (O(1) memory).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct HashTarget<C> {
    size: Size,
    hash: u64,
    pixels: u32,
    _c: core::marker::PhantomData<C>,
}

impl<C> HashTarget<C> {
    /// A fresh target.
    #[must_use]
    pub const fn new(width: u32, height: u32) -> Self {
        HashTarget {
            size: Size::new(width, height),
            hash: FNV_OFFSET,
            pixels: 0,
            _c: core::marker::PhantomData,
        }
    }

    /// The hash of everything drawn so far.
    #[must_use]
    pub fn hash(&self) -> u64 {
        self.hash
    }

    /// How many pixels were drawn.
    #[must_use]
    pub fn pixels(&self) -> u32 {
        self.pixels
    }

    /// Starts over.
    pub fn reset(&mut self) {
        self.hash = FNV_OFFSET;
        self.pixels = 0;
    }

    #[inline]
    fn byte(&mut self, b: u8) {
        self.hash = (self.hash ^ b as u64).wrapping_mul(FNV_PRIME);
    }
}

impl<C: PixelColor + Into<Rgb888>> HashTarget<C> {
    #[inline]
    fn color(&mut self, c: C) {
        let c: Rgb888 = c.into();
        self.byte(c.r());
        self.byte(c.g());
        self.byte(c.b());
        self.pixels = self.pixels.wrapping_add(1);
    }
}

impl<C> OriginDimensions for HashTarget<C> {
    fn size(&self) -> Size {
        self.size
    }
}

impl<C: PixelColor + Into<Rgb888>> DrawTarget for HashTarget<C> {
    type Color = C;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in pixels {
            let i = (p.y as u32)
                .wrapping_mul(self.size.width)
                .wrapping_add(p.x as u32);
            for b in i.to_le_bytes() {
                self.byte(b);
            }
            self.color(c);
        }
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = C>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        let n = area.size.width as usize * area.size.height as usize;
        for c in colors.into_iter().take(n) {
            self.color(c);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics_core::geometry::Point;
    use embedded_graphics_core::pixelcolor::Rgb565;

    #[test]
    fn hash_depends_on_every_pixel_and_its_order() {
        let area = Rectangle::new(Point::zero(), Size::new(3, 1));
        let h = |cols: [Rgb565; 3]| {
            let mut t = HashTarget::<Rgb565>::new(3, 1);
            t.fill_contiguous(&area, cols).unwrap();
            (t.hash(), t.pixels())
        };
        let a = h([Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE]);
        assert_eq!(a.1, 3);
        assert_ne!(a.0, h([Rgb565::RED, Rgb565::BLUE, Rgb565::GREEN]).0);
        assert_ne!(
            a.0,
            h([Rgb565::RED, Rgb565::GREEN, Rgb565::new(0, 0, 30)]).0
        );
        assert_eq!(a, h([Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE]));
    }
}
