// Baked by `cargo run --release -p scanline3d-tools --bin bake -- --texture checker8.png --name CHECKER8 --wrap repeat`
// from checker8.png (Rgba, 8 bits per sample). Do not edit.
//
// 8 x 8 texels, RGB565 (red bits 11..15, green 5..10, blue 0..4), 128 bytes of flash.
// Quantized by rounding: largest error 3.613, mean 1.552 (8-bit units, every channel of
// the 62 opaque pixels).
// 2 transparent pixels (alpha below one half) are the colour key 0xF81F, the value of no
// opaque texel: `Material::color_key(CHECKER8_KEY)` leaves them undrawn.

/// The texels, row-major, top row first.
pub static CHECKER8_TEXELS: [u16; 64] = [
    0xF800, 0x0FC0, 0x8218, 0x0FC0, 0x8218, 0x0FC0, 0x8218, 0xFFFF,
    0x0FC0, 0x8218, 0x0FC0, 0x8218, 0x0FC0, 0x8218, 0x0FC0, 0x8218,
    0x8218, 0x0FC0, 0x8218, 0x0FC0, 0x8218, 0x0FC0, 0x8218, 0x0FC0,
    0x0FC0, 0x8218, 0x0FC0, 0x8218, 0x0FC0, 0x8218, 0x0FC0, 0x8218,
    0x8218, 0x0FC0, 0x8218, 0x0FC0, 0xF81F, 0x0FC0, 0x8218, 0x0FC0,
    0x0FC0, 0x8218, 0x0FC0, 0x8218, 0x0FC0, 0x8218, 0x0FC0, 0x8218,
    0x8218, 0x0FC0, 0x8218, 0x0FC0, 0x8218, 0x0FC0, 0x8218, 0x0FC0,
    0x8410, 0x8218, 0x0FC0, 0x8218, 0x0FC0, 0x8218, 0x0FC0, 0xF81F,
];

/// The 8 x 8 texture, wrap repeat across (s) and down (t).
pub static CHECKER8: scanline3d::Texture =
    match scanline3d::Texture::new(&CHECKER8_TEXELS, 8, 8) {
        Ok(t) => t.with_wrap(scanline3d::Wrap::Repeat, scanline3d::Wrap::Repeat),
        Err(_) => panic!("CHECKER8: not a texture size"),
    };

/// The value of the transparent texels, for `Material::color_key`.
pub const CHECKER8_KEY: u16 = 0xF81F;
