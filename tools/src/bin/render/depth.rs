//! `render --budget`: whether the scene needs the depth lines, measured. Each frame drawn in one
//! pass is drawn again by a renderer without depth lines (`NoDepthRenderer`) in both orders and
//! compared with the Z-buffer's frame pixel for pixel; its depth complexity after culling is
//! the fragments drawn less the pixels covered (a pixel is covered when it keeps its colour
//! under two different backgrounds).

use super::*;
use scanline3d::{DrawOrder, NoDepthRenderer};

/// `--depth`: how the output frames are drawn.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum DepthArg {
    /// The Z-buffer (Renderer)
    Zbuffer,
    /// Without depth lines, farthest triangle first on each row (NoDepthRenderer, DrawOrder::FarToNear)
    Painter,
    /// Without depth lines, in any order: back-face culling alone (DrawOrder::Any)
    Any,
}

impl DepthArg {
    fn order(self) -> Option<DrawOrder> {
        match self {
            DepthArg::Zbuffer => None,
            DepthArg::Painter => Some(DrawOrder::FarToNear),
            DepthArg::Any => Some(DrawOrder::Any),
        }
    }
}

/// Why a scene cannot be drawn without depth lines, if it cannot.
fn needs_depth(args: &Args, textured: bool) -> Option<&'static str> {
    if textured {
        Some("a textured material needs the attribute stores")
    } else if matches!(
        args.shading,
        ShadingArg::Phong | ShadingArg::FastPhong | ShadingArg::Toon
    ) {
        Some("Phong shading needs the attribute stores")
    } else if edges::chosen(args) != edges::EdgesArg::None {
        Some("edges are tested against the depth lines")
    } else {
        None
    }
}

/// `--depth` with the other flags.
pub fn check(args: &Args) -> Result<(), String> {
    if args.depth == DepthArg::Zbuffer {
        return Ok(());
    }
    if let Some(why) = needs_depth(args, args.texture.is_some()) {
        return Err(format!(
            "--depth painter and --depth any draw without depth lines, but {why}"
        ));
    }
    if args.scene == Some(SceneArg::Shadow) || args.pass_triangles.is_some() {
        return Err(
            "--depth painter and --depth any: not with --scene shadow or --pass-triangles".into(),
        );
    }
    Ok(())
}

/// The host's renderer without depth lines: the library's limits, as `Big` without the
/// attribute stores (a renderer without depth lines has none).
type NoDepth<S, C> = NoDepthRenderer<S, C, MAX_W, MAX_H, 32768, 32767, 32768>;

/// One frame's measurement.
#[derive(Copy, Clone, Debug, Default)]
pub struct Check {
    /// Fragments after culling (every one drawn without depth lines).
    pub fragments: u64,
    /// Pixels at least one triangle covers.
    pub covered: u64,
    /// Pixels that differ from the Z-buffer's frame: any order, painter's order.
    pub any_differ: usize,
    pub painter_differ: usize,
}

/// The frames' checks.
#[derive(Debug, Default)]
pub struct Summary {
    pub checks: Vec<Check>,
    /// Why frames were not checked (a feature that needs the depth lines), if any.
    pub not_checked: Option<&'static str>,
}

/// The renderer without depth lines and the frames' checks (`--budget` only).
pub struct DepthCheck<S, C> {
    renderer: Box<NoDepth<S, C>>,
    pub summary: Summary,
}

impl<S: Scalar, C: TargetColor> DepthCheck<S, C> {
    /// For `--budget` or `--depth painter|any`.
    pub fn new(args: &Args, textured: bool) -> Option<Self> {
        if !args.budget && args.depth == DepthArg::Zbuffer {
            return None;
        }
        let not_checked = needs_depth(args, textured);
        let mut renderer: Box<NoDepth<S, C>> = Box::default();
        renderer.set_viewport(args.size.0, args.size.1);
        renderer.set_dither(args.dither == OnOff::On);
        Some(DepthCheck {
            renderer,
            summary: Summary {
                checks: Vec::new(),
                not_checked,
            },
        })
    }

    /// Draws the frame of `scene` as `--depth` says, into `f`, if it says so (the frame's
    /// statistics then).
    pub fn draw(
        &mut self,
        args: &Args,
        scene: &Scene<'_, S, LIGHTS>,
        f: &mut Frame<C>,
    ) -> Result<Option<Stats>, String> {
        let Some(order) = args.depth.order() else {
            return Ok(None);
        };
        self.renderer.set_order(order);
        f.px.fill(C::from_channels([0; 3]));
        self.renderer
            .render(scene, f)
            .map(Some)
            .map_err(|e| format!("without depth lines: {e}"))
    }

    /// The renderer without depth lines, in `--depth`'s order (for timing).
    pub fn renderer(&mut self) -> &mut NoDepth<S, C> {
        &mut self.renderer
    }

    /// Checks the frame of `scene` the Z-buffer drew as `zbuffer`.
    pub fn check(
        &mut self,
        scene: &Scene<'_, S, LIGHTS>,
        zbuffer: &Frame<C>,
        background: [u8; 3],
    ) -> Result<(), String> {
        if self.summary.not_checked.is_some() {
            return Ok(());
        }
        let (w, h) = (zbuffer.w, zbuffer.h);
        let mut draw = |order, background| -> Result<(Frame<C>, Stats), String> {
            let mut f = Frame::new(w, h, C::from_channels([0; 3]));
            self.renderer.set_order(order);
            let scene = (*scene).with_background(background);
            let stats = self
                .renderer
                .render(&scene, &mut f)
                .map_err(|e| format!("without depth lines: {e}"))?;
            Ok((f, stats))
        };
        let differ = |a: &Frame<C>| a.px.iter().zip(&zbuffer.px).filter(|(x, y)| x != y).count();
        let (any, stats) = draw(DrawOrder::Any, background)?;
        let (painter, _) = draw(DrawOrder::FarToNear, background)?;
        let other = background.map(|c| if c < 128 { 255 } else { 0 });
        let (any2, _) = draw(DrawOrder::Any, other)?;
        let covered = any.px.iter().zip(&any2.px).filter(|(a, b)| a == b).count();
        self.summary.checks.push(Check {
            fragments: stats.fragments as u64,
            covered: covered as u64,
            any_differ: differ(&any),
            painter_differ: differ(&painter),
        });
        Ok(())
    }
}

impl Summary {
    /// The `--budget` lines: the measurement and the mode to pick.
    pub fn report(&self, frames: usize, lines: usize, width: usize) {
        if let Some(why) = self.not_checked {
            println!("  depth: the Z-buffer ({why}); depth modes not checked");
            return;
        }
        if self.checks.len() < frames {
            println!(
                "  depth: {} of {frames} frame(s) checked (the others were drawn in passes); \
                 keep the Z-buffer",
                self.checks.len()
            );
            return;
        }
        let n = self.checks.len();
        let overlap = self
            .checks
            .iter()
            .map(|c| c.fragments.saturating_sub(c.covered))
            .max()
            .unwrap_or(0);
        let ok = |f: fn(&Check) -> usize| self.checks.iter().filter(|c| f(c) == 0).count();
        let worst = |f: fn(&Check) -> usize| self.checks.iter().map(f).max().unwrap_or(0);
        let (any_ok, painter_ok) = (ok(|c| c.any_differ), ok(|c| c.painter_differ));
        println!(
            "  depth complexity after culling over {n} frame(s): at most {overlap} fragment(s) \
             drawn over another in a frame"
        );
        println!(
            "    without depth lines, any order: the Z-buffer's pixels in {any_ok}/{n} frame(s) \
             (worst {} px differ)",
            worst(|c| c.any_differ)
        );
        println!(
            "    without depth lines, painter's: the Z-buffer's pixels in {painter_ok}/{n} \
             frame(s) (worst {} px differ)",
            worst(|c| c.painter_differ)
        );
        let saved = lines * width * 2;
        if any_ok == n {
            println!(
                "  pick: NoDepthRenderer with DrawOrder::Any (no sort, no depth test; {saved} \
                 bytes less RAM)"
            );
        } else if painter_ok == n {
            println!(
                "  pick: NoDepthRenderer with DrawOrder::FarToNear (painter's; no depth test; \
                 {saved} bytes less RAM)"
            );
        } else {
            println!("  pick: the Z-buffer (Renderer): neither order draws every frame right");
            return;
        }
        println!(
            "    (RAM for speed: the Z-buffer's RGB565 Gouraud rows run in assembly on Cortex-M, \
             the rows without depth lines in portable code, so large triangles get faster and a \
             fine Gouraud mesh slower: compare the cube_* and icosphere_* rows of BENCHMARKS.md)"
        );
    }
}
