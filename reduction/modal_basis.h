#pragma once

// The reduced basis of a flexible body (the result type shared by every reduction) and the two
// modal bases: free-free normal modes and fixed-interface normal modes.
//
// A basis Phi (num_dofs x n) approximates the FE displacement as u = Phi q. Its reduced
// matrices are K_r = Phi^T K Phi and M_r = Phi^T M Phi (Rayleigh-Ritz; Craig & Kurdila,
// "Fundamentals of Structural Dynamics", 2nd ed. 2006, on the Rayleigh-Ritz method).

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "eigensolvers/eigensolver.h"
#include "reduction/interface_coupling.h"
#include "eigensolvers/model_operators.h"

namespace flexmbs::reduction {

/// What a column of a basis is.
enum class ModeKind {
  kRigid,             ///< a rigid-body mode (zero strain energy)
  kNormal,            ///< an eigenvector of K phi = lambda M phi (of the body as held, or of a reduced system)
  kConstraint,        ///< unit motion of one boundary DOF, interior statically condensed (Craig-Bampton)
  kStaticCorrection,  ///< the static response to a named load (residual / attachment mode)
};

/// "rigid", "normal", "constraint", "static_correction": the names used in files.
std::string_view ModeKindName(ModeKind kind);
/// The kind named `name` (see ModeKindName), or nothing.
std::optional<ModeKind> ModeKindFromName(std::string_view name);

/// Number of columns of each kind.
struct ModeCounts {
  Eigen::Index rigid = 0;
  Eigen::Index normal = 0;
  Eigen::Index constraint = 0;
  Eigen::Index static_correction = 0;
  Eigen::Index total() const { return rigid + normal + constraint + static_correction; }
  bool operator==(const ModeCounts&) const = default;
};
/// "6 rigid, 10 normal, 0 constraint, 2 static_correction".
std::string FormatModeCounts(const ModeCounts& counts);

/// The FE model a basis is built from (views, not copies): K [N/m] and M [kg], symmetric, DOF
/// 3 n + i (fem::SystemMatrices), and the node positions p_BoN_B [m] (3 x n). K and M are either
/// assembled in this process (full storage) or known by their products and static solves only
/// (ModelOperators: the distributed path of `reduce`, where no rank holds them whole). The
/// builders of modal bases, correction modes, orthonormalised bases and the SID data take
/// either; Craig-Bampton, the held body's matrices (interior_problem.h) and the eigensolvers
/// need them assembled.
class FeModel {
 public:
  /// K and M assembled in this process.
  FeModel(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M, const Eigen::Matrix3Xd& p_BoN_B)
      : nodes(p_BoN_B), K_(K), M_(M) {}
  /// K and M known by `operators` only.
  FeModel(const eigensolvers::ModelOperators& operators, const Eigen::Matrix3Xd& p_BoN_B) : nodes(p_BoN_B), operators_(&operators) {}

  const Eigen::Matrix3Xd& nodes;

  /// Products with K and M (either way).
  const eigensolvers::SymmetricOperator& stiffness() const { return operators_ ? operators_->stiffness() : *K_; }
  const eigensolvers::SymmetricOperator& mass() const { return operators_ ? operators_->mass() : *M_; }
  /// The number of rows of K (3 x the number of nodes if the model is valid: ValidateModel).
  Eigen::Index num_dofs() const { return stiffness().rows(); }
  /// Whether K and M are assembled here; K() and M() are those matrices (InternalError if not).
  bool assembled() const { return operators_ == nullptr; }
  const Eigen::SparseMatrix<double>& K() const;
  const Eigen::SparseMatrix<double>& M() const;
  /// The operators of a model that is not assembled here; null if it is.
  const eigensolvers::ModelOperators* operators() const { return operators_; }

 private:
  std::optional<eigensolvers::SparseOperator> K_, M_;
  const eigensolvers::ModelOperators* operators_ = nullptr;
};

/// Throws InputError unless K and M are square, of size 3 x (number of nodes), and non-empty.
void ValidateModel(const FeModel& model);

struct HeldFactorization;  // interior_problem.h

/// The eigen-solve behind a basis's normal modes in brief: EigenSolution's accounting, for
/// reports (`flexmbs reduce --json`, `seconds.eigensolver`). Where the builder factorised the
/// held body once and the eigensolver used that factorisation (SolveHeldModes), it is counted
/// here as the solve's factorisation (its time in `seconds` and `factorization_seconds`).
struct EigensolverSummary {
  double seconds = 0.0;                ///< wall-clock time of the eigen-solve [s]
  double factorization_seconds = 0.0;  ///< of which: factorising K - sigma M [s]
  double sturm_seconds = 0.0;          ///< of which: Sturm counts (LDL^T factorisations) [s]
  double krylov_seconds = 0.0;         ///< of which: Krylov runs and Rayleigh-Ritz [s]
  int factorizations = 0;              ///< numeric sparse factorisations (Sturm counts included)
  int operator_applications = 0;       ///< solves with the factorisation, one per right-hand side
  int krylov_runs = 0;                 ///< Krylov (Lanczos / Krylov-Schur) runs
  int restarts = 0;                    ///< restarts over all runs
  eigensolvers::MissedModeCheck missed_mode_check = eigensolvers::MissedModeCheck::kNone;  ///< the check made against missed modes
  std::string factorization;  ///< slepc: "mumps" or "substructured" (EigenSolution::factorization)
  int lanczos_block_size = 0;  ///< spectra: columns per Lanczos solve (EigenSolution::lanczos_block_size)
};

/// The summary of `solution` (its fields of the same names).
EigensolverSummary SummarizeEigenSolution(const eigensolvers::EigenSolution& solution);

/// A reduced basis with its reduced matrices and what each column is.
struct ReducedBasis {
  /// "free_free_modal", "fixed_interface_modal", "craig_bampton",
  /// "craig_bampton_orthonormalized"; "+static_correction" appended when correction modes were added.
  std::string method;
  /// One line for people: how the basis was made and what its columns are.
  std::string description;
  /// num_dofs x n: one mode shape per column, DOF 3 node + axis [m per unit modal coordinate].
  Eigen::MatrixXd Phi;
  std::vector<ModeKind> kinds;     ///< per column
  std::vector<std::string> names;  ///< per column, unique: "rigid_tx", "normal_3", "constraint_tip_rx", ...
  Eigen::MatrixXd K_reduced;       ///< Phi^T K Phi [N/m scaled by the modal normalisation]
  Eigen::MatrixXd M_reduced;       ///< Phi^T M Phi
  /// Per column: the eigenfrequency [Hz] of rigid (0 or the computed round-off value) and normal
  /// modes; NaN for constraint and static correction modes.
  Eigen::VectorXd frequency_hz;
  /// Per column: relative residual of the eigenpair (EigenSolution) for rigid and normal modes
  /// that are eigenpairs of the model as held; NaN otherwise (constraint and correction modes,
  /// and the normal modes of a reduced system, which are Ritz vectors, not eigenvectors).
  Eigen::VectorXd relative_residuals;
  /// Per column: the round-off floor of that residual (EigenSolution::residual_floors); NaN otherwise.
  Eigen::VectorXd residual_floors;
  /// The supports and interfaces the basis was computed with (empty: free-free). Static
  /// correction modes are computed for the body held the same way.
  BoundaryConditions held_by;
  /// The eigensolver backend that computed the normal modes ("" if none was used).
  std::string eigensolver;
  /// How that eigen-solve went (unset if no eigensolver was used).
  std::optional<EigensolverSummary> eigensolver_summary;
  /// The Cholesky factor of the held body's K_oo that the builder made (Craig-Bampton;
  /// fixed-interface when the eigensolver used it, SharesHeldFactorization), for the static
  /// solves of the body held as `held_by` after the basis (AddStaticCorrectionModes,
  /// ComputeGeometricStiffening through SolveStaticResponses), which then do not factorise
  /// again. Null if none. Copies of the basis share it; it holds the factor's memory (nnz(L)
  /// doubles) until the last copy drops it (reset it when no static solve follows).
  std::shared_ptr<const HeldFactorization> held_factorization;
  /// Only for a transformed basis (OrthonormalizeBasis): Phi = Phi_original * original_transform,
  /// with the kinds and names of the original columns.
  std::vector<ModeKind> original_kinds;
  std::vector<std::string> original_names;
  Eigen::MatrixXd original_transform;

  Eigen::Index num_modes() const { return Phi.cols(); }
  ModeCounts Counts() const;
};

/// Sets basis->K_reduced and M_reduced from the full matrices: Phi^T K Phi and Phi^T M Phi
/// (symmetrised).
void ComputeReducedMatrices(const FeModel& model, ReducedBasis* basis);

/// The six rigid-body modes of the mesh (3 n x 6), M-orthonormal: unit translations along B's
/// axes scaled by 1 / sqrt(m), then unit rotations about the principal axes of inertia through
/// the centre of mass scaled by 1 / sqrt(J_k) (mutually M-orthogonal for the consistent mass,
/// from fem::MassPropertiesFromMassMatrix), cleaned by one Cholesky-QR pass in the M inner
/// product. Columns: translation x, y, z, rotation about principal axis 1, 2, 3 (ascending J).
Eigen::MatrixXd MOrthonormalRigidModes(const FeModel& model);

/// Which rigid-body modes a free-free basis carries.
enum class RigidModes {
  /// The six lowest eigenvectors as computed (rigid to the eigensolver's accuracy; any
  /// orthonormal basis of the rigid subspace, mixed translations and rotations).
  kComputed,
  /// MOrthonormalRigidModes, exactly rigid; the elastic modes are made exactly M-orthogonal to
  /// them and re-diagonalised by Rayleigh-Ritz (same subspace, residuals recomputed).
  kExact,
};

/// Options of a free-free modal basis.
struct FreeFreeOptions {
  /// The eigensolver settings. `num_modes` counts the ELASTIC modes: the lowest `num_modes`
  /// elastic modes, or with `max_frequency_hz` all elastic modes below it (num_modes then caps
  /// their number). The six rigid-body modes come on top.
  eigensolvers::EigenOptions eigen;
  RigidModes rigid_modes = RigidModes::kExact;
};

/// Free-free normal modes of an unsupported body: 6 rigid-body modes, then the elastic modes,
/// ascending, all M-orthonormal (M_reduced = I, K_reduced = diag(omega^2)). Repeated
/// frequencies are fine: their modes are any M-orthonormal basis of the eigenspace.
/// Throws a one-line InputError for: a bad model, no modes asked for, more elastic modes than
/// DOF - 6, a band with no elastic mode, a number of zero-frequency modes other than 6 (a
/// disconnected part or a mechanism), and the eigensolver's own errors (prefixed).
ReducedBasis FreeFreeModalBasis(const FeModel& model, const FreeFreeOptions& options, const eigensolvers::Eigensolver& solver);
/// The same from eigenpairs computed elsewhere (the distributed solve of `reduce`): `solution`
/// holds the pairs the solver would have returned for `options` (the six rigid-body modes
/// included, full length). Works on a model known by its products. Throws as above; with no
/// elastic mode in the band, without naming the lowest one (that needs another solve).
ReducedBasis FreeFreeModalBasis(const FeModel& model, const FreeFreeOptions& options, const eigensolvers::EigenSolution& solution);

/// Fixed-interface normal modes: the eigenmodes of the body with every support clamped and
/// every interface held (node-set and rigid interfaces: their node DOF fixed; averaging
/// interfaces: the marker held, W u = 0, the nodes free to deform). Solved in the interior
/// coordinates of BuildConstraintTransform, K_oo = G^T K G, M_oo = G^T M G (symmetric positive
/// definite), expanded to the full DOF: Phi = G phi_o. M-orthonormal; the residuals are those
/// of the constrained problem (the constraint forces are not residual). Where the solver shares
/// the held body's factorisation (SharesHeldFactorization), K_oo is factorised once for the
/// eigen-solve and kept in held_factorization for the static solves that follow.
/// `eigen`: the lowest num_modes, or all below max_frequency_hz (Craig & Bampton 1968;
/// Craig & Kurdila 2006, component-mode synthesis).
/// Throws a one-line InputError for: no interface or support, bad interfaces (see
/// BuildConstraintTransform), no modes asked for, more modes than interior DOF, conditions
/// that do not hold the body (a zero-frequency mode remains), a band with no modes.
ReducedBasis FixedInterfaceModalBasis(const FeModel& model, const BoundaryConditions& conditions,
                                      const eigensolvers::EigenOptions& eigen, const eigensolvers::Eigensolver& solver);
/// The same from the held body's eigenpairs computed elsewhere (the distributed solve of
/// `reduce`), for conditions that clamp whole node DOF (ClampedDofs; else InputError):
/// `solution` holds the pairs of K_oo, M_oo that `eigen` asks for, with the modes full length
/// and zero at the clamped DOF, and their residuals. Works on a model known by its products;
/// no factorisation is made or kept.
ReducedBasis FixedInterfaceModalBasis(const FeModel& model, const BoundaryConditions& conditions,
                                      const eigensolvers::EigenOptions& eigen, const eigensolvers::EigenSolution& solution);

}  // namespace flexmbs::reduction
