//! A draw target that keeps no pixels, only a hash of everything drawn into it: the way to
//! compare a frame rendered on a microcontroller with the same frame rendered on the host.
//!
//! The hash is two 32-bit FNV-1a lanes with different offset bases and primes, run over one
//! 32-bit word per pixel — its colour as `R << 16 | G << 8 | B` in 8-bit channels (through
//! [`Rgb888`], exact for every embedded-graphics RGB type), preceded by its row-major index for
//! [`DrawTarget::draw_iter`] — and reported as one `u64`. Only 32-bit multiplies, which a
//! Cortex-M0 does in one instruction. The renderer only uses `fill_contiguous`, so a frame's hash
//! depends on nothing but its pixels, in order.

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{OriginDimensions, Size};
use embedded_graphics_core::pixelcolor::{PixelColor, Rgb888, RgbColor};
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;

const OFFSET_A: u32 = 0x811c_9dc5;
const PRIME_A: u32 = 0x0100_0193;
const OFFSET_B: u32 = 0x2545_f491;
const PRIME_B: u32 = 0x9e37_79b1;

/// A `width × height` target that hashes what is drawn (O(1) memory).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct HashTarget<C> {
    size: Size,
    a: u32,
    b: u32,
    pixels: u32,
    _c: core::marker::PhantomData<C>,
}

impl<C> HashTarget<C> {
    /// A fresh target.
    #[must_use]
    pub const fn new(width: u32, height: u32) -> Self {
        HashTarget {
            size: Size::new(width, height),
            a: OFFSET_A,
            b: OFFSET_B,
            pixels: 0,
            _c: core::marker::PhantomData,
        }
    }

    /// The hash of everything drawn so far.
    #[must_use]
    pub fn hash(&self) -> u64 {
        (self.a as u64) << 32 | self.b as u64
    }

    /// How many pixels were drawn.
    #[must_use]
    pub fn pixels(&self) -> u32 {
        self.pixels
    }

    /// Starts over.
    pub fn reset(&mut self) {
        self.a = OFFSET_A;
        self.b = OFFSET_B;
        self.pixels = 0;
    }

    #[inline]
    fn word(&mut self, w: u32) {
        self.a = (self.a ^ w).wrapping_mul(PRIME_A);
        self.b = (self.b ^ w).wrapping_mul(PRIME_B);
    }
}

impl<C: PixelColor + Into<Rgb888>> HashTarget<C> {
    #[inline]
    fn color(&mut self, c: C) {
        let c: Rgb888 = c.into();
        self.word((c.r() as u32) << 16 | (c.g() as u32) << 8 | c.b() as u32);
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
            self.word(i);
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

/// A target that accepts every strip and does nothing with it: for measuring the renderer
/// without any output cost.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct NullTarget<C> {
    size: Size,
    _c: core::marker::PhantomData<C>,
}

impl<C> NullTarget<C> {
    /// A `width × height` null target.
    #[must_use]
    pub const fn new(width: u32, height: u32) -> Self {
        NullTarget {
            size: Size::new(width, height),
            _c: core::marker::PhantomData,
        }
    }
}

impl<C> OriginDimensions for NullTarget<C> {
    fn size(&self) -> Size {
        self.size
    }
}

impl<C: PixelColor> DrawTarget for NullTarget<C> {
    type Color = C;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(&mut self, _: I) -> Result<(), Self::Error> {
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = C>>(
        &mut self,
        _: &Rectangle,
        _: I,
    ) -> Result<(), Self::Error> {
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
