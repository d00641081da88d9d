// The ASCII SID export (docs/sid-ascii.md): flexmbs' Taylor blocks mapped to the layout of the
// files SIMPACK's FEMBS writes, and written line by line.
#include "sid/sid_ascii.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/version.h"
#include "sid/sid_file.h"

namespace flexmbs::sid {
namespace {

/// A Taylor block in the file's layout: m0 and one m1 per modal coordinate (none for order 0).
struct FileBlock {
  Eigen::MatrixXd m0;
  std::vector<Eigen::MatrixXd> m1;
};

/// The SID `structure` codes: what m0 is (Wallrapp 1994; FEMBS writes all five).
enum Structure { kZero = 0, kDiagonal = 1, kSymmetric = 2, kFull = 3, kUnit = 4 };

bool AllZero(const Eigen::MatrixXd& m) { return (m.array() == 0.0).all(); }

/// The code of a block: kZero if m0 and every m1 vanish; for order-0 square blocks kUnit,
/// kDiagonal or kSymmetric when m0 is exactly so; kFull otherwise. Every non-zero entry is
/// written whatever the code, so a reader that ignores the code reads the same block.
Structure StructureOf(const FileBlock& block) {
  const Eigen::MatrixXd& m0 = block.m0;
  if (AllZero(m0) && std::all_of(block.m1.begin(), block.m1.end(), AllZero)) return kZero;
  if (!block.m1.empty() || m0.rows() != m0.cols()) return kFull;
  if (m0 == Eigen::MatrixXd::Identity(m0.rows(), m0.cols())) return kUnit;
  if (m0.isDiagonal(0.0)) return kDiagonal;
  if (m0 == m0.transpose()) return kSymmetric;
  return kFull;
}

/// flexmbs' block in the same layout (an order-2 term is left out).
FileBlock AsIs(const TaylorMatrix& block) { return {block.m0, block.m1}; }

/// The entries of a symmetric 3 x 3 matrix in the order of the file's 6 x 1 inertia column.
constexpr std::array<std::pair<int, int>, 6> kInertiaEntries{{{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}}};

Eigen::MatrixXd InertiaColumn(const Eigen::MatrixXd& J) {
  Eigen::MatrixXd column(6, 1);
  for (std::size_t e = 0; e < kInertiaEntries.size(); ++e) {
    column(static_cast<Eigen::Index>(e), 0) = J(kInertiaEntries[e].first, kInertiaEntries[e].second);
  }
  return column;
}

/// J (3 x 3, symmetric) as the file's 6 x 1 column [xx, yy, zz, xy, xz, yz], m0 and m1.
FileBlock InertiaBlock(const TaylorMatrix& J) {
  FileBlock block{InertiaColumn(J.m0), {}};
  for (const Eigen::MatrixXd& m1 : J.m1) block.m1.push_back(InertiaColumn(m1));
  return block;
}

/// A rows x 3n matrix [X_1 .. X_n] of per-mode blocks X_k (rows x 3: flexmbs' Gr and Ge) with
/// its columns grouped by axis instead: column a n + k holds column a of X_k (0-based).
Eigen::MatrixXd ColumnsByAxis(const Eigen::MatrixXd& per_mode) {
  const Eigen::Index n = per_mode.cols() / 3;
  Eigen::MatrixXd by_axis(per_mode.rows(), per_mode.cols());
  for (Eigen::Index k = 0; k < n; ++k) {
    for (Eigen::Index a = 0; a < 3; ++a) by_axis.col(a * n + k) = per_mode.col(3 * k + a);
  }
  return by_axis;
}

FileBlock AxisGroupedBlock(const TaylorMatrix& per_mode) {
  FileBlock block{ColumnsByAxis(per_mode.m0), {}};
  for (const Eigen::MatrixXd& m1 : per_mode.m1) block.m1.push_back(ColumnsByAxis(m1));
  return block;
}

/// `value` with 17 significant digits and a Fortran exponent, a space before positive values as
/// FEMBS writes them: " 1.2500000000000000D+00". Enough digits to read back the same double.
std::string FortranNumber(double value, std::string_view item) {
  FLEXMBS_CHECK(std::isfinite(value), fmt::format("ASCII SID: {} holds a non-finite value", item));
  std::string text = fmt::format("{: .16E}", value);
  std::replace(text.begin(), text.end(), 'E', 'D');
  return text;
}

/// `text` on one line (names come from user files).
std::string OneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

/// Indented lines with the keys aligned, as FEMBS writes them.
class Writer {
 public:
  explicit Writer(std::ostream& out) : out_(out) {}

  void Line(std::string_view text) { out_ << std::string(4 * depth_, ' ') << text << '\n'; }
  /// `key = value` (numbers carry their own sign column: `key =-1.0D+00`).
  void Entry(std::string_view key, std::string_view value) {
    Line(fmt::format("{:<22}={}", key, value));
  }
  void Integer(std::string_view key, long long value) { Entry(key, fmt::format(" {}", value)); }
  /// Writes `line` and indents what follows until Close.
  void Open(std::string_view line) {
    Line(line);
    ++depth_;
  }
  /// Ends the innermost open item with `end <name>`.
  void Close(std::string_view name) {
    FLEXMBS_CHECK(depth_ > 0, "ASCII SID: more ends than opened items");
    --depth_;
    Line(fmt::format("end {}", name));
  }

  /// A Taylor block for `num_modes` modal coordinates: its header, then the non-zero entries
  /// m0(row, column) row by row and m1(row, mode, column) by column, row and mode (1-based).
  void Taylor(std::string_view name, const FileBlock& block, Eigen::Index num_modes) {
    Open(name);
    Integer("order", block.m1.empty() ? 0 : 1);
    Integer("nrow", block.m0.rows());
    Integer("ncol", block.m0.cols());
    Integer("nq", num_modes);
    Integer("nqn", 0);
    Integer("structure", StructureOf(block));
    for (Eigen::Index i = 0; i < block.m0.rows(); ++i) {
      for (Eigen::Index j = 0; j < block.m0.cols(); ++j) {
        if (block.m0(i, j) == 0.0) continue;
        Entry(fmt::format("m0({:2d},{:2d})", i + 1, j + 1), FortranNumber(block.m0(i, j), name));
      }
    }
    for (Eigen::Index j = 0; j < block.m0.cols(); ++j) {
      for (Eigen::Index i = 0; i < block.m0.rows(); ++i) {
        for (std::size_t k = 0; k < block.m1.size(); ++k) {
          const double value = block.m1[k](i, j);
          if (value == 0.0) continue;
          Entry(fmt::format("m1({:2d},{:2d},{:2d})", i + 1, k + 1, j + 1), FortranNumber(value, name));
        }
      }
    }
    Close(name);
  }

 private:
  std::ostream& out_;
  std::size_t depth_ = 0;
};

/// The first line: node and mode counts (read by some tools), then what the file is and which
/// marker node each `new node` number stands for.
std::string HeaderLine(const ReducedBody& body) {
  std::string nodes;
  for (std::size_t k = 0; k < body.nodes.size(); ++k) {
    nodes += fmt::format("{}{} = {}", k == 0 ? "" : ", ", k + 1, OneLine(body.nodes[k].name));
  }
  return fmt::format("{:5d} {:4d}    :No. nodes, No. modes: flexmbs {} ASCII SID of '{}'; nodes: {}",
                     body.nodes.size(), body.num_modes(), Version(), OneLine(body.name),
                     nodes.empty() ? "none" : nodes);
}

void WriteRefmod(Writer& w, const ReducedBody& body) {
  w.Open("refmod");
  w.Entry("mass", FortranNumber(body.mass, "refmod mass"));
  w.Integer("nelastq", body.num_modes());
  for (Eigen::Index k = 0; k < body.num_modes(); ++k) {
    const std::string name = OneLine(body.mode_names[static_cast<std::size_t>(k)]);
    const double f = body.frequency_hz(k);
    w.Entry(fmt::format("ielastq({:4d})", k + 1),
            std::isfinite(f) ? fmt::format(" {} : {:.17g} Hz", name, f) : fmt::format(" {}", name));
  }
  w.Close("refmod");
}

void WriteFrame(Writer& w, const ReducedBody& body) {
  const Eigen::Index n = body.num_modes();
  w.Open("frame");
  for (std::size_t k = 0; k < body.nodes.size(); ++k) {
    const Node& node = body.nodes[k];
    w.Open(fmt::format("{:<22}= {}", "new node", k + 1));
    w.Entry("rframe", " body ref");
    w.Taylor("origin", AsIs(node.origin), n);
    w.Taylor("phi", AsIs(node.phi), n);
    w.Taylor("psi", AsIs(node.psi), n);
    w.Taylor("AP", AsIs(node.AP), n);
    w.Close("node");
  }
  w.Close("frame");
}

void WriteBody(std::ostream& out, const ReducedBody& body) {
  const Eigen::Index n = body.num_modes();
  Writer w(out);
  w.Line(HeaderLine(body));
  w.Open("part");
  w.Open("new modal =");
  WriteRefmod(w, body);
  WriteFrame(w, body);
  w.Taylor("mdCM", AsIs(body.mdCM), n);
  w.Taylor("J", InertiaBlock(body.J), n);
  w.Taylor("Ct", AsIs(body.Ct), n);
  w.Taylor("Cr", AsIs(body.Cr), n);
  w.Taylor("Me", AsIs(body.Me), n);
  w.Taylor("Gr", AxisGroupedBlock(body.Gr), n);
  w.Taylor("Ge", AxisGroupedBlock(body.Ge), n);
  w.Taylor("Oe", AsIs(body.Oe), n);
  w.Taylor("ksigma", AsIs(body.ksigma), n);
  w.Taylor("Ke", AsIs(body.Ke), n);
  w.Taylor("De", AsIs(body.De), n);
  w.Close("modal");
  w.Close("part");
}

}  // namespace

void WriteSidAscii(const std::filesystem::path& path, const ReducedBody& body) {
  CheckConsistent(body);
  WriteFileAtomically(path, [&body](std::ostream& out) { WriteBody(out, body); });
}

}  // namespace flexmbs::sid
