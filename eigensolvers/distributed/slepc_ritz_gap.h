#pragma once
// Where the SLEPc backend puts the cut after the wanted modes: its guard rule (not GuardPairs,
// which the Spectra backend uses). The first run asks SLEPc for exactly the wanted pairs, and
// the gap after them, where the cut goes, is located by the run's last Ritz values beyond the
// converged ones, each with its residual bound. Converged guard pairs cost whole Krylov-Schur
// restarts (bench bar, 20 modes, 19 k DOF: 53 solves, 63-67 with one converged guard, 80 with
// GuardPairs' 5); Spectra keeps its unconverged Ritz values to itself, SLEPc passes them to a
// monitor. The Ritz values only place the cut: the modes found below it are converged pairs,
// and the check (a factorisation's inertia or the block Krylov check) is unchanged.

#include <slepceps.h>

#include <Eigen/Core>
#include <vector>

namespace flexmbs::eigensolvers {

/// Lower bounds of the eigenvalues that the last iteration's unconverged Ritz values approximate.
/// For shift-and-invert the Ritz values are theta = 1 / (lambda - sigma) of the operator
/// (K - sigma M)^-1 M, symmetric in the M inner product, and SLEPc's estimate is e = ||r|| / |theta|;
/// an eigenvalue lies within ||r|| of theta, hence at or above the back-transform of
/// theta + e |theta| (e < 1).
struct RitzLowerBounds {
  ST st = nullptr;
  std::vector<double> lambda;
};

/// EPSMonitorSet callback: keeps the lower bounds of the latest iteration (the last call is the
/// final one). Never throws into SLEPc.
PetscErrorCode RecordRitzLowerBounds(EPS, PetscInt, PetscInt converged, PetscScalar* theta, PetscScalar*,
                                     PetscReal* error, PetscInt count, void* context);

/// The converged eigenvalues (ascending) followed by the Ritz lower bounds above the largest of
/// them, ascending: the values SturmCutAfter places the cut among.
Eigen::VectorXd ValuesForTheCut(const Eigen::VectorXd& converged, std::vector<double> ritz_lower);

}  // namespace flexmbs::eigensolvers
