//! Light a solution counts twice: on faces lying on other faces in their plane
//! (`radiosity/overlap.rs`), lit on the same side. Each face of such a pair takes the light
//! that arrives over their shared area, where a ray would have lit only one of them.

use super::solution::Solution;
use super::system::RadiositySystem;
use crate::radiosity::{PatchId, Side};
use std::collections::{HashMap, HashSet};

/// What a solution counts twice on overlapping faces.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CountedTwice {
    /// Root patches in an overlapping pair that both take light on one side.
    pub patches: usize,
    /// The area those pairs share, scene units².
    pub area: f64,
    /// The light arriving on the shared area that is counted a second time, W (luminance).
    pub power: f64,
    /// The light arriving on all surfaces, counted twice included, W (luminance).
    pub received: f64,
}

impl Solution {
    /// The light `system`'s overlapping faces take twice in this solution: per pair, over
    /// the area shared, the smaller of the two faces' mean irradiance on each side (the side
    /// facing the same way for both), both sides summed. Faces where solids touch are dark
    /// on the sides facing into the solids, and count nothing.
    pub fn light_counted_twice(&self, system: &RadiositySystem) -> CountedTwice {
        let received = (0..system.len())
            .map(|k| self.irradiance[k].luminance() * system.area[k] * system.coverage[k])
            .sum();
        if system.overlaps.is_empty() {
            return CountedTwice {
                received,
                ..CountedTwice::default()
            };
        }
        // The mean irradiance (luminance) of each side of the roots in a pair, over its leaves.
        let mut sides: HashMap<PatchId, [(f64, f64); 2]> = HashMap::new();
        for o in &system.overlaps {
            sides.insert(o.first, [(0.0, 0.0); 2]);
            sides.insert(o.second, [(0.0, 0.0); 2]);
        }
        for (k, element) in system.elements.iter().enumerate() {
            let mut root = element.patch;
            while let Some(parent) = system.mesh.patch(root).parent {
                root = parent;
            }
            if let Some(side) = sides.get_mut(&root) {
                let area = system.area[k] * system.coverage[k];
                let s = &mut side[element.side.index()];
                s.0 += self.irradiance[k].luminance() * area;
                s.1 += area;
            }
        }
        let mean = |root: PatchId, side: Side| {
            let (sum, area) = sides[&root][side.index()];
            if area > 0.0 { sum / area } else { 0.0 }
        };
        let mut counted = CountedTwice {
            received,
            ..CountedTwice::default()
        };
        let mut lit_twice = HashSet::new();
        for o in &system.overlaps {
            let power: f64 = Side::BOTH
                .into_iter()
                .map(|side| {
                    let other = if o.same_facing { side } else { side.other() };
                    mean(o.first, side).min(mean(o.second, other)) * o.area
                })
                .sum();
            if power > 0.0 {
                lit_twice.extend([o.first, o.second]);
                counted.area += o.area;
                counted.power += power;
            }
        }
        counted.patches = lit_twice.len();
        counted
    }
}
