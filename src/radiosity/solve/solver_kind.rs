//! The radiosity solvers by name: what a caller picks, what a solution records, and what
//! each one's convergence history measures.

use crate::radiosity::MeshSize;

/// A radiosity solver.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum SolverKind {
    /// The full form-factor matrix, iterated by Jacobi or Gauss-Seidel sweeps.
    Matrix,
    /// Progressive refinement: the patch with the most unshot power shoots it.
    Progressive,
    /// Hierarchical radiosity: links between quadtree nodes, refined by an oracle.
    Hierarchical,
    /// Hierarchical shooting: progressive refinement over links refined by an oracle.
    HierarchicalShooting,
}

crate::choice::named_values!(SolverKind {
    SolverKind::Matrix = "matrix", "Radiosity: full form-factor matrix, Jacobi or Gauss-Seidel";
    SolverKind::Progressive = "progressive", "Radiosity: progressive refinement (shoot the patch with the most unshot power)";
    SolverKind::Hierarchical = "hierarchical", "Hierarchical radiosity: links between quadtree nodes, refined by an oracle";
    SolverKind::HierarchicalShooting = "hierarchical-shooting", "Hierarchical shooting: progressive refinement, each root side's unshot light sent over links refined by an oracle";
});

impl SolverKind {
    /// True for the solvers that refine their own mesh (hierarchical radiosity and
    /// hierarchical shooting).
    pub fn is_hierarchical(self) -> bool {
        matches!(
            self,
            SolverKind::Hierarchical | SolverKind::HierarchicalShooting
        )
    }

    /// The initial mesh when none is asked for: the root patches for the hierarchical
    /// solvers, which refine where the light needs it; 2³ × 2³ patches per face for the
    /// others.
    pub fn default_mesh_size(self) -> MeshSize {
        MeshSize::Levels(if self.is_hierarchical() { 0 } else { 3 })
    }

    /// What the convergence history measures: the `residual` of a sweep, the `unshot` power
    /// after a shot, or the `change` of a hierarchical round.
    pub fn convergence_measure(self) -> &'static str {
        match self {
            SolverKind::Matrix => "residual",
            SolverKind::Progressive | SolverKind::HierarchicalShooting => "unshot",
            SolverKind::Hierarchical => "change",
        }
    }
}
