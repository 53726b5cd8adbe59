//! Raw bytes → a shape constructor call with any parameters (NaN, infinities, huge counts) →
//! `Ok` or a `ShapeError` that agrees with the constructor's documentation, with every number
//! type. Any panic (including a debug overflow), hang or failed check is a crash.
#![no_main]

#[path = "shapes_input.rs"]
mod shapes_input;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    shapes_input::shapes_all(data);
});
