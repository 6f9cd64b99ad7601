//! Moving parts of a scene by a translation (the viewer's "move a light or an object"): an
//! object through its transform, a point, Lambertian or spot light by its position.

use super::{LightKind, Scene};
use crate::geometry::Transform;
use glam::Vec3;

/// What was moved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Moved {
    /// The object of this index.
    Object(usize),
    /// The light of this index.
    Light(usize),
}

/// What a move refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MoveError {
    /// Neither an object nor a light has that name.
    #[error("no object or light is named '{0}'")]
    NoSuchName(String),
    /// A directional light or the sky: they have no position.
    #[error("light '{0}' is directional or a sky: it has no position to move")]
    NotPlaced(String),
    /// The offset or position is not three finite numbers.
    #[error("the offset or position must be three finite numbers")]
    NotFinite,
    /// An object without bounds (an infinite plane) or without surfaces: it has no centre
    /// to move to.
    #[error("object '{0}' has no centre (it is unbounded or empty): move it by an offset")]
    NoCentre(String),
}

/// Segments around the axis of a curved shape when its centre is found (the centre of a
/// symmetric facet mesh is the shape's whatever the count).
const CENTRE_SEGMENTS: u32 = 16;

impl Scene {
    /// The name of light `index`: its own, or `light-<index>`.
    pub fn light_name(&self, index: usize) -> String {
        self.lights[index]
            .name
            .clone()
            .unwrap_or_else(|| format!("light-{index}"))
    }

    /// The names of what [`Scene::move_named`] can move: every object, then every point,
    /// Lambertian and spot light.
    pub fn movable_names(&self) -> Vec<String> {
        let objects = (0..self.objects.len()).map(|k| self.object_name(k));
        let lights = (0..self.lights.len())
            .filter(|&k| placed(&self.lights[k].kind))
            .map(|k| self.light_name(k));
        objects.chain(lights).collect()
    }

    /// Where each of [`Scene::movable_names`] is, in that order ([`Scene::position_of`]
    /// each, found by index: `None` for an object without a centre).
    pub fn movable_positions(&self) -> Vec<Option<Vec3>> {
        let objects = (0..self.objects.len()).map(|k| self.object_centre(k));
        let lights = (0..self.lights.len())
            .filter(|&k| placed(&self.lights[k].kind))
            .map(|k| self.light_place(k));
        objects.chain(lights).collect()
    }

    /// Where [`Scene::move_named`] finds `name`: the first object of that name at the centre
    /// of the box around its surfaces (scene units; curved shapes' by their facets), or else
    /// the first light of that name at its position.
    pub fn position_of(&self, name: &str) -> Result<Vec3, MoveError> {
        match self.named(name)? {
            Moved::Object(k) => self
                .object_centre(k)
                .ok_or_else(|| MoveError::NoCentre(name.to_string())),
            Moved::Light(k) => self
                .light_place(k)
                .ok_or_else(|| MoveError::NotPlaced(name.to_string())),
        }
    }

    /// Moves `name` as [`Scene::move_named`] does so that its position
    /// ([`Scene::position_of`]) becomes `to` (scene units).
    pub fn move_named_to(&mut self, name: &str, to: Vec3) -> Result<Moved, MoveError> {
        if !to.is_finite() {
            return Err(MoveError::NotFinite);
        }
        let by = to - self.position_of(name)?;
        self.move_named(name, by)
    }

    /// Moves the first object named `name` (after its own transform), or else the first
    /// light of that name, by `by` (scene units).
    pub fn move_named(&mut self, name: &str, by: Vec3) -> Result<Moved, MoveError> {
        if !by.is_finite() {
            return Err(MoveError::NotFinite);
        }
        let moved = self.named(name)?;
        match moved {
            Moved::Object(k) => {
                let object = &mut self.objects[k];
                object.transform = object.transform.then(&Transform::translate(by));
            }
            Moved::Light(k) => match &mut self.lights[k].kind {
                LightKind::Point { position, .. }
                | LightKind::Lambertian { position, .. }
                | LightKind::Spot { position, .. } => *position += by,
                LightKind::Directional { .. }
                | LightKind::Sky { .. }
                | LightKind::CieSky { .. } => {
                    return Err(MoveError::NotPlaced(name.to_string()));
                }
            },
        }
        Ok(moved)
    }

    /// The first object named `name`, or else the first light of that name.
    fn named(&self, name: &str) -> Result<Moved, MoveError> {
        if let Some(k) = (0..self.objects.len()).find(|&k| self.object_name(k) == name) {
            return Ok(Moved::Object(k));
        }
        (0..self.lights.len())
            .find(|&k| self.light_name(k) == name)
            .map(Moved::Light)
            .ok_or_else(|| MoveError::NoSuchName(name.to_string()))
    }

    /// The centre of the box around object `k`'s surfaces in the scene; `None` for an
    /// unbounded or empty one.
    fn object_centre(&self, k: usize) -> Option<Vec3> {
        let object = &self.objects[k];
        let mesh = object.shape.to_mesh(CENTRE_SEGMENTS).ok()?;
        let corners = mesh.positions.iter().map(|&p| object.transform.point(p));
        let (min, max) = corners.fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p), hi.max(p))
        });
        let centre = 0.5 * (min + max);
        centre.is_finite().then_some(centre)
    }

    /// Where light `k` is; `None` for a directional light or a sky.
    fn light_place(&self, k: usize) -> Option<Vec3> {
        match &self.lights[k].kind {
            LightKind::Point { position, .. }
            | LightKind::Lambertian { position, .. }
            | LightKind::Spot { position, .. } => Some(*position),
            LightKind::Directional { .. } | LightKind::Sky { .. } | LightKind::CieSky { .. } => {
                None
            }
        }
    }
}

/// Whether a light of this kind has a position.
fn placed(kind: &LightKind) -> bool {
    !matches!(kind, LightKind::Directional { .. }) && !kind.is_sky()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;
    use crate::scene::{Light, Shape, open};

    #[test]
    fn a_moved_object_keeps_its_shape_and_moves_by_the_offset() {
        let mut scene = open("cornell", &Default::default()).unwrap();
        let before = scene.clone();
        let by = Vec3::new(0.1, -0.05, 0.2);
        let Ok(Moved::Object(k)) = scene.move_named("light", by) else {
            panic!("the light is an object");
        };
        assert_eq!(scene.object_name(k), "light");
        let (old, new) = (&before.objects[k], &scene.objects[k]);
        assert_eq!(old.shape, new.shape);
        let p = Vec3::new(0.3, 0.7, -0.2);
        let moved = new.transform.point(p) - old.transform.point(p);
        assert!((moved - by).length() < 1e-6, "{moved}");
        assert_eq!(new.transform.normal(Vec3::Y), old.transform.normal(Vec3::Y));
        assert!(
            (0..scene.objects.len())
                .filter(|&j| j != k)
                .all(|j| scene.objects[j] == before.objects[j])
        );
        assert!(scene.movable_names().contains(&"light".to_string()));
    }

    #[test]
    fn moves_that_cannot_be_made_are_refused_by_name() {
        let mut scene = open("cornell", &Default::default()).unwrap();
        let before = scene.clone();
        assert_eq!(
            scene.move_named("no such thing", Vec3::X),
            Err(MoveError::NoSuchName("no such thing".into()))
        );
        assert_eq!(
            scene.move_named("light", Vec3::new(f32::NAN, 0.0, 0.0)),
            Err(MoveError::NotFinite)
        );
        assert_eq!(scene, before);
    }

    #[test]
    fn placed_lights_move_and_lights_without_a_place_are_refused() {
        let mut scene = open("canopy:10", &Default::default()).unwrap();
        let sky = scene
            .lights
            .iter()
            .position(|l| matches!(l.kind, LightKind::Sky { .. }))
            .expect("the canopy has a sky");
        let sky_name = scene.light_name(sky);
        assert_eq!(
            scene.move_named(&sky_name, Vec3::X),
            Err(MoveError::NotPlaced(sky_name.clone()))
        );
        assert!(!scene.movable_names().contains(&sky_name));
        scene.lights.push(Light {
            name: Some("bulb".into()),
            kind: LightKind::Point {
                position: Vec3::ONE,
                intensity: Rgb::splat(1.0),
            },
        });
        let point = scene.lights.len() - 1;
        assert_eq!(
            scene.move_named("bulb", Vec3::new(0.0, 2.0, 0.0)),
            Ok(Moved::Light(point))
        );
        assert!(matches!(
            scene.lights[point].kind,
            LightKind::Point { position, .. } if position == Vec3::new(1.0, 3.0, 1.0)
        ));
        assert!(scene.movable_names().contains(&"bulb".to_string()));
    }

    #[test]
    fn an_object_or_a_light_moves_to_a_position_typed() {
        let mut scene = open("cornell", &Default::default()).unwrap();
        // The measured box's lamp, 13 × 10.5 cm in the ceiling, centred over (0.278, 0.2795).
        let lamp = scene.position_of("light").unwrap();
        assert!(
            (lamp.x - 0.278).abs() < 2e-3 && (lamp.z - 0.28).abs() < 2e-3,
            "{lamp}"
        );
        let to = Vec3::new(0.2, lamp.y, 0.35);
        assert_eq!(
            scene.move_named_to("light", to),
            scene.clone().move_named("light", to - lamp)
        );
        assert!((scene.position_of("light").unwrap() - to).length() < 1e-5);
        // A sphere's centre whatever its facets.
        let mut spheres = open("spheres:6", &Default::default()).unwrap();
        let Shape::Sphere { center, .. } = spheres.objects[2].shape else {
            panic!("spheres");
        };
        let name = spheres.object_name(2);
        let at = spheres.objects[2].transform.point(center);
        assert!((spheres.position_of(&name).unwrap() - at).length() < 1e-5);
        spheres.move_named_to(&name, Vec3::ZERO).unwrap();
        assert!(spheres.position_of(&name).unwrap().length() < 1e-5);
        // Refused: nothing of that name, a position not finite, a light with no place.
        assert_eq!(
            scene.move_named_to("nothing", Vec3::ZERO),
            Err(MoveError::NoSuchName("nothing".into()))
        );
        assert_eq!(
            scene.move_named_to("light", Vec3::splat(f32::INFINITY)),
            Err(MoveError::NotFinite)
        );
        let mut ground = scene.objects[0].clone();
        ground.name = Some("ground".into());
        ground.shape = Shape::Plane {
            point: Vec3::ZERO,
            normal: Vec3::Y,
        };
        scene.objects.push(ground);
        assert_eq!(
            scene.move_named_to("ground", Vec3::ONE),
            Err(MoveError::NoCentre("ground".into()))
        );
        assert!(scene.move_named("ground", Vec3::ONE).is_ok());
        // The positions of everything movable, by index, are those found by name.
        let by_name: Vec<Option<Vec3>> = (scene.movable_names().iter())
            .map(|n| scene.position_of(n).ok())
            .collect();
        assert_eq!(scene.movable_positions(), by_name);
        assert_eq!(by_name.iter().filter(|p| p.is_none()).count(), 1);
    }
}
