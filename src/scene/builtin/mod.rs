//! Scenes built into the engine, loaded by name: `cornell`, `cornell-textured`, `spheres`
//! (or `spheres:N`), `neon`, `canopy` (or `canopy:N`), `field` (or `field:N`), `blocks` (or
//! `blocks:N`) and `building` (or `building:N`). Lengths are in metres.

pub mod blocks;
pub mod building;
pub mod canopy;
pub mod cornell;
pub mod cornell_textured;
pub mod field;
pub mod neon;
pub mod spectrum;
pub mod spheres;

use super::Scene;

/// The built-in scenes: name and one-line description.
const NAMES: [(&str, &str); 8] = [
    (
        "cornell",
        "the measured Cornell box (Cornell University data, metres, spectral colours)",
    ),
    (
        "cornell-textured",
        "the Cornell box with a checkerboard floor and a striped back wall",
    ),
    (
        "spheres",
        "spheres:N (default 100) random spheres and five point lights, for acceleration tests",
    ),
    (
        "neon",
        "a dark room lit only by a neon sign (emissive texture, no lights)",
    ),
    (
        "canopy",
        "canopy:N (default 10000) small leaves under sky and sun, for the light model",
    ),
    (
        "field",
        "field:N (default 160000) 5 cm leaves at LAI 1 on a periodic plot: an endless field",
    ),
    (
        "blocks",
        "blocks:N (default 1000) small cubes in a closed room under a lamp, for radiosity",
    ),
    (
        "building",
        "building:N (default 100) furnished offices, about 1,100 triangles each, for radiosity",
    ),
];

/// The built-in scene names with a one-line description each.
pub fn names() -> &'static [(&'static str, &'static str)] {
    &NAMES
}

/// Builds the built-in scene `spec`: a name from [`names`], optionally followed by `:` and a
/// parameter (`spheres:N`, `canopy:N`, `field:N`, `blocks:N` and `building:N` take one). `None` when `spec` names no built-in scene;
/// `Some(Err)` with a message for a bad parameter.
pub fn load(spec: &str) -> Option<Result<Scene, String>> {
    let (name, parameter) = match spec.split_once(':') {
        Some((name, parameter)) => (name, Some(parameter)),
        None => (spec, None),
    };
    let no_parameter = |build: fn() -> Result<Scene, String>| match parameter {
        Some(p) => Err(format!(
            "built-in scene '{name}' takes no parameter (got ':{p}')"
        )),
        None => build(),
    };
    Some(match name {
        "cornell" => no_parameter(cornell::scene),
        "cornell-textured" => no_parameter(cornell_textured::scene),
        "neon" => no_parameter(|| Ok(neon::scene())),
        "spheres" => spheres::parse_count(parameter).map(spheres::scene),
        "canopy" => canopy::parse_count(parameter).map(canopy::scene),
        "field" => field::parse_count(parameter).map(field::scene),
        "blocks" => blocks::parse_count(parameter).map(blocks::scene),
        "building" => building::parse_count(parameter).map(building::scene),
        _ => return None,
    })
}

/// Parses the `N` of `name:N`, a count of `what` from 1 to `max`; `default` without one.
fn parse_count(
    name: &str,
    what: &str,
    parameter: Option<&str>,
    default: usize,
    max: usize,
) -> Result<usize, String> {
    let Some(p) = parameter else {
        return Ok(default);
    };
    match p.trim().parse::<usize>() {
        Ok(n) if (1..=max).contains(&n) => Ok(n),
        _ => Err(format!(
            "{name}:N needs a {what} count from 1 to {max} (got '{p}')"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Shape;

    #[test]
    fn names_lists_every_builtin_and_each_loads_valid() {
        let listed: Vec<&str> = names().iter().map(|(n, _)| *n).collect();
        assert_eq!(
            listed,
            [
                "cornell",
                "cornell-textured",
                "spheres",
                "neon",
                "canopy",
                "field",
                "blocks",
                "building"
            ]
        );
        for (name, description) in names() {
            assert!(!description.is_empty());
            let scene = load(name).unwrap().unwrap();
            assert!(!scene.objects.is_empty(), "{name}");
            assert!(scene.camera.rays().is_some(), "{name}");
            for m in &scene.materials {
                assert!(m.albedo_bound() <= 1.0, "{name}: {}", m.name);
            }
            for o in &scene.objects {
                assert!((o.material as usize) < scene.materials.len(), "{name}");
                if let Shape::Mesh(mesh) = &o.shape {
                    mesh.validate().unwrap();
                }
            }
            for m in &scene.materials {
                for t in [m.diffuse_texture, m.emission_texture]
                    .into_iter()
                    .flatten()
                {
                    assert!((t as usize) < scene.textures.len(), "{name}");
                }
            }
        }
    }

    #[test]
    fn parameters_are_parsed_and_checked() {
        assert_eq!(load("spheres").unwrap().unwrap().objects.len(), 100);
        let thousand = load("spheres:1000").unwrap().unwrap();
        assert_eq!(thousand.objects.len(), 1000);
        assert_eq!(thousand.lights.len(), 5);
        assert_eq!(thousand, load("spheres:1000").unwrap().unwrap());
        assert!(load("spheres:abc").unwrap().is_err());
        assert!(load("spheres:0").unwrap().is_err());
        assert!(load("cornell:2").unwrap().is_err());
        assert!(load("no-such-scene").is_none());
        assert!(load("no-such-scene:3").is_none());
    }
}
