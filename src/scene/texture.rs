//! Textures: RGB565 images in flash (`&'static` texels), sampled by nearest texel with wrap or
//! clamp per axis, and how a material maps them ([`Texturing`]: the image, the span mode and an
//! optional colour key).
//!
//! Texture coordinates are per mesh vertex ([`crate::Mesh::with_uvs`]): `(s, t)` with
//! `(0, 0)` at the top-left corner of the image and `(1, 1)` at its bottom-right corner, so
//! texel `(i, j)` covers `s ∈ [i/width, (i+1)/width)`, `t ∈ [j/height, (j+1)/height)`.
//! Nearest sampling takes the texel whose square contains the interpolated `(s, t)` (the
//! value at the pixel centre). A lit textured pixel is `texel × lit colour / 255` per channel,
//! where the lit colour is the material's colour lit as it would be without a texture
//! (ambient + diffuse, flat or Gouraud): a white material shows the texture's own colours
//! under full light. The specular term is not added to textured pixels.

/// How texture coordinates outside `[0, 1)` map to texels, per axis.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Default, Hash)]
pub enum Wrap {
    /// The image repeats (`s` modulo 1).
    #[default]
    Repeat,
    /// The edge texels extend outward (`s` clamped to the image).
    Clamp,
}

/// Why a texture could not be made.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum TextureError {
    /// Width or height is not a power of two in 1..=[`MAX_TEXTURE_SIZE`].
    BadSize {
        /// The width given.
        width: u32,
        /// The height given.
        height: u32,
    },
    /// The texel slice is not `width × height` long.
    TexelCount {
        /// `width × height`.
        expected: usize,
        /// The slice's length.
        given: usize,
    },
}

impl core::fmt::Display for TextureError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            TextureError::BadSize { width, height } => write!(
                f,
                "texture size {width}x{height}: width and height must be powers of two \
                 from 1 to {MAX_TEXTURE_SIZE}"
            ),
            TextureError::TexelCount { expected, given } => {
                write!(f, "texture has {given} texels, its size needs {expected}")
            }
        }
    }
}

impl core::error::Error for TextureError {}

/// The largest texture width or height (1024 texels).
pub const MAX_TEXTURE_SIZE: u32 = 1024;

/// An RGB565 image for texturing, borrowed for the whole program (`static` arrays in flash,
/// for instance from `bake --texture`). Width and height are powers of two, so that wrapping
/// and addressing are masks and shifts.
///
/// ```
/// use scanline3d::{Texture, Wrap};
/// static TEXELS: [u16; 4] = [0xffff, 0x0000, 0x0000, 0xffff];
/// static CHECKER: Texture = match Texture::new(&TEXELS, 2, 2) {
///     Ok(t) => t.with_wrap(Wrap::Repeat, Wrap::Clamp),
///     Err(_) => panic!("bad texture"),
/// };
/// assert_eq!(CHECKER.texel(1, 0), 0x0000);
/// ```
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct Texture {
    /// Row-major texels, RGB565 words (red in bits 11..=15, green 5..=10, blue 0..=4).
    texels: &'static [u16],
    /// log₂ of the width and height (0..=10).
    width_log2: u8,
    height_log2: u8,
    wrap: [Wrap; 2],
}

impl Texture {
    /// A texture of `width × height` RGB565 texels (row-major, top row first), repeating on
    /// both axes.
    ///
    /// # Errors
    ///
    /// [`TextureError::BadSize`] unless both sizes are powers of two up to
    /// [`MAX_TEXTURE_SIZE`]; [`TextureError::TexelCount`] unless `texels` has `width × height`
    /// entries.
    pub const fn new(
        texels: &'static [u16],
        width: u32,
        height: u32,
    ) -> Result<Texture, TextureError> {
        if !(width.is_power_of_two()
            && height.is_power_of_two()
            && width <= MAX_TEXTURE_SIZE
            && height <= MAX_TEXTURE_SIZE)
        {
            return Err(TextureError::BadSize { width, height });
        }
        let expected = (width * height) as usize;
        if texels.len() != expected {
            return Err(TextureError::TexelCount {
                expected,
                given: texels.len(),
            });
        }
        Ok(Texture {
            texels,
            width_log2: width.trailing_zeros() as u8,
            height_log2: height.trailing_zeros() as u8,
            wrap: [Wrap::Repeat; 2],
        })
    }

    /// This texture with the given wrap modes for `s` (across) and `t` (down).
    #[must_use]
    pub const fn with_wrap(self, s: Wrap, t: Wrap) -> Self {
        Texture {
            wrap: [s, t],
            ..self
        }
    }

    /// Width in texels.
    #[must_use]
    pub const fn width(&self) -> u32 {
        1 << self.width_log2
    }

    /// Height in texels.
    #[must_use]
    pub const fn height(&self) -> u32 {
        1 << self.height_log2
    }

    /// The wrap modes of `s` and `t`.
    #[must_use]
    pub const fn wrap(&self) -> [Wrap; 2] {
        self.wrap
    }

    /// The texels, row-major.
    #[must_use]
    pub const fn texels(&self) -> &'static [u16] {
        self.texels
    }

    /// The texel at column `i`, row `j` after wrapping or clamping them.
    #[must_use]
    pub fn texel(&self, i: i32, j: i32) -> u16 {
        let (w, h) = (self.width_log2 as u32, self.height_log2 as u32);
        self.texels[(self.row_index(j, h) << w) | self.col_index(i, w, 0)]
    }

    #[inline(always)]
    pub(crate) fn col_index(&self, i: i32, log2: u32, axis: usize) -> usize {
        let n = 1i32 << log2;
        match self.wrap[axis] {
            Wrap::Repeat => (i & (n - 1)) as usize,
            Wrap::Clamp => i.clamp(0, n - 1) as usize,
        }
    }

    #[inline(always)]
    fn row_index(&self, j: i32, log2: u32) -> usize {
        self.col_index(j, log2, 1)
    }

    pub(crate) fn logs(&self) -> (u32, u32) {
        (self.width_log2 as u32, self.height_log2 as u32)
    }

    /// The texel nearest to `(s, t)` (texture units, as [`crate::Mesh::with_uvs`] gives them),
    /// in `f64`: the reference the renderer's sampling is measured against.
    #[must_use]
    pub fn sample_f64(&self, s: f64, t: f64) -> u16 {
        let i = libm::floor(s * self.width() as f64);
        let j = libm::floor(t * self.height() as f64);
        // Far outside the i32 range the texel does not matter for a repeat (any multiple of
        // the width) and is the edge for a clamp.
        let c = |v: f64| v.clamp(-1073741824.0, 1073741824.0) as i32;
        self.texel(c(i), c(j))
    }
}

/// How a textured triangle's spans find their texture coordinates.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Default, Hash)]
#[repr(u8)]
#[non_exhaustive]
pub enum TextureMode {
    /// Perspective-correct at every pixel (a reciprocal per pixel): the reference, slowest.
    PerPixel,
    /// Perspective-correct every 16 pixels (one reciprocal per 16-pixel segment), linear in
    /// between: the default.
    #[default]
    Subdivided16,
    /// Perspective-correct every 8 pixels, linear in between.
    Subdivided8,
    /// Linear in screen space (no reciprocal): fastest, and wrong in perspective by an amount
    /// that grows with the triangle's depth range.
    Affine,
}

impl TextureMode {
    /// Pixels per segment between exact texture coordinates (`None`: the whole span).
    pub(crate) fn segment(self) -> Option<i32> {
        match self {
            TextureMode::PerPixel => Some(1),
            TextureMode::Subdivided16 => Some(16),
            TextureMode::Subdivided8 => Some(8),
            TextureMode::Affine => None,
        }
    }
}

/// A material's texture: the image, how spans map it, and an optional colour key (a texel
/// value that is not drawn: the pixel keeps what it had, its depth is not written). Built
/// with [`Texturing::new`] and the `with_` methods (or [`crate::Material::textured`]); 8
/// bytes on a 32-bit core (a [`crate::Material`] is on the deepest stack of a frame).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct Texturing {
    texture: &'static Texture,
    key: u16,
    keyed: bool,
    mode: TextureMode,
}

impl Texturing {
    /// `texture` with the default mode ([`TextureMode::Subdivided16`]) and no colour key.
    #[must_use]
    pub const fn new(texture: &'static Texture) -> Self {
        Texturing {
            texture,
            key: 0,
            keyed: false,
            mode: TextureMode::Subdivided16,
        }
    }

    /// This texturing with span mode `mode`.
    #[must_use]
    pub const fn with_mode(self, mode: TextureMode) -> Self {
        Texturing { mode, ..self }
    }

    /// This texturing with colour key `key` (`None`: every texel is drawn).
    #[must_use]
    pub const fn with_key(self, key: Option<u16>) -> Self {
        match key {
            Some(k) => Texturing {
                key: k,
                keyed: true,
                ..self
            },
            None => Texturing {
                key: 0,
                keyed: false,
                ..self
            },
        }
    }

    /// The image.
    #[must_use]
    pub const fn texture(&self) -> &'static Texture {
        self.texture
    }

    /// The span mode.
    #[must_use]
    pub const fn mode(&self) -> TextureMode {
        self.mode
    }

    /// The colour key, if any.
    #[must_use]
    pub const fn key(&self) -> Option<u16> {
        if self.keyed {
            Some(self.key)
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    static T4: [u16; 8] = [0, 1, 2, 3, 4, 5, 6, 7];

    #[test]
    fn sizes_are_checked() {
        assert_eq!(
            Texture::new(&T4, 3, 2),
            Err(TextureError::BadSize {
                width: 3,
                height: 2
            })
        );
        assert_eq!(
            Texture::new(&T4, 2, 2),
            Err(TextureError::TexelCount {
                expected: 4,
                given: 8
            })
        );
        static BIG: [u16; 0] = [];
        assert!(matches!(
            Texture::new(&BIG, 2048, 1),
            Err(TextureError::BadSize { .. })
        ));
    }

    #[test]
    fn texturing_is_two_words_on_a_32_bit_core() {
        static T: [u16; 1] = [0];
        static TEX: Texture = match Texture::new(&T, 1, 1) {
            Ok(t) => t,
            Err(_) => panic!(),
        };
        let t = Texturing::new(&TEX)
            .with_key(Some(7))
            .with_mode(TextureMode::Affine);
        assert_eq!((t.key(), t.mode()), (Some(7), TextureMode::Affine));
        assert_eq!(t.with_key(None).key(), None);
        let words = core::mem::size_of::<usize>();
        assert_eq!(
            core::mem::size_of::<Option<Texturing>>(),
            words + 4.max(words)
        );
    }

    #[test]
    fn wrap_and_clamp_per_axis() {
        let t = Texture::new(&T4, 4, 2).unwrap();
        assert_eq!((t.width(), t.height()), (4, 2));
        assert_eq!(t.texel(5, 0), 1);
        assert_eq!(t.texel(-1, 1), 7);
        assert_eq!(t.texel(1, 3), 5);
        let c = t.with_wrap(Wrap::Clamp, Wrap::Repeat);
        assert_eq!(c.texel(-3, 0), 0);
        assert_eq!(c.texel(9, 3), 7);
        let c = t.with_wrap(Wrap::Repeat, Wrap::Clamp);
        assert_eq!(c.texel(5, -4), 1);
        assert_eq!(c.texel(-1, 9), 7);
        // Nearest texel of (s, t): the square that contains it.
        assert_eq!(t.sample_f64(0.24, 0.49), 0);
        assert_eq!(t.sample_f64(0.25, 0.5), 5);
        assert_eq!(t.sample_f64(-0.01, 0.0), 3);
    }
}
