#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "eigensolvers/model_operators.h"

namespace flexmbs::eigensolvers {

class ShiftedFactorization;

/// How Solve makes sure no mode below the last returned one was missed (Lanczos from a single
/// start vector can miss a copy of a repeated eigenvalue).
enum class MissedModeCheck {
  kNone,
  /// Sylvester's law of inertia: the number of negative pivots of K - c M = L D L^T is the
  /// number of eigenvalues below the cut c. Rigorous; a simplicial LDL^T (no pivoting), 5-20x
  /// the cost of the supernodal Cholesky on bulky 3D meshes.
  kSturmCount,
  /// One more Lanczos run from a new random start vector, deflated against every mode found,
  /// must find nothing below the cut (a missed mode has, with probability one, a component
  /// along that start vector). Costs a few tens of single-vector solves.
  kDeflatedLanczos,
  /// Block Lanczos from 8 random vectors, deflated against every mode found, with an a
  /// posteriori bound on the probability that a mode below the cut hides from them (at most
  /// 1e-15; eigensolvers/block_krylov_check.h, docs/reduction.md). Each step solves 8 columns at
  /// once; falls back to kDeflatedLanczos if the bound does not get there in 16 steps.
  kBlockKrylov,
  /// kSturmCount when the factorisation is cheap (<= 5e9 flops), else kBlockKrylov.
  kAuto,
};

/// "none", "sturm_count", "deflated_lanczos", "block_krylov", "auto": the names used in reports.
std::string_view MissedModeCheckName(MissedModeCheck check);

/// How the slepc backend factorises K - sigma M on more than one rank.
enum class DistributedFactorization {
  /// Substructuring where it applies (K - sigma M positive definite) and its interface has at
  /// most a set number of rows (eigensolvers/distributed/slepc_shifted_matrix.cc), else MUMPS.
  kAuto,
  /// MUMPS's own distributed Cholesky (L D L^T).
  kMumps,
  /// eigensolvers/distributed/substructured_factor.h wherever K - sigma M is positive definite.
  kSubstructured,
};

/// What to compute for the generalized symmetric eigenproblem K phi = lambda M phi
/// (K symmetric positive semi-definite [N/m], M symmetric positive definite [kg]).
struct EigenOptions {
  /// The lowest `num_modes` eigenpairs. With `max_frequency_hz` set, an upper limit on the
  /// number returned (0 = no limit): the lowest min(num_modes, modes in band) are returned.
  int num_modes = 0;
  /// If > 0: all eigenpairs with frequency below this [Hz], i.e. lambda < (2 pi f)^2, checked
  /// by `check_missed_modes` at lambda_max (a Sturm count gives the band's size up front).
  double max_frequency_hz = 0.0;
  /// Shift of the spectral transformation, signed frequency [Hz]: sigma = sign(f) (2 pi f)^2.
  /// A negative value (sigma < 0) makes K - sigma M positive definite for free-free bodies.
  /// Unset: automatic. sigma = 0 if K is positive definite (its Cholesky factorisation
  /// succeeds and two steps of inverse iteration find no eigenvalue at zero to round-off);
  /// else (free-free bodies, mechanisms) sigma = FreeBodyShift(K, M) < 0. K - sigma M must be
  /// positive definite (sigma below the lowest eigenvalue), else Solve throws InputError: the
  /// factorisation is a Cholesky one, and the lowest modes are the ones returned.
  std::optional<double> shift_hz;
  /// Convergence tolerance of the Krylov iteration, relative to each Ritz value of the
  /// shift-inverted problem (Spectra's criterion).
  double tolerance = 1e-10;
  /// Largest number of restarts of each Krylov run.
  int max_iterations = 1000;
  /// Every returned pair must reach this relative residual, or come within
  /// kResidualFloorFactor of its round-off floor where the floor is higher (see
  /// EigenSolution). Pairs that do not are refined by subspace iteration with the same
  /// factorisation; if that fails, Solve throws.
  double residual_tolerance = 1e-8;
  /// Check that no mode below the cut was missed: the band edge, or a point between the last
  /// returned and the next eigenvalue. Missed modes are then found by another run (Spectra:
  /// deflated Lanczos; SLEPc: Krylov-Schur for all of them). The slepc backend makes a Sturm
  /// count or a block Krylov check (kAuto: by the flops of its factorisation; kNone and
  /// kDeflatedLanczos: the Sturm count).
  MissedModeCheck check_missed_modes = MissedModeCheck::kAuto;
  /// The slepc backend's factorisation of K - sigma M (on one rank kAuto is MUMPS).
  DistributedFactorization distributed_factorization = DistributedFactorization::kAuto;
  /// The spectra backend's Lanczos runs: 1 = Spectra's implicitly restarted single-vector
  /// Lanczos; b > 1 = block Lanczos with blocks of b columns, unrestarted
  /// (eigensolvers/serial/block_lanczos_run.h); 0 = automatic (kAutoLanczosBlockSize).
  int lanczos_block_size = 0;
};

/// What lanczos_block_size = 0 picks: blocks of 8 columns when the factorisation of
/// K - sigma M takes more than kAutoBlockLanczosMinFlops (there one solve of 8 columns costs
/// about twice one of a single column), else Spectra's single-vector Lanczos.
inline constexpr int kAutoLanczosBlockSize = 8;
inline constexpr double kAutoBlockLanczosMinFlops = 5e9;

/// Relative gap that separates the last wanted eigenvalue from the next one when placing a
/// Sturm cut (of max(|lambda|, |sigma|)); closer eigenvalues are one cluster, counted together.
inline constexpr double kClusterGap = 1e-6;

/// Extra pairs to compute beyond `wanted`, so that the gap after the last wanted one shows.
Eigen::Index GuardPairs(Eigen::Index wanted);

/// A Sturm cut after the first `wanted` of the ascending `values` (shift sigma): midway to the
/// next value clearly above values(wanted - 1) (kClusterGap), or just above it if no such value
/// is known. Precondition: 0 < wanted <= values.size().
double SturmCutAfter(const Eigen::VectorXd& values, Eigen::Index wanted, double sigma);

/// Eigenpairs of K phi = lambda M phi and how they were obtained.
struct EigenSolution {
  /// lambda = omega^2 [rad^2/s^2], ascending. Rigid-body modes give |lambda| near round-off.
  Eigen::VectorXd eigenvalues;
  /// One mode per column, M-orthonormal: modes^T M modes = I.
  Eigen::MatrixXd modes;
  /// ||K phi - lambda M phi|| / d with d = max(||K phi||, |lambda| ||M phi||, tiny); for a
  /// rigid-body mode (|lambda| <= kZeroEigenvalue trace(K)/trace(M)), whose K phi is round-off,
  /// d also includes |sigma| ||M phi||, the scale the shift sets.
  Eigen::VectorXd relative_residuals;
  /// The round-off floor of each relative residual: eps || |K| |phi| + |lambda| |M| |phi| || / d,
  /// the residual that rounding phi to double precision alone can cause. It exceeds 1e-8 for
  /// the lowest modes of slender meshes (lambda_max / lambda_1 ~ 1e10: 5e-6 for the first
  /// bending mode of the 26k-DOF tet10 beam of cases/01), where no double-precision vector
  /// reaches a smaller residual.
  Eigen::VectorXd residual_floors;
  /// max |modes^T M modes - I| (entrywise).
  double orthonormality_error = 0.0;
  /// The shift sigma used [rad^2/s^2].
  double shift = 0.0;
  /// The check made against missed modes (kNone for a dense solve, which misses nothing).
  MissedModeCheck missed_mode_check = MissedModeCheck::kNone;
  /// Below this every eigenvalue was found and checked [rad^2/s^2].
  double checked_cut = 0.0;
  /// Sturm count: number of eigenvalues below `sturm_cut` from the inertia of
  /// K - sturm_cut M; -1 if no count was made. Equals the number of eigenvalues Solve found
  /// below the cut (else it throws).
  int sturm_count = -1;
  double sturm_cut = 0.0;  ///< [rad^2/s^2]
  int factorizations = 0;         ///< numeric sparse factorisations
  int operator_applications = 0;  ///< solves with the factorisation (one per right-hand side)
  int krylov_runs = 0;            ///< Lanczos runs and block checks (more of them if modes were missed)
  int restarts = 0;               ///< implicit restarts over all runs
  int refinement_steps = 0;       ///< subspace-iteration steps after the Krylov runs
  double seconds = 0.0;           ///< wall-clock time of Solve
  double factorization_seconds = 0.0;  ///< of which: factorising K - sigma M
  double sturm_seconds = 0.0;          ///< of which: Sturm counts (LDL^T factorisations)
  double krylov_seconds = 0.0;         ///< of which: Lanczos runs and Rayleigh-Ritz
  std::string backend;            ///< the backend's name
  /// slepc: how K - sigma M was factorised, "mumps" or "substructured"; empty for the others.
  std::string factorization;
  /// spectra: the columns of each Lanczos solve (1: Spectra's single-vector Lanczos); 0 for
  /// the others and for a dense solve.
  int lanczos_block_size = 0;
};

/// The frequency of each eigenvalue [Hz]: sign(lambda) sqrt(|lambda|) / (2 pi), so round-off
/// rigid-body eigenvalues stay near zero and a negative eigenvalue stays visible.
Eigen::VectorXd FrequenciesHz(const Eigen::VectorXd& eigenvalues);
/// FrequenciesHz(solution.eigenvalues).
Eigen::VectorXd FrequenciesHz(const EigenSolution& solution);

/// sigma [rad^2/s^2] of a signed shift frequency f [Hz]: sign(f) (2 pi f)^2.
double ShiftFromHz(double shift_hz);

/// The automatic shift of a K with zero eigenvalues: sigma = -1e-6 trace(K) / trace(M)
/// [rad^2/s^2]. trace(K)/trace(M) is the mass-weighted mean of the DOF-wise stiffness-to-mass
/// ratios, an upper-spectrum scale of the mesh. The factor keeps K - sigma M safely positive
/// definite (the round-off pivots of a singular K reached 1e-8 of the largest on a test box)
/// and the rigid-body residuals, measured against |sigma|, near 1e-10. Returns -1 if
/// trace(K) = 0.
double FreeBodyShift(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M);

/// A generalized symmetric eigensolver backend (serial Spectra + CHOLMOD, later SLEPc).
class Eigensolver {
 public:
  virtual ~Eigensolver() = default;
  /// The backend's name as accepted by MakeEigensolver.
  virtual std::string_view name() const = 0;
  /// Solves K phi = lambda M phi for the pairs `options` asks for. K, M: square, same size,
  /// symmetric, full storage (both triangles). Throws InputError (one line) for bad input:
  /// mismatched or non-square matrices, more modes than DOF, a band without modes, a singular
  /// K - sigma M, no convergence.
  virtual EigenSolution Solve(const Eigen::SparseMatrix<double>& K,
                              const Eigen::SparseMatrix<double>& M,
                              const EigenOptions& options) const = 0;
  /// Whether SolveFactorized uses the factorisation it is given (else it factorises K - sigma M
  /// itself, as Solve does). The serial backend does; SLEPc (its own MUMPS factorisation) does not.
  virtual bool UsesGivenFactorization() const { return false; }
  /// Solve with a factorisation of K - sigma M the caller already holds, so that it is not made
  /// again: the Craig-Bampton and fixed-interface bases share the Cholesky factor of the held
  /// body's K_oo (FactorHeldInterior, sigma = 0) between the constraint modes, the held check,
  /// the eigen-solve and the static solves after it. Preconditions: `factor` is an ok()
  /// kSupernodalCholesky factorisation of exactly these K and M at factor.sigma() (positive
  /// definite), and options.shift_hz is unset or gives that sigma (ShiftFromHz); the shift is
  /// factor.sigma(), never chosen automatically. The given factorisation is not counted in
  /// EigenSolution::factorizations or factorization_seconds (the caller made it); Sturm
  /// counts still make their own LDL^T factorisations. The results equal those of Solve at the
  /// same shift (same factor, same Lanczos runs), except that Solve's automatic shift also
  /// probes for a zero eigenvalue (operator_applications). The default (backends for which
  /// UsesGivenFactorization() is false) ignores `factor` and calls Solve.
  virtual EigenSolution SolveFactorized(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                                        const EigenOptions& options, const ShiftedFactorization& factor) const;
};

/// The backend named `backend` ("spectra"). Throws InputError
/// "unknown eigensolver backend 'x' (available: spectra)".
std::unique_ptr<Eigensolver> MakeEigensolver(std::string_view backend);

/// Names accepted by MakeEigensolver.
std::vector<std::string> AvailableEigensolvers();

// ---- Shared by the backends ---------------------------------------------------------------

/// Throws InputError unless K and M are square, of equal size, non-empty and finite in size,
/// and the options are consistent (num_modes >= 0 and <= DOF, max_frequency_hz >= 0 and
/// finite, one of the two set, tolerances > 0, max_iterations > 0).
void ValidateEigenInputs(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                         const EigenOptions& options);

/// Eigenvalues within this fraction of trace(K)/trace(M) of zero are zero to round-off:
/// rigid-body modes (1e-18 .. 1e-15 of that scale on the meshes measured; the lowest elastic
/// modes of realistic meshes lie above 1e-11). A computed eigenvalue this close to the shift
/// means K - sigma M was numerically singular.
inline constexpr double kZeroEigenvalue = 1e-13;

/// A pair is accepted if its relative residual is <= max(residual_tolerance,
/// kResidualFloorFactor * its round-off floor). Converged pairs measured on the 26k-DOF beam
/// sit at 0.5 .. 1 times their floor.
inline constexpr double kResidualFloorFactor = 4.0;

/// Relative residuals and their round-off floors, as defined in EigenSolution.
struct PairResiduals {
  Eigen::VectorXd relative;
  Eigen::VectorXd floor;
  /// Whether every pair meets max(tolerance, floor_factor * floor); if not, `worst` is the
  /// pair furthest above its bound.
  bool Accepted(double tolerance, Eigen::Index* worst = nullptr,
                double floor_factor = kResidualFloorFactor) const;
  /// The largest relative(j) / max(tolerance, floor_factor * floor(j)) (infinity for a NaN
  /// residual; 0 without pairs): Accepted is WorstRatio <= 1.
  double WorstRatio(double tolerance, Eigen::Index* worst = nullptr,
                    double floor_factor = kResidualFloorFactor) const;
};
/// The squared norms residuals are made of, per mode (column), summed over rows so that
/// ranks holding different rows can add theirs: ||K phi||^2, ||M phi||^2,
/// ||K phi - lambda M phi||^2 and || |K| |phi| + |lambda| |M| |phi| ||^2.
using ResidualSums = Eigen::Matrix<double, 4, Eigen::Dynamic>;
/// Residuals and round-off floors (as defined in EigenSolution) from summed squares;
/// `zero_eigenvalue` = kZeroEigenvalue trace(K) / trace(M) marks rigid-body modes.
PairResiduals ResidualsFromSums(const ResidualSums& sums, const Eigen::VectorXd& eigenvalues,
                                double sigma, double zero_eigenvalue);
/// Residuals of K, M known by their products (K X, M X, |K| |X|, |M| |X|, the diagonals).
PairResiduals ComputeResiduals(const SymmetricOperator& K, const SymmetricOperator& M,
                               const Eigen::VectorXd& eigenvalues, const Eigen::MatrixXd& modes, double sigma);
/// Residuals of K, M held whole in this process (SparseOperator).
PairResiduals ComputeResiduals(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                               const Eigen::VectorXd& eigenvalues, const Eigen::MatrixXd& modes,
                               double sigma);

/// max |modes^T M modes - I| over all entries.
double MOrthonormalityError(const SymmetricOperator& M, const Eigen::MatrixXd& modes);
/// The same for M held whole in this process.
double MOrthonormalityError(const Eigen::SparseMatrix<double>& M, const Eigen::MatrixXd& modes);

}  // namespace flexmbs::eigensolvers
