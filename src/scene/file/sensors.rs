//! `[[sensors]]` entries: measuring points, alone or in grids.

use super::error::SceneError;
use super::fields::Table;
use super::format::SensorEntry;
use crate::scene::{MAX_SENSORS, Sensor};
use glam::Vec3;

/// The sensors of entry `index` (one, or the points of a grid), added to `sensors`.
pub(super) fn build_sensors(
    t: &Table<'_>,
    index: usize,
    e: &SensorEntry,
    sensors: &mut Vec<Sensor>,
) -> Result<(), SceneError> {
    let position = t.required_vec3("position", e.position.as_ref(), "a sensor")?;
    let normal = match &e.normal {
        Some(n) => t
            .required_vec3("normal", Some(n), "a sensor")?
            .try_normalize()
            .ok_or_else(|| t.error(n.span(), "normal", "must not be zero"))?,
        None => Vec3::Y,
    };
    let name = e.name.clone().unwrap_or_else(|| format!("sensor-{index}"));
    let edge_u = t.vec3("edge_u", e.edge_u.as_ref())?;
    let edge_v = t.vec3("edge_v", e.edge_v.as_ref())?;
    let grid = match (edge_u, edge_v, &e.count) {
        (None, None, None) => None,
        (Some(u), Some(v), Some(count)) => Some(((u, v), *count.get_ref(), count.span())),
        _ => {
            return Err(t.table_error(
                "a grid of sensors needs all of edge_u, edge_v and count (a single sensor none)",
            ));
        }
    };
    match grid {
        None => sensors.push(Sensor {
            name,
            position,
            normal,
        }),
        Some((edges, [nu, nv], span)) => {
            let points = nu as usize * nv as usize;
            if points == 0 || sensors.len() + points > MAX_SENSORS {
                return Err(t.error(
                    span,
                    "count",
                    format!("a grid needs 1 to {MAX_SENSORS} points in all sensors of the scene"),
                ));
            }
            sensors.extend(Sensor::grid(&name, position, edges, (nu, nv), normal));
        }
    }
    if sensors.len() > MAX_SENSORS {
        return Err(t.table_error(format!("more than {MAX_SENSORS} sensors")));
    }
    Ok(())
}
