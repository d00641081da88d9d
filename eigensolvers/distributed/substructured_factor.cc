#include "eigensolvers/distributed/substructured_factor.h"

#include <dmumps_c.h>
#include <fmt/format.h>
#include <metis.h>
#include <petscmat.h>

#include <algorithm>
#include <cstddef>
#include <optional>
#include <vector>

#include "core/error.h"
#include "fem/petsc_check.h"

// LAPACK (Fortran ABI: trailing hidden lengths of the character arguments).
extern "C" {
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info,
             std::size_t uplo_len);
void dpotrs_(const char* uplo, const int* n, const int* nrhs, const double* a, const int* lda,
             double* b, const int* ldb, int* info, std::size_t uplo_len);
}

namespace flexmbs::eigensolvers {
namespace {

// MUMPS's JOB values and its ICNTL / INFOG entries used here (1-based in its documentation).
constexpr int kJobInit = -1, kJobEnd = -2, kJobSolve = 3, kJobAnalyseFactorise = 4;
constexpr int kSchurComplete = 3;          // ICNTL(19): the whole Schur complement, by columns
constexpr int kCondense = 1, kExpand = 2;  // ICNTL(26) in a solve
constexpr int kHostWorks = 1;              // PAR
constexpr int kPositiveDefinite = 1;       // SYM
// ICNTL(7): the pivot order given in PERM_IN.
constexpr int kGivenOrder = 1;
// Sums of this many doubles at most per MPI call (counts are int).
constexpr std::size_t kSumChunk = std::size_t{1} << 26;

int& Icntl(DMUMPS_STRUC_C& id, int i) { return id.icntl[i - 1]; }

// In-place sum over `comm` of `count` doubles, in chunks.
void SumInPlace(double* data, std::size_t count, MPI_Comm comm) {
  for (std::size_t at = 0; at < count; at += kSumChunk) {
    const int n = static_cast<int>(std::min(kSumChunk, count - at));
    FLEXMBS_PETSC(MPI_Allreduce(MPI_IN_PLACE, data + at, n, MPI_DOUBLE, MPI_SUM, comm));
  }
}

// A sequential AIJ block's rows (CSR) and values, released with the object.
class CsrView {
 public:
  explicit CsrView(Mat A) : A_(A) {
    PetscBool done = PETSC_FALSE;
    FLEXMBS_PETSC(MatGetRowIJ(A_, 0, PETSC_FALSE, PETSC_FALSE, &rows_, &ia_, &ja_, &done));
    FLEXMBS_CHECK(done == PETSC_TRUE, "substructured factor: no CSR access to a local block");
    FLEXMBS_PETSC(MatSeqAIJGetArrayRead(A_, &values_));
  }
  ~CsrView() {
    MatSeqAIJRestoreArrayRead(A_, &values_);
    PetscBool done = PETSC_FALSE;
    MatRestoreRowIJ(A_, 0, PETSC_FALSE, PETSC_FALSE, &rows_, &ia_, &ja_, &done);
  }
  CsrView(const CsrView&) = delete;
  CsrView& operator=(const CsrView&) = delete;

  PetscInt begin(PetscInt row) const { return ia_[row]; }
  PetscInt end(PetscInt row) const { return ia_[row + 1]; }
  PetscInt column(PetscInt k) const { return ja_[k]; }
  double value(PetscInt k) const { return values_[k]; }

 private:
  Mat A_;
  PetscInt rows_ = 0;
  const PetscInt* ia_ = nullptr;
  const PetscInt* ja_ = nullptr;
  const PetscScalar* values_ = nullptr;
};

// A's rows on this rank: the block of its own columns and, on more than one rank, the block of
// the other ranks' columns (`garray` maps its columns to global ones).
struct LocalBlocks {
  Mat own = nullptr, other = nullptr;
  const PetscInt* garray = nullptr;
};

LocalBlocks LocalBlocksOf(Mat A) {
  LocalBlocks blocks;
  PetscBool parallel = PETSC_FALSE;
  FLEXMBS_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(A), MATMPIAIJ, &parallel));
  if (parallel) {
    FLEXMBS_PETSC(MatMPIAIJGetSeqAIJ(A, &blocks.own, &blocks.other, &blocks.garray));
  } else {
    blocks.own = A;
  }
  return blocks;
}

// The row distribution of A and its split into interior and interface rows.
struct RowSplit {
  MPI_Comm comm = MPI_COMM_NULL;
  PetscMPIInt rank = 0, size = 1;
  PetscInt first = 0, rows = 0;          // this rank's first global row and row count
  std::vector<PetscInt> ranges;          // every rank's first row, then the global count
  std::vector<char> interface;           // per local row: coupled to a higher rank
  std::vector<PetscInt> interface_rows;  // global, ascending: the interface of all ranks

  // The interface position of global row `g` (-1: interior).
  PetscInt Position(PetscInt g) const {
    const auto it = std::lower_bound(interface_rows.begin(), interface_rows.end(), g);
    return it != interface_rows.end() && *it == g
               ? static_cast<PetscInt>(it - interface_rows.begin())
               : -1;
  }
  int Owner(PetscInt g) const {
    return static_cast<int>(std::upper_bound(ranges.begin(), ranges.end(), g) - ranges.begin()) - 1;
  }
};

RowSplit SplitRows(Mat A) {
  RowSplit split;
  FLEXMBS_PETSC(PetscObjectGetComm(reinterpret_cast<PetscObject>(A), &split.comm));
  FLEXMBS_PETSC(MPI_Comm_rank(split.comm, &split.rank));
  FLEXMBS_PETSC(MPI_Comm_size(split.comm, &split.size));
  PetscInt end = 0;
  FLEXMBS_PETSC(MatGetOwnershipRange(A, &split.first, &end));
  split.rows = end - split.first;
  const PetscInt* ranges = nullptr;
  FLEXMBS_PETSC(MatGetOwnershipRanges(A, &ranges));
  split.ranges.assign(ranges, ranges + split.size + 1);
  const LocalBlocks blocks = LocalBlocksOf(A);
  split.interface.assign(static_cast<std::size_t>(split.rows), 0);
  std::vector<PetscInt> mine;
  std::optional<CsrView> other;
  if (blocks.other) other.emplace(blocks.other);
  for (PetscInt i = 0; other && i < split.rows; ++i) {
    const CsrView& off = *other;
    const PetscInt* garray = blocks.garray;
    for (PetscInt k = off.begin(i); k < off.end(i); ++k) {
      if (split.Owner(garray[off.column(k)]) > split.rank) {
        split.interface[static_cast<std::size_t>(i)] = 1;
        mine.push_back(split.first + i);
        break;
      }
    }
  }
  const int count = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(split.size)),
      offsets(static_cast<std::size_t>(split.size) + 1, 0);
  FLEXMBS_PETSC(MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, split.comm));
  for (std::size_t r = 0; r < counts.size(); ++r) offsets[r + 1] = offsets[r] + counts[r];
  split.interface_rows.resize(static_cast<std::size_t>(offsets.back()));
  FLEXMBS_PETSC(MPI_Allgatherv(mine.data(), count, MPIU_INT, split.interface_rows.data(),
                               counts.data(), offsets.data(), MPIU_INT, split.comm));
  return split;
}

}  // namespace

struct SubstructuredFactor::State {
  RowSplit split;
  std::vector<PetscInt> interior;        // local rows of the interior, ascending
  std::vector<PetscInt> own_interface;   // local rows of this rank's interface rows
  std::vector<PetscInt> own_position;    // their interface positions
  std::vector<PetscInt> schur_position;  // per local Schur variable: its interface position
  std::vector<MUMPS_INT> irn, jcn, listvar, order;
  std::vector<double> values;
  mutable DMUMPS_STRUC_C id{};  // solves write their arrays and ICNTL(26) into it
  bool mumps_started = false;
  int interface_size = 0;
  std::vector<double> S;  // dense interface matrix, then its Cholesky factor (lower)
  double flops = 0.0;
  bool positive_definite = false;
  // Solve scratch.
  mutable std::vector<double> rhs, reduced, G;

  int local_size() const { return static_cast<int>(interior.size() + schur_position.size()); }
  int schur_size() const { return static_cast<int>(schur_position.size()); }

  void Mumps(int job) const {
    id.job = job;
    dmumps_c(&id);
    FLEXMBS_CHECK(
        id.infog[0] >= 0,
        fmt::format(
            "substructured factor: MUMPS (job {}) failed on rank {}: INFOG(1) = {}, INFOG(2) = {}",
            job, split.rank, id.infog[0], id.infog[1]));
  }

  // The local problem: interior rows with their interface columns, lower triangle, 1-based.
  void BuildLocalProblem(Mat A) {
    const LocalBlocks blocks = LocalBlocksOf(A);
    const CsrView diag(blocks.own);
    std::optional<CsrView> off;
    if (blocks.other) off.emplace(blocks.other);
    std::vector<PetscInt> local_of(static_cast<std::size_t>(split.rows), -1);
    for (PetscInt i = 0; i < split.rows; ++i) {
      if (split.interface[static_cast<std::size_t>(i)]) {
        own_interface.push_back(i);
        own_position.push_back(split.Position(split.first + i));
      } else {
        local_of[static_cast<std::size_t>(i)] = static_cast<PetscInt>(interior.size());
        interior.push_back(i);
      }
    }
    std::vector<PetscInt> schur_of(split.interface_rows.size(), -1);
    const auto n_interior = static_cast<PetscInt>(interior.size());
    auto schur_variable = [&](PetscInt position) {
      PetscInt& v = schur_of[static_cast<std::size_t>(position)];
      if (v < 0) {
        v = static_cast<PetscInt>(schur_position.size());
        schur_position.push_back(position);
      }
      return n_interior + v;
    };
    auto add = [&](PetscInt row, PetscInt column, double value) {
      irn.push_back(static_cast<MUMPS_INT>(row + 1));
      jcn.push_back(static_cast<MUMPS_INT>(column + 1));
      values.push_back(value);
    };
    for (PetscInt li = 0; li < n_interior; ++li) {
      const PetscInt i = interior[static_cast<std::size_t>(li)];
      for (PetscInt k = diag.begin(i); k < diag.end(i); ++k) {
        const PetscInt c = diag.column(k);
        const PetscInt lc = local_of[static_cast<std::size_t>(c)];
        if (lc >= 0) {
          if (lc <= li) add(li, lc, diag.value(k));
        } else {
          add(schur_variable(split.Position(split.first + c)), li, diag.value(k));
        }
      }
      for (PetscInt k = off ? off->begin(i) : 0; off && k < off->end(i); ++k) {
        const PetscInt position = split.Position(blocks.garray[off->column(k)]);
        FLEXMBS_CHECK(position >= 0,
                      "substructured factor: an interior row couples to another rank's interior");
        add(schur_variable(position), li, off->value(k));
      }
    }
    for (PetscInt v = 0; v < static_cast<PetscInt>(schur_position.size()); ++v)
      add(n_interior + v, n_interior + v, 0.0);
    OrderInterior(diag, local_of);
    listvar.resize(schur_position.size());
    for (std::size_t v = 0; v < listvar.size(); ++v)
      listvar[v] = static_cast<MUMPS_INT>(interior.size() + v + 1);
  }

  // The pivot order of the local problem (MUMPS's PERM_IN): METIS's nested dissection of the
  // interior's graph, then the Schur variables. (MUMPS's own PORD ordering of the whole local
  // graph with the Schur variables moved last afterwards carries them through every front near
  // them: at 98k DOF each half took more flops than the whole problem.)
  void OrderInterior(const CsrView& diag, const std::vector<PetscInt>& local_of) {
    const auto n = static_cast<idx_t>(interior.size());
    std::vector<idx_t> xadj(static_cast<std::size_t>(n) + 1, 0), adjacency;
    for (idx_t li = 0; li < n; ++li) {
      const PetscInt i = interior[static_cast<std::size_t>(li)];
      for (PetscInt k = diag.begin(i); k < diag.end(i); ++k) {
        const PetscInt lc = local_of[static_cast<std::size_t>(diag.column(k))];
        if (lc >= 0 && lc != li) adjacency.push_back(static_cast<idx_t>(lc));
      }
      xadj[static_cast<std::size_t>(li) + 1] = static_cast<idx_t>(adjacency.size());
    }
    std::vector<idx_t> permutation(static_cast<std::size_t>(n)),
        position(static_cast<std::size_t>(n));
    if (n > 0) {
      idx_t options[METIS_NOPTIONS];
      METIS_SetDefaultOptions(options);
      idx_t vertices = n;
      const int status = METIS_NodeND(&vertices, xadj.data(), adjacency.data(), nullptr, options,
                                      permutation.data(), position.data());
      FLEXMBS_CHECK(status == METIS_OK, "substructured factor: METIS_NodeND failed");
    }
    order.resize(interior.size() + schur_position.size());
    for (std::size_t v = 0; v < order.size(); ++v) {
      order[v] =
          static_cast<MUMPS_INT>(v < interior.size() ? position[v] + 1 : static_cast<idx_t>(v) + 1);
    }
  }

  // This rank's part of S: its Schur complement and the interface block of its interface rows.
  void AddToInterfaceMatrix(Mat A, const std::vector<double>& schur) {
    const auto n = static_cast<std::size_t>(interface_size);
    const std::size_t m = schur_position.size();
    for (std::size_t b = 0; b < m; ++b) {
      const auto pb = static_cast<std::size_t>(schur_position[b]);
      for (std::size_t a = 0; a < m; ++a) {
        S[static_cast<std::size_t>(schur_position[a]) + pb * n] += schur[a + b * m];
      }
    }
    const LocalBlocks blocks = LocalBlocksOf(A);
    const CsrView diag(blocks.own);
    std::optional<CsrView> off;
    if (blocks.other) off.emplace(blocks.other);
    for (std::size_t r = 0; r < own_interface.size(); ++r) {
      const PetscInt i = own_interface[r];
      const auto row = static_cast<std::size_t>(own_position[r]);
      for (PetscInt k = diag.begin(i); k < diag.end(i); ++k) {
        const PetscInt position = split.Position(split.first + diag.column(k));
        if (position >= 0) S[row + static_cast<std::size_t>(position) * n] += diag.value(k);
      }
      for (PetscInt k = off ? off->begin(i) : 0; off && k < off->end(i); ++k) {
        const PetscInt position = split.Position(blocks.garray[off->column(k)]);
        if (position >= 0) S[row + static_cast<std::size_t>(position) * n] += off->value(k);
      }
    }
  }
};

SubstructuredLogEvents SubstructuredEvents() {
  static const SubstructuredLogEvents events = [] {
    SubstructuredLogEvents e;
    FLEXMBS_PETSC(PetscLogEventRegister("SubstrFactor", MAT_CLASSID, &e.factor));
    FLEXMBS_PETSC(PetscLogEventRegister("SubstrSolve", MAT_CLASSID, &e.solve));
    return e;
  }();
  return events;
}

SubstructuredFactor::SubstructuredFactor(Mat A)
    : SubstructuredFactor(std::make_unique<State>(), A) {}

std::unique_ptr<SubstructuredFactor> SubstructuredFactor::IfInterfaceAtMost(
    Mat A, std::int64_t max_interface_rows) {
  auto state = std::make_unique<State>();
  state->split = SplitRows(A);
  if (static_cast<std::int64_t>(state->split.interface_rows.size()) > max_interface_rows)
    return nullptr;
  return std::unique_ptr<SubstructuredFactor>(new SubstructuredFactor(std::move(state), A));
}

SubstructuredFactor::SubstructuredFactor(std::unique_ptr<State> state, Mat A)
    : s_(std::move(state)) {
  if (s_->split.comm == MPI_COMM_NULL)
    s_->split = SplitRows(A);  // not split yet (public constructor)
  const PetscLogEvent event = SubstructuredEvents().factor;
  FLEXMBS_PETSC(PetscLogEventBegin(event, A, nullptr, nullptr, nullptr));
  Factorize(A);
  FLEXMBS_PETSC(PetscLogEventEnd(event, A, nullptr, nullptr, nullptr));
}

void SubstructuredFactor::Factorize(Mat A) {
  State& s = *s_;
  s.interface_size = static_cast<int>(s.split.interface_rows.size());
  s.BuildLocalProblem(A);

  // A rank whose rows all couple to a higher rank has no interior and no MUMPS instance.
  DMUMPS_STRUC_C& id = s.id;
  id.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(MPI_COMM_SELF));
  id.par = kHostWorks;
  id.sym = kPositiveDefinite;
  if (!s.interior.empty()) {
    s.Mumps(kJobInit);
    s.mumps_started = true;
  }
  for (int i : {1, 2, 3}) Icntl(id, i) = -1;  // no output: failures are read from INFOG
  Icntl(id, 4) = 0;
  Icntl(id, 7) = kGivenOrder;
  id.perm_in = s.order.data();
  id.n = static_cast<MUMPS_INT>(s.local_size());
  id.nnz = static_cast<MUMPS_INT8>(s.values.size());
  id.irn = s.irn.data();
  id.jcn = s.jcn.data();
  id.a = s.values.data();
  std::vector<double> schur(static_cast<std::size_t>(s.schur_size()) *
                            static_cast<std::size_t>(s.schur_size()));
  if (s.schur_size() > 0) {
    Icntl(id, 19) = kSchurComplete;
    id.size_schur = static_cast<MUMPS_INT>(s.schur_size());
    id.listvar_schur = s.listvar.data();
    id.nprow = id.npcol = 1;
    id.mblock = id.nblock = 100;
    id.schur_lld = id.size_schur;
    id.schur = schur.data();
  }
  id.job = kJobAnalyseFactorise;
  if (s.mumps_started) dmumps_c(&id);
  // Agreed by every rank: 0 factorised, 1 an interior is not positive definite (MUMPS's
  // "singular" or a negative pivot, INFOG(12)), 2 MUMPS failed otherwise (INFOG(1) < 0).
  int status = id.infog[0] == -10 || (id.infog[0] >= 0 && id.infog[11] > 0) ? 1
               : id.infog[0] < 0                                            ? 2
                                                                            : 0;
  int mumps_error = status == 2 ? id.infog[0] : 0;
  FLEXMBS_PETSC(MPI_Allreduce(MPI_IN_PLACE, &status, 1, MPI_INT, MPI_MAX, s.split.comm));
  FLEXMBS_PETSC(MPI_Allreduce(MPI_IN_PLACE, &mumps_error, 1, MPI_INT, MPI_MIN, s.split.comm));
  if (status == 2) {
    throw InputError(fmt::format(
        "substructured factor: MUMPS failed to factorise a rank's interior (INFOG(1) = {})",
        mumps_error));
  }
  s.flops = s.mumps_started ? id.rinfog[2] : 0.0;
  // The MUMPS arrays of the matrix are not needed by solves.
  id.irn = id.jcn = nullptr;
  id.a = nullptr;
  std::vector<MUMPS_INT>().swap(s.irn);
  std::vector<MUMPS_INT>().swap(s.jcn);
  std::vector<double>().swap(s.values);
  if (status == 1) return;

  const auto n = static_cast<std::size_t>(s.interface_size);
  s.S.assign(n * n, 0.0);
  s.AddToInterfaceMatrix(A, schur);
  std::vector<double>().swap(schur);
  SumInPlace(s.S.data(), s.S.size(), s.split.comm);
  FLEXMBS_PETSC(MPI_Allreduce(MPI_IN_PLACE, &s.flops, 1, MPI_DOUBLE, MPI_SUM, s.split.comm));
  s.flops += static_cast<double>(n) * static_cast<double>(n) * static_cast<double>(n) / 3.0;
  int info = 0;
  if (n > 0) {
    const int order = s.interface_size;
    dpotrf_("L", &order, s.S.data(), &order, &info, 1);  // the same S and result on every rank
  }
  s.positive_definite = info == 0;
}

SubstructuredFactor::~SubstructuredFactor() {
  if (s_ && s_->mumps_started) {
    s_->id.job = kJobEnd;
    dmumps_c(&s_->id);
  }
}

std::int64_t SubstructuredFactor::interface_rows() const { return s_->interface_size; }

double SubstructuredFactor::flops() const { return s_->flops; }

bool SubstructuredFactor::positive_definite() const { return s_->positive_definite; }

void SubstructuredFactor::Solve(Vec b, Vec x) const {
  const PetscLogEvent event = SubstructuredEvents().solve;
  FLEXMBS_PETSC(PetscLogEventBegin(event, b, x, nullptr, nullptr));
  const PetscScalar* in = nullptr;
  FLEXMBS_PETSC(VecGetArrayRead(b, &in));
  std::vector<double> B(in, in + s_->split.rows);
  FLEXMBS_PETSC(VecRestoreArrayRead(b, &in));
  PetscScalar* out = nullptr;
  FLEXMBS_PETSC(VecGetArray(x, &out));
  SolveColumns(B.data(), out, 1);
  FLEXMBS_PETSC(VecRestoreArray(x, &out));
  FLEXMBS_PETSC(PetscLogEventEnd(event, b, x, nullptr, nullptr));
}

void SubstructuredFactor::SolveColumns(const double* B, double* X, int columns) const {
  const State& s = *s_;
  FLEXMBS_CHECK(s.positive_definite,
                "substructured factor: solve with a matrix that is not positive definite");
  DMUMPS_STRUC_C& id = s.id;
  const auto rows = static_cast<std::size_t>(s.split.rows);
  const auto local = static_cast<std::size_t>(s.local_size());
  const auto m = static_cast<std::size_t>(s.schur_size());
  const auto n = static_cast<std::size_t>(s.interface_size);
  const auto k = static_cast<std::size_t>(columns);
  s.rhs.assign(local * k, 0.0);
  for (std::size_t c = 0; c < k; ++c) {
    for (std::size_t li = 0; li < s.interior.size(); ++li) {
      s.rhs[li + c * local] = B[static_cast<std::size_t>(s.interior[li]) + c * rows];
    }
  }
  s.reduced.assign(m * k, 0.0);
  id.nrhs = static_cast<MUMPS_INT>(columns);
  id.lrhs = static_cast<MUMPS_INT>(local);
  id.rhs = s.rhs.data();
  if (m > 0) {
    id.redrhs = s.reduced.data();
    id.lredrhs = static_cast<MUMPS_INT>(m);
    Icntl(id, 26) = kCondense;
  }
  if (s.mumps_started) s.Mumps(kJobSolve);
  // The interface right-hand side: the owners' rows of B minus every rank's condensed part.
  s.G.assign(n * k, 0.0);
  for (std::size_t c = 0; c < k; ++c) {
    for (std::size_t a = 0; a < m; ++a)
      s.G[static_cast<std::size_t>(s.schur_position[a]) + c * n] += s.reduced[a + c * m];
    for (std::size_t r = 0; r < s.own_interface.size(); ++r) {
      s.G[static_cast<std::size_t>(s.own_position[r]) + c * n] +=
          B[static_cast<std::size_t>(s.own_interface[r]) + c * rows];
    }
  }
  SumInPlace(s.G.data(), s.G.size(), s.split.comm);
  if (n > 0) {
    int info = 0;
    const int order = s.interface_size;
    dpotrs_("L", &order, &columns, s.S.data(), &order, s.G.data(), &order, &info, 1);
    FLEXMBS_CHECK(info == 0, "substructured factor: LAPACK dpotrs failed");
  }
  if (m > 0) {
    for (std::size_t c = 0; c < k; ++c) {
      for (std::size_t a = 0; a < m; ++a)
        s.reduced[a + c * m] = s.G[static_cast<std::size_t>(s.schur_position[a]) + c * n];
    }
    Icntl(id, 26) = kExpand;
    s.Mumps(kJobSolve);
  }
  for (std::size_t c = 0; c < k; ++c) {
    for (std::size_t li = 0; li < s.interior.size(); ++li) {
      X[static_cast<std::size_t>(s.interior[li]) + c * rows] = s.rhs[li + c * local];
    }
    for (std::size_t r = 0; r < s.own_interface.size(); ++r) {
      X[static_cast<std::size_t>(s.own_interface[r]) + c * rows] =
          s.G[static_cast<std::size_t>(s.own_position[r]) + c * n];
    }
  }
}

}  // namespace flexmbs::eigensolvers
