// The Spectra eigensolver's bad input (eigensolvers/eigensolver.h): every one is an InputError
// of one line naming the value — sizes, mode counts and bands, shifts that cannot be factorised,
// indefinite stiffness, options out of range.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "tests/eigensolvers/spectra_test_support.h"
#include "tests/support/test_problems.h"

namespace flexmbs::eigensolvers {
namespace {

using flexmbs::testing::HexBox;
using flexmbs::testing::SolveDense;
using flexmbs::testing::Steel;
using spectra_test::Assemble;
using spectra_test::Cantilever;
using spectra_test::ExpectContract;
using spectra_test::ExpectMatchesDense;
using spectra_test::MakeCantilever;
using spectra_test::Problem;
using spectra_test::Spectra;
using SparseMatrix = Eigen::SparseMatrix<double>;

/// The one-line InputError message of solving with `options`, or "no InputError".
std::string SolveError(const SparseMatrix& K, const SparseMatrix& M, const EigenOptions& options) {
  try {
    Spectra()->Solve(K, M, options);
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line";
    return message;
  }
  return "no InputError";
}

TEST(SpectraEigensolver, MoreModesThanDofIsAnInputError) {
  const Problem p = Assemble(HexBox({1, 1, 1}, {0.1, 0.1, 0.1}, Steel()));
  EigenOptions options;
  options.num_modes = 25;
  EXPECT_EQ(SolveError(p.K, p.M, options), "eigenproblem: 25 modes requested but the model has only 24 DOF");
}

TEST(SpectraEigensolver, MismatchedOrNonSquareMatricesAreInputErrors) {
  const Problem p = Assemble(HexBox({1, 1, 1}, {0.1, 0.1, 0.1}, Steel()));
  EigenOptions options;
  options.num_modes = 3;
  const SparseMatrix M23 = p.M.topRows(21);
  EXPECT_NE(SolveError(p.K, M23, options).find("mass matrix M is 21 x 24, must be square"), std::string::npos);
  const SparseMatrix K21 = p.K.topLeftCorner(21, 21);
  EXPECT_NE(SolveError(K21, p.M, options).find("K is 21 x 21 but M is 24 x 24"), std::string::npos);
  EXPECT_NE(SolveError(SparseMatrix(0, 0), SparseMatrix(0, 0), options).find("empty"), std::string::npos);
}

TEST(SpectraEigensolver, NoModeCountOrBandIsAnInputError) {
  const Problem p = Assemble(HexBox({1, 1, 1}, {0.1, 0.1, 0.1}, Steel()));
  EXPECT_NE(SolveError(p.K, p.M, EigenOptions{}).find("neither num_modes nor max_frequency_hz"), std::string::npos);
}

TEST(SpectraEigensolver, BandWithoutModesIsAnInputErrorNamingTheLowestMode) {
  const Cantilever c = MakeCantilever(Steel(), Steel());
  const double lowest_hz = FrequenciesHz(SolveDense(c.K, c.M, 0.0).values)(0);
  for (const MissedModeCheck check : {MissedModeCheck::kSturmCount, MissedModeCheck::kDeflatedLanczos}) {
    EigenOptions options;
    options.max_frequency_hz = 1.0;
    options.check_missed_modes = check;
    const std::string message = SolveError(c.K, c.M, options);
    EXPECT_EQ(message, fmt::format("eigenproblem: no mode below max_frequency_hz = 1 Hz: the lowest mode is at {:g} Hz",
                                   lowest_hz));
  }
}

TEST(SpectraEigensolver, UnconstrainedBodyWithZeroOrPositiveShiftIsAnInputError) {
  const Problem p = Assemble(HexBox({4, 2, 2}, {0.4, 0.2, 0.2}, Steel()));
  EigenOptions options;
  options.num_modes = 8;
  for (const double shift_hz : {0.0, 5.0}) {
    options.shift_hz = shift_hz;
    const std::string message = SolveError(p.K, p.M, options);
    EXPECT_NE(message.find("the body is likely unconstrained"), std::string::npos) << message;
  }
  // A negative shift works, even a small one: the rigid-body residuals, measured against
  // |sigma| ||M phi||, then sit at their (higher) round-off floor.
  options.shift_hz = -1.0;
  const EigenSolution s = Spectra()->Solve(p.K, p.M, options);
  ExpectContract(p.K, p.M, s, /*strict=*/false);
  for (int j = 0; j < 6; ++j) EXPECT_GT(s.residual_floors(j), 1e-9) << j;
}

TEST(SpectraEigensolver, IndefiniteStiffnessOrATooSmallNegativeShiftAreInputErrors) {
  const Problem p = Assemble(HexBox({4, 2, 2}, {0.4, 0.2, 0.2}, Steel()));
  EigenOptions options;
  options.num_modes = 8;
  // A negative shift of round-off size does not make K - sigma M positive definite.
  options.shift_hz = -1e-4;
  EXPECT_NE(SolveError(p.K, p.M, options).find("the negative shift is too close to zero for the rigid-body modes"),
            std::string::npos);
  // K with a negative eigenvalue (a negative diagonal entry).
  SparseMatrix K = p.K;
  K.coeffRef(0, 0) *= -1.0;
  options.shift_hz.reset();
  EXPECT_NE(SolveError(K, p.M, options).find("so it is not positive semi-definite"), std::string::npos);
}

TEST(SpectraEigensolver, ShiftAboveTheLowestModeIsAnInputError) {
  const Cantilever c = MakeCantilever(Steel(), Steel());
  const testing::DenseEigen dense = SolveDense(c.K, c.M, 0.0);
  EigenOptions options;
  options.num_modes = 3;
  options.shift_hz = 2.0 * FrequenciesHz(dense.values)(0);
  EXPECT_NE(SolveError(c.K, c.M, options).find("not positive definite"), std::string::npos);
  // Just below the lowest mode is fine and converges.
  options.shift_hz = 0.9 * FrequenciesHz(dense.values)(0);
  const EigenSolution s = Spectra()->Solve(c.K, c.M, options);
  ExpectMatchesDense(c.M, s, dense, dense.values(0));
}

TEST(SpectraEigensolver, BadOptionsAreInputErrors) {
  const Problem p = Assemble(HexBox({1, 1, 1}, {0.1, 0.1, 0.1}, Steel()));
  EigenOptions options;
  options.num_modes = -1;
  EXPECT_NE(SolveError(p.K, p.M, options).find("num_modes -1 must be >= 0"), std::string::npos);
  options.num_modes = 2;
  options.max_frequency_hz = -5.0;
  EXPECT_NE(SolveError(p.K, p.M, options).find("max_frequency_hz -5"), std::string::npos);
  options.max_frequency_hz = 0.0;
  options.tolerance = 0.0;
  EXPECT_NE(SolveError(p.K, p.M, options).find("tolerance 0 must be in (0, 1)"), std::string::npos);
  options.tolerance = 1e-10;
  options.lanczos_block_size = -2;
  EXPECT_NE(SolveError(p.K, p.M, options).find("lanczos_block_size -2 must be >= 0"), std::string::npos);
}

}  // namespace
}  // namespace flexmbs::eigensolvers
