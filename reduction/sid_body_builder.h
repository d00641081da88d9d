#pragma once
// Everything `flexmbs reduce` writes about a body: the reduced basis turned into the SID data of
// `.sid.h5` (docs/sid.md): inertia invariants, stiffness, damping, geometric stiffening, marker
// nodes, contact surfaces and provenance.

#include "fem/assembly.h"
#include "fem/body_spec.h"
#include "fem/mesh.h"
#include "reduction/modal_basis.h"
#include "reduction/reduction_spec.h"
#include "reduction/sid_spec.h"
#include "sid/reduced_body.h"

namespace flexmbs::reduction {

/// What a reduced body is made from: the body file's FE, reduction and SID sections, the mesh
/// and its matrices (views, not copies).
struct SidSource {
  const fem::BodySpec& body;
  const ReductionSpec& reduction;
  const SidSpec& sid;
  const fem::Mesh& mesh;
  const fem::SystemMatrices& system;
};

/// The SID data of `basis` (docs/sid.md). The mass properties come from the consistent mass
/// matrix (source.system.mass must be consistent: the invariants need it). Throws InputError
/// for a lumped mass matrix, markers or contact surfaces the mesh cannot give (sid_nodes.h,
/// contact_surface.h), per-mode damping ratios of the wrong count.
sid::ReducedBody BuildReducedBody(const SidSource& source, const ReducedBasis& basis);

}  // namespace flexmbs::reduction
