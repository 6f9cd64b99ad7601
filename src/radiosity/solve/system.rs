//! The linear radiosity system of a meshed scene, per RGB channel in `f64`, with one unknown
//! per side of every leaf patch (an [`Element`]):
//! `B_i = E_i + ρ_i H_i + τ_i H_ī` with `H_i = H_light,i + Σ_j F_ij V_ij B_j`, `ī` the
//! other side of `i`'s leaf.
//!
//! - `B_i`: radiosity leaving element `i` (one side of a leaf), W·m⁻².
//! - `E_i = π·L`: emitted radiosity, the emission texture averaged over the patch; the front
//!   side emits, the back only for a `two_sided` material.
//! - `ρ_i`: diffuse reflectance (the material's diffuse part times its texture averaged over
//!   the patch); 0 on the back of a `one_sided` material, which absorbs what reaches it.
//!   Specular, mirror and transmission parts are ignored.
//! - `τ_i`: diffuse transmittance (translucency): the share of the irradiance on the other side
//!   `ī` that leaves side `i`, the coupling of a leaf's two sides; 0 for a `one_sided`
//!   material. Where an alpha texture cuts the surface, `E_i`, `ρ_i` and `τ_i` are scaled by
//!   the share `c_i` of the patch left in place, and the element intercepts `c_i·A_i·H_i` of
//!   the light reaching it (`coverage`).
//! - `H_light,i`: irradiance from point, spot and directional lights and the sky through
//!   emitter-only links (seed §9.3.1, [`light_irradiance`]): these lights send and never
//!   receive.
//! - `F_ij`: the form factor from receiver side `i` to emitter `j` ([`form_factor`]) and
//!   `V_ij` the visible fraction ([`Visibility::between`]); sides that do not face each other
//!   ([`facing`] = `Away`) and two sides of one patch couple with 0.
//!
//! Elements are ordered leaf by leaf, front then back: element `2k + s` is side `s` of leaf
//! `k`.

use super::SolveError;
use super::far_field::FarField;
use crate::color::Rgb64;
use crate::progress::{Cancel, NoProgress, ProgressListener};
use crate::radiosity::element::{Element, Side};
use crate::radiosity::light_links::exact_shadows;
use crate::radiosity::surface;
use crate::radiosity::visibility::Blockers;
use crate::radiosity::{
    Facing, FormFactorOptions, MeshOptions, Overlap, Patch, PatchId, PatchMesh, Visibility,
    VisibilityOptions, coplanar_overlaps, facing, form_factor, light_irradiance,
};
use crate::world::World;
use rayon::prelude::*;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// Visibility rays between a pair of patches one of which straddles the other's plane
/// (an 8 × 8 grid on each, joined only where each end is in front of the other's side).
const STRADDLING_RAYS: u32 = 64;

/// How the system is set up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SystemOptions {
    /// Patch mesh: curved-shape segments and initial subdivision.
    pub mesh: MeshOptions,
    /// Form-factor approximation.
    pub form_factor: FormFactorOptions,
    /// Visibility rays and shaft culling.
    pub visibility: VisibilityOptions,
    /// Receiver points per axis for the links from point, spot and directional lights and
    /// the sky. Shadows cast by small things (leaves on leaves) need many: at 2 × 2 the
    /// canopy's leaves, whose shadows fall in a regular pattern, took up to 9 % too much sun
    /// (what all points of a partly shadowed leaf see is what all of it gets); 8 × 8 brings
    /// every leaf within the light model's noise (1.8 % RMS against its 1.5 %).
    pub link_samples: u32,
    /// How far around the plot of a periodic scene its copies are solved with it, scene
    /// units (`World::unrolled`); `None` for none: the solvers take the light of the field
    /// beyond the margin by rays (their far field), so copies only cost. Ignored for a scene
    /// that is not periodic.
    pub periodic_margin: Option<f32>,
}

impl Default for SystemOptions {
    /// Default mesh, analytic form factors at the centroid, adaptive visibility, 8 × 8 link
    /// samples.
    fn default() -> Self {
        SystemOptions {
            mesh: MeshOptions::default(),
            form_factor: FormFactorOptions::default(),
            visibility: VisibilityOptions::default(),
            link_samples: 8,
            periodic_margin: None,
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
    /// The non-zero entries of `(index, value)` pairs, in ascending index order.
    pub(super) fn of_entries(entries: impl Iterator<Item = (usize, f64)>) -> Couplings {
        let mut out = Couplings::default();
        for (k, v) in entries {
            if v > 0.0 {
                out.leaves.push(k as u32);
                out.values.push(v);
            }
        }
        out
    }

    /// Bytes held (for memory budgets).
    pub fn bytes(&self) -> usize {
        self.leaves.len() * 4 + self.values.len() * 8
    }
}

/// The radiosity system of one scene: the two sides of its leaf patches with their areas,
/// emission, reflectance and light-link irradiance, and the couplings computed on demand.
pub struct RadiositySystem {
    world: Arc<World>,
    /// The patch mesh (all quadtree nodes).
    pub mesh: PatchMesh,
    /// The leaf patches; leaf index `k` is patch `leaves[k]`.
    pub leaves: Vec<PatchId>,
    /// The unknowns: element `2k + s` is side `s` of leaf `k`.
    pub elements: Vec<Element>,
    /// Element areas (their leaf's area), scene units².
    pub area: Vec<f64>,
    /// Emitted radiosity `E = π·L` per element, W·m⁻².
    pub emission: Vec<Rgb64>,
    /// Diffuse reflectance per element, in `[0, 1]`.
    pub reflectance: Vec<Rgb64>,
    /// Diffuse transmittance per element, in `[0, 1]`: the share of the other side's
    /// irradiance this side sends out.
    pub translucency: Vec<Rgb64>,
    /// The share of each element's area its material's alpha texture leaves in place, in
    /// `[0, 1]` (1 without one): `emission` and `reflectance` are per unit of the whole
    /// area, and the element intercepts its irradiance over this share only.
    pub coverage: Vec<f64>,
    /// Irradiance from point, spot and directional lights and the sky per element, W·m⁻².
    pub light_irradiance: Vec<Rgb64>,
    /// Wall-clock seconds spent meshing and linking lights.
    pub setup_seconds: f64,
    /// The pairs of root patches overlapping in their plane, which every radiosity solver
    /// lights each fully ([`coplanar_overlaps`]; [`super::Solution::light_counted_twice`]).
    pub overlaps: Vec<Overlap>,
    /// Per element: the largest distance from its patch's centroid to a corner.
    radius: Vec<f64>,
    visibility: Arc<Visibility>,
    options: SystemOptions,
    form_factors: AtomicU64,
    visibility_rays: AtomicU64,
    /// On a periodic plot, the couplings through the endless field beyond the margin
    /// (`far_field.rs`), for the solvers that ask the system for its couplings.
    far: Option<FarField>,
}

impl RadiositySystem {
    /// Meshes `world`'s scene, averages emission and reflectance over each side of each leaf
    /// and gathers the light-link irradiance (in parallel over elements); on an unrolled
    /// periodic plot casts the leaves' far field too (`far_field.rs`).
    pub fn new(world: &Arc<World>, options: SystemOptions) -> Result<Self, SolveError> {
        Self::with_progress(world, options, &NoProgress, &Cancel::new())
    }

    /// [`Self::new`], telling `progress` of the far field's rays (phase "far-field rays"); once
    /// `cancel` is requested the rays left are not cast and the far field holds what was (a
    /// solver handed the system then stops at once, keeping what it has).
    pub fn with_progress(
        world: &Arc<World>,
        options: SystemOptions,
        progress: &dyn ProgressListener,
        cancel: &Cancel,
    ) -> Result<Self, SolveError> {
        Self::built(world, options, false, progress, cancel)
    }

    /// [`Self::with_progress`] with the visibility rays between patches seeded by what the
    /// patches are rather than by their indices ([`Visibility::seeded_by_geometry`]), as
    /// couplings kept between solves need (`kept_couplings.rs`): as accurate, not the same
    /// bit for bit.
    pub fn with_progress_by_geometry(
        world: &Arc<World>,
        options: SystemOptions,
        progress: &dyn ProgressListener,
        cancel: &Cancel,
    ) -> Result<Self, SolveError> {
        Self::built(world, options, true, progress, cancel)
    }

    fn built(
        world: &Arc<World>,
        options: SystemOptions,
        by_geometry: bool,
        progress: &dyn ProgressListener,
        cancel: &Cancel,
    ) -> Result<Self, SolveError> {
        let start = Instant::now();
        let mesh = PatchMesh::from_scene(&world.scene, &options.mesh)?;
        let visibility = by_geometry
            .then(|| {
                let visibility = Visibility::new(world, options.visibility, options.mesh.segments);
                visibility.map(|v| Arc::new(v.seeded_by_geometry()))
            })
            .transpose()?;
        let mut system = Self::from_mesh(world, mesh, options, None, visibility)?;
        let element = |k: usize, side: Side| Self::element(k, side) as u32;
        let (mesh, leaves) = (&system.mesh, &system.leaves);
        if let Some((far, rays)) = FarField::cast(world, mesh, leaves, element, progress, cancel) {
            system.visibility_rays.fetch_add(rays, Ordering::Relaxed);
            system.far = Some(far);
        }
        system.setup_seconds = start.elapsed().as_secs_f64();
        Ok(system)
    }

    /// The system on the leaves of `mesh` (a mesh of `world`'s scene). The light-link
    /// irradiance per element is `linked` when given (a solver that linked the lights
    /// itself), else gathered here; the visibility estimator is `visibility` when given (one
    /// a solver built for `world` with `options`), else built here.
    pub fn from_mesh(
        world: &Arc<World>,
        mesh: PatchMesh,
        options: SystemOptions,
        linked: Option<Vec<Rgb64>>,
        visibility: Option<Arc<Visibility>>,
    ) -> Result<Self, SolveError> {
        let start = Instant::now();
        let leaves = mesh.leaves();
        if leaves.is_empty() {
            return Err(SolveError::NoPatches);
        }
        let scene = &world.scene;
        let elements: Vec<Element> = leaves
            .iter()
            .flat_map(|&patch| Side::BOTH.map(|side| Element { patch, side }))
            .collect();
        let area = elements.iter().map(|e| mesh.patch(e.patch).area).collect();
        let radius = elements
            .iter()
            .map(|e| {
                let p = mesh.patch(e.patch);
                p.corners()
                    .iter()
                    .map(|c| c.distance(p.centroid))
                    .fold(0.0, f64::max)
            })
            .collect();
        let emission = elements
            .iter()
            .map(|e| surface::emission(scene, mesh.patch(e.patch), e.side))
            .collect();
        let reflectance = elements
            .iter()
            .map(|e| surface::reflectance(scene, mesh.patch(e.patch), e.side))
            .collect();
        let translucency = elements
            .iter()
            .map(|e| surface::translucency(scene, mesh.patch(e.patch)))
            .collect();
        let coverage = elements
            .iter()
            .map(|e| surface::coverage(scene, mesh.patch(e.patch)))
            .collect();
        let visibility = match visibility {
            Some(v) => v,
            None => Arc::new(Visibility::new(
                world,
                options.visibility,
                options.mesh.segments,
            )?),
        };
        let light_irradiance = linked.unwrap_or_else(|| {
            let exact = exact_shadows(world, &visibility);
            elements
                .par_iter()
                .map(|e| {
                    let lights = scene.lights.iter().zip(&exact);
                    lights.fold(Rgb64::BLACK, |sum, (light, exact)| {
                        let patch = mesh.patch(e.patch);
                        sum + light_irradiance(
                            visibility.world(),
                            (&light.kind, exact.as_ref()),
                            patch,
                            e.side,
                            options.link_samples,
                        )
                    })
                })
                .collect()
        });
        let overlaps = coplanar_overlaps(&mesh);
        Ok(RadiositySystem {
            world: Arc::clone(world),
            overlaps,
            leaves,
            elements,
            area,
            emission,
            reflectance,
            translucency,
            coverage,
            light_irradiance,
            setup_seconds: start.elapsed().as_secs_f64(),
            radius,
            visibility,
            mesh,
            options,
            form_factors: AtomicU64::new(0),
            visibility_rays: AtomicU64::new(0),
            far: None,
        })
    }

    /// The world the system was built from.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// Whether every coupling holds what the endless field of a periodic plot sends
    /// (`far_field.rs`).
    pub(super) fn has_far_field(&self) -> bool {
        self.far.is_some()
    }

    /// The options it was built with.
    pub fn options(&self) -> &SystemOptions {
        &self.options
    }

    /// The visibility between patches (and from points), with the world its rays meet.
    pub fn visibility(&self) -> &Visibility {
        &self.visibility
    }

    /// Number of elements (unknowns per channel): two per leaf.
    pub fn len(&self) -> usize {
        self.elements.len()
    }

    /// True when there are no elements (never for a built system).
    pub fn is_empty(&self) -> bool {
        self.elements.is_empty()
    }

    /// The patch of element `k`.
    pub fn patch(&self, k: usize) -> &Patch {
        self.mesh.patch(self.elements[k].patch)
    }

    /// The element of side `side` of leaf index `leaf` (an index into [`Self::leaves`]).
    pub fn element(leaf: usize, side: Side) -> usize {
        2 * leaf + side.index()
    }

    /// The other side of element `k`'s leaf.
    #[inline]
    pub fn other_side(k: usize) -> usize {
        k ^ 1
    }

    /// The radiosity element `k` scatters, W·m⁻², when the irradiance on it is `own` and on
    /// the other side of its leaf `other` (W·m⁻²): `ρ_k·own + τ_k·other`.
    #[inline]
    pub fn scattered(&self, k: usize, own: Rgb64, other: Rgb64) -> Rgb64 {
        self.reflectance[k] * own + self.translucency[k] * other
    }

    /// The share of the light arriving on element `k` that its leaf scatters back out,
    /// `ρ_k + τ_k` (the rest is absorbed).
    #[inline]
    pub fn albedo(&self, k: usize) -> Rgb64 {
        self.reflectance[k] + self.translucency[k]
    }

    /// The largest reflectance plus translucency of any element, any channel.
    pub fn largest_albedo(&self) -> f64 {
        (0..self.len())
            .map(|k| self.albedo(k).max_channel())
            .fold(0.0, f64::max)
    }

    /// True when some element is translucent (the two sides of its leaf are coupled).
    pub fn has_translucency(&self) -> bool {
        self.translucency.iter().any(|t| !t.is_black())
    }

    /// The source term `S_i = E_i + ρ_i H_light,i + τ_i H_light,ī` of element `k`, W·m⁻².
    pub fn source(&self, k: usize) -> Rgb64 {
        let other = self.light_irradiance[Self::other_side(k)];
        self.emission[k] + self.scattered(k, self.light_irradiance[k], other)
    }

    /// Total area of all elements (both sides of every leaf), scene units².
    pub fn total_area(&self) -> f64 {
        self.area.iter().sum()
    }

    /// `F_ij V_ij` between receiver element `i` and emitter element `j`: within the scene
    /// solved 0 for two sides of one patch and for sides that do not face each other; on a
    /// periodic plot plus what `i` sees of `j` in the endless field beyond the margin.
    pub fn coupling(&self, i: usize, j: usize) -> f64 {
        let far = self.far.as_ref().map_or(0.0, |f| f.share(i, j));
        far + self.near_coupling(i, j)
    }

    /// `F_ij V_ij` within the scene solved.
    fn near_coupling(&self, i: usize, j: usize) -> f64 {
        let (ri, ej) = (self.elements[i], self.elements[j]);
        if ri.patch == ej.patch {
            return 0.0;
        }
        let (receiver, emitter) = (self.patch(i), self.patch(j));
        // Quick rejection: one patch lies wholly behind the other's side (a bounding sphere
        // behind a plane); the full facing test decides the rest.
        let between = emitter.centroid - receiver.centroid;
        if between.dot(ri.side.normal(receiver)) < -self.radius[j]
            || between.dot(ej.side.normal(emitter)) > self.radius[i]
        {
            return 0.0;
        }
        let facing = facing(receiver, ri.side, emitter, ej.side);
        if facing == Facing::Away {
            return 0.0;
        }
        self.form_factors.fetch_add(1, Ordering::Relaxed);
        let f = form_factor(
            receiver,
            ri.side,
            emitter,
            ej.side,
            &self.options.form_factor,
        );
        if f <= 0.0 {
            return 0.0;
        }
        let v = match facing {
            // One patch straddles the other's plane: only the parts in front of the sides
            // that exchange light count, or the back of a block's top face would see, past
            // the block's own walls, the part of a wall patch above the top that its front
            // sees (the light leaked into the closed blocks of the Cornell box).
            Facing::Partly => {
                let (r, e) = (
                    (ri.patch, ri.side.normal(receiver)),
                    (ej.patch, ej.side.normal(emitter)),
                );
                let (a, b) = if ri.patch < ej.patch { (r, e) } else { (e, r) };
                self.visibility
                    .look(&self.mesh, a, b, STRADDLING_RAYS, Blockers::UNKNOWN)
            }
            _ => self.visibility.estimate(&self.mesh, ri.patch, ej.patch),
        };
        self.visibility_rays.fetch_add(v.rays, Ordering::Relaxed);
        f * v.visible
    }

    /// Row `i` of the coupling matrix: what receiver `i` gathers from every element.
    pub fn row(&self, i: usize) -> Couplings {
        Couplings::of_entries((0..self.len()).map(|j| (j, self.coupling(i, j))))
    }

    /// Column `j` of the coupling matrix: what every receiver gets from emitter `j`
    /// (computed in parallel over receivers).
    pub fn column(&self, j: usize) -> Couplings {
        let values: Vec<f64> = (0..self.len())
            .into_par_iter()
            .map(|i| self.coupling(i, j))
            .collect();
        Couplings::of_entries(values.into_iter().enumerate())
    }

    /// Adds work a solver did on its own (a hierarchical solver's links): `form_factors` form
    /// factors and `rays` visibility rays.
    pub fn count_work(&self, form_factors: u64, rays: u64) {
        self.form_factors.fetch_add(form_factors, Ordering::Relaxed);
        self.visibility_rays.fetch_add(rays, Ordering::Relaxed);
    }

    /// Form factors evaluated so far (facing pairs).
    pub fn form_factor_count(&self) -> u64 {
        self.form_factors.load(Ordering::Relaxed)
    }

    /// Visibility rays cast so far (pairs the shaft proves unoccluded cast none).
    pub fn visibility_ray_count(&self) -> u64 {
        self.visibility_rays.load(Ordering::Relaxed)
    }
}
