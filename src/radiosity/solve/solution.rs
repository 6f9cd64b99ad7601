//! A radiosity solution: radiosity and irradiance per leaf patch, the convergence history
//! and the time spent per phase.

use super::system::RadiositySystem;
use crate::report::{Rgb64, luminance};

/// Wall-clock seconds per phase of a solve.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PhaseTimes {
    /// Meshing, material averages and light links.
    pub setup: f64,
    /// Form factors and visibility (matrix assembly, or the columns of the shots).
    pub form_factors: f64,
    /// The iterations themselves (without form factors).
    pub iterations: f64,
}

/// The result of a radiosity solver, per leaf of its [`RadiositySystem`].
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// Solver name (`matrix-jacobi`, `matrix-gauss-seidel`, `progressive`).
    pub solver: String,
    /// Radiosity `B` per leaf, W·m⁻² (front side).
    pub radiosity: Vec<Rgb64>,
    /// Irradiance `H` gathered per leaf (light links included), W·m⁻².
    pub irradiance: Vec<Rgb64>,
    /// Ambient radiosity estimate of the light not yet distributed (progressive refinement,
    /// seed 004), W·m⁻²; zero for the matrix solvers. Display adds `ρ_i × ambient`.
    pub ambient: Rgb64,
    /// Per iteration (sweep or shot): the residual or unshot power as a fraction of the
    /// source power ([`power_fraction`]).
    pub convergence: Vec<f64>,
    /// True when the last convergence value is at or below the tolerance.
    pub converged: bool,
    /// True when Ctrl-C stopped the solve; the state reached is kept.
    pub interrupted: bool,
    /// Time per phase.
    pub seconds: PhaseTimes,
}

impl Solution {
    /// Iterations done (sweeps or shots).
    pub fn iterations(&self) -> usize {
        self.convergence.len()
    }

    /// The radiosity to display per leaf: `B_i + ρ_i × ambient`, W·m⁻².
    pub fn display_radiosity(&self, system: &RadiositySystem) -> Vec<Rgb64> {
        self.radiosity
            .iter()
            .zip(&system.reflectance)
            .map(|(b, r)| std::array::from_fn(|c| b[c] + r[c] * self.ambient[c]))
            .collect()
    }

    /// The initial state: radiosity = source term, irradiance = light-link irradiance.
    pub(super) fn start(system: &RadiositySystem, solver: &str) -> Solution {
        Solution {
            solver: solver.to_string(),
            radiosity: (0..system.len()).map(|k| system.source(k)).collect(),
            irradiance: system.light_irradiance.clone(),
            ambient: [0.0; 3],
            convergence: Vec::new(),
            converged: false,
            interrupted: false,
            seconds: PhaseTimes {
                setup: system.setup_seconds,
                ..PhaseTimes::default()
            },
        }
    }
}

/// `Σ_i A_i Y(|d_i|) / Σ_i A_i Y(S_i)`: a per-leaf radiosity change or unshot radiosity `d`
/// as a fraction of the source power (Y = luminance, `S` the source term). 0 when the scene
/// has no source.
pub fn power_fraction(system: &RadiositySystem, d: &[Rgb64]) -> f64 {
    let source = source_power(system);
    if source <= 0.0 {
        return 0.0;
    }
    let change: f64 = d
        .iter()
        .zip(&system.area)
        .map(|(v, a)| a * luminance(v.map(f64::abs)))
        .sum();
    change / source
}

/// Luminance of the source power `Σ_i A_i S_i`, W.
pub fn source_power(system: &RadiositySystem) -> f64 {
    (0..system.len())
        .map(|k| system.area[k] * luminance(system.source(k)))
        .sum()
}
