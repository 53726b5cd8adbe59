//! Issue #21, API point 3: the renderer type written with named capacities
//! (`renderer_type!`, `Capacities`) is exactly the positional type the names say, whatever the
//! order of the names; the values are checked by name. The compile errors (a missing, repeated
//! or unknown name, a value out of range, something else than a `Capacities`) are
//! `compile_fail` doctests on `renderer_type!` and `Capacities` (`cargo test --doc`).

use std::any::TypeId;
use std::panic::{catch_unwind, AssertUnwindSafe};

use embedded_graphics::pixelcolor::{BinaryColor, Rgb565, Rgb888, RgbColor};
use scanline3d::fixed::types::I16F16;
use scanline3d::prelude::*;

type Q = Fx<I16F16>;

fn id<T: 'static>() -> TypeId {
    TypeId::of::<T>()
}

/// The example: `vertices: 400, triangles: 600` is `Renderer<.., 400, 600, ..>` in
/// every order of the names, never the swapped type; `lines` defaults to 1.
#[test]
fn names_in_any_order_spell_the_positional_type() {
    type Positional = Renderer<Q, Rgb565, 240, 240, 400, 600, 64, 1>;
    type Swapped = Renderer<Q, Rgb565, 240, 240, 600, 400, 64, 1>;
    type A = renderer_type!(Q, Rgb565,
        width: 240, height: 240, vertices: 400, triangles: 600, active: 64);
    type B = renderer_type!(Q, Rgb565,
        triangles: 600, vertices: 400, active: 64, height: 240, width: 240);
    type C = renderer_type!(Q, Rgb565,
        active: 64, width: 240, triangles: 600, height: 240, vertices: 400, lines: 1,);
    type D = renderer_type!(Q, Rgb565,
        lines: 1, vertices: 400, height: 240, active: 64, width: 240, triangles: 600);
    let spellings = [id::<A>(), id::<B>(), id::<C>(), id::<D>()];
    for (k, s) in spellings.iter().enumerate() {
        assert_eq!(*s, id::<Positional>(), "spelling {k}");
        assert_ne!(*s, id::<Swapped>(), "spelling {k}");
    }
    // Width and height are told apart too, and `lines` goes last.
    type E = renderer_type!(f32, Rgb888,
        height: 32, lines: 4, width: 48, active: 5, triangles: 6, vertices: 7);
    assert_eq!(id::<E>(), id::<Renderer<f32, Rgb888, 48, 32, 7, 6, 5, 4>>());
    // Values are any constant expressions.
    const SIDE: usize = 60;
    type F = renderer_type!(f32, Rgb565,
        width: SIDE * 2, height: SIDE, vertices: 1 << 9, triangles: 480, active: 80 - 16);
    assert_eq!(
        id::<F>(),
        id::<Renderer<f32, Rgb565, 120, 60, 512, 480, 64>>()
    );
}

const BOARD: Capacities = Capacities {
    width: 240,
    height: 240,
    vertices: 512,
    triangles: 480,
    active: 64,
    lines: 8,
    attr_vertices: 0,
    attr_active: 0,
};

/// A `Capacities` constant, or a struct expression (with `..` from another), gives the same
/// type as the names; `CAPACITIES` reads a type's back, `CAPACITY` agrees with `capacity()`.
#[test]
fn a_capacities_constant_gives_the_same_type() {
    type Board = renderer_type!(Q, Rgb565, BOARD);
    assert_eq!(
        id::<Board>(),
        id::<Renderer<Q, Rgb565, 240, 240, 512, 480, 64, 8>>()
    );
    assert_eq!(
        id::<Board>(),
        id::<
            renderer_type!(Q, Rgb565,
            width: 240, height: 240, vertices: 512, triangles: 480, active: 64, lines: 8),
        >()
    );
    assert_eq!(Board::CAPACITIES, BOARD);
    assert_eq!(Board::CAPACITY, BOARD.capacity());
    assert_eq!(BOARD.capacity(), Needs::new(512, 480, 64));

    type OneLine = renderer_type!(Q, Rgb565, Capacities { lines: 1, ..BOARD });
    assert_eq!(
        id::<OneLine>(),
        id::<Renderer<Q, Rgb565, 240, 240, 512, 480, 64>>()
    );
    assert_eq!(OneLine::CAPACITIES, Capacities { lines: 1, ..BOARD });
    // Every field of a positional type, by name.
    let c = Renderer::<f64, BinaryColor, 11, 12, 13, 14, 15, 16>::CAPACITIES;
    assert_eq!(
        (
            c.width,
            c.height,
            c.vertices,
            c.triangles,
            c.active,
            c.lines
        ),
        (11, 12, 13, 14, 15, 16)
    );
}

/// `Display` prints the macro's arguments; the named type built from them is the type the
/// constant gives (the string is what a tool would print for pasting).
#[test]
fn display_is_the_macros_arguments() {
    assert_eq!(
        BOARD.to_string(),
        "width: 240, height: 240, vertices: 512, triangles: 480, active: 64, lines: 8"
    );
    let small = Capacities {
        width: 1,
        height: 2,
        vertices: 3,
        triangles: 4,
        active: 5,
        lines: 6,
        attr_vertices: 0,
        attr_active: 0,
    };
    assert_eq!(
        small.to_string(),
        "width: 1, height: 2, vertices: 3, triangles: 4, active: 5, lines: 6"
    );
}

/// The renderer built from named capacities works like the positional one: a `static` by
/// `const_new`, the same pixels as `Renderer::new()` of the positional type.
#[test]
fn a_named_renderer_renders_like_the_positional_one() {
    use embedded_graphics::mock_display::MockDisplay;
    use std::sync::Mutex;

    const SMALL: Capacities = Capacities {
        width: 64,
        height: 64,
        vertices: 32,
        triangles: 12,
        active: 12,
        lines: 1,
        attr_vertices: 0,
        attr_active: 0,
    };
    type Small = renderer_type!(Q, Rgb565, SMALL);
    static NAMED: Mutex<Small> = Mutex::new(Small::const_new(Rgb565::BLACK));

    let cube = Shape::<Q, 24, 12>::cube(1.0).unwrap();
    let mut material = Material::matte([255, 160, 64], Q::lit(0.15), Q::lit(0.85));
    material.shading = Shading::Flat;
    let objects = [Object {
        mesh: cube.mesh(),
        transform: Mat4::rotate_y(Q::lit(0.5)) * Mat4::rotate_x(Q::lit(0.4)),
        material,
    }];
    let camera = Camera::look_at(
        [Q::ZERO, Q::ZERO, Q::lit(5.0)],
        [Q::ZERO; 3],
        [Q::ZERO, Q::ONE, Q::ZERO],
        Projection::Perspective {
            fov_y: Q::lit(0.8),
            near: Q::lit(0.1),
            far: Q::lit(10.0),
        },
    )
    .unwrap();
    let scene = Scene::new(&objects, camera, [Light::white([-Q::ONE, Q::ONE, Q::ONE])]);

    let mut a = MockDisplay::<Rgb565>::new();
    let mut b = MockDisplay::<Rgb565>::new();
    let sa = NAMED.lock().unwrap().render(&scene, &mut a).unwrap();
    let sb = Renderer::<Q, Rgb565, 64, 64, 32, 12, 12>::new()
        .render(&scene, &mut b)
        .unwrap();
    assert_eq!(sa, sb);
    assert_eq!(a, b);
    assert!(sa.pixels_written > 0);
    // The measured needs fit the named capacities.
    assert!(Needs::from_stats(&sa).fits(&SMALL.capacity()));
}

/// The most each capacity may be is what the renderer accepts: a renderer type at every limit
/// has its constructor compiled here (the renderer's own compile-time check runs when
/// `const_new` is instantiated), and `checked` passes it.
#[test]
fn the_limits_are_the_renderers() {
    const MAX: Capacities = Capacities {
        width: Capacities::MAX_SCREEN,
        height: Capacities::MAX_SCREEN,
        vertices: Capacities::MAX_VERTICES,
        triangles: Capacities::MAX_TRIANGLES,
        active: Capacities::MAX_ACTIVE,
        lines: 1,
        attr_vertices: 0,
        attr_active: 0,
    }
    .checked();
    type Max = renderer_type!(f32, BinaryColor, MAX);
    // Instantiated, not called (it would be 4 MB on the stack).
    let make: fn(BinaryColor) -> Max = Max::const_new;
    std::hint::black_box(make);
    assert_eq!(
        (
            MAX.width,
            MAX.height,
            MAX.vertices,
            MAX.triangles,
            MAX.active
        ),
        (1024, 1024, 32768, 32767, 32768)
    );
    assert_eq!(Max::CAPACITIES, MAX);
}

fn panic_message(f: impl FnOnce()) -> Option<String> {
    let err = catch_unwind(AssertUnwindSafe(f)).err()?;
    Some(
        err.downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| err.downcast_ref::<String>().cloned())
            .unwrap_or_default(),
    )
}

/// `checked` (the same checks the macro runs at compile time) rejects zero and one past the
/// limit in each field, naming the field, and accepts 1 and the limit.
#[test]
fn checked_names_the_field_out_of_range() {
    let base = Capacities {
        width: 8,
        height: 8,
        vertices: 8,
        triangles: 8,
        active: 8,
        lines: 1,
        attr_vertices: 0,
        attr_active: 0,
    };
    assert_eq!(base.checked(), base);
    type Set = fn(&mut Capacities, usize);
    let fields: [(&str, usize, Set); 6] = [
        ("width", Capacities::MAX_SCREEN, |c, v| c.width = v),
        ("height", Capacities::MAX_SCREEN, |c, v| c.height = v),
        ("vertices", Capacities::MAX_VERTICES, |c, v| c.vertices = v),
        ("triangles", Capacities::MAX_TRIANGLES, |c, v| {
            c.triangles = v
        }),
        ("active", Capacities::MAX_ACTIVE, |c, v| c.active = v),
        ("lines", usize::MAX, |c, v| c.lines = v),
    ];
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    for (name, max, set) in fields {
        for (value, ok) in [
            (0, false),
            (1, true),
            (max, true),
            (max.wrapping_add(1), false),
        ] {
            let mut c = base;
            set(&mut c, value);
            match (panic_message(|| assert_eq!(c.checked(), c)), ok) {
                (None, true) => {}
                (Some(m), false) => assert!(
                    m.starts_with(&format!("{name} must be")),
                    "{name} = {value}: {m}"
                ),
                (m, _) => panic!("{name} = {value}: {m:?}"),
            }
        }
    }
    std::panic::set_hook(hook);
}

/// `ram_estimate` is the documented formula: the exact `RAM_BYTES` of the type the same
/// capacities give is at most 160 bytes more.
#[test]
fn ram_estimate_is_within_the_formulas_slack() {
    fn check(caps: Capacities, color_bytes: usize, exact: usize) {
        let est = caps.ram_estimate(color_bytes);
        assert!(
            exact >= est && exact <= est + 160,
            "{caps}: {exact} vs {est}"
        );
    }
    type Board = renderer_type!(Q, Rgb565, BOARD);
    check(BOARD, 2, Board::RAM_BYTES);
    const WIDE: Capacities = Capacities {
        width: 320,
        height: 200,
        vertices: 100,
        triangles: 300,
        active: 20,
        lines: 4,
        attr_vertices: 0,
        attr_active: 0,
    };
    type Wide = renderer_type!(f32, Rgb888, WIDE);
    check(WIDE, 4, Wide::RAM_BYTES);
    assert_eq!(
        BOARD.ram_estimate(2),
        8 * 240 * 4 + 12 * 512 + 6 * 480 + 84 * 64 + 4 * 240
    );
}
