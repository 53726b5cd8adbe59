//! The performance ratchet of `scripts/mcu-bench` (issue #22): the renderer instruction counts
//! measured in QEMU, compared with the committed baseline (`mcu-bench/baseline.txt`). The counts
//! are exact, so the comparison has no noise: a row that costs more than [`TOLERANCE_PERCENT`]
//! over its baseline fails, unless the baseline is updated in the same commit
//! ([`UPDATE_COMMAND`]).
//!
//! Used by `tools/src/bin/mcu_report.rs`; tested on the host by `tests/mcu_ratchet.rs`, which
//! includes this file (`cargo test` does not run the tests of examples).

use std::collections::BTreeMap;
use std::fmt;
use std::fmt::Write as _;

/// The committed baseline, relative to the repository root.
pub const BASELINE_PATH: &str = "mcu-bench/baseline.txt";
/// What regenerates the baseline from the current measurement.
pub const UPDATE_COMMAND: &str = "scripts/mcu-bench --update-baseline";
/// What lowers the baseline to the current measurement where it is cheaper, and only there.
pub const LOWER_COMMAND: &str = "scripts/mcu-bench --lower-baseline";
/// How much a row may grow over its baseline, in percent, before the ratchet fails.
pub const TOLERANCE_PERCENT: u64 = 1;

/// One measured frame: a benchmark scene, its number type and the core (the log's label:
/// `m0`, `m4f`, `m33`, `microbit`).
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Key {
    pub scene: String,
    pub number: String,
    pub core: String,
}

impl Key {
    pub fn new(scene: &str, number: &str, core: &str) -> Self {
        Key {
            scene: scene.to_string(),
            number: number.to_string(),
            core: core.to_string(),
        }
    }
}

impl fmt::Display for Key {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} | {} | {}", self.scene, self.number, self.core)
    }
}

/// Renderer instructions per frame, in the report's order.
pub type Counts = Vec<(Key, u64)>;

/// True if `measured` is more than [`TOLERANCE_PERCENT`] above `baseline` (exact integer
/// arithmetic: 1 % of 2 000 000 is 20 000, and 2 020 000 still passes).
pub fn exceeds(baseline: u64, measured: u64) -> bool {
    u128::from(measured) * 100 > u128::from(baseline) * u128::from(100 + TOLERANCE_PERCENT)
}

/// One row present in both the baseline and the measurement.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Delta {
    pub key: Key,
    pub baseline: u64,
    pub measured: u64,
}

impl Delta {
    /// The change relative to the baseline, in percent.
    pub fn percent(&self) -> f64 {
        if self.baseline == 0 {
            return if self.measured == 0 {
                0.0
            } else {
                f64::INFINITY
            };
        }
        100.0 * (self.measured as f64 - self.baseline as f64) / self.baseline as f64
    }
}

impl fmt::Display for Delta {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}: baseline {}, measured {} ({:+}, {:+.2} %)",
            self.key,
            self.baseline,
            self.measured,
            self.measured as i128 - self.baseline as i128,
            self.percent()
        )
    }
}

/// The measurement against the baseline, row by row.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Comparison {
    /// More than [`TOLERANCE_PERCENT`] above the baseline: failures.
    pub regressed: Vec<Delta>,
    /// Above the baseline, within the tolerance.
    pub grew: Vec<Delta>,
    /// Below the baseline.
    pub improved: Vec<Delta>,
    /// Rows equal to their baseline.
    pub unchanged: usize,
    /// Measured rows the baseline lacks: failures.
    pub new: Counts,
    /// Baseline rows no longer measured: failures.
    pub missing: Counts,
}

/// Compares the measured counts with the baseline.
pub fn compare(baseline: &[(Key, u64)], measured: &[(Key, u64)]) -> Comparison {
    let base: BTreeMap<&Key, u64> = baseline.iter().map(|(k, v)| (k, *v)).collect();
    let seen: BTreeMap<&Key, u64> = measured.iter().map(|(k, v)| (k, *v)).collect();
    let mut c = Comparison::default();
    for (key, m) in measured {
        let Some(&b) = base.get(key) else {
            c.new.push((key.clone(), *m));
            continue;
        };
        let d = Delta {
            key: key.clone(),
            baseline: b,
            measured: *m,
        };
        if exceeds(b, *m) {
            c.regressed.push(d);
        } else if *m > b {
            c.grew.push(d);
        } else if *m < b {
            c.improved.push(d);
        } else {
            c.unchanged += 1;
        }
    }
    c.missing = baseline
        .iter()
        .filter(|(k, _)| !seen.contains_key(k))
        .cloned()
        .collect();
    c
}

impl Comparison {
    /// No row regressed, none is new and none is missing.
    pub fn passed(&self) -> bool {
        self.regressed.is_empty() && self.new.is_empty() && self.missing.is_empty()
    }

    /// What changed, for the log: every row that is not equal to its baseline, and the verdict.
    pub fn summary(&self, path: &str) -> String {
        let mut s = String::new();
        let compared =
            self.regressed.len() + self.grew.len() + self.improved.len() + self.unchanged;
        let _ = writeln!(
            s,
            "ratchet ({path}, fails above +{TOLERANCE_PERCENT} %): {compared} rows compared: {} unchanged, {} cheaper, {} dearer within the tolerance, {} regressed; {} new, {} missing",
            self.unchanged,
            self.improved.len(),
            self.grew.len(),
            self.regressed.len(),
            self.new.len(),
            self.missing.len()
        );
        for d in &self.improved {
            let _ = writeln!(s, "  cheaper: {d}");
        }
        for d in &self.grew {
            let _ = writeln!(s, "  dearer (within {TOLERANCE_PERCENT} %): {d}");
        }
        if !self.improved.is_empty() && self.passed() {
            let _ = writeln!(
                s,
                "  some rows got cheaper: `{LOWER_COMMAND}` lowers the baseline to lock the gain in"
            );
        }
        s
    }

    /// The failure message, listing each failing row, or `None` if the ratchet passes.
    pub fn failure(&self, path: &str) -> Option<String> {
        if self.passed() {
            return None;
        }
        let mut s = String::new();
        if !self.regressed.is_empty() {
            let _ = writeln!(
                s,
                "performance ratchet: {} row(s) cost more than {TOLERANCE_PERCENT} % over the baseline in {path} (scene | number | core):",
                self.regressed.len()
            );
            for d in &self.regressed {
                let _ = writeln!(s, "  {d}");
            }
        }
        if !self.new.is_empty() {
            let _ = writeln!(
                s,
                "performance ratchet: {} measured row(s) have no baseline in {path}:",
                self.new.len()
            );
            for (k, m) in &self.new {
                let _ = writeln!(s, "  {k}: measured {m}");
            }
        }
        if !self.missing.is_empty() {
            let _ = writeln!(
                s,
                "performance ratchet: {} baseline row(s) in {path} were not measured:",
                self.missing.len()
            );
            for (k, b) in &self.missing {
                let _ = writeln!(s, "  {k}: baseline {b}");
            }
        }
        let _ = write!(
            s,
            "if this is intended, update the baseline from this measurement and commit it with the change: {UPDATE_COMMAND}"
        );
        Some(s)
    }
}

/// Parses a baseline file: `#` comments, blank lines, and rows `scene | number | core | count`.
pub fn parse(text: &str) -> Result<Counts, String> {
    let mut rows: Counts = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split('|').map(str::trim).collect();
        let [scene, number, core, count] = fields[..] else {
            return Err(format!(
                "line {}: expected `scene | number | core | renderer instructions`, found {line:?}",
                i + 1
            ));
        };
        if scene.is_empty() || number.is_empty() || core.is_empty() {
            return Err(format!("line {}: an empty field in {line:?}", i + 1));
        }
        let count: u64 = count
            .parse()
            .map_err(|e| format!("line {}: instruction count {count:?}: {e}", i + 1))?;
        let key = Key::new(scene, number, core);
        if rows.iter().any(|(k, _)| *k == key) {
            return Err(format!("line {}: a second row for {key}", i + 1));
        }
        rows.push((key, count));
    }
    Ok(rows)
}

/// The baseline lowered to `measured` where a row got cheaper, every other row as it was, and
/// the rows `measured` has that the baseline has not (a new scene's) added after them at their
/// measured counts: the gains are locked in, and a row that grew within the tolerance keeps its
/// old count (so growth within the tolerance cannot creep in through the baseline, as
/// [`UPDATE_COMMAND`] would let it). Refused (with the reason) when a row regressed or is
/// missing: that needs [`UPDATE_COMMAND`] and a reason in its commit.
pub fn lowered(baseline: &[(Key, u64)], measured: &[(Key, u64)]) -> Result<Counts, String> {
    let c = compare(baseline, measured);
    if !c.regressed.is_empty() || !c.missing.is_empty() {
        return Err(format!(
            "not lowered: {} regressed and {} missing rows (use `{UPDATE_COMMAND}` for a \
             change that moves the rows on purpose)",
            c.regressed.len(),
            c.missing.len()
        ));
    }
    let seen: BTreeMap<&Key, u64> = measured.iter().map(|(k, v)| (k, *v)).collect();
    let known: BTreeMap<&Key, u64> = baseline.iter().map(|(k, v)| (k, *v)).collect();
    Ok(baseline
        .iter()
        .map(|(k, b)| (k.clone(), seen.get(k).map_or(*b, |m| (*m).min(*b))))
        .chain(
            measured
                .iter()
                .filter(|(k, _)| !known.contains_key(k))
                .cloned(),
        )
        .collect())
}

/// The baseline file's text for `rows`, in their order, columns aligned.
pub fn format(rows: &[(Key, u64)]) -> String {
    let w = |f: fn(&Key) -> &str, title: &str| {
        rows.iter()
            .map(|(k, _)| f(k).chars().count())
            .chain([title.chars().count()])
            .max()
            .unwrap_or(0)
    };
    let ws = w(|k| &k.scene, "# scene");
    let wn = w(|k| &k.number, "number");
    let wc = w(|k| &k.core, "core");
    let pad = |s: &str, n: usize| format!("{s}{}", " ".repeat(n.saturating_sub(s.chars().count())));
    let mut s = String::new();
    s.push_str(
        "# The performance ratchet (issue #22): renderer instructions for one frame of each benchmark\n\
         # scene, per number type and core, measured in QEMU by scripts/mcu-bench (exact counts: no\n\
         # noise). scripts/mcu-bench fails when a row grows by more than 1 % over this file, or when\n\
         # a row is new or no longer measured. Update it in the same commit as the change that moves\n\
         # the counts, with `scripts/mcu-bench --update-baseline` (or `--lower-baseline`, which only\n\
         # lowers the rows that got cheaper); do not edit it by hand.\n\
         #\n",
    );
    let _ = writeln!(
        s,
        "# {} | {} | {} | renderer instructions",
        pad("scene", ws.saturating_sub(2)),
        pad("number", wn),
        pad("core", wc)
    );
    for (k, v) in rows {
        let _ = writeln!(
            s,
            "{} | {} | {} | {v}",
            pad(&k.scene, ws),
            pad(&k.number, wn),
            pad(&k.core, wc)
        );
    }
    s
}
