// The ASCII SID export (docs/sid-ascii.md): the file is read back by a small parser written
// here from the documented layout (not from the writer), and every m0/m1 entry must come back
// as the same double; the remapped blocks (J as a 6-vector, Gr and Ge grouped by axis) must give
// the same inertia and gyroscopic terms as the body's own blocks.
#include "sid/sid_ascii.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "tests/input_error.h"

namespace flexmbs::sid {
namespace {

namespace fs = std::filesystem;

class SidAsciiTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / fmt::format("flexmbs_sid_ascii_{}_{}", info->name(), getpid());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
};

// --- a body with values that test the number format: full 53-bit mantissas over the whole
// exponent range, subnormals, the extremes, signed zeros ------------------------------------

constexpr Eigen::Index kModes = 3;
constexpr Eigen::Index kFeNodes = 4;

class Values {
 public:
  double Next() {
    std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-300, 300);
    const double m = mantissa(rng_);
    return std::ldexp(m, exponent(rng_));
  }
  Eigen::MatrixXd Matrix(Eigen::Index rows, Eigen::Index cols) {
    Eigen::MatrixXd m(rows, cols);
    for (Eigen::Index i = 0; i < rows; ++i) {
      for (Eigen::Index j = 0; j < cols; ++j) m(i, j) = Next();
    }
    return m;
  }
  Eigen::MatrixXd Symmetric(Eigen::Index size) {
    const Eigen::MatrixXd a = Matrix(size, size);
    Eigen::MatrixXd s = a;
    s.triangularView<Eigen::StrictlyLower>() = a.transpose().triangularView<Eigen::StrictlyLower>();
    return s;
  }
  TaylorMatrix Taylor(Eigen::Index rows, Eigen::Index cols, int order) {
    TaylorMatrix block;
    block.m0 = Matrix(rows, cols);
    for (Eigen::Index k = 0; order >= 1 && k < kModes; ++k) block.m1.push_back(Matrix(rows, cols));
    for (Eigen::Index k = 0; order >= 2 && k < kModes * kModes; ++k) block.m2.push_back(Matrix(rows, cols));
    return block;
  }

 private:
  std::mt19937_64 rng_{20240611};
};

ReducedBody SampleBody() {
  Values v;
  const Eigen::Index n = kModes;
  ReducedBody body;
  body.name = "bracket";
  body.mass = 1.0 / 3.0;
  body.mode_names = {"constraint_tip_tx", "normal_1", "normal_2"};
  body.mode_kinds = {"constraint", "normal", "normal"};
  body.frequency_hz = Eigen::Vector3d(std::nan(""), 12.5, 1.0 / 7.0);
  body.relative_residuals = Eigen::Vector3d(std::nan(""), 1e-12, 3e-11);
  body.mdCM = v.Taylor(3, 1, 1);
  body.J = v.Taylor(3, 3, 2);
  body.J.m0 = v.Symmetric(3);
  for (Eigen::MatrixXd& m1 : body.J.m1) m1 = v.Symmetric(3);
  body.Ct = v.Taylor(n, 3, 1);
  // Extremes of the double range and exact zeros of either sign (zeros are not written).
  body.Ct.m0.col(0) << DBL_MAX, -DBL_TRUE_MIN, 0.0;
  body.Ct.m0.col(1) << -DBL_MIN, 4.9406564584124654e-324, -0.0;
  body.Cr = v.Taylor(n, 3, 1);
  body.Me = {Eigen::MatrixXd::Identity(n, n), {}, {}};
  body.Gr = v.Taylor(3, 3 * n, 1);
  body.Ge = v.Taylor(n, 3 * n, 0);
  body.Oe = v.Taylor(n, 6, 1);
  body.Ke = {v.Symmetric(n), {}, {}};
  body.De = {Eigen::Vector3d(v.Next(), v.Next(), v.Next()).asDiagonal(), {}, {}};
  body.ksigma = {Eigen::MatrixXd::Zero(n, 1), {}, {}};
  for (auto* cases : {&body.stiffening.K0t, &body.stiffening.K0r}) {
    for (Eigen::MatrixXd& K : *cases) K = v.Matrix(n, n);
  }
  for (Eigen::MatrixXd& K : body.stiffening.K0omega) K = v.Matrix(n, n);
  body.node_positions = v.Matrix(3, kFeNodes);
  body.phi = v.Matrix(3 * kFeNodes, n);
  Node tip;
  tip.name = "tip";
  tip.fe_nodes = {2, 3};
  tip.coupling = "rigid";
  tip.origin = v.Taylor(3, 1, 1);
  tip.phi = v.Taylor(3, n, 1);
  tip.psi = v.Taylor(3, n, 1);
  tip.AP = v.Taylor(3, 3, 1);
  Node hub;
  hub.name = "hub";
  hub.fe_nodes = {0};
  hub.coupling = "node";
  hub.origin = v.Taylor(3, 1, 1);
  hub.phi = v.Taylor(3, n, 0);
  hub.psi = v.Taylor(3, n, 0);
  hub.AP = v.Taylor(3, 3, 1);
  hub.AP.m0 = Eigen::Matrix3d::Identity();
  body.nodes = {tip, hub};
  ContactSurface pad;
  pad.name = "pad";
  pad.fe_nodes = {0, 1, 2};
  pad.vertices = v.Matrix(3, 3);
  pad.face_sizes = {3};
  pad.face_vertices = {0, 1, 2};
  pad.face_normals = Eigen::MatrixX3d::Zero(1, 3);
  pad.phi = v.Matrix(9, n);
  body.surfaces = {pad};
  body.provenance = {{"mesh", "bracket.msh"}};
  return body;
}

// --- an independent reader of the block structure (docs/sid-ascii.md) ----------------------

std::string Trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t");
  if (begin == std::string::npos) return "";
  return s.substr(begin, s.find_last_not_of(" \t") - begin + 1);
}

double ReadFortranNumber(std::string text) {
  for (char& c : text) {
    if (c == 'D') c = 'E';
  }
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  EXPECT_EQ(*end, '\0') << "not a number: '" << text << "'";
  return value;
}

std::vector<int> Indices(const std::string& key) {
  const auto open = key.find('('), close = key.find(')');
  std::vector<int> indices;
  std::stringstream list(key.substr(open + 1, close - open - 1));
  for (std::string item; std::getline(list, item, ',');) indices.push_back(std::stoi(item));
  return indices;
}

struct ParsedTaylor {
  std::map<std::string, long> header;          // order, nrow, ncol, nq, nqn, structure
  std::map<std::array<int, 2>, double> m0;     // (row, column), 1-based
  std::map<std::array<int, 3>, double> m1;     // (row, mode, column), 1-based
  int repeated_entries = 0;
};

struct ParsedFile {
  std::vector<std::string> lines;                // trimmed, header line included
  std::vector<std::string> modal_items;          // items directly inside `new modal`, in order
  std::map<std::string, std::string> refmod;     // key -> value (ielastq(k) keyed as written)
  std::vector<std::string> nodes;                // `new node` values, in order
  std::map<std::string, std::string> rframe;     // node -> rframe
  std::map<std::string, ParsedTaylor> blocks;    // "J", "node 1/origin", ...
  std::vector<std::string> errors;               // structural problems found while reading
};

ParsedFile Parse(const fs::path& path) {
  ParsedFile file;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) file.lines.push_back(Trim(line));
  std::vector<std::string> open;  // open items, innermost last
  std::string node;
  for (std::size_t number = 1; number < file.lines.size(); ++number) {
    const std::string& line = file.lines[number];
    const std::string where = fmt::format("line {}: '{}'", number + 1, line);
    const auto equals = line.find('=');
    const std::string key = Trim(line.substr(0, equals));
    const std::string value = equals == std::string::npos ? "" : Trim(line.substr(equals + 1));
    const std::string top = open.empty() ? "" : open.back();
    if (line.starts_with("end ")) {
      const std::string name = line.substr(4);
      const std::string expected = top.starts_with("node ") ? "node" : top;
      if (name != expected) file.errors.push_back(where + " closes '" + top + "'");
      if (top.starts_with("node ")) node.clear();
      if (!open.empty()) open.pop_back();
    } else if (key == "new modal") {
      open.push_back("modal");
    } else if (key == "new node") {
      node = "node " + value;
      file.nodes.push_back(value);
      open.push_back(node);
    } else if (top == "modal" && equals == std::string::npos) {
      file.modal_items.push_back(line);
      open.push_back(line);
      if (line != "refmod" && line != "frame") file.blocks[line];
    } else if (top.starts_with("node ") && equals == std::string::npos) {
      open.push_back(line);
      file.blocks[node + "/" + line];
    } else if (line == "part" && open.empty()) {
      open.push_back("part");
    } else if (top == "refmod") {
      file.refmod[key] = value;
    } else if (top.starts_with("node ") && key == "rframe") {
      file.rframe[node] = value;
    } else if (file.blocks.contains(node.empty() ? top : node + "/" + top) && equals != std::string::npos) {
      ParsedTaylor& block = file.blocks[node.empty() ? top : node + "/" + top];
      const std::vector<int> at = key.starts_with("m") ? Indices(key) : std::vector<int>{};
      if (key.starts_with("m0(") && at.size() == 2) {
        block.repeated_entries += block.m0.contains({at[0], at[1]});
        block.m0[{at[0], at[1]}] = ReadFortranNumber(value);
      } else if (key.starts_with("m1(") && at.size() == 3) {
        block.repeated_entries += block.m1.contains({at[0], at[1], at[2]});
        block.m1[{at[0], at[1], at[2]}] = ReadFortranNumber(value);
      } else {
        block.header[key] = std::stol(value);
      }
    } else {
      file.errors.push_back(where + " is not expected inside '" + top + "'");
    }
  }
  if (!open.empty()) file.errors.push_back("unclosed '" + open.back() + "' at the end");
  return file;
}

// --- the documented mapping, restated ---------------------------------------------------------

struct Expected {
  Eigen::MatrixXd m0;
  std::vector<Eigen::MatrixXd> m1;
};

Expected Same(const TaylorMatrix& t) { return {t.m0, t.m1}; }

// J as [xx, yy, zz, xy, xz, yz].
Eigen::MatrixXd SixVector(const Eigen::MatrixXd& J) {
  Eigen::MatrixXd v(6, 1);
  v << J(0, 0), J(1, 1), J(2, 2), J(0, 1), J(0, 2), J(1, 2);
  return v;
}
Expected Inertia(const TaylorMatrix& J) {
  Expected e{SixVector(J.m0), {}};
  for (const Eigen::MatrixXd& m1 : J.m1) e.m1.push_back(SixVector(m1));
  return e;
}

// File column a n + k = column a of mode k's block (columns 3 k + a in flexmbs).
Eigen::MatrixXd ByAxis(const Eigen::MatrixXd& per_mode) {
  const Eigen::Index n = per_mode.cols() / 3;
  Eigen::MatrixXd out(per_mode.rows(), per_mode.cols());
  for (Eigen::Index a = 0; a < 3; ++a) {
    for (Eigen::Index k = 0; k < n; ++k) out.col(a * n + k) = per_mode.col(3 * k + a);
  }
  return out;
}
Expected AxisGrouped(const TaylorMatrix& t) {
  Expected e{ByAxis(t.m0), {}};
  for (const Eigen::MatrixXd& m1 : t.m1) e.m1.push_back(ByAxis(m1));
  return e;
}

// Every m0 and m1 entry of `block` equals `expected` bit for bit (== also makes -0 equal 0,
// the one value the file does not keep), and no entry lies outside the block.
void ExpectEntries(const ParsedTaylor& block, const Expected& expected, const std::string& name) {
  SCOPED_TRACE(name);
  ASSERT_EQ(block.header.at("nrow"), expected.m0.rows());
  ASSERT_EQ(block.header.at("ncol"), expected.m0.cols());
  EXPECT_EQ(block.header.at("nq"), kModes);
  EXPECT_EQ(block.header.at("nqn"), 0);
  EXPECT_EQ(block.header.at("order"), expected.m1.empty() ? 0 : 1);
  EXPECT_EQ(block.repeated_entries, 0);
  int mismatches = 0;
  for (Eigen::Index i = 0; i < expected.m0.rows(); ++i) {
    for (Eigen::Index j = 0; j < expected.m0.cols(); ++j) {
      const auto found = block.m0.find({static_cast<int>(i + 1), static_cast<int>(j + 1)});
      const double read = found == block.m0.end() ? 0.0 : found->second;
      mismatches += read != expected.m0(i, j);
      for (std::size_t k = 0; k < expected.m1.size(); ++k) {
        const auto f1 = block.m1.find({static_cast<int>(i + 1), static_cast<int>(k + 1), static_cast<int>(j + 1)});
        const double read1 = f1 == block.m1.end() ? 0.0 : f1->second;
        mismatches += read1 != expected.m1[k](i, j);
      }
    }
  }
  EXPECT_EQ(mismatches, 0);
  for (const auto& [at, value] : block.m0) {
    EXPECT_TRUE(at[0] >= 1 && at[0] <= expected.m0.rows() && at[1] >= 1 && at[1] <= expected.m0.cols());
  }
  for (const auto& [at, value] : block.m1) {
    EXPECT_TRUE(at[1] >= 1 && at[1] <= static_cast<int>(expected.m1.size()) && at[0] <= expected.m0.rows() &&
                at[2] <= expected.m0.cols());
  }
}

// A parsed block back as a dense m0 and one m1 per mode.
Expected Dense(const ParsedTaylor& block) {
  Expected e{Eigen::MatrixXd::Zero(block.header.at("nrow"), block.header.at("ncol")), {}};
  if (block.header.at("order") >= 1) {
    e.m1.assign(static_cast<std::size_t>(block.header.at("nq")), Eigen::MatrixXd::Zero(e.m0.rows(), e.m0.cols()));
  }
  for (const auto& [at, value] : block.m0) e.m0(at[0] - 1, at[1] - 1) = value;
  for (const auto& [at, value] : block.m1) e.m1[static_cast<std::size_t>(at[1] - 1)](at[0] - 1, at[2] - 1) = value;
  return e;
}

// --- tests ----------------------------------------------------------------------------------

TEST_F(SidAsciiTest, FileHasTheSidBlockStructure) {
  const fs::path path = dir_ / "bracket.SID_FEM";
  WriteSidAscii(path, SampleBody());
  const ParsedFile file = Parse(path);
  EXPECT_TRUE(file.errors.empty()) << file.errors.front();
  ASSERT_GE(file.lines.size(), 4u);
  // Header: node and mode counts first (tools read them), then the node numbering.
  std::istringstream header(file.lines[0]);
  int nodes = 0, modes = 0;
  header >> nodes >> modes;
  EXPECT_EQ(nodes, 2);
  EXPECT_EQ(modes, kModes);
  EXPECT_NE(file.lines[0].find("nodes: 1 = tip, 2 = hub"), std::string::npos) << file.lines[0];
  EXPECT_EQ(file.lines[1], "part");
  EXPECT_EQ(file.lines[2], "new modal =");
  EXPECT_EQ(file.lines[file.lines.size() - 2], "end modal");
  EXPECT_EQ(file.lines.back(), "end part");
  // The SID items in their order, and nothing else (surfaces and the stiffening split have no
  // ASCII counterpart).
  EXPECT_EQ(file.modal_items, (std::vector<std::string>{"refmod", "frame", "mdCM", "J", "Ct", "Cr", "Me", "Gr",
                                                         "Ge", "Oe", "ksigma", "Ke", "De"}));
  EXPECT_EQ(file.nodes, (std::vector<std::string>{"1", "2"}));
  for (const std::string node : {"node 1", "node 2"}) {
    EXPECT_EQ(file.rframe.at(node), "body ref");
    for (const std::string item : {"origin", "phi", "psi", "AP"}) {
      EXPECT_TRUE(file.blocks.contains(node + "/" + item)) << node << "/" << item;
    }
  }
}

TEST_F(SidAsciiTest, RefmodHoldsMassAndModes) {
  const ReducedBody body = SampleBody();
  const fs::path path = dir_ / "bracket.SID_FEM";
  WriteSidAscii(path, body);
  const ParsedFile file = Parse(path);
  EXPECT_EQ(ReadFortranNumber(file.refmod.at("mass")), body.mass);
  EXPECT_EQ(file.refmod.at("nelastq"), "3");
  EXPECT_EQ(file.refmod.at("ielastq(   1)"), "constraint_tip_tx");
  EXPECT_EQ(file.refmod.at("ielastq(   2)"), "normal_1 : 12.5 Hz");
  const std::string third = file.refmod.at("ielastq(   3)");
  ASSERT_TRUE(third.starts_with("normal_2 : ") && third.ends_with(" Hz")) << third;
  EXPECT_EQ(std::strtod(third.substr(11).c_str(), nullptr), 1.0 / 7.0);
}

TEST_F(SidAsciiTest, EveryEntryReadsBackExactly) {
  const ReducedBody body = SampleBody();
  const fs::path path = dir_ / "bracket.SID_FEM";
  WriteSidAscii(path, body);
  const ParsedFile file = Parse(path);
  ASSERT_TRUE(file.errors.empty()) << file.errors.front();
  ExpectEntries(file.blocks.at("mdCM"), Same(body.mdCM), "mdCM");
  ExpectEntries(file.blocks.at("J"), Inertia(body.J), "J");
  ExpectEntries(file.blocks.at("Ct"), Same(body.Ct), "Ct");
  ExpectEntries(file.blocks.at("Cr"), Same(body.Cr), "Cr");
  ExpectEntries(file.blocks.at("Me"), Same(body.Me), "Me");
  ExpectEntries(file.blocks.at("Gr"), AxisGrouped(body.Gr), "Gr");
  ExpectEntries(file.blocks.at("Ge"), AxisGrouped(body.Ge), "Ge");
  ExpectEntries(file.blocks.at("Oe"), Same(body.Oe), "Oe");
  ExpectEntries(file.blocks.at("ksigma"), Same(body.ksigma), "ksigma");
  ExpectEntries(file.blocks.at("Ke"), Same(body.Ke), "Ke");
  ExpectEntries(file.blocks.at("De"), Same(body.De), "De");
  for (std::size_t k = 0; k < body.nodes.size(); ++k) {
    const std::string node = fmt::format("node {}/", k + 1);
    ExpectEntries(file.blocks.at(node + "origin"), Same(body.nodes[k].origin), node + "origin");
    ExpectEntries(file.blocks.at(node + "phi"), Same(body.nodes[k].phi), node + "phi");
    ExpectEntries(file.blocks.at(node + "psi"), Same(body.nodes[k].psi), node + "psi");
    ExpectEntries(file.blocks.at(node + "AP"), Same(body.nodes[k].AP), node + "AP");
  }
  // Zeros are left out: Ct's m0 has two, every other entry of the sample is non-zero.
  EXPECT_EQ(file.blocks.at("Ct").m0.size(), static_cast<std::size_t>(3 * kModes - 2));
}

TEST_F(SidAsciiTest, StructureCodeSaysWhatM0Is) {
  WriteSidAscii(dir_ / "b.SID_FEM", SampleBody());
  const ParsedFile file = Parse(dir_ / "b.SID_FEM");
  // SID codes: 0 zero, 1 diagonal, 2 symmetric, 3 full, 4 unit matrix.
  EXPECT_EQ(file.blocks.at("ksigma").header.at("structure"), 0);
  EXPECT_EQ(file.blocks.at("De").header.at("structure"), 1);
  EXPECT_EQ(file.blocks.at("Ke").header.at("structure"), 2);
  EXPECT_EQ(file.blocks.at("Ct").header.at("structure"), 3);
  EXPECT_EQ(file.blocks.at("Me").header.at("structure"), 4);
  // Order-1 blocks are "full" even with a symmetric or unit m0, and list every entry.
  EXPECT_EQ(file.blocks.at("J").header.at("structure"), 3);
  EXPECT_EQ(file.blocks.at("node 2/AP").header.at("structure"), 3);
  EXPECT_EQ(file.blocks.at("node 2/AP").m0.size(), 3u);
  EXPECT_EQ(file.blocks.at("Ke").m0.size(), static_cast<std::size_t>(kModes * kModes)) << "both triangles";
}

// The remapped blocks mean what the body's blocks mean: J(q) without its order-2 term, and the
// gyroscopic terms sum_k Gr_k(q) w qdot_k (3-vector) and sum_k Ge_k w qdot_k (n-vector), with
// the file's column (a n + k) multiplying w_a qdot_k.
TEST_F(SidAsciiTest, InertiaAndGyroscopicTermsAgreeWithTheBody) {
  // Sums of a few products of values of order 1: relative round-off of double arithmetic.
  constexpr double kRoundOff = 1e-12;
  ReducedBody body = SampleBody();
  // Values of order 1, so that no single term dominates the sums below.
  body.Gr = {Eigen::MatrixXd::Random(3, 3 * kModes), {}, {}};
  for (Eigen::Index k = 0; k < kModes; ++k) body.Gr.m1.push_back(Eigen::MatrixXd::Random(3, 3 * kModes));
  body.Ge = {Eigen::MatrixXd::Random(kModes, 3 * kModes), {}, {}};
  for (Eigen::MatrixXd* J : {&body.J.m0, &body.J.m1[0], &body.J.m1[1], &body.J.m1[2]}) {
    const Eigen::Matrix3d a = Eigen::Matrix3d::Random();
    *J = a + a.transpose();
  }
  const fs::path path = dir_ / "b.SID_FEM";
  WriteSidAscii(path, body);
  const ParsedFile file = Parse(path);

  const Eigen::Vector3d q(0.3, -0.7, 1.1), qdot(-0.4, 0.9, 0.2), w(0.5, -1.3, 0.8);
  // J(q) from the 6-vector.
  const Expected j_file = Dense(file.blocks.at("J"));
  Eigen::VectorXd j6 = j_file.m0;
  for (Eigen::Index k = 0; k < kModes; ++k) j6 += q(k) * j_file.m1[static_cast<std::size_t>(k)];
  Eigen::Matrix3d J_file;
  J_file << j6(0), j6(3), j6(4), j6(3), j6(1), j6(5), j6(4), j6(5), j6(2);
  TaylorMatrix J_linear = body.J;
  J_linear.m2.clear();
  EXPECT_LT((J_file - J_linear.Evaluate(q)).norm(), kRoundOff * J_linear.Evaluate(q).norm());

  // Gr: the body's per-mode blocks at q against the file's axis-grouped columns.
  const Eigen::MatrixXd Gr_q = body.Gr.Evaluate(q);
  Eigen::Vector3d h_body = Eigen::Vector3d::Zero();
  for (Eigen::Index k = 0; k < kModes; ++k) h_body += Gr_q.middleCols(3 * k, 3) * w * qdot(k);
  const Expected gr_file = Dense(file.blocks.at("Gr"));
  Eigen::MatrixXd Gr_file_q = gr_file.m0;
  for (Eigen::Index k = 0; k < kModes; ++k) Gr_file_q += q(k) * gr_file.m1[static_cast<std::size_t>(k)];
  Eigen::Vector3d h_file = Eigen::Vector3d::Zero();
  for (Eigen::Index a = 0; a < 3; ++a) {
    for (Eigen::Index k = 0; k < kModes; ++k) h_file += Gr_file_q.col(a * kModes + k) * w(a) * qdot(k);
  }
  EXPECT_LT((h_file - h_body).norm(), kRoundOff * h_body.norm());

  Eigen::VectorXd g_body = Eigen::VectorXd::Zero(kModes);
  for (Eigen::Index k = 0; k < kModes; ++k) g_body += body.Ge.m0.middleCols(3 * k, 3) * w * qdot(k);
  const Eigen::MatrixXd Ge_file = Dense(file.blocks.at("Ge")).m0;
  Eigen::VectorXd g_file = Eigen::VectorXd::Zero(kModes);
  for (Eigen::Index a = 0; a < 3; ++a) {
    for (Eigen::Index k = 0; k < kModes; ++k) g_file += Ge_file.col(a * kModes + k) * w(a) * qdot(k);
  }
  EXPECT_LT((g_file - g_body).norm(), kRoundOff * g_body.norm());
}

TEST_F(SidAsciiTest, ReplacesAnExistingFileAndLeavesNoTemporary) {
  const fs::path path = dir_ / "b.SID_FEM";
  std::ofstream(path) << "old content\n";
  WriteSidAscii(path, SampleBody());
  EXPECT_EQ(Parse(path).lines.back(), "end part");
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"b.SID_FEM"});
}

TEST_F(SidAsciiTest, UnwritableFolderIsAnInputErrorNamingTheFile) {
  const fs::path path = dir_ / "missing" / "b.SID_FEM";
  const std::string message = testing::InputErrorMessage([&] { WriteSidAscii(path, SampleBody()); });
  EXPECT_TRUE(message.starts_with(path.string() + ": ")) << message;
  EXPECT_FALSE(fs::exists(dir_ / "missing"));
}

TEST_F(SidAsciiTest, InconsistentOrNonFiniteBodyIsAnInternalErrorAndWritesNothing) {
  ReducedBody wrong_shape = SampleBody();
  wrong_shape.Ct.m0.resize(2, 3);
  EXPECT_THROW(WriteSidAscii(dir_ / "a.SID_FEM", wrong_shape), InternalError);
  ReducedBody not_finite = SampleBody();
  not_finite.Oe.m1[1](0, 4) = std::nan("");
  EXPECT_THROW(WriteSidAscii(dir_ / "b.SID_FEM", not_finite), InternalError);
  EXPECT_TRUE(fs::is_empty(dir_));
}

}  // namespace
}  // namespace flexmbs::sid
