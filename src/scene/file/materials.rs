//! `[materials.NAME]` tables: values, textures and the energy-conservation check.

use super::error::SceneError;
use super::fields::Table;
use super::format::MaterialEntry;
use super::photometry;
use super::textures::TextureCache;
use super::value::{ColorSpaceName, TextureEntry, WrapName};
use crate::color::Rgb;
use crate::scene::{ColorSpace, ENERGY_TOLERANCE, Material, Scene, TextureId, Wrap};
use std::path::Path;
use toml::Spanned;

/// Where textures come from while building materials.
pub(super) struct TextureContext<'a> {
    /// Folder that relative texture paths start from (the scene file's folder).
    pub base_dir: &'a Path,
    /// Textures loaded so far.
    pub cache: &'a mut TextureCache,
}

/// The material `name` described by `e`, with its textures added to `scene`.
pub(super) fn build_material(
    t: &Table<'_>,
    name: &str,
    e: &MaterialEntry,
    textures: &mut TextureContext<'_>,
    scene: &mut Scene,
) -> Result<Material, SceneError> {
    let defaults = Material::default();
    let weight = |field: &str, v: Option<&Spanned<super::value::Triple>>, default: Rgb| {
        let c = t.rgb(field, v)?.unwrap_or(default);
        match v {
            Some(s) if c.max_channel() > 1.0 => {
                Err(t.error(s.span(), field, "weight must be in [0, 1]"))
            }
            _ => Ok(c),
        }
    };
    let diffuse = weight("diffuse", e.diffuse.as_ref(), defaults.diffuse)?;
    let specular = weight("specular", e.specular.as_ref(), Rgb::BLACK)?;
    let mirror = weight("mirror", e.mirror.as_ref(), Rgb::BLACK)?;
    let transmission = weight("transmission", e.transmission.as_ref(), Rgb::BLACK)?;
    let translucency = weight("translucency", e.translucency.as_ref(), Rgb::BLACK)?;
    let sum = diffuse + translucency + specular + mirror + transmission;
    if sum.max_channel() > 1.0 + ENERGY_TOLERANCE {
        let channel = ["red", "green", "blue"][(0..3)
            .max_by(|&a, &b| sum[a].total_cmp(&sum[b]))
            .unwrap_or(0)];
        return Err(t.table_error(format!(
            "material \"{name}\" reflects more than it receives: diffuse + translucency + \
             specular + mirror + transmission = {:.3} in the {channel} channel (must be ≤ 1)",
            sum.max_channel()
        )));
    }
    let one_sided = e.one_sided.unwrap_or(false);
    if one_sided
        && !translucency.is_black()
        && let Some(span) = e.translucency.as_ref().map(Spanned::span)
    {
        return Err(t.error(
            span,
            "translucency",
            "a one-sided material absorbs on its back, so nothing passes through it: \
             remove one_sided or translucency",
        ));
    }
    let emission = photometry::amount(
        t,
        ("emission", e.emission.as_ref()),
        &[("luminance_cd_m2", e.luminance_cd_m2.as_ref(), 1.0)],
        ("emission_color", e.emission_color.as_ref()),
    )?
    .unwrap_or(Rgb::BLACK);
    let shininess = match t.number("shininess", e.shininess.as_ref())? {
        Some(s) if s < 0.0 => {
            let span = e.shininess.as_ref().map_or(t.span.clone(), Spanned::span);
            return Err(t.error(span, "shininess", "shininess must be ≥ 0"));
        }
        Some(s) => s,
        None => defaults.shininess,
    };
    let ior = match t.number("ior", e.ior.as_ref())? {
        Some(i) if i <= 0.0 => {
            let span = e.ior.as_ref().map_or(t.span.clone(), Spanned::span);
            return Err(t.error(span, "ior", "index of refraction must be > 0"));
        }
        Some(i) => i,
        None => defaults.ior,
    };
    let mut texture = |field: &str, entry: Option<&Spanned<TextureEntry>>, alpha: bool| {
        entry
            .map(|s| texture_id(t, field, s, alpha, textures, scene))
            .transpose()
    };
    Ok(Material {
        name: name.to_string(),
        diffuse,
        diffuse_texture: texture("diffuse_texture", e.diffuse_texture.as_ref(), false)?,
        translucency,
        emission,
        emission_texture: texture("emission_texture", e.emission_texture.as_ref(), false)?,
        two_sided: e.two_sided.unwrap_or(false),
        specular,
        shininess,
        mirror,
        transmission,
        ior,
        alpha_texture: texture("alpha_texture", e.alpha_texture.as_ref(), true)?,
        one_sided,
    })
}

/// Loads the texture named by `entry` (relative to the scene file). Alpha textures decode
/// linearly unless a colour space is given, and take alpha from the grey level when the
/// image has no alpha.
fn texture_id(
    t: &Table<'_>,
    field: &str,
    entry: &Spanned<TextureEntry>,
    alpha: bool,
    textures: &mut TextureContext<'_>,
    scene: &mut Scene,
) -> Result<TextureId, SceneError> {
    let path = textures.base_dir.join(&entry.get_ref().file);
    let space = match entry.get_ref().colorspace {
        Some(ColorSpaceName::Linear) => ColorSpace::Linear,
        Some(ColorSpaceName::Srgb) => ColorSpace::Srgb,
        None if alpha => ColorSpace::Linear,
        None => ColorSpace::default_for(&path),
    };
    let wrap = match entry.get_ref().wrap {
        WrapName::Repeat => Wrap::Repeat,
        WrapName::Clamp => Wrap::Clamp,
    };
    textures
        .cache
        .file(scene, &path, space, alpha, wrap)
        .map_err(|m| t.error(entry.span(), field, m))
}
