//! MGF's named contexts, the current vertex, colour and material, and the entities that
//! select them (`v`, `c`, `m` with a name, `NAME =` or `NAME = TEMPLATE`) and set their fields
//! (`p`, `n`; `cxy`, `cspec`, `cct`, `cmix`; `sides`, `rd`, `td`, `ed`, `rs`, `ts`, `ir`).
//! Material fields take the colour current when they are given.

use super::mgf_color::{Chroma, Component, MgfMaterial};
use super::mgf_syntax::{arity, number, vector};
use glam::DVec3;
use std::collections::HashMap;

/// A named context kind (vertices, colours, materials): the named values, which one is
/// current (`None`: the unnamed one) and the unnamed one's value.
pub(super) struct Contexts<T> {
    named: HashMap<String, T>,
    /// The current context's name; `None` for the unnamed one.
    pub current: Option<String>,
    unnamed: T,
    default: T,
}

impl<T: Clone> Contexts<T> {
    fn new(default: T) -> Self {
        Contexts {
            named: HashMap::new(),
            current: None,
            unnamed: default.clone(),
            default,
        }
    }

    /// `KEY`, `KEY NAME`, `KEY NAME =` or `KEY NAME = TEMPLATE` for contexts of `kind`.
    fn select(&mut self, args: &[&str], kind: &str) -> Result<(), String> {
        match args {
            [] => {
                self.current = None;
                self.unnamed = self.default.clone();
            }
            [name] => {
                if !self.named.contains_key(*name) {
                    return Err(format!("{kind} \"{name}\" is not defined"));
                }
                self.current = Some(name.to_string());
            }
            [name, equals, template @ ..] if *equals == "=" && template.len() <= 1 => {
                let value = match template.first() {
                    None => self.default.clone(),
                    Some(t) => self
                        .named
                        .get(*t)
                        .cloned()
                        .ok_or_else(|| format!("template {kind} \"{t}\" is not defined"))?,
                };
                self.named.insert(name.to_string(), value);
                self.current = Some(name.to_string());
            }
            _ => return Err("NAME, NAME = or NAME = TEMPLATE expected after it".into()),
        }
        Ok(())
    }

    /// The current context's value.
    pub fn get(&self) -> &T {
        match &self.current {
            Some(name) => self.named.get(name).unwrap_or(&self.unnamed),
            None => &self.unnamed,
        }
    }

    /// The current context's value, to change.
    fn get_mut(&mut self) -> &mut T {
        match &self.current {
            Some(name) => self.named.get_mut(name).unwrap_or(&mut self.unnamed),
            None => &mut self.unnamed,
        }
    }
}

/// A vertex context: position and normal (zero: none), untransformed.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Vertex {
    /// Position.
    pub p: DVec3,
    /// Normal; zero when none is set.
    pub n: DVec3,
}

/// The three named context kinds.
pub(super) struct Named {
    /// Vertices.
    pub vertices: Contexts<Vertex>,
    /// Colours.
    pub colors: Contexts<Chroma>,
    /// Materials.
    pub materials: Contexts<MgfMaterial>,
}

impl Named {
    /// The unnamed contexts of every kind current: the origin without normal, neutral grey,
    /// the two-sided black absorber.
    pub fn new() -> Self {
        Named {
            vertices: Contexts::new(Vertex::default()),
            colors: Contexts::new(Chroma::NEUTRAL),
            materials: Contexts::new(MgfMaterial::default()),
        }
    }

    /// The vertex named `name`.
    pub fn vertex(&self, name: &str) -> Result<Vertex, String> {
        self.vertices
            .named
            .get(name)
            .copied()
            .ok_or_else(|| format!("vertex \"{name}\" is not defined"))
    }

    /// Interprets `keyword args` when it is a context entity (true), or leaves it (false);
    /// problems that do not stop the import go to `warn`.
    pub fn entity(
        &mut self,
        keyword: &str,
        args: &[&str],
        warn: &mut dyn FnMut(String),
    ) -> Result<bool, String> {
        match keyword {
            "c" => self.colors.select(args, "colour")?,
            "cxy" => {
                arity(args, 2, 2, "cxy x y")?;
                *self.colors.get_mut() =
                    Chroma::from_xy(number(args[0], "x")?, number(args[1], "y")?)?;
            }
            "cspec" => {
                arity(args, 4, usize::MAX, "cspec l_min l_max v1 v2 …")?;
                *self.colors.get_mut() = Chroma::from_spectrum(args, warn)?;
            }
            "cct" => {
                arity(args, 1, 1, "cct temperature")?;
                *self.colors.get_mut() = Chroma::blackbody(number(args[0], "temperature")?)?;
            }
            "cmix" => {
                if args.len() < 2 || !args.len().is_multiple_of(2) {
                    return Err(format!(
                        "pairs of weight and colour expected, got {} arguments",
                        args.len()
                    ));
                }
                let parts =
                    args.chunks_exact(2)
                        .map(|pair| {
                            let weight = number(pair[0], "weight")?;
                            let color =
                                self.colors.named.get(pair[1]).ok_or_else(|| {
                                    format!("colour \"{}\" is not defined", pair[1])
                                })?;
                            Ok((weight, *color))
                        })
                        .collect::<Result<Vec<_>, String>>()?;
                *self.colors.get_mut() = Chroma::mix(&parts)?;
            }
            "m" => self.materials.select(args, "material")?,
            "sides" => {
                arity(args, 1, 1, "sides 1|2")?;
                self.materials.get_mut().one_sided = match args[0] {
                    "1" => true,
                    "2" => false,
                    other => return Err(format!("1 or 2 expected, got \"{other}\"")),
                };
            }
            "rd" | "td" | "ed" => {
                let field = ["rho_d", "tau_d", "epsilon_d"][["rd", "td", "ed"]
                    .iter()
                    .position(|k| *k == keyword)
                    .unwrap_or(0)];
                arity(args, 1, 1, &format!("{keyword} {field}"))?;
                let amount = number(args[0], field)?;
                let most = if keyword == "ed" { f64::INFINITY } else { 1.0 };
                if !(0.0..=most).contains(&amount) {
                    return Err(format!("{field}: {amount} is outside [0, {most}]"));
                }
                let component = Component {
                    amount,
                    color: *self.colors.get(),
                };
                let m = self.materials.get_mut();
                *match keyword {
                    "rd" => &mut m.rd,
                    "td" => &mut m.td,
                    _ => &mut m.ed,
                } = component;
            }
            "rs" | "ts" => {
                let (field, rough) = if keyword == "rs" {
                    ("rho_s", "alpha_r")
                } else {
                    ("tau_s", "alpha_t")
                };
                arity(args, 2, 2, &format!("{keyword} {field} {rough}"))?;
                let amount = number(args[0], field)?;
                let roughness = number(args[1], rough)?;
                if !(0.0..=1.0).contains(&amount) {
                    return Err(format!("{field}: {amount} is outside [0, 1]"));
                }
                if roughness < 0.0 {
                    return Err(format!("{rough}: {roughness} is negative"));
                }
                let component = (
                    Component {
                        amount,
                        color: *self.colors.get(),
                    },
                    roughness,
                );
                let m = self.materials.get_mut();
                *if keyword == "rs" {
                    &mut m.rs
                } else {
                    &mut m.ts
                } = component;
            }
            "ir" => {
                arity(args, 2, 2, "ir n_real n_imag")?;
                let real = number(args[0], "n_real")?;
                if real <= 0.0 {
                    return Err(format!("n_real: {real} is not > 0"));
                }
                self.materials.get_mut().ir = Some((real, number(args[1], "n_imag")?));
            }
            "v" => self.vertices.select(args, "vertex")?,
            "p" => {
                arity(args, 3, 3, "p x y z")?;
                self.vertices.get_mut().p = vector(args, "p")?;
            }
            "n" => {
                arity(args, 3, 3, "n dx dy dz")?;
                self.vertices.get_mut().n = vector(args, "n")?;
            }
            _ => return Ok(false),
        }
        Ok(true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(named: &mut Named, line: &str) -> Result<bool, String> {
        let words: Vec<&str> = line.split_whitespace().collect();
        named.entity(words[0], &words[1..], &mut |w| panic!("{w}"))
    }

    #[test]
    fn contexts_are_named_copied_from_templates_and_reset_when_unnamed() {
        let mut named = Named::new();
        for line in [
            "c blue =",
            "cxy .15 .2",
            "m paint =",
            "rd .5",
            "c",
            "rs .04 0",
        ] {
            assert_eq!(run(&mut named, line), Ok(true), "{line}");
        }
        // rd took the blue current then, rs the neutral grey current later.
        let paint = *named.materials.get();
        assert_eq!(
            (paint.rd.color.x, paint.rs.0.color),
            (0.15, Chroma::NEUTRAL)
        );
        run(&mut named, "m gloss = paint").unwrap();
        run(&mut named, "rd .2").unwrap();
        assert_eq!(named.materials.get().rs.0.amount, 0.04);
        run(&mut named, "m paint").unwrap();
        assert_eq!(named.materials.get().rd.amount, 0.5);
        // The unnamed colour starts grey again each time it is selected.
        run(&mut named, "cxy .3 .5").unwrap();
        run(&mut named, "c").unwrap();
        assert_eq!(*named.colors.get(), Chroma::NEUTRAL);
        assert_eq!(run(&mut named, "f a b c"), Ok(false));
        assert!(
            run(&mut named, "c x = y z")
                .unwrap_err()
                .contains("NAME = TEMPLATE")
        );
        assert!(
            run(&mut named, "ed -1")
                .unwrap_err()
                .contains("epsilon_d: -1 is outside")
        );
    }
}
