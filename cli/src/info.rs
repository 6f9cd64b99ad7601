//! `strahl info`: validate a scene and print its statistics.

use super::choice::choice;
use anyhow::{Context, Result};
use clap::Args;
use std::collections::BTreeMap;
use std::fmt::Write;
use strahl::method::{AccelKind, World};
use strahl::scene::LightKind;

/// Arguments of `strahl info`.
#[derive(Debug, Args)]
pub struct InfoArgs {
    /// Scene: a built-in name, a .toml scene file or a mesh file.
    pub scene: String,
    /// Accelerator whose statistics to show.
    #[arg(long, value_parser = choice::<AccelKind>(), default_value_t = AccelKind::Bvh)]
    pub accel: AccelKind,
    /// The memory bound.
    #[command(flatten)]
    pub memory: super::limits::MemoryArgs,
}

/// Runs `strahl info`.
pub fn run(args: &InfoArgs) -> Result<()> {
    let scene = strahl::scene::open(&args.scene, &strahl::scene::LoadOptions::default())?;
    let world = World::new(scene, args.accel).with_context(|| format!("scene '{}'", args.scene))?;
    let scene = &world.scene;
    let mut kinds: BTreeMap<&str, usize> = BTreeMap::new();
    for o in &scene.objects {
        *kinds.entry(o.shape.kind_name()).or_default() += 1;
    }
    let kinds: Vec<String> = kinds.iter().map(|(k, n)| format!("{n} {k}")).collect();
    let c = &scene.camera;
    let mut out = String::new();
    writeln!(out, "scene       {}", scene.name)?;
    writeln!(
        out,
        "camera      at {:?} looking at {:?}, fov {}°, {}×{}",
        c.position.to_array(),
        c.look_at.to_array(),
        c.fov_degrees,
        c.width,
        c.height
    )?;
    writeln!(
        out,
        "objects     {} ({})",
        scene.objects.len(),
        kinds.join(", ")
    )?;
    writeln!(
        out,
        "primitives  {} triangles, {} analytic shapes",
        world.geometry.triangle_count(),
        world.geometry.analytic_count()
    )?;
    if world.geometry.placement_count() > 0 {
        writeln!(
            out,
            "placed      {} copies of shared meshes, {} triangles kept once",
            world.geometry.placement_count(),
            world.geometry.placed_mesh_triangles()
        )?;
    }
    writeln!(
        out,
        "materials   {}, textures {}",
        scene.materials.len(),
        scene.textures.len()
    )?;
    let mut lights: BTreeMap<&str, usize> = BTreeMap::new();
    for l in &scene.lights {
        let k = match l.kind {
            LightKind::Point { .. } => "point",
            LightKind::Lambertian { .. } => "lambertian",
            LightKind::Spot { .. } => "spot",
            LightKind::Directional { .. } => "directional",
            LightKind::Sky { .. } => "sky",
            LightKind::CieSky { .. } => "cie_sky",
        };
        *lights.entry(k).or_default() += 1;
    }
    let mut light_list: Vec<String> = lights.iter().map(|(k, n)| format!("{n} {k}")).collect();
    // A fold from +0 (an empty float sum is −0, printed "-0.000000").
    let area = world.lights.area.iter().fold(0.0f32, |a, l| a + l.area);
    light_list.push(format!(
        "{} area (emissive objects, {} triangles, {area:.6} units²)",
        world.lights.area.len(),
        world
            .lights
            .area
            .iter()
            .map(|l| l.prims.len())
            .sum::<usize>()
    ));
    writeln!(out, "lights      {}", light_list.join(", "))?;
    if !scene.sensors.is_empty() {
        writeln!(out, "sensors     {}", scene.sensors.len())?;
    }
    let b = world.geometry.bounds();
    writeln!(
        out,
        "bounds      {:?} .. {:?}",
        b.min.to_array(),
        b.max.to_array()
    )?;
    if let Some(field) = world.field() {
        let p = field.plot;
        writeln!(
            out,
            "periodic    plot x {:?} z {:?}, area {} (square scene units), repeated without \
             end; {} copies of the geometry reach into it",
            p.x,
            p.z,
            p.area(),
            field.copies()
        )?;
    }
    let s = world.accel_stats();
    writeln!(
        out,
        "{:<11} built in {:.3} s: {} nodes, {} leaves, depth {}, {} primitive references",
        s.kind,
        world.build_seconds(),
        s.nodes,
        s.leaves,
        s.max_depth,
        s.references
    )?;
    super::print_text(&out)?;
    Ok(())
}
