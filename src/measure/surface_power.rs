//! Power per reported surface, the way every light solver hands it on: incident, absorbed,
//! emitted and reflected power per entry of a [`SurfaceTable`], plus the scene-wide emission
//! of lights that are not surfaces and the power that left the scene.

use super::surfaces::SurfaceTable;
use crate::color::Rgb64;
use serde::{Deserialize, Serialize};

/// The power balance of one surface, W per channel.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PowerBalance {
    /// Power arriving on either side.
    pub incident: Rgb64,
    /// The part of `incident` that came straight from a light or an emitting surface,
    /// without a reflection on its way, when the solver tells it apart.
    pub direct: Option<Rgb64>,
    /// Power absorbed.
    pub absorbed: Rgb64,
    /// Power emitted by the surface itself.
    pub emitted: Rgb64,
    /// Power reflected or transmitted.
    pub reflected: Rgb64,
}

/// Scene-wide power balance, W per channel.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Totals {
    /// Power emitted by all lights and emissive surfaces.
    pub emitted_power: Rgb64,
    /// Power absorbed by all surfaces.
    pub absorbed_power: Rgb64,
    /// Power that left the scene (zero in a closed scene).
    pub escaped_power: Rgb64,
}

/// Power per entry of a surface table plus the scene-wide terms, W per channel.
#[derive(Clone, Debug)]
pub struct SurfacePower {
    table: SurfaceTable,
    balances: Vec<PowerBalance>,
    /// Per entry, the standard error of its incident power (Monte Carlo solvers only).
    standard_errors: Option<Vec<Option<Rgb64>>>,
    /// The standard errors of the incident power of all entries together and of its indirect
    /// part (Monte Carlo solvers only).
    total_standard_errors: Option<[Rgb64; 2]>,
    light_emission: Rgb64,
    escaped: Rgb64,
}

impl SurfacePower {
    /// All zeros for the entries of `table`.
    pub fn new(table: SurfaceTable) -> Self {
        SurfacePower {
            balances: vec![PowerBalance::default(); table.len()],
            standard_errors: None,
            total_standard_errors: None,
            table,
            light_emission: Rgb64::BLACK,
            escaped: Rgb64::BLACK,
        }
    }

    /// The entries.
    pub fn table(&self) -> &SurfaceTable {
        &self.table
    }

    /// The balance of entry `entry` (an index from [`SurfaceTable::entry`]) to add to.
    pub fn balance_mut(&mut self, entry: usize) -> &mut PowerBalance {
        &mut self.balances[entry]
    }

    /// The balance of entry `entry`.
    pub fn balance(&self, entry: usize) -> &PowerBalance {
        &self.balances[entry]
    }

    /// Sets the standard error of every entry's incident power, W per channel, in entry
    /// order (for solvers that estimate by Monte Carlo; `None` for an entry not estimated so).
    pub fn set_standard_errors(&mut self, errors: Vec<Option<Rgb64>>) {
        debug_assert_eq!(errors.len(), self.balances.len());
        self.standard_errors = Some(errors);
    }

    /// Sets the standard errors of the incident power summed over all entries and of its
    /// indirect part (the sum less the direct power), W per channel.
    pub fn set_total_standard_errors(&mut self, incident: Rgb64, indirect: Rgb64) {
        self.total_standard_errors = Some([incident, indirect]);
    }

    /// The standard errors of the incident power summed over all entries and of its
    /// indirect part, W per channel, when the solver gave them.
    pub fn total_standard_errors(&self) -> Option<[Rgb64; 2]> {
        self.total_standard_errors
    }

    /// The standard error of entry `entry`'s incident power, W per channel, when the solver
    /// gave one.
    pub fn standard_error(&self, entry: usize) -> Option<Rgb64> {
        self.standard_errors.as_ref().and_then(|e| e[entry])
    }

    /// Adds power (W) emitted by lights that are not surfaces (point, spot, directional, sky).
    pub fn add_light_emission(&mut self, power: Rgb64) {
        self.light_emission += power;
    }

    /// Adds power (W) that left the scene.
    pub fn add_escaped(&mut self, power: Rgb64) {
        self.escaped += power;
    }

    /// Adds the power `lights` (W) of the lights that are not surfaces, and counts all that
    /// is emitted and not absorbed as escaped: the balance of solvers that measure what
    /// surfaces receive, not what leaves the scene (radiosity, the surface tracer).
    pub fn balance_with_lights(&mut self, lights: Rgb64) {
        self.add_light_emission(lights);
        let totals = self.totals();
        self.add_escaped((totals.emitted_power - totals.absorbed_power).map(|p| p.max(0.0)));
    }

    /// Multiplies every power by `factor` (e.g. to scale a partial run to its full size).
    pub fn scale(&mut self, factor: f64) {
        for b in &mut self.balances {
            b.incident *= factor;
            b.direct = b.direct.map(|d| d * factor);
            b.absorbed *= factor;
            b.emitted *= factor;
            b.reflected *= factor;
        }
        if let Some(errors) = &mut self.standard_errors {
            errors.iter_mut().flatten().for_each(|e| *e *= factor);
        }
        if let Some(errors) = &mut self.total_standard_errors {
            errors.iter_mut().for_each(|e| *e *= factor);
        }
        self.light_emission *= factor;
        self.escaped *= factor;
    }

    /// Scene-wide totals: emission of surfaces and lights, absorption, escape.
    pub fn totals(&self) -> Totals {
        let surface_emission = self
            .balances
            .iter()
            .fold(Rgb64::BLACK, |a, b| a + b.emitted);
        Totals {
            emitted_power: surface_emission + self.light_emission,
            absorbed_power: self
                .balances
                .iter()
                .fold(Rgb64::BLACK, |a, b| a + b.absorbed),
            escaped_power: self.escaped,
        }
    }
}
