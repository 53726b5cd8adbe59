//! `render --tone clamp|reinhard|filmic --exposure E|auto --light-intensity X`: HDR lighting
//! and tone mapping ([`ToneMap`]), with the exposure adapting over the frames (`auto`:
//! [`AutoExposure`] fed by [`Metered`], as a device measures the strips it sends).

use clap::ValueEnum;
use scanline3d::{
    limits::MAX_TONE_SCALE, tone::AutoExposure, tone::Metered, tone::ToneCurve, Scalar, Scene,
    TargetColor, ToneMap,
};
use scanline3d_support::hash::NullTarget;

use super::{Args, Big, LIGHTS};

/// The mean luma `--exposure auto` aims at (0..=255).
pub const AUTO_TARGET: u8 = 96;
/// How far the exposure moves toward the one that would reach the target, per frame (256ths).
pub const AUTO_RATE: u16 = 96;
/// Frames the exposure adapts over (at the first frame's pose) before the first frame kept.
pub const AUTO_WARMUP: usize = 16;

/// `--tone`.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum ToneArg {
    /// Clamp at white (with exposure and intensity 1: the image without a tone map)
    Clamp,
    /// x / (1 + x)
    Reinhard,
    /// Filmic (a fit of the ACES curve): a toe and a soft shoulder
    Filmic,
}

/// `--exposure`: a number, or `auto`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum ExposureArg {
    Fixed(f64),
    Auto,
}

/// Parses `--exposure`.
pub fn exposure(s: &str) -> Result<ExposureArg, String> {
    if s == "auto" {
        return Ok(ExposureArg::Auto);
    }
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 && v <= MAX_TONE_SCALE => Ok(ExposureArg::Fixed(v)),
        _ => Err(format!(
            "--exposure must be `auto` or a number above 0 and at most {MAX_TONE_SCALE}, got {s}"
        )),
    }
}

/// Whether the command line asks for a tone map (any of its flags).
pub fn on(args: &Args) -> bool {
    args.tone.is_some() || args.exposure.is_some() || args.light_intensity.is_some()
}

/// The flags' checks (usage errors).
pub fn check(args: &Args) -> Result<(), String> {
    if let Some(i) = args.light_intensity {
        if !(i.is_finite() && (0.0..=MAX_TONE_SCALE).contains(&i)) {
            return Err(format!(
                "--light-intensity must be in [0, {MAX_TONE_SCALE}], got {i}"
            ));
        }
    }
    Ok(())
}

/// The tone map for the next frame (`auto`: its exposure so far), or `None` without the flags.
pub fn tone_map<S: Scalar>(args: &Args, auto: Option<&AutoExposure>) -> Option<ToneMap<S>> {
    if !on(args) {
        return None;
    }
    let curve = match args.tone.unwrap_or(ToneArg::Clamp) {
        ToneArg::Clamp => ToneCurve::Clamp,
        ToneArg::Reinhard => ToneCurve::Reinhard,
        ToneArg::Filmic => ToneCurve::Filmic,
    };
    let exposure = match (auto, args.exposure) {
        (Some(a), _) => a.exposure::<S>(),
        (None, Some(ExposureArg::Fixed(e))) => S::from_f64(e),
        (None, _) => S::ONE,
    };
    Some(
        ToneMap::new(curve)
            .with_intensity(S::from_f64(args.light_intensity.unwrap_or(1.0)))
            .with_exposure(exposure),
    )
}

/// The automatic exposure, when `--exposure auto`.
pub fn auto(args: &Args) -> Option<AutoExposure> {
    (args.exposure == Some(ExposureArg::Auto)).then(|| AutoExposure::new(AUTO_TARGET, AUTO_RATE))
}

/// Draws `scene` into a target that keeps nothing but measures the mean luma (as the display
/// would receive it), and adapts `auto` to it.
pub fn adapt<S: Scalar, C: TargetColor>(
    auto: &mut AutoExposure,
    r: &mut Big<S, C>,
    scene: &Scene<'_, S, LIGHTS>,
    (w, h): (usize, usize),
) {
    let mut sink = NullTarget::<C>::new(w as u32, h as u32);
    // The model's pixels, not the background's.
    let mut metered =
        Metered::new(&mut sink).excluding(scanline3d::color::quantize::<C>(scene.background));
    if r.render(scene, &mut metered).is_ok() {
        auto.adapt(metered.mean());
    }
}

/// `--budget`'s lines for the tone map: the largest radiance the lights can reach (units of
/// white), exposed, against what Q16.16 holds in the lighting (a channel's value below 32 768,
/// 128.5 × white in channel units 0..=255). `Err` when it does not fit.
pub fn budget(args: &Args, ambient: f64, diffuse: f64, specular: f64) -> Result<(), String> {
    if !on(args) {
        return Ok(());
    }
    let m = scanline3d::Material::matte([255; 3], ambient, diffuse).specular(specular, 1);
    let t = tone_map::<f64>(args, None).expect("the flags are on");
    let lights = args.light.len().max(1) + args.point_light.len();
    let peak = t.peak(&m, lights);
    let exposure = match args.exposure {
        Some(ExposureArg::Fixed(e)) => e,
        Some(ExposureArg::Auto) => MAX_TONE_SCALE,
        None => 1.0,
    };
    let range = 32768.0 / 255.0;
    println!(
        "  HDR lighting: radiance up to {peak:.2} × white from {lights} light(s), × exposure {exposure} = {:.2} (Q16.16 holds {range:.1} × white: margin {:.1}x)",
        peak * exposure,
        range / (peak * exposure).max(1e-30)
    );
    if peak * exposure >= range {
        return Err(format!(
            "the HDR radiance ({:.1} × white) overflows Q16.16's {range:.1}: lower --light-intensity or --exposure",
            peak * exposure
        ));
    }
    Ok(())
}
