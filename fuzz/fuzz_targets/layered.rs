//! Raw bytes → a layered frame (planar and blob shadows, shadow volumes, outlines, translucent,
//! textured and Phong objects, point lights, fog, tone maps; adjacency tables right or
//! garbage) → a layered frame (`FrameOptions::layered`) and `render` with every number type. The renderer must return
//! Ok or a named error; any panic (including a debug overflow), hang or failed documented
//! invariant is a crash.
#![no_main]

#[path = "layered_input.rs"]
mod layered_input;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    layered_input::layered_all(data);
});
