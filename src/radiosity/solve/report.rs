//! The per-object light report of a radiosity solution, in the schema every solver shares
//! ([`crate::report::Report`]).
//!
//! Per leaf `i` with area `A_i`, irradiance `H_i`, emitted radiosity `E_i` and reflectance
//! `ρ_i`: incident power `A_i H_i`, absorbed `(1 − ρ_i) A_i H_i`, emitted `A_i E_i`,
//! reflected `ρ_i A_i H_i`, summed per report entry. Scene-wide, the point, spot and
//! directional lights count with the power they send into the mesh (`Σ A_i H_light,i`), and
//! the escaped power is what is emitted but not absorbed by any patch (light leaving an open
//! scene, plus the small imbalance of the discretisation).

use super::solution::{Solution, source_power};
use super::system::RadiositySystem;
use crate::report::{PowerAccumulator, Report, Stats, SurfaceTable};
use serde_json::json;

/// The report of `solution` on `system` for scene `scene`.
pub fn radiosity_report(system: &RadiositySystem, solution: &Solution, scene: &str) -> Report {
    let world = system.world();
    let mut acc = PowerAccumulator::new(SurfaceTable::new(&world.scene, &world.geometry));
    let mut light_power = [0.0; 3];
    for k in 0..system.len() {
        let patch = system.patch(k);
        let entry = acc.table().entry(patch.object, patch.face);
        let (a, h, e, r) = (
            system.area[k],
            solution.irradiance[k],
            system.emission[k],
            system.reflectance[k],
        );
        let balance = acc.balance_mut(entry);
        for c in 0..3 {
            balance.incident[c] += a * h[c];
            balance.absorbed[c] += (1.0 - r[c]) * a * h[c];
            balance.emitted[c] += a * e[c];
            balance.reflected[c] += r[c] * a * h[c];
            light_power[c] += a * system.light_irradiance[k][c];
        }
    }
    acc.add_light_emission(light_power);
    let totals = acc.totals();
    let escaped = std::array::from_fn(|c| totals.emitted_power[c] - totals.absorbed_power[c]);
    acc.add_escaped(escaped);
    let mut stats = Stats {
        seconds: solution.seconds.setup
            + solution.seconds.form_factors
            + solution.seconds.iterations,
        rays: system.visibility_ray_count(),
        ..Stats::default()
    };
    let s = &solution.seconds;
    let extra = [
        ("patches", json!(system.len())),
        ("patch_nodes", json!(system.mesh.len())),
        ("form_factors", json!(system.form_factor_count())),
        ("visibility_rays", json!(system.visibility_ray_count())),
        ("iterations", json!(solution.iterations())),
        ("converged", json!(solution.converged)),
        ("interrupted", json!(solution.interrupted)),
        ("convergence", json!(solution.convergence)),
        ("source_power", json!(source_power(system))),
        ("unlinked_sky_lights", json!(system.unlinked_sky_lights)),
        ("seconds_setup", json!(s.setup)),
        ("seconds_form_factors", json!(s.form_factors)),
        ("seconds_iterations", json!(s.iterations)),
    ];
    for (key, value) in extra {
        stats.extra.insert(key.to_string(), value);
    }
    acc.report(scene, &solution.solver, stats)
}
