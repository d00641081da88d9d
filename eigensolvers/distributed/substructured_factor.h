#pragma once
// A direct solver for a symmetric positive definite matrix distributed by rows over MPI ranks,
// by substructuring: each rank's rows that couple to no higher rank are its interior; the others
// form the interface. Every rank eliminates its interior with a sequential MUMPS Cholesky of its
// own (its rows only, no communication) and gets from it its Schur complement on the interface;
// their sum plus the interface block of the matrix is the interface matrix S, dense, which every
// rank factorises (LAPACK). A solve is the rank's forward condensation, one sum of the reduced
// right-hand sides, the dense solve and the rank's expansion. The ranks' subtrees never wait for
// each other, which MUMPS's own distributed factorisation does not reach on two ranks
// (docs/reduction.md, "Substructured factorisation"); the price is a dense S of the
// interface's size on every rank.

#include <cstdint>
#include <memory>

struct _p_Mat;  // PETSc's Mat and Vec
struct _p_Vec;

namespace flexmbs::eigensolvers {

/// PETSc log events (Mat package): "SubstrFactor", one per factorisation (analysis included),
/// and "SubstrSolve", one per single-vector Solve. Registered on the first call.
struct SubstructuredLogEvents {
  int factor = 0, solve = 0;  // PetscLogEvent
};
SubstructuredLogEvents SubstructuredEvents();

/// The factorisation of A (MPIAIJ on two or more ranks, symmetric positive definite, symmetric
/// sparsity); A's values are copied, A may change afterwards. Every member is collective over A's
/// communicator.
class SubstructuredFactor {
 public:
  /// Factorises A; whether A is positive definite (a rank's interior or S not) tells
  /// positive_definite(). Throws flexmbs::InputError (on every rank) if MUMPS fails otherwise
  /// (memory).
  explicit SubstructuredFactor(_p_Mat* A);
  /// The same, or null (nothing factorised) where A's interface has more than
  /// `max_interface_rows` rows: the dense S would take 8 n^2 bytes on every rank.
  static std::unique_ptr<SubstructuredFactor> IfInterfaceAtMost(_p_Mat* A,
                                                                std::int64_t max_interface_rows);
  ~SubstructuredFactor();
  SubstructuredFactor(const SubstructuredFactor&) = delete;
  SubstructuredFactor& operator=(const SubstructuredFactor&) = delete;

  /// Whether the factorisation met no negative or zero pivot: A is positive definite to working
  /// precision; solves need it.
  bool positive_definite() const;
  /// x = A^-1 b (b and x distributed like A's rows; may be the same vector).
  void Solve(_p_Vec* b, _p_Vec* x) const;
  /// X = A^-1 B for `columns` columns: this rank's rows of B and X, column-major with leading
  /// dimension the rank's row count (may be the same array).
  void SolveColumns(const double* B, double* X, int columns) const;

  /// Interface rows (global), the dense S's order.
  std::int64_t interface_rows() const;
  /// Flops of the factorisation summed over the ranks (MUMPS interiors and the dense S).
  double flops() const;

 private:
  struct State;
  /// Factorises A with `state` holding A's row split.
  SubstructuredFactor(std::unique_ptr<State> state, _p_Mat* A);
  void Factorize(_p_Mat* A);

  std::unique_ptr<State> s_;
};

}  // namespace flexmbs::eigensolvers
