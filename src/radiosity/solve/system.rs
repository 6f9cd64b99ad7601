//! The linear radiosity system of a meshed scene, per RGB channel in `f64`:
//! `B_i = E_i + ρ_i (H_light,i + Σ_j F_ij V_ij B_j)`.
//!
//! - `B_i`: radiosity of leaf patch `i`, W·m⁻² (front side).
//! - `E_i = π·L`: emitted radiosity, the emission texture averaged over the patch; only the
//!   front side emits (a `two_sided` emitter's back side is not part of the system).
//! - `ρ_i`: diffuse reflectance (the material's diffuse part times its texture averaged over
//!   the patch); specular, mirror and transmission parts are ignored.
//! - `H_light,i`: irradiance from point, spot and directional lights through emitter-only
//!   links (seed §9.3.1): these lights send and never receive. Sky lights are not linked.
//! - `F_ij`: the form factor from receiver `i` to emitter `j` ([`form_factor`]) and `V_ij`
//!   the visible fraction ([`Visibility::between`]); pairs that do not face each other
//!   ([`facing`] = `Away`) and `i = j` couple with 0.
//!
//! Limitation: every patch exchanges light through its front side only (the side its normal
//! points to); a surface lit from behind stays dark on its front in the solution.

use super::SolveError;
use crate::color::{Rgb, Rgb64};
use crate::radiosity::{
    Facing, FormFactorOptions, MeshOptions, Patch, PatchId, PatchMesh, Visibility,
    VisibilityOptions, facing, form_factor, light_irradiance,
};
use crate::scene::{LightKind, Texture};
use crate::world::World;
use glam::Vec2;
use rayon::prelude::*;
use std::f64::consts::PI;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// Texture samples per axis when averaging a texture over a patch.
const TEXTURE_SAMPLES: u32 = 4;

/// How the system is set up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SystemOptions {
    /// Patch mesh: curved-shape segments and initial subdivision.
    pub mesh: MeshOptions,
    /// Form-factor approximation.
    pub form_factor: FormFactorOptions,
    /// Visibility rays and shaft culling.
    pub visibility: VisibilityOptions,
    /// Receiver points per axis for the point/spot/directional light links.
    pub link_samples: u32,
}

impl Default for SystemOptions {
    /// Default mesh, analytic form factors at the centroid, adaptive visibility, 2×2 link
    /// samples.
    fn default() -> Self {
        SystemOptions {
            mesh: MeshOptions::default(),
            form_factor: FormFactorOptions::default(),
            visibility: VisibilityOptions::default(),
            link_samples: 2,
        }
    }
}

/// One row or column of the coupling matrix `F_ij V_ij`: leaf indices and values.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Couplings {
    /// Leaf indices of the non-zero entries, ascending.
    pub leaves: Vec<u32>,
    /// The entries `F_ij V_ij` (dimensionless, in `[0, 1]`).
    pub values: Vec<f64>,
}

impl Couplings {
    /// Bytes held (for memory budgets).
    pub fn bytes(&self) -> usize {
        self.leaves.len() * 4 + self.values.len() * 8
    }
}

/// The radiosity system of one scene: its leaf patches with their areas, emission,
/// reflectance and light-link irradiance, and the couplings computed on demand.
pub struct RadiositySystem<'w> {
    world: &'w World,
    /// The patch mesh (all quadtree nodes).
    pub mesh: PatchMesh,
    /// The leaf patches the system is solved on; leaf index `k` is patch `leaves[k]`.
    pub leaves: Vec<PatchId>,
    /// Leaf areas, scene units².
    pub area: Vec<f64>,
    /// Emitted radiosity `E = π·L` per leaf, W·m⁻².
    pub emission: Vec<Rgb64>,
    /// Diffuse reflectance per leaf, in `[0, 1]`.
    pub reflectance: Vec<Rgb64>,
    /// Irradiance from point, spot and directional lights per leaf, W·m⁻².
    pub light_irradiance: Vec<Rgb64>,
    /// Sky lights present in the scene but not linked into the mesh.
    pub unlinked_sky_lights: usize,
    /// Wall-clock seconds spent meshing and linking lights.
    pub setup_seconds: f64,
    visibility: Visibility<'w>,
    options: SystemOptions,
    form_factors: AtomicU64,
    visibility_rays: AtomicU64,
}

impl<'w> RadiositySystem<'w> {
    /// Meshes `world`'s scene, averages emission and reflectance over each leaf and gathers
    /// the light-link irradiance (in parallel over leaves).
    pub fn new(world: &'w World, options: SystemOptions) -> Result<Self, SolveError> {
        let start = Instant::now();
        let mesh = PatchMesh::from_scene(&world.scene, &options.mesh)?;
        let leaves = mesh.leaves();
        if leaves.is_empty() {
            return Err(SolveError::NoPatches);
        }
        let scene = &world.scene;
        let patches: Vec<&Patch> = leaves.iter().map(|&id| mesh.patch(id)).collect();
        let area = patches.iter().map(|p| p.area).collect();
        let texture = |id: Option<u32>| id.and_then(|t| scene.textures.get(t as usize));
        let emission = patches
            .iter()
            .map(|p| {
                let m = &scene.materials[p.material as usize];
                PI * m.emission.to_f64() * texture_mean(texture(m.emission_texture), p)
            })
            .collect();
        let reflectance = patches
            .iter()
            .map(|p| {
                let m = &scene.materials[p.material as usize];
                let tex = texture_mean(texture(m.diffuse_texture), p);
                (m.diffuse.to_f64() * tex).map(|v| v.clamp(0.0, 1.0))
            })
            .collect();
        let linked: Vec<&LightKind> = scene
            .lights
            .iter()
            .map(|l| &l.kind)
            .filter(|k| !matches!(k, LightKind::Sky { .. }))
            .collect();
        let unlinked_sky_lights = scene.lights.len() - linked.len();
        let light_irradiance = patches
            .par_iter()
            .map(|p| {
                linked.iter().fold(Rgb64::BLACK, |sum, kind| {
                    sum + light_irradiance(world, kind, p, options.link_samples)
                        .map_or(Rgb64::BLACK, Rgb::to_f64)
                })
            })
            .collect();
        Ok(RadiositySystem {
            world,
            leaves,
            area,
            emission,
            reflectance,
            light_irradiance,
            unlinked_sky_lights,
            setup_seconds: start.elapsed().as_secs_f64(),
            visibility: Visibility::new(world, options.visibility),
            mesh,
            options,
            form_factors: AtomicU64::new(0),
            visibility_rays: AtomicU64::new(0),
        })
    }

    /// The world the system was built from.
    pub fn world(&self) -> &'w World {
        self.world
    }

    /// The options it was built with.
    pub fn options(&self) -> &SystemOptions {
        &self.options
    }

    /// Number of leaf patches (unknowns per channel).
    pub fn len(&self) -> usize {
        self.leaves.len()
    }

    /// True when there are no leaves (never for a built system).
    pub fn is_empty(&self) -> bool {
        self.leaves.is_empty()
    }

    /// The patch of leaf `k`.
    pub fn patch(&self, k: usize) -> &Patch {
        self.mesh.patch(self.leaves[k])
    }

    /// The source term `S_i = E_i + ρ_i H_light,i` of leaf `k`, W·m⁻².
    pub fn source(&self, k: usize) -> Rgb64 {
        self.emission[k] + self.reflectance[k] * self.light_irradiance[k]
    }

    /// Total area of all leaves, scene units².
    pub fn total_area(&self) -> f64 {
        self.area.iter().sum()
    }

    /// `F_ij V_ij` between receiver leaf `i` and emitter leaf `j` (0 for `i = j` and for
    /// pairs that do not face each other).
    pub fn coupling(&self, i: usize, j: usize) -> f64 {
        if i == j {
            return 0.0;
        }
        let (receiver, emitter) = (self.patch(i), self.patch(j));
        if facing(receiver, emitter) == Facing::Away {
            return 0.0;
        }
        self.form_factors.fetch_add(1, Ordering::Relaxed);
        let f = form_factor(receiver, emitter, &self.options.form_factor);
        if f <= 0.0 {
            return 0.0;
        }
        let m = self.visibility.rays_per_axis(receiver, emitter) as u64;
        self.visibility_rays.fetch_add(m * m, Ordering::Relaxed);
        f * self
            .visibility
            .between(&self.mesh, self.leaves[i], self.leaves[j])
    }

    /// Row `i` of the coupling matrix: what receiver `i` gathers from every leaf.
    pub fn row(&self, i: usize) -> Couplings {
        collect((0..self.len()).map(|j| (j, self.coupling(i, j))))
    }

    /// Column `j` of the coupling matrix: what every receiver gets from emitter `j`
    /// (computed in parallel over receivers).
    pub fn column(&self, j: usize) -> Couplings {
        let values: Vec<f64> = (0..self.len())
            .into_par_iter()
            .map(|i| self.coupling(i, j))
            .collect();
        collect(values.into_iter().enumerate())
    }

    /// Form factors evaluated so far (facing pairs).
    pub fn form_factor_count(&self) -> u64 {
        self.form_factors.load(Ordering::Relaxed)
    }

    /// Visibility rays of the pairs tested so far: the full ray grid of every pair with a
    /// non-zero form factor (pairs the shaft proves unoccluded cast fewer).
    pub fn visibility_ray_count(&self) -> u64 {
        self.visibility_rays.load(Ordering::Relaxed)
    }
}

/// The non-zero entries of `(index, value)` pairs.
fn collect(entries: impl Iterator<Item = (usize, f64)>) -> Couplings {
    let mut out = Couplings::default();
    for (k, v) in entries {
        if v > 0.0 {
            out.leaves.push(k as u32);
            out.values.push(v);
        }
    }
    out
}

/// Mean colour of `texture` over `patch` (its UV polygon sampled on a `4 × 4` grid of the
/// patch's parameter domain, equal weights: area-weighted for triangles and parallelograms);
/// `[1, 1, 1]` without a texture.
fn texture_mean(texture: Option<&Texture>, patch: &Patch) -> Rgb64 {
    let Some(texture) = texture else {
        return Rgb64::WHITE;
    };
    let n = TEXTURE_SAMPLES;
    let mut sum = Rgb64::BLACK;
    for a in 0..n {
        for b in 0..n {
            let (s, t) = ((a as f64 + 0.5) / n as f64, (b as f64 + 0.5) / n as f64);
            let uv = patch.uv_at(s, t);
            sum += texture.color(Vec2::new(uv.x as f32, uv.y as f32)).to_f64();
        }
    }
    sum.map(|v| v / (n * n) as f64)
}
