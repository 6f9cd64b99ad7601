//! `strahl render --batch I/N --partial FILE` and the image `strahl merge PARTS -o IMAGE`
//! makes of such files: a path-traced render's samples per pixel split into batches that
//! run anywhere (a job array, other machines), each summing its samples exactly, so that the
//! merged image is the one `strahl render` with the same settings writes, byte for byte.
//!
//! The file is JSON: `{"scene": …, "render": {"scene_digest", "settings", "batch",
//! "seconds", "sums": {"width", "height", "samples", "sums"}}}`, the last `sums` one base64
//! string of the per-pixel fixed-point sums as zigzag varints (about 11 bytes a channel,
//! some 9 MB for a 512×512 image).

use super::batch_file;
use super::radiosity::method_error;
use super::render::RenderArgs;
use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};
use std::path::Path;
use strahl::image::{self, ToneMapping};
use strahl::method::{AccelKind, Batch, Method, RenderPartial, World};

/// A render batch's partial result as `strahl render --partial` writes it: how to open the
/// scene again, and the batch's sums.
#[derive(Serialize, Deserialize)]
pub struct RenderPartialFile {
    /// The scene as `render` was given it (a built-in name or a file path).
    pub scene: String,
    /// The batch.
    pub render: RenderPartial,
}

/// Renders batch `batch` of `method` on `world` and writes its partial result to `path`.
pub fn write(
    args: &RenderArgs,
    world: &World,
    method: &Method,
    batch: Batch,
    path: &Path,
) -> Result<()> {
    let render = batch_file::run_whole("rendering", args.quiet, |bar, cancel| {
        strahl::method::run_render_batch(world, method, batch, bar, cancel)
    })?;
    let file = RenderPartialFile {
        scene: args.scene.clone(),
        render,
    };
    batch_file::write(path, &file)?;
    if !args.quiet {
        eprintln!(
            "batch {batch}: {} paths per pixel in {:.2} s → {}",
            file.render.samples_per_pixel(),
            file.render.seconds,
            path.display()
        );
    }
    Ok(())
}

/// Merges the render batches `files` (of one scene, `scene`) into the image at `output`,
/// tone-mapped by `tone` where it is 8-bit.
pub fn merge(
    scene: &str,
    files: Vec<RenderPartialFile>,
    output: &Path,
    tone: &ToneMapping,
    quiet: bool,
) -> Result<()> {
    let opened = strahl::scene::open(scene, &Default::default())?;
    let world = World::new(opened, AccelKind::Bvh).with_context(|| format!("scene '{scene}'"))?;
    let partials: Vec<RenderPartial> = files.into_iter().map(|f| f.render).collect();
    let outcome = strahl::method::merge_render_batches(&world, &partials).map_err(method_error)?;
    let film = outcome.image.context("the merge made no image")?;
    image::save(&film, output, tone)?;
    if !quiet {
        eprintln!(
            "{} {}×{}: {}, {:.2} s in all",
            output.display(),
            film.width(),
            film.height(),
            outcome.summary,
            outcome.seconds
        );
    }
    Ok(())
}
