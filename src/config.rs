//! Named capacities: the renderer's type spelled with names instead of seven positions.
//!
//! [`Renderer`]'s size and capacities are const generic parameters — its storage is arrays of
//! those lengths, which stable Rust cannot take from a trait's associated constants — and
//! `Renderer<Q, Rgb565, 240, 240, 400, 600, 64>` says nothing about which number is which:
//! with `VERTS` and `TRIS` swapped it compiles just as well. Two ways to name them, which
//! expand to that same positional type:
//!
//! * [`renderer_type!`](crate::renderer_type) with `name: value` pairs, in any order, every
//!   one required except `lines` (default 1):
//!
//!   ```
//!   use embedded_graphics::pixelcolor::Rgb565;
//!   use scanline3d::fixed::types::I16F16;
//!   use scanline3d::{renderer_type, Fx, Renderer};
//!
//!   type Q = Fx<I16F16>;
//!   type Device = renderer_type!(Q, Rgb565,
//!       width: 240, height: 240, vertices: 400, triangles: 600, active: 64);
//!   // The same type as the positional spelling:
//!   let r: Box<Renderer<Q, Rgb565, 240, 240, 400, 600, 64, 1>> = Box::new(Device::new());
//!   assert_eq!(Device::CAPACITIES.vertices, 400);
//!   ```
//!
//! * a [`Capacities`] constant, a struct with named fields (the compiler then reports a
//!   missing, unknown or repeated field as for any struct), given to the same macro:
//!
//!   ```
//!   use embedded_graphics::pixelcolor::Rgb565;
//!   use scanline3d::fixed::types::I16F16;
//!   use scanline3d::{renderer_type, Capacities, Fx};
//!
//!   const BOARD: Capacities = Capacities {
//!       width: 240,
//!       height: 240,
//!       vertices: 512,
//!       triangles: 480,
//!       active: 64,
//!       lines: 8,
//!       attr_vertices: 0,
//!       attr_active: 0,
//!   };
//!   type Board = renderer_type!(Fx<I16F16>, Rgb565, BOARD);
//!   // A variant: struct update syntax.
//!   type Narrow = renderer_type!(Fx<I16F16>, Rgb565, Capacities { active: 16, ..BOARD });
//!   assert_eq!(Board::CAPACITIES, BOARD);
//!   assert_eq!(Narrow::CAPACITY.active, 16);
//!   ```
//!
//! Either way every value is checked when the type is written — a `cargo check` fails on a
//! zero or too large capacity, with the capacity's name in the message ([`Capacities`] lists
//! the limits) — where the positional type's own check runs only when
//! [`Renderer::new`] or [`Renderer::const_new`] is compiled for it (a `cargo build`).
//!
//! The values are constants, so they can come from anywhere a constant can, e.g. the largest
//! [`Needs`] measured over an animation on the host with [`Renderer::needs`] (and a margin),
//! pasted in; on the host, check a measurement against them with
//! [`Needs::fits`]`(&BOARD.capacity())` or [`Renderer::CAPACITY`].
//!
//! The macro's values must be constant expressions that do not use a generic parameter (they
//! are evaluated in a `{ … }` block): in code generic over the size, write the positional
//! type.

use core::fmt;

use crate::raster::{ActiveList, FLAT_BIT};
use crate::renderer::{ram_formula, Needs, Renderer};

/// The size and capacities of a [`Renderer`], by name: what its const generic parameters
/// `W`, `H`, `VERTS`, `TRIS`, `ACTIVE`, `LINES`, `XV` and `XA` are.
///
/// Build it with a struct expression, so that every figure is named (and each exactly once:
/// the compiler rejects a missing, unknown or repeated field), and give it to
/// [`renderer_type!`](crate::renderer_type) for the renderer type; or read a renderer type's
/// own ([`Renderer::CAPACITIES`]).
///
/// | field | parameter | range | what |
/// |---|---|---|---|
/// | `width`, `height` | `W`, `H` | 1..=[`MAX_SCREEN`](Self::MAX_SCREEN) (1024) | screen size in pixels |
/// | `vertices` | `VERTS` | 1..=[`MAX_VERTICES`](Self::MAX_VERTICES) (32 768) | vertex store: a frame's [`Needs::vertices`] |
/// | `triangles` | `TRIS` | 1..=[`MAX_TRIANGLES`](Self::MAX_TRIANGLES) (32 767) | triangles kept for the row pass: [`Needs::triangles`] |
/// | `active` | `ACTIVE` | 1..=[`MAX_ACTIVE`](Self::MAX_ACTIVE) (32 768) | triangles crossing one row: [`Needs::active`] |
/// | `lines` | `LINES` | 1.. | rows per strip |
/// | `attr_vertices` | `XV` | 0..=32 768 | attribute store (textures, Phong): [`Needs::attr_vertices`] |
/// | `attr_active` | `XA` | 0..=32 768 | attribute pool (textures, Phong): [`Needs::attr_active`] |
///
/// ```
/// use scanline3d::{Capacities, Needs};
///
/// const DEVICE: Capacities = Capacities {
///     width: 240,
///     height: 240,
///     vertices: 512,
///     triangles: 480,
///     active: 64,
///     lines: 1,
///     attr_vertices: 0,
///     attr_active: 0,
/// }
/// .checked(); // optional: fails the build here, not only where the type is written
/// // What a frame measured on the host needed (`Renderer::needs`, `Needs::max`):
/// let worst = Needs::new(512, 466, 61);
/// assert!(worst.fits(&DEVICE.capacity()));
/// // The renderer's RAM in bytes for 2-byte pixels (RGB565), by the documented formula.
/// assert_eq!(DEVICE.ram_estimate(2), 240 * 4 + 12 * 512 + 6 * 480 + 84 * 64 + 4 * 240);
/// // Ready to paste into `renderer_type!(Q, Rgb565, …)`:
/// assert_eq!(
///     DEVICE.to_string(),
///     "width: 240, height: 240, vertices: 512, triangles: 480, active: 64, lines: 1"
/// );
/// ```
///
/// A field left out does not compile (nor does a misspelt or repeated one):
///
/// ```compile_fail,E0063
/// const DEVICE: scanline3d::Capacities = scanline3d::Capacities {
///     width: 240,
///     height: 240,
///     vertices: 512,
///     triangles: 480,
///     lines: 1,
///     attr_vertices: 0,
///     attr_active: 0,
/// }; // error[E0063]: missing field `active`
/// ```
///
/// Nor does a capacity out of range, once checked ([`Capacities::checked`], or given to
/// [`renderer_type!`](crate::renderer_type)):
///
/// ```compile_fail,E0080
/// const DEVICE: scanline3d::Capacities = scanline3d::Capacities {
///     width: 240,
///     height: 240,
///     vertices: 512,
///     triangles: 0, // panicked: "triangles must be 1..=32767 (Capacities::MAX_TRIANGLES)"
///     active: 64,
///     lines: 1,
///     attr_vertices: 0,
///     attr_active: 0,
/// }
/// .checked();
/// ```
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Capacities {
    /// Screen width in pixels (`W`).
    pub width: usize,
    /// Screen height in pixels (`H`).
    pub height: usize,
    /// Vertex store (`VERTS`): mesh vertices of every object, vertices made by clipping, and
    /// one face-colour vertex per drawn flat-shaded triangle ([`Needs::vertices`]).
    pub vertices: usize,
    /// Triangles stored for the row pass (`TRIS`, [`Needs::triangles`]).
    pub triangles: usize,
    /// Triangles crossing one pixel row at once (`ACTIVE`, [`Needs::active`]).
    pub active: usize,
    /// Rows per strip (`LINES`; 1 is the usual choice).
    pub lines: usize,
    /// The attribute store's vertices (`XV`, [`Needs::attr_vertices`]): 0 for a renderer
    /// without textures and Phong shading.
    pub attr_vertices: usize,
    /// The attribute pool's entries (`XA`, [`Needs::attr_active`]): 0 for a renderer without
    /// textures and Phong shading.
    pub attr_active: usize,
}

impl Capacities {
    /// Largest `width` and `height`.
    pub const MAX_SCREEN: usize = crate::geometry::project::MAX_SCREEN;
    /// Largest `vertices`.
    pub const MAX_VERTICES: usize = FLAT_BIT as usize;
    /// Largest `triangles`.
    pub const MAX_TRIANGLES: usize = i16::MAX as usize;
    /// Largest `active`.
    pub const MAX_ACTIVE: usize = ActiveList::<1>::MAX;

    /// `self`, after checking every field against its range (see the table above); panics
    /// with the field's name otherwise, which in a `const` is a compile error.
    #[must_use]
    pub const fn checked(self) -> Self {
        __macro::width(self.width);
        __macro::height(self.height);
        __macro::vertices(self.vertices);
        __macro::triangles(self.triangles);
        __macro::active(self.active);
        __macro::lines(self.lines);
        __macro::attr_vertices(self.attr_vertices);
        __macro::attr_active(self.attr_active);
        self
    }

    /// The capacities a frame's [`Needs`] are compared with ([`Needs::fits`]), as
    /// [`Renderer::CAPACITY`] gives them for a renderer type (for a layered frame, add the
    /// [`crate::Layers`]' lists with [`Needs::with_layers`]).
    #[must_use]
    pub const fn capacity(&self) -> Needs {
        Needs::new(self.vertices, self.triangles, self.active)
            .with_stores(self.attr_vertices, self.attr_active)
    }

    /// The renderer's RAM in bytes by the documented formula
    /// ([`ram_formula`], plus the attribute stores) for pixels of `color_bytes` bytes
    /// (`size_of::<C>()`: 2 for RGB565); the renderer type's [`Renderer::RAM_BYTES`] is the
    /// exact figure, at most 160 bytes more.
    #[must_use]
    pub const fn ram_estimate(&self, color_bytes: usize) -> usize {
        ram_formula(
            self.width,
            self.height,
            color_bytes,
            self.lines,
            self.vertices,
            self.triangles,
            self.active,
        ) + self.attr_vertices * crate::renderer::VERTEX_EXTRA_BYTES
            + self.attr_active * crate::renderer::ACTIVE_EXTRA_BYTES
    }
}

/// `width: W, height: H, vertices: V, triangles: T, active: A, lines: L` (and
/// `, attr_vertices: XV, attr_active: XA` when either is not 0): the arguments
/// [`renderer_type!`](crate::renderer_type) takes after the two types.
impl fmt::Display for Capacities {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "width: {}, height: {}, vertices: {}, triangles: {}, active: {}, lines: {}",
            self.width, self.height, self.vertices, self.triangles, self.active, self.lines
        )?;
        if self.attr_vertices != 0 || self.attr_active != 0 {
            write!(
                f,
                ", attr_vertices: {}, attr_active: {}",
                self.attr_vertices, self.attr_active
            )?;
        }
        Ok(())
    }
}

impl<
        S,
        C,
        const W: usize,
        const H: usize,
        const VERTS: usize,
        const TRIS: usize,
        const ACTIVE: usize,
        const LINES: usize,
        const XV: usize,
        const XA: usize,
        const ZL: usize,
    > Renderer<S, C, W, H, VERTS, TRIS, ACTIVE, LINES, XV, XA, ZL>
{
    /// This renderer type's size and capacities, by name.
    pub const CAPACITIES: Capacities = Capacities {
        width: W,
        height: H,
        vertices: VERTS,
        triangles: TRIS,
        active: ACTIVE,
        lines: LINES,
        attr_vertices: XV,
        attr_active: XA,
    };
}

/// The [`Renderer`] type for a number type, a colour type and named capacities.
///
/// `renderer_type!(S, C, width: W, height: H, vertices: V, triangles: T, active: A)` (with an
/// optional `lines: L`, default 1, and the attribute stores `attr_vertices: XV` and
/// `attr_active: XA`, default 0) is `Renderer<S, C, W, H, V, T, A, L, XV, XA>`. The names may
/// come in any order; each is required (but `lines`, `attr_vertices` and `attr_active`) and
/// may be given once. Or
/// `renderer_type!(S, C, CAPS)` with `CAPS` a [`Capacities`] constant (any constant
/// expression of that type). The values are checked against their ranges ([`Capacities`])
/// where the type is written. It is a type, so it goes where a type goes: a `type` alias, a
/// `static`'s type, `Box<…>`, `<…>::new()`.
///
/// ```
/// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
/// use scanline3d::{renderer_type, Renderer};
///
/// type Small = renderer_type!(f32, Rgb565,
///     active: 16, vertices: 64, triangles: 96, height: 32, width: 48, lines: 4);
/// let small: Renderer<f32, Rgb565, 48, 32, 64, 96, 16, 4> = Small::const_new(Rgb565::BLACK);
/// assert_eq!(small.viewport(), (48, 32));
///
/// // With the attribute stores, for textured or Phong objects:
/// type Textured = renderer_type!(f32, Rgb565, width: 48, height: 32, vertices: 64,
///     triangles: 96, active: 16, attr_vertices: 64, attr_active: 20);
/// let t: Renderer<f32, Rgb565, 48, 32, 64, 96, 16, 1, 64, 20> = Textured::new();
/// assert_eq!(Textured::CAPACITY.attr_active, 20);
/// ```
///
/// Mistakes are compile errors that name the mistake. A name left out:
///
/// ```compile_fail
/// # use embedded_graphics::pixelcolor::Rgb565;
/// // error: renderer_type!: `triangles: …` is missing
/// type R = scanline3d::renderer_type!(f32, Rgb565,
///     width: 48, height: 32, vertices: 64, active: 16);
/// ```
///
/// A name given twice:
///
/// ```compile_fail
/// # use embedded_graphics::pixelcolor::Rgb565;
/// // error: renderer_type!: `vertices` is given twice
/// type R = scanline3d::renderer_type!(f32, Rgb565,
///     width: 48, height: 32, vertices: 64, triangles: 96, active: 16, vertices: 96);
/// ```
///
/// An unknown name:
///
/// ```compile_fail
/// # use embedded_graphics::pixelcolor::Rgb565;
/// // error: renderer_type!: unknown name `verts` (the names are width, height, vertices,
/// // triangles, active, lines, attr_vertices and attr_active)
/// type R = scanline3d::renderer_type!(f32, Rgb565,
///     width: 48, height: 32, verts: 64, triangles: 96, active: 16);
/// ```
///
/// A value out of range, where the type is written (a `cargo check` reports it, with the name;
/// the positional type's own check needs a renderer built, and a `cargo build`: here
/// `Renderer<f32, Rgb565, 48, 32, 64, 96, 0>::CAPACITIES` compiles):
///
/// ```compile_fail,E0080
/// # use embedded_graphics::pixelcolor::Rgb565;
/// // error[E0080]: evaluation panicked: active must be 1..=32768 (Capacities::MAX_ACTIVE)
/// type R = scanline3d::renderer_type!(f32, Rgb565,
///     width: 48, height: 32, vertices: 64, triangles: 96, active: 0);
/// let caps = R::CAPACITIES;
/// ```
///
/// ```compile_fail,E0080
/// # use embedded_graphics::pixelcolor::Rgb565;
/// // error[E0080]: evaluation panicked: width must be 1..=1024 (Capacities::MAX_SCREEN)
/// type R = scanline3d::renderer_type!(f32, Rgb565,
///     width: 1025, height: 32, vertices: 64, triangles: 96, active: 16);
/// let caps = R::CAPACITIES;
/// ```
///
/// Something else than a [`Capacities`] where one is expected (here [`Needs`], which has no
/// size and whose figures are positional):
///
/// ```compile_fail,E0308
/// # use embedded_graphics::pixelcolor::Rgb565;
/// type R = scanline3d::renderer_type!(f32, Rgb565, scanline3d::Needs::new(64, 96, 16));
/// let caps = R::CAPACITIES;
/// ```
#[macro_export]
macro_rules! renderer_type {
    ($s:ty, $c:ty, $($name:ident : $value:expr),+ $(,)?) => {
        $crate::__renderer_type_named!($s, $c, [] [] [] [] [] [] [] []; $($name : $value,)+)
    };
    ($s:ty, $c:ty, $caps:expr $(,)?) => {
        $crate::Renderer<
            $s,
            $c,
            { $crate::__renderer_type::width($crate::__renderer_type::caps($caps).width) },
            { $crate::__renderer_type::height($crate::__renderer_type::caps($caps).height) },
            { $crate::__renderer_type::vertices($crate::__renderer_type::caps($caps).vertices) },
            { $crate::__renderer_type::triangles($crate::__renderer_type::caps($caps).triangles) },
            { $crate::__renderer_type::active($crate::__renderer_type::caps($caps).active) },
            { $crate::__renderer_type::lines($crate::__renderer_type::caps($caps).lines) },
            { $crate::__renderer_type::attr_vertices($crate::__renderer_type::caps($caps).attr_vertices) },
            { $crate::__renderer_type::attr_active($crate::__renderer_type::caps($caps).attr_active) },
        >
    };
    ($($other:tt)*) => {
        ::core::compile_error!(
            "renderer_type!(S, C, width: W, height: H, vertices: V, triangles: T, active: A \
             [, lines: L] [, attr_vertices: XV] [, attr_active: XA]) or renderer_type!(S, C, \
             CAPACITIES) with a scanline3d::Capacities"
        )
    };
}

/// The named form of [`renderer_type!`]: takes the `name: value,` pairs one at a time into eight
/// slots (`[]` while empty) in the order width, height, vertices, triangles, active, lines,
/// attr_vertices, attr_active.
#[doc(hidden)]
#[macro_export]
macro_rules! __renderer_type_named {
    // A name into its empty slot.
    ($s:ty, $c:ty, [] $h:tt $v:tt $t:tt $a:tt $l:tt $xv:tt $xa:tt; width : $x:expr, $($rest:tt)*) => {
        $crate::__renderer_type_named!($s, $c, [$x] $h $v $t $a $l $xv $xa; $($rest)*)
    };
    ($s:ty, $c:ty, $w:tt [] $v:tt $t:tt $a:tt $l:tt $xv:tt $xa:tt; height : $x:expr, $($rest:tt)*) => {
        $crate::__renderer_type_named!($s, $c, $w [$x] $v $t $a $l $xv $xa; $($rest)*)
    };
    ($s:ty, $c:ty, $w:tt $h:tt [] $t:tt $a:tt $l:tt $xv:tt $xa:tt; vertices : $x:expr, $($rest:tt)*) => {
        $crate::__renderer_type_named!($s, $c, $w $h [$x] $t $a $l $xv $xa; $($rest)*)
    };
    ($s:ty, $c:ty, $w:tt $h:tt $v:tt [] $a:tt $l:tt $xv:tt $xa:tt; triangles : $x:expr, $($rest:tt)*) => {
        $crate::__renderer_type_named!($s, $c, $w $h $v [$x] $a $l $xv $xa; $($rest)*)
    };
    ($s:ty, $c:ty, $w:tt $h:tt $v:tt $t:tt [] $l:tt $xv:tt $xa:tt; active : $x:expr, $($rest:tt)*) => {
        $crate::__renderer_type_named!($s, $c, $w $h $v $t [$x] $l $xv $xa; $($rest)*)
    };
    ($s:ty, $c:ty, $w:tt $h:tt $v:tt $t:tt $a:tt [] $xv:tt $xa:tt; lines : $x:expr, $($rest:tt)*) => {
        $crate::__renderer_type_named!($s, $c, $w $h $v $t $a [$x] $xv $xa; $($rest)*)
    };
    ($s:ty, $c:ty, $w:tt $h:tt $v:tt $t:tt $a:tt $l:tt [] $xa:tt; attr_vertices : $x:expr, $($rest:tt)*) => {
        $crate::__renderer_type_named!($s, $c, $w $h $v $t $a $l [$x] $xa; $($rest)*)
    };
    ($s:ty, $c:ty, $w:tt $h:tt $v:tt $t:tt $a:tt $l:tt $xv:tt []; attr_active : $x:expr, $($rest:tt)*) => {
        $crate::__renderer_type_named!($s, $c, $w $h $v $t $a $l $xv [$x]; $($rest)*)
    };
    // A known name whose slot is full: given twice.
    ($s:ty, $c:ty, $w:tt $h:tt $v:tt $t:tt $a:tt $l:tt $xv:tt $xa:tt; $name:ident : $x:expr, $($rest:tt)*) => {
        $crate::__renderer_type_twice_or_unknown!($name)
    };
    // Every pair taken; `lines` (1), `attr_vertices` and `attr_active` (0) may be left out.
    ($s:ty, $c:ty, $w:tt $h:tt $v:tt $t:tt $a:tt [] $xv:tt $xa:tt;) => {
        $crate::__renderer_type_named!($s, $c, $w $h $v $t $a [1] $xv $xa;)
    };
    ($s:ty, $c:ty, $w:tt $h:tt $v:tt $t:tt $a:tt $l:tt [] $xa:tt;) => {
        $crate::__renderer_type_named!($s, $c, $w $h $v $t $a $l [0] $xa;)
    };
    ($s:ty, $c:ty, $w:tt $h:tt $v:tt $t:tt $a:tt $l:tt $xv:tt [];) => {
        $crate::__renderer_type_named!($s, $c, $w $h $v $t $a $l $xv [0];)
    };
    ($s:ty, $c:ty, [$w:expr] [$h:expr] [$v:expr] [$t:expr] [$a:expr] [$l:expr] [$xv:expr] [$xa:expr];) => {
        $crate::Renderer<
            $s,
            $c,
            { $crate::__renderer_type::width($w) },
            { $crate::__renderer_type::height($h) },
            { $crate::__renderer_type::vertices($v) },
            { $crate::__renderer_type::triangles($t) },
            { $crate::__renderer_type::active($a) },
            { $crate::__renderer_type::lines($l) },
            { $crate::__renderer_type::attr_vertices($xv) },
            { $crate::__renderer_type::attr_active($xa) },
        >
    };
    ($s:ty, $c:ty, [] $h:tt $v:tt $t:tt $a:tt $l:tt $xv:tt $xa:tt;) => {
        ::core::compile_error!("renderer_type!: `width: …` is missing")
    };
    ($s:ty, $c:ty, $w:tt [] $v:tt $t:tt $a:tt $l:tt $xv:tt $xa:tt;) => {
        ::core::compile_error!("renderer_type!: `height: …` is missing")
    };
    ($s:ty, $c:ty, $w:tt $h:tt [] $t:tt $a:tt $l:tt $xv:tt $xa:tt;) => {
        ::core::compile_error!("renderer_type!: `vertices: …` is missing")
    };
    ($s:ty, $c:ty, $w:tt $h:tt $v:tt [] $a:tt $l:tt $xv:tt $xa:tt;) => {
        ::core::compile_error!("renderer_type!: `triangles: …` is missing")
    };
    ($s:ty, $c:ty, $w:tt $h:tt $v:tt $t:tt [] $l:tt $xv:tt $xa:tt;) => {
        ::core::compile_error!("renderer_type!: `active: …` is missing")
    };
}

/// The error for a `name: value` pair that [`__renderer_type_named!`] could not take.
#[doc(hidden)]
#[macro_export]
macro_rules! __renderer_type_twice_or_unknown {
    (width) => {
        ::core::compile_error!("renderer_type!: `width` is given twice")
    };
    (height) => {
        ::core::compile_error!("renderer_type!: `height` is given twice")
    };
    (vertices) => {
        ::core::compile_error!("renderer_type!: `vertices` is given twice")
    };
    (triangles) => {
        ::core::compile_error!("renderer_type!: `triangles` is given twice")
    };
    (active) => {
        ::core::compile_error!("renderer_type!: `active` is given twice")
    };
    (lines) => {
        ::core::compile_error!("renderer_type!: `lines` is given twice")
    };
    (attr_vertices) => {
        ::core::compile_error!("renderer_type!: `attr_vertices` is given twice")
    };
    (attr_active) => {
        ::core::compile_error!("renderer_type!: `attr_active` is given twice")
    };
    ($name:ident) => {
        ::core::compile_error!(::core::concat!(
            "renderer_type!: unknown name `",
            ::core::stringify!($name),
            "` (the names are width, height, vertices, triangles, active, lines, \
             attr_vertices and attr_active)"
        ))
    };
}

/// What [`renderer_type!`](crate::renderer_type) expands to: one check per value, so that a
/// value out of range is reported once, by name.
#[doc(hidden)]
pub mod __macro {
    use super::Capacities;

    /// The macro's `CAPS` argument, as a [`Capacities`] (a type error otherwise).
    pub const fn caps(c: Capacities) -> Capacities {
        c
    }

    pub const fn width(x: usize) -> usize {
        assert!(
            x >= 1 && x <= Capacities::MAX_SCREEN,
            "width must be 1..=1024 (Capacities::MAX_SCREEN)"
        );
        x
    }

    pub const fn height(x: usize) -> usize {
        assert!(
            x >= 1 && x <= Capacities::MAX_SCREEN,
            "height must be 1..=1024 (Capacities::MAX_SCREEN)"
        );
        x
    }

    pub const fn vertices(x: usize) -> usize {
        assert!(
            x >= 1 && x <= Capacities::MAX_VERTICES,
            "vertices must be 1..=32768 (Capacities::MAX_VERTICES)"
        );
        x
    }

    pub const fn triangles(x: usize) -> usize {
        assert!(
            x >= 1 && x <= Capacities::MAX_TRIANGLES,
            "triangles must be 1..=32767 (Capacities::MAX_TRIANGLES)"
        );
        x
    }

    pub const fn active(x: usize) -> usize {
        assert!(
            x >= 1 && x <= Capacities::MAX_ACTIVE,
            "active must be 1..=32768 (Capacities::MAX_ACTIVE)"
        );
        x
    }

    pub const fn lines(x: usize) -> usize {
        assert!(x >= 1, "lines must be at least 1");
        x
    }

    pub const fn attr_vertices(x: usize) -> usize {
        assert!(
            x <= Capacities::MAX_VERTICES,
            "attr_vertices must be 0..=32768 (Capacities::MAX_VERTICES)"
        );
        x
    }

    pub const fn attr_active(x: usize) -> usize {
        assert!(
            x <= Capacities::MAX_ACTIVE,
            "attr_active must be 0..=32768 (Capacities::MAX_ACTIVE)"
        );
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_are_the_renderers() {
        // The numbers the messages and the table quote.
        assert_eq!(Capacities::MAX_SCREEN, 1024);
        assert_eq!(Capacities::MAX_VERTICES, 32768);
        assert_eq!(Capacities::MAX_TRIANGLES, 32767);
        assert_eq!(Capacities::MAX_ACTIVE, 32768);
    }
}
