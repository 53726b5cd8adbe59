//! `render --edges none|silhouette|crease|all --edge-color R,G,B --crease-angle DEG
//! --see-through` and `--shading wireframe`: the model's edges drawn over it (or, as a
//! wireframe, over its surfaces unlit in the background colour, which hide the lines behind
//! them) by a layered frame with an [`Outline`].

use clap::ValueEnum;
use scanline3d::{
    mesh::mesh_adjacency, mesh::mesh_creases, mesh::Adjacency, shadow::Edges, shadow::Layering,
    shadow::Outline, Layers, Mesh, Scalar, Scene, Stats, TargetColor,
};
use scanline3d_support::hash::NullTarget;

use super::{Args, Big, ShadingArg, MAX_W};

/// Most triangles whose edges the tool draws: the adjacency is found by
/// [`mesh_adjacency`]'s O(T²) search (a mesh's setup), seconds at this size.
pub const MAX_EDGE_TRIANGLES: usize = 20_000;

/// Edge triangles active on one row at once (the layers' post list).
const EDGE_ACTIVE: usize = 4096;

/// Which edges `--edges` draws.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum EdgesArg {
    /// No edges (the default, except with --shading wireframe)
    None,
    /// The contour as seen from the eye
    Silhouette,
    /// The contour and the edges whose faces meet at more than --crease-angle
    Crease,
    /// Every edge (of the faces toward the eye, unless --see-through)
    All,
}

/// The edges the command line asks for: `--edges`, else every edge for a wireframe.
pub fn chosen(args: &Args) -> EdgesArg {
    match (args.edges, args.shading) {
        (Some(e), _) => e,
        (None, ShadingArg::Wireframe) => EdgesArg::All,
        (None, _) => EdgesArg::None,
    }
}

/// The lines' colour: `--edge-color`, else the model's colour for a wireframe and black over
/// shaded surfaces.
pub fn color(args: &Args) -> [u8; 3] {
    match (args.edge_color, args.shading) {
        (Some(c), _) => c,
        (None, ShadingArg::Wireframe) => args.color,
        (None, _) => [0; 3],
    }
}

/// The flags' checks (usage errors).
pub fn check(args: &Args) -> Result<(), String> {
    if !(0.0..=180.0).contains(&args.crease_angle) {
        return Err(format!(
            "--crease-angle must be in [0, 180] degrees, got {}",
            args.crease_angle
        ));
    }
    let on = chosen(args) != EdgesArg::None;
    if !on && (args.edge_color.is_some() || args.see_through) {
        return Err("--edge-color and --see-through need --edges (or --shading wireframe)".into());
    }
    if args.shading == ShadingArg::Wireframe && !on {
        return Err("--shading wireframe draws edges: not with --edges none".into());
    }
    if on && (args.texture.is_some() || args.pass_triangles.is_some()) {
        return Err(
            "--edges and --shading wireframe draw the model in one layered frame: not \
                    with --texture or --pass-triangles"
                .into(),
        );
    }
    Ok(())
}

/// A model's adjacency and crease tables and the layers its frames are drawn with.
pub struct EdgeFrames {
    edges: EdgesArg,
    color: [u8; 3],
    see_through: bool,
    adjacency: Vec<[u16; 3]>,
    creases: Vec<u8>,
    layers: Box<Layers<MAX_W, 1, 4, EDGE_ACTIVE>>,
}

impl EdgeFrames {
    /// The tables of `mesh` (named `name` in errors) for the command line's edges, or `None`
    /// when it asks for none.
    pub fn new<S: Scalar>(
        args: &Args,
        name: &str,
        mesh: &Mesh<'_, S>,
    ) -> Result<Option<Self>, String> {
        let edges = chosen(args);
        if edges == EdgesArg::None {
            return Ok(None);
        }
        let n = mesh.indices().len();
        if n > MAX_EDGE_TRIANGLES {
            return Err(format!(
                "{name}: {n} triangles, but edges are found for at most {MAX_EDGE_TRIANGLES} \
                 (simplify with --max-triangles)"
            ));
        }
        let mut adjacency = vec![[0u16; 3]; n];
        mesh_adjacency(mesh, &mut adjacency)
            .map_err(|e| format!("{name}: its edges cannot be found: {e}"))?;
        let mut creases = vec![0u8; (3 * n).div_ceil(8)];
        if edges == EdgesArg::Crease {
            mesh_creases(mesh, &adjacency, args.crease_angle, &mut creases)
                .map_err(|e| format!("{name}: {e}"))?;
        }
        Ok(Some(EdgeFrames {
            edges,
            color: color(args),
            see_through: args.see_through,
            adjacency,
            creases,
            layers: Box::new(Layers::new()),
        }))
    }

    /// Draws `scene` (one object: the model) with its edges into `target`.
    pub fn draw<S: Scalar, C: TargetColor, D>(
        &mut self,
        r: &mut Big<S, C>,
        scene: &Scene<'_, S, { super::LIGHTS }>,
        target: &mut D,
    ) -> Result<Stats, String>
    where
        D: embedded_graphics::draw_target::DrawTarget<Color = C>,
        D::Error: core::fmt::Debug + core::fmt::Display,
    {
        // Checked against the frame's mesh (the host preview builds its mesh per frame).
        let adjacency = [Adjacency::new(&scene.objects[0].mesh, &self.adjacency)
            .map_err(|e| format!("the edges' table: {e}"))?];
        let creases: [&[u8]; 1] = [&self.creases];
        let edges = match self.edges {
            EdgesArg::Silhouette | EdgesArg::None => Edges::Silhouette,
            EdgesArg::Crease => Edges::Crease(&creases),
            EdgesArg::All => Edges::All,
        };
        let layering = Layering::<S>::none().with_outline(
            Outline::silhouette(&[0], &adjacency, self.color)
                .with_edges(edges)
                .see_through(self.see_through),
        );
        r.render_with(
            scene,
            scanline3d::FrameOptions::new().layered(&layering, &mut self.layers),
            target,
        )
        .map_err(|e| {
            format!("{e} (edges are drawn in one frame: simplify the model with --max-triangles)")
        })
    }

    /// [`EdgeFrames::draw`] into a target that keeps nothing (for timing).
    pub fn draw_timed<S: Scalar, C: TargetColor>(
        &mut self,
        r: &mut Big<S, C>,
        scene: &Scene<'_, S, { super::LIGHTS }>,
        (w, h): (usize, usize),
    ) -> f64 {
        let mut sink = NullTarget::<C>::new(w as u32, h as u32);
        let t = std::time::Instant::now();
        let _ = self.draw(r, scene, &mut sink);
        t.elapsed().as_nanos() as f64
    }
}
