#pragma once
// Everything `flexmbs reduce` writes about a body: the reduced basis turned into the SID data of
// `.sid.h5` (docs/sid.md): inertia invariants, stiffness, damping, geometric stiffening, marker
// nodes, contact surfaces and provenance.

#include <map>
#include <string>

#include "fem/assembly.h"
#include "fem/body_spec.h"
#include "fem/mesh.h"
#include "reduction/modal_basis.h"
#include "reduction/reduction_spec.h"
#include "reduction/sid_spec.h"
#include "sid/reduced_body.h"

namespace flexmbs::reduction {

/// What the SID data of a basis is computed from (views, not copies): the mesh, its matrices
/// and the mass matrix kind they were assembled with, and the body file's `sid:` section.
struct SidSource {
  const fem::Mesh& mesh;
  const fem::SystemMatrices& system;
  fem::MassMatrixKind mass_matrix;
  const SidSpec& sid;
};

/// The SID data of `basis` (docs/sid.md): refmod, invariants (from the consistent mass matrix,
/// assembled here if `mass_matrix` is lumped), damping, geometric stiffening (if the spec asks),
/// marker nodes, contact surfaces, the basis and the mesh. Name and provenance are left to the
/// caller (ReductionProvenance). Throws InputError for markers or contact surfaces the mesh
/// cannot give (sid_nodes.h, contact_surface.h) and per-mode damping ratios of the wrong count.
sid::ReducedBody BuildReducedBody(const SidSource& source, const ReducedBasis& basis);
/// The same from a FeModel of `mesh`, assembled or known by its products only (the distributed
/// path of `reduce`: the invariants then come from products with ModelOperators::
/// consistent_mass(), the stiffening's static solves from ModelOperators::SolveFixed).
/// `mass_matrix`: the kind of the model's M.
sid::ReducedBody BuildReducedBody(const fem::Mesh& mesh, const FeModel& model, fem::MassMatrixKind mass_matrix,
                                  const SidSpec& sid, const ReducedBasis& basis);

/// The provenance of a body reduced from `body` (docs/sid.md): files and their SHA-256, mesh
/// counts, materials, reduction method and settings, eigensolver, largest residual. Throws
/// InputError if the geometry file cannot be read.
std::map<std::string, std::string> ReductionProvenance(const fem::BodySpec& body, const ReductionSpec& reduction,
                                                       const SidSpec& sid, const fem::Mesh& mesh,
                                                       const ReducedBasis& basis);

}  // namespace flexmbs::reduction
