//! Raw bytes → a mesh (any f32 bit patterns, NaN and infinities included), indices (in or out
//! of range), a camera, a light, a material and options → a frame with every number type. The
//! renderer must return Ok or a named error; any panic (including a debug overflow) is a crash.
#![no_main]

#[path = "render_input.rs"]
mod render_input;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    render_input::render_all(data);
});
