//! A solver-neutral accumulator of per-surface power: any solver adds incident, absorbed,
//! emitted and reflected power per report entry (and scene-wide emission by non-surface
//! lights and escaped power), then turns it into a [`Report`].

use super::schema::{ObjectReport, PowerBalance, Report, Rgb64, Stats, Totals, Units, add};
use super::surfaces::SurfaceTable;

/// Power per report entry plus the scene-wide terms, W per channel.
#[derive(Clone, Debug)]
pub struct PowerAccumulator {
    table: SurfaceTable,
    balances: Vec<PowerBalance>,
    light_emission: Rgb64,
    escaped: Rgb64,
}

impl PowerAccumulator {
    /// All zeros for the entries of `table`.
    pub fn new(table: SurfaceTable) -> Self {
        PowerAccumulator {
            balances: vec![PowerBalance::default(); table.len()],
            table,
            light_emission: [0.0; 3],
            escaped: [0.0; 3],
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

    /// Adds power (W) emitted by lights that are not surfaces (point, spot, directional, sky).
    pub fn add_light_emission(&mut self, power: Rgb64) {
        self.light_emission = add(self.light_emission, power);
    }

    /// Adds power (W) that left the scene.
    pub fn add_escaped(&mut self, power: Rgb64) {
        self.escaped = add(self.escaped, power);
    }

    /// Multiplies every power by `factor` (e.g. to scale a partial run to its full size).
    pub fn scale(&mut self, factor: f64) {
        let s = |v: &mut Rgb64| *v = v.map(|c| c * factor);
        for b in &mut self.balances {
            s(&mut b.incident);
            s(&mut b.absorbed);
            s(&mut b.emitted);
            s(&mut b.reflected);
        }
        s(&mut self.light_emission);
        s(&mut self.escaped);
    }

    /// Scene-wide totals: emission of surfaces and lights, absorption, escape.
    pub fn totals(&self) -> Totals {
        let surface_emission = self
            .balances
            .iter()
            .fold([0.0; 3], |a, b| add(a, b.emitted));
        Totals {
            emitted_power: add(surface_emission, self.light_emission),
            absorbed_power: self
                .balances
                .iter()
                .fold([0.0; 3], |a, b| add(a, b.absorbed)),
            escaped_power: self.escaped,
        }
    }

    /// The report of scene `scene` solved by `solver`, in metres and watts.
    pub fn report(&self, scene: &str, solver: &str, stats: Stats) -> Report {
        let objects = self
            .table
            .surfaces()
            .iter()
            .zip(&self.balances)
            .map(|(s, b)| ObjectReport::new(s.name.clone(), s.face, s.area, b))
            .collect();
        Report {
            scene: scene.to_string(),
            solver: solver.to_string(),
            units: Units::default(),
            stats,
            objects,
            totals: self.totals(),
        }
    }
}
