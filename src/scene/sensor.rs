//! Point sensors: places where the light is measured without being part of the scene. A
//! sensor is a point with a unit normal; it reads the irradiance arriving on the side its
//! normal faces (W·m⁻², lux when lengths are metres), the way a cosine-corrected
//! illuminance meter does. Sensors block no light and reflect none.

use glam::Vec3;

/// Most sensors a scene may hold (a grid of 1000 × 1000 points).
pub const MAX_SENSORS: usize = 1_000_000;

/// One measuring point.
#[derive(Clone, Debug, PartialEq)]
pub struct Sensor {
    /// Name in reports (`desk[2,3]` for a point of a grid).
    pub name: String,
    /// Where it is, scene units.
    pub position: Vec3,
    /// Unit normal of the side that receives light.
    pub normal: Vec3,
}

impl Sensor {
    /// The sensors of a grid named `name`: one at the centre of each of the `nu × nv` cells
    /// of the parallelogram `origin + s·edge_u + t·edge_v` (`s, t ∈ [0, 1]`), named
    /// `name[i,j]` with `i` along `edge_u` and `j` along `edge_v`, all with the unit normal
    /// `normal`.
    pub fn grid(
        name: &str,
        origin: Vec3,
        (edge_u, edge_v): (Vec3, Vec3),
        (nu, nv): (u32, u32),
        normal: Vec3,
    ) -> Vec<Sensor> {
        let mut sensors = Vec::with_capacity(nu as usize * nv as usize);
        for i in 0..nu {
            for j in 0..nv {
                let s = (i as f32 + 0.5) / nu as f32;
                let t = (j as f32 + 0.5) / nv as f32;
                sensors.push(Sensor {
                    name: format!("{name}[{i},{j}]"),
                    position: origin + edge_u * s + edge_v * t,
                    normal,
                });
            }
        }
        sensors
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grid_has_a_sensor_at_the_centre_of_every_cell() {
        let g = Sensor::grid(
            "desk",
            Vec3::ZERO,
            (Vec3::X * 2.0, Vec3::Z * 4.0),
            (2, 4),
            Vec3::Y,
        );
        assert_eq!(g.len(), 8);
        assert_eq!(g[0].name, "desk[0,0]");
        assert_eq!(g[0].position, Vec3::new(0.5, 0.0, 0.5));
        assert_eq!(g[7].name, "desk[1,3]");
        assert_eq!(g[7].position, Vec3::new(1.5, 0.0, 3.5));
    }
}
