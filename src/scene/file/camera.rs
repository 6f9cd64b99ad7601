//! The `[camera]` table.

use super::error::{SceneError, Source};
use super::fields::Table;
use super::format::CameraEntry;
use crate::scene::{Camera, Scene};
use glam::Vec3;
use toml::Spanned;

/// The camera of `entry`; defaults (also for a missing table): position `[0, 0, 5]`, look-at
/// the origin, up `[0, 1, 0]`, 45° vertical field of view, 512 × 512 pixels.
pub(super) fn build_camera(
    src: Source<'_>,
    entry: Option<&Spanned<CameraEntry>>,
) -> Result<Camera, SceneError> {
    let defaults = Scene::empty("").camera;
    let Some(entry) = entry else {
        return Ok(defaults);
    };
    let t = Table::new(src, "camera", entry.span());
    let e = entry.get_ref();
    let fov = match t.number("fov", e.fov.as_ref())? {
        Some(f) if !(f > 0.0 && f < 180.0) => {
            let span = e.fov.as_ref().map_or(t.span.clone(), Spanned::span);
            return Err(t.error(
                span,
                "fov",
                "vertical field of view must be in (0, 180) degrees",
            ));
        }
        Some(f) => f,
        None => defaults.fov_degrees,
    };
    let pixels = |name: &str, v: Option<&Spanned<u32>>, default: u32| match v {
        Some(s) if *s.get_ref() == 0 => Err(t.error(s.span(), name, "must be at least 1 pixel")),
        Some(s) => Ok(*s.get_ref()),
        None => Ok(default),
    };
    let camera = Camera {
        position: t
            .vec3("position", e.position.as_ref())?
            .unwrap_or(defaults.position),
        look_at: t
            .vec3("look_at", e.look_at.as_ref())?
            .unwrap_or(defaults.look_at),
        up: t.vec3("up", e.up.as_ref())?.unwrap_or(Vec3::Y),
        fov_degrees: fov,
        width: pixels("width", e.width.as_ref(), defaults.width)?,
        height: pixels("height", e.height.as_ref(), defaults.height)?,
    };
    if camera.rays().is_none() {
        return Err(t.table_error(
            "degenerate view: position equals look_at, or up is parallel to the view direction",
        ));
    }
    Ok(camera)
}
