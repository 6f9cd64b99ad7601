//! The radiosity state of every node of the patch quadtrees, per side: what it emits and
//! reflects, what it gathered over its links, and the radiosity push-pull makes consistent
//! across levels (seed 000 §6.7, §6.8).
//!
//! Node `2·p + s` is side `s` of patch `p` (roots and inner nodes as well as leaves).

use crate::color::Rgb64;
use crate::radiosity::element::Side;
use crate::radiosity::mesh::{PatchId, PatchMesh};
use crate::radiosity::surface;
use crate::scene::Scene;

/// The index of side `side` of patch `patch`.
#[inline]
pub fn node(patch: PatchId, side: Side) -> usize {
    2 * patch as usize + side.index()
}

/// The patch and side of node `n`.
#[inline]
pub fn split_node(n: usize) -> (PatchId, Side) {
    let side = if n.is_multiple_of(2) {
        Side::Front
    } else {
        Side::Back
    };
    ((n / 2) as PatchId, side)
}

/// Per node (one side of one quadtree node): material terms, gathered irradiance and
/// radiosity.
#[derive(Clone, Debug, Default)]
pub struct Nodes {
    /// Emitted radiosity, W·m⁻².
    pub emission: Vec<Rgb64>,
    /// Diffuse reflectance.
    pub reflectance: Vec<Rgb64>,
    /// Diffuse transmittance: the share of the other side's irradiance this side sends out.
    pub translucency: Vec<Rgb64>,
    /// Radiosity: at a leaf `E + ρ·H + τ·H̄` (H everything gathered at it and its ancestors,
    /// H̄ the same on the other side), at an
    /// inner node the area-weighted mean of its children, W·m⁻².
    pub radiosity: Vec<Rgb64>,
    /// Irradiance gathered over the node's own links in the last gather, W·m⁻².
    pub gathered: Vec<Rgb64>,
    /// Irradiance from the lights linked to the node itself, W·m⁻².
    pub lit: Vec<Rgb64>,
    /// At a leaf: all irradiance it receives (its own and its ancestors' links), W·m⁻².
    pub irradiance: Vec<Rgb64>,
    /// At a leaf: the part of `irradiance` that comes from lights, W·m⁻².
    pub lit_total: Vec<Rgb64>,
    /// Smallest and largest radiosity luminance of the leaves below (the node's own at a
    /// leaf), W·m⁻².
    pub range: Vec<(f64, f64)>,
    /// How much the textures make the emitted radiosity (W·m⁻²) and the reflectance vary
    /// across the node: the luminance of each term at the largest less at the smallest texel
    /// under it; zero without textures.
    pub spread: Vec<(f64, f64)>,
}

impl Nodes {
    /// Material terms for every patch of `mesh`; radiosity starts at the emission.
    pub fn new(scene: &Scene, mesh: &PatchMesh) -> Self {
        let mut nodes = Nodes::default();
        nodes.grow(scene, mesh);
        for &root in &mesh.roots {
            nodes.push_pull_from(mesh, root, [Rgb64::BLACK; 2], [Rgb64::BLACK; 2]);
        }
        nodes
    }

    /// Adds the nodes of patches `mesh` gained since the last call (children of split
    /// nodes); their radiosity and irradiance start as their parent's.
    pub fn grow(&mut self, scene: &Scene, mesh: &PatchMesh) {
        for id in (self.emission.len() / 2) as PatchId..mesh.len() as PatchId {
            let patch = mesh.patch(id);
            for side in Side::BOTH {
                let parent = patch.parent.map(|p| node(p, side));
                let start = match parent {
                    Some(p) => self.radiosity[p],
                    None => surface::emission(scene, patch, side),
                };
                let (h, h_lit) = parent.map_or((Rgb64::BLACK, Rgb64::BLACK), |p| {
                    (self.irradiance[p], self.lit_total[p])
                });
                let y = start.luminance();
                self.emission.push(surface::emission(scene, patch, side));
                self.reflectance
                    .push(surface::reflectance(scene, patch, side));
                self.translucency.push(surface::translucency(scene, patch));
                self.radiosity.push(start);
                self.gathered.push(Rgb64::BLACK);
                self.lit.push(Rgb64::BLACK);
                self.irradiance.push(h);
                self.lit_total.push(h_lit);
                self.range.push((y, y));
                self.spread
                    .push(if surface::is_textured(scene, patch.material) {
                        let at = surface::TextureAt::Spread(patch);
                        (
                            surface::emission_of(scene, patch.material, side, at).luminance(),
                            surface::reflectance_of(scene, patch.material, side, at).luminance(),
                        )
                    } else {
                        (0.0, 0.0)
                    });
            }
        }
    }

    /// The radiosity node `n` scatters when the irradiance on it is `own` and on the other
    /// side of its patch `other` (W·m⁻²): `ρ·own + τ·other`.
    #[inline]
    pub fn scattered(&self, n: usize, own: Rgb64, other: Rgb64) -> Rgb64 {
        self.reflectance[n] * own + self.translucency[n] * other
    }

    /// The largest reflectance plus translucency of any node, any channel.
    pub fn largest_albedo(&self) -> f64 {
        self.reflectance
            .iter()
            .zip(&self.translucency)
            .map(|(&r, &t)| (r + t).max_channel())
            .fold(0.0, f64::max)
    }

    /// Push-pull over every tree (seed §6.8): irradiance gathered at a node is handed down to
    /// its leaves, where it becomes radiosity `E + ρ·H + τ·H̄` (`H̄` on the other side), and
    /// the leaves' radiosity is pulled up as area-weighted means. Returns
    /// `(Σ A·Y(|ΔB|), Σ A·Y(S))` over the leaves: the change of radiosity and the source term
    /// `S = E + ρ·H_lights + τ·H̄_lights`, both as power.
    pub fn push_pull(&mut self, mesh: &PatchMesh) -> (f64, f64) {
        let mut change = 0.0;
        let mut source = 0.0;
        for &root in &mesh.roots {
            let (c, s) = self.push_pull_from(mesh, root, [Rgb64::BLACK; 2], [Rgb64::BLACK; 2]);
            change += c;
            source += s;
        }
        (change, source)
    }

    /// Per node, at the leaves: what `gathered` (irradiance gathered per node) and the light
    /// links hand down to each leaf from it and its ancestors, W·m⁻² (zero at inner nodes).
    pub fn push_down(&self, mesh: &PatchMesh, gathered: &[Rgb64]) -> Vec<Rgb64> {
        let mut at_leaves = vec![Rgb64::BLACK; gathered.len()];
        let mut stack: Vec<(usize, Rgb64)> = mesh
            .roots
            .iter()
            .flat_map(|&root| Side::BOTH.map(|side| (node(root, side), Rgb64::BLACK)))
            .collect();
        while let Some((n, above)) = stack.pop() {
            let (patch, side) = split_node(n);
            let h = above + gathered[n] + self.lit[n];
            match mesh.patch(patch).children {
                None => at_leaves[n] = h,
                Some(children) => stack.extend(children.map(|c| (node(c, side), h))),
            }
        }
        at_leaves
    }

    /// Push-pull below patch `patch`, whose sides receive `above` (irradiance from their
    /// ancestors' links, per side, of which `above_lit` from lights). Both sides go down
    /// together: at a leaf each side's radiosity takes the other side's irradiance through
    /// the translucency. Returns the change and source powers of its leaves.
    fn push_pull_from(
        &mut self,
        mesh: &PatchMesh,
        patch: PatchId,
        above: [Rgb64; 2],
        above_lit: [Rgb64; 2],
    ) -> (f64, f64) {
        let nodes = Side::BOTH.map(|side| node(patch, side));
        let h = [0, 1].map(|s| above[s] + self.gathered[nodes[s]] + self.lit[nodes[s]]);
        let h_lit = [0, 1].map(|s| above_lit[s] + self.lit[nodes[s]]);
        let area = mesh.patch(patch).area;
        match mesh.patch(patch).children {
            None => {
                let (mut change, mut source) = (0.0, 0.0);
                for s in 0..2 {
                    let n = nodes[s];
                    let b = self.emission[n] + self.scattered(n, h[s], h[1 - s]);
                    change += area * (b - self.radiosity[n]).map(f64::abs).luminance();
                    let lit = self.scattered(n, h_lit[s], h_lit[1 - s]);
                    source += area * (self.emission[n] + lit).luminance();
                    let y = b.luminance();
                    self.radiosity[n] = b;
                    self.irradiance[n] = h[s];
                    self.lit_total[n] = h_lit[s];
                    self.range[n] = (y, y);
                }
                (change, source)
            }
            Some(children) => {
                let mut sum = [Rgb64::BLACK; 2];
                let mut range = [(f64::INFINITY, f64::NEG_INFINITY); 2];
                let (mut change, mut source) = (0.0, 0.0);
                for child in children {
                    let (dc, ds) = self.push_pull_from(mesh, child, h, h_lit);
                    change += dc;
                    source += ds;
                    for (s, side) in Side::BOTH.into_iter().enumerate() {
                        let c = node(child, side);
                        sum[s] += self.radiosity[c] * mesh.patch(child).area;
                        range[s] = (
                            range[s].0.min(self.range[c].0),
                            range[s].1.max(self.range[c].1),
                        );
                    }
                }
                for s in 0..2 {
                    self.radiosity[nodes[s]] = sum[s].map(|v| v / area);
                    self.range[nodes[s]] = range[s];
                }
                (change, source)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::radiosity::mesh::MeshOptions;
    use crate::scene::{Material, Shape};
    use glam::Vec3;

    #[test]
    fn push_pull_hands_irradiance_down_and_averages_radiosity_up() {
        let mut scene = Scene::empty("square");
        let m = scene.add_material(Material::diffuse("grey", crate::color::Rgb::splat(0.5)));
        scene.add_object(
            "square",
            Shape::Parallelogram {
                origin: Vec3::ZERO,
                edge_u: Vec3::X,
                edge_v: Vec3::Y,
            },
            m,
        );
        let mut mesh = PatchMesh::from_scene(&scene, &MeshOptions::default()).unwrap();
        let mut nodes = Nodes::new(&scene, &mesh);
        let children = mesh.subdivide(0);
        nodes.grow(&scene, &mesh);
        // 2 W·m⁻² gathered at the root, 4 more at one child.
        nodes.gathered[node(0, Side::Front)] = Rgb64::splat(2.0);
        nodes.gathered[node(children[0], Side::Front)] = Rgb64::splat(4.0);
        nodes.push_pull(&mesh);
        let b = |p: PatchId| nodes.radiosity[node(p, Side::Front)].g;
        assert!((b(children[0]) - 3.0).abs() < 1e-12);
        assert!((b(children[1]) - 1.0).abs() < 1e-12);
        // The root holds the area-weighted mean: (3 + 1 + 1 + 1) / 4.
        assert!((b(0) - 1.5).abs() < 1e-12);
        assert_eq!(nodes.range[node(0, Side::Front)], (1.0, 3.0));
    }
}
