//! `render --scene shadow --budget [--ram BYTES]`: every shadow method of the shadow scene with
//! its RAM and its instructions per frame as `scripts/mcu-bench` measured them on the devices
//! (`BENCHMARKS.md`, compiled into this tool, so that the report needs no QEMU), what it can
//! shadow, and the cheapest method that fits the RAM: overall, among the methods that shadow
//! every model and the models themselves, and among those with soft edges.

use super::{Args, NumberArg};

/// `BENCHMARKS.md` as it was when this tool was built (rewritten by `scripts/mcu-bench`).
const BENCHMARKS: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/../BENCHMARKS.md"));

/// The RP2040's RAM (264 KB), `--ram`'s default.
pub const RP2040_RAM: usize = 270_336;

/// What a method can shadow, from least to most.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Reach {
    /// Nothing.
    Nothing,
    /// The ground plane only (a disc or the models' projection on it).
    Plane,
    /// Any receiver that casts nothing (here the ground), curved ones too: no self-shadowing.
    NonCasters,
    /// Every model, curved ones included, and each model itself.
    Everything,
}

/// The shadow scene's methods: the benchmark scene, how `--shadow` names it, what it shadows,
/// whether its edges are soft.
const METHODS: [(&str, &str, Reach, bool); 11] = [
    ("shadow_none", "none", Reach::Nothing, false),
    ("shadow_blob", "blob", Reach::Plane, true),
    ("shadow", "projected", Reach::Plane, false),
    ("shadow_image", "image,64", Reach::NonCasters, false),
    (
        "shadow_image_blur",
        "image,64,blur",
        Reach::NonCasters,
        true,
    ),
    ("shadow_volume", "volume", Reach::Everything, false),
    ("shadow_map_32", "map,32", Reach::Everything, false),
    ("shadow_map", "map,64", Reach::Everything, false),
    ("shadow_map_128", "map,128", Reach::Everything, false),
    ("shadow_map_pcf", "map,64,pcf", Reach::Everything, true),
    ("shadow_map_pcf3", "map,64,pcf3", Reach::Everything, true),
];

/// A method's measured figures.
#[derive(Clone, Debug)]
struct Measured {
    scene: &'static str,
    flag: &'static str,
    reach: Reach,
    soft: bool,
    /// Renderer instructions per frame on the Cortex-M0 and the Cortex-M4F.
    m0: u64,
    m4f: Option<u64>,
    /// The renderer's, the layers' or the map's bytes (the same on every core).
    ram: usize,
}

/// `(instructions, RAM bytes)` of scene `scene`, number `number` on core `core` from the
/// benchmark table in `text` (columns found by their headers), or `None` when it has no row.
fn figures(text: &str, scene: &str, number: &str, core: &str) -> Option<(u64, usize)> {
    let cells = |line: &str| -> Vec<String> {
        line.trim()
            .trim_matches('|')
            .split('|')
            .map(|c| c.trim().to_string())
            .collect()
    };
    let mut columns: Option<(usize, usize)> = None;
    for line in text.lines().filter(|l| l.trim_start().starts_with('|')) {
        let c = cells(line);
        if c.first().map(String::as_str) == Some("scene") {
            let at = |h: &str| c.iter().position(|x| x == h);
            columns = at("renderer instructions").zip(at("renderer RAM B"));
            continue;
        }
        if let Some((ins, ram)) = columns {
            if c.len() > ins.max(ram) && c[0] == scene && c[1] == number && c[2] == core {
                return Some((c[ins].parse().ok()?, c[ram].parse().ok()?));
            }
        }
    }
    None
}

/// Prints the report; an error when the measurements are missing or no method fits.
pub fn report(args: &Args) -> Result<(), (String, i32)> {
    report_from(
        BENCHMARKS,
        args.number,
        args.ram.map_or(RP2040_RAM, |r| r as usize),
    )
    .map(|text| {
        print!("{text}");
    })
}

/// The report for `number` within `ram` bytes from benchmark table `text`.
fn report_from(text: &str, number: NumberArg, ram: usize) -> Result<String, (String, i32)> {
    use std::fmt::Write as _;
    let number = match number {
        NumberArg::Fixed => "I16F16",
        NumberArg::F32 => "f32",
        NumberArg::F64 => {
            return Err((
                "--budget with --scene shadow reports the devices' measurements, made in \
                 fixed point and f32: give --number fixed or f32"
                    .into(),
                2,
            ))
        }
    };
    let mut rows = Vec::new();
    for (scene, flag, reach, soft) in METHODS {
        let (m0, ram) = figures(text, scene, number, "m0").ok_or_else(|| {
            (
                format!(
                    "BENCHMARKS.md has no {scene} row for {number} on m0: run scripts/mcu-bench \
                     and rebuild this tool"
                ),
                1,
            )
        })?;
        let m4f = figures(text, scene, number, "m4f").map(|f| f.0);
        rows.push(Measured {
            scene,
            flag,
            reach,
            soft,
            m0,
            m4f,
            ram,
        });
    }
    let mut out = String::new();
    let _ = writeln!(
        out,
        "shadow scene ({number}): each shadow method's renderer RAM (renderer, layers or map) \
         and renderer instructions per frame as scripts/mcu-bench measured them \
         (BENCHMARKS.md), against {ram} bytes of RAM"
    );
    let _ = writeln!(
        out,
        "{:<18} {:<14} {:>8} {:>12} {:>12}  {:<4} shadows",
        "scene", "--shadow", "RAM B", "M0 instr.", "M4F instr.", "fits"
    );
    for r in &rows {
        let _ = writeln!(
            out,
            "{:<18} {:<14} {:>8} {:>12} {:>12}  {:<4} {}{}",
            r.scene,
            r.flag,
            r.ram,
            r.m0,
            r.m4f.map_or("-".to_string(), |i| i.to_string()),
            if r.ram <= ram { "yes" } else { "no" },
            match r.reach {
                Reach::Nothing => "nothing",
                Reach::Plane => "the ground plane only",
                Reach::NonCasters => "the receivers that cast nothing (here the ground)",
                Reach::Everything => "every model, curved ones and each itself",
            },
            if r.soft { ", soft edges" } else { "" }
        );
    }
    let fits: Vec<&Measured> = rows.iter().filter(|r| r.ram <= ram).collect();
    let cheapest = |keep: &dyn Fn(&Measured) -> bool| {
        fits.iter()
            .filter(|r| keep(r))
            .min_by_key(|r| (r.m0, r.ram))
            .copied()
    };
    let name = |r: &Measured| {
        format!(
            "--shadow {} ({}: {} instructions on M0, {} B)",
            r.flag, r.scene, r.m0, r.ram
        )
    };
    let Some(any) = cheapest(&|r| r.reach > Reach::Nothing) else {
        let smallest = rows
            .iter()
            .filter(|r| r.reach > Reach::Nothing)
            .min_by_key(|r| r.ram)
            .map(|r| {
                format!(
                    "the smallest, --shadow {} ({}), needs {} B",
                    r.flag, r.scene, r.ram
                )
            })
            .unwrap_or_default();
        return Err((
            format!("{out}no shadow method fits in {ram} bytes: {smallest}"),
            1,
        ));
    };
    let _ = writeln!(out, "cheapest that fits: {}", name(any));
    for (what, keep) in [
        (
            "shadowing every model and itself",
            &(|r: &Measured| r.reach == Reach::Everything) as &dyn Fn(&Measured) -> bool,
        ),
        ("with soft edges", &|r: &Measured| r.soft),
        ("with soft edges on every model", &|r: &Measured| {
            r.soft && r.reach == Reach::Everything
        }),
    ] {
        match cheapest(keep) {
            Some(r) => {
                let _ = writeln!(out, "cheapest {what}: {}", name(r));
            }
            None => {
                let _ = writeln!(out, "cheapest {what}: none fits in {ram} bytes");
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    const TABLE: &str = "\
| scene | number | core | renderer instructions | renderer RAM B | hash = host |
|---|---|---|---:|---:|---|
| shadow_none | I16F16 | m0 | 100 | 1000 | yes |
| shadow_blob | I16F16 | m0 | 300 | 1500 | yes |
| shadow | I16F16 | m0 | 200 | 3000 | yes |
| shadow_volume | I16F16 | m0 | 800 | 9000 | yes |
| shadow_image | I16F16 | m0 | 700 | 3500 | yes |
| shadow_image_blur | I16F16 | m0 | 750 | 3500 | yes |
| shadow_map_32 | I16F16 | m0 | 900 | 4000 | yes |
| shadow_map | I16F16 | m0 | 1000 | 6000 | yes |
| shadow_map_128 | I16F16 | m0 | 1500 | 20000 | yes |
| shadow_map_pcf | I16F16 | m0 | 1200 | 6000 | yes |
| shadow_map_pcf3 | I16F16 | m0 | 1400 | 6000 | yes |
| shadow_map | I16F16 | m4f | 700 | 6000 | yes |
";

    #[test]
    fn names_the_cheapest_that_fits() {
        let r = report_from(TABLE, NumberArg::Fixed, 100_000).unwrap();
        assert!(r.contains("cheapest that fits: --shadow projected"), "{r}");
        assert!(r.contains("every model and itself: --shadow volume"), "{r}");
        assert!(r.contains("with soft edges: --shadow blob"), "{r}");
        assert!(r.contains("image,64 "), "{r}");
        assert!(
            r.contains("soft edges on every model: --shadow map,64,pcf "),
            "{r}"
        );
        // The volumes' layers do not fit in 8 KB: the 32-texel map is the cheapest that does.
        let r = report_from(TABLE, NumberArg::Fixed, 8_000).unwrap();
        assert!(
            r.contains("every model and itself: --shadow map,32 "),
            "{r}"
        );
        // 2 KB: the projected shadow does not fit, the blob does.
        let r = report_from(TABLE, NumberArg::Fixed, 2_000).unwrap();
        assert!(r.contains("cheapest that fits: --shadow blob"), "{r}");
        assert!(
            r.contains("every model and itself: none fits in 2000 bytes"),
            "{r}"
        );
        // Nothing fits: an error naming the smallest.
        let e = report_from(TABLE, NumberArg::Fixed, 1_200).unwrap_err();
        assert!(
            e.0.contains("the smallest, --shadow blob (shadow_blob), needs 1500 B"),
            "{e:?}"
        );
        // No f32 rows, no f64 on a device.
        assert!(report_from(TABLE, NumberArg::F32, 100_000).is_err());
        assert_eq!(
            report_from(TABLE, NumberArg::F64, 100_000).unwrap_err().1,
            2
        );
    }

    /// The committed benchmark table has every method's row.
    #[test]
    fn benchmarks_have_every_method() {
        for n in [NumberArg::Fixed, NumberArg::F32] {
            let r = report_from(BENCHMARKS, n, RP2040_RAM).unwrap();
            assert!(r.contains("cheapest that fits"), "{r}");
        }
    }
}
