#include "gear_tooth_fe/tooth_model.h"

#include <fmt/format.h>
#include <unistd.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/error.h"
#include "fem/assembly.h"
#include "fem/gmsh_import.h"
#include "fem/material.h"

namespace flexmbs::gear_tooth_fe {
namespace {

namespace fs = std::filesystem;

/// A scratch .geo file, removed when it goes out of scope.
class ScratchGeo {
 public:
  explicit ScratchGeo(const std::string& text)
      : path_(fs::temp_directory_path() /
              fmt::format("flexmbs_gear_tooth_{}_{}.geo", ::getpid(), counter_++)) {
    std::ofstream out(path_);
    out << text;
    if (!out) throw InputError(fmt::format("{}: cannot write the FE tooth", path_.string()));
  }
  ~ScratchGeo() {
    std::error_code ec;
    fs::remove(path_, ec);
  }
  ScratchGeo(const ScratchGeo&) = delete;
  ScratchGeo& operator=(const ScratchGeo&) = delete;
  const fs::path& path() const { return path_; }

 private:
  static inline int counter_ = 0;
  fs::path path_;
};

/// The nodes at p in the transverse plane (any z), sorted by z.
std::vector<int> NodesAt(const fem::Mesh& mesh, const Eigen::Vector2d& p, double tolerance) {
  std::vector<int> nodes;
  for (Eigen::Index n = 0; n < mesh.num_nodes(); ++n) {
    if ((mesh.nodes.col(n).head<2>() - p).norm() <= tolerance) nodes.push_back(static_cast<int>(n));
  }
  std::sort(nodes.begin(), nodes.end(),
            [&](int a, int b) { return mesh.nodes(2, a) < mesh.nodes(2, b); });
  FLEXMBS_CHECK(nodes.size() == 2 || nodes.size() == 3,
                "an FE tooth's load or centre point is not a vertex through the slab");
  return nodes;
}

/// The consistent weights of a unit load along an element edge through the slab (2 or 3 nodes).
std::vector<double> EdgeWeights(std::size_t count) {
  if (count == 2) return {0.5, 0.5};
  return {1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0};
}

/// True for a node on the clamped boundary: the bore or a cut face.
bool Clamped(const Eigen::Vector3d& p, const ToothGeometry& g, double tolerance) {
  const Eigen::Vector2d xy = p.head<2>();
  if (xy.norm() <= g.bore_radius + tolerance) return true;
  const double c = std::cos(g.segment_angle), s = std::sin(g.segment_angle);
  return std::abs(std::abs(xy.x()) * c - xy.y() * s) <= tolerance;
}

/// The segment of `options` solved: its outline, mesh, free DOFs and the displacements of one
/// load case per load point (a unit force along -n at the loaded tooth's flank point, i.e.
/// w = 1 / b per face width), the cut faces and the bore clamped, z held (plane strain).
struct SolvedSegment {
  ToothGeometry geometry;
  fem::Mesh mesh;
  std::vector<int> free_index;  ///< per DOF 3 n + i its column in u, -1 where held
  Eigen::MatrixXd u;            ///< free DOFs x load cases
  double tolerance = 0.0;       ///< [m] for finding vertices
};

SolvedSegment SolveSegment(const contact::SpurGear& gear, const contact::ToothMaterial& material,
                           const ToothModelOptions& options) {
  fem::IsotropicMaterial steel{"tooth", material.youngs_modulus, material.poisson_ratio, 7850.0};
  fem::ValidateMaterial(steel, "FE tooth");
  SolvedSegment s;
  s.geometry = MakeToothGeometry(gear, options.geometry, options.loads);
  const ToothGeometry& g = s.geometry;
  const ScratchGeo geo(g.geo);
  s.mesh = fem::ImportMesh(
      geo.path(), {options.geometry.mesh_size * gear.spec.module, options.element_order}, {});
  fem::Mesh& mesh = s.mesh;
  for (fem::ElementBlock& block : mesh.blocks) block.material = steel;
  const Eigen::SparseMatrix<double> K =
      fem::AssembleSystem(mesh, fem::MassMatrixKind::kLumped).stiffness;

  // Free DOFs: x and y of every node off the clamped boundary (plane strain: z held).
  s.tolerance = 1e-7 * gear.tip_radius;
  s.free_index.assign(static_cast<std::size_t>(mesh.num_dofs()), -1);
  int free_count = 0;
  for (Eigen::Index n = 0; n < mesh.num_nodes(); ++n) {
    if (Clamped(mesh.nodes.col(n), g, s.tolerance)) continue;
    for (int i = 0; i < 2; ++i) s.free_index[static_cast<std::size_t>(3 * n + i)] = free_count++;
  }
  std::vector<Eigen::Triplet<double>> entries;
  for (int col = 0; col < K.outerSize(); ++col) {
    const int j = s.free_index[static_cast<std::size_t>(col)];
    if (j < 0) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, col); it; ++it) {
      const int i = s.free_index[static_cast<std::size_t>(it.row())];
      if (i >= 0) entries.emplace_back(i, j, it.value());
    }
  }
  Eigen::SparseMatrix<double> K_ff(free_count, free_count);
  K_ff.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor(K_ff);
  FLEXMBS_CHECK(factor.info() == Eigen::Success,
                "the FE tooth's stiffness is not positive definite");

  const std::size_t loads = g.roll.size();
  Eigen::MatrixXd f = Eigen::MatrixXd::Zero(free_count, static_cast<Eigen::Index>(loads));
  for (std::size_t k = 0; k < loads; ++k) {
    const std::vector<int> nodes = NodesAt(mesh, g.load_point[k], s.tolerance);
    const std::vector<double> weights = EdgeWeights(nodes.size());
    for (std::size_t a = 0; a < nodes.size(); ++a) {
      for (int i = 0; i < 2; ++i) {
        const int dof = s.free_index[static_cast<std::size_t>(3 * nodes[a] + i)];
        FLEXMBS_CHECK(dof >= 0, "an FE tooth's load point lies on the clamped boundary");
        f(dof, static_cast<Eigen::Index>(k)) = -weights[a] * g.load_normal[k](i);
      }
    }
  }
  s.u = factor.solve(f);
  return s;
}

/// The displacement along -n of the nodes through `point` (averaged) in load case k, times the
/// face width: the deflection per load per face width [m^2/N].
double Deflection(const SolvedSegment& s, const Eigen::Vector2d& point, const Eigen::Vector2d& n,
                  std::size_t k) {
  const std::vector<int> nodes = NodesAt(s.mesh, point, s.tolerance);
  double deflection = 0.0;
  for (const int node : nodes) {
    for (int i = 0; i < 2; ++i) {
      const int dof = s.free_index[static_cast<std::size_t>(3 * node + i)];
      deflection -= s.u(dof, static_cast<Eigen::Index>(k)) * n(i);
    }
  }
  return deflection / static_cast<double>(nodes.size()) * s.geometry.face_width;
}

}  // namespace

ToothModelResult ToothComplianceFromFe(const contact::SpurGear& gear,
                                       const contact::ToothMaterial& material,
                                       const ToothModelOptions& options) {
  const SolvedSegment s = SolveSegment(gear, material, options);
  const ToothGeometry& g = s.geometry;
  ToothModelResult result;
  result.nodes = s.mesh.num_nodes();
  result.elements = s.mesh.num_elements();
  contact::ToothCompliance& table = result.compliance;
  for (std::size_t k = 0; k < g.roll.size(); ++k) {
    table.roll.push_back(g.roll[k]);
    table.compliance.push_back(Deflection(s, g.centre_point[k], g.load_normal[k], k));
    table.centre_depth.push_back((g.load_point[k] - g.centre_point[k]).norm());
  }
  return result;
}

ToothCoupling ToothCouplingFromFe(const contact::SpurGear& gear,
                                  const contact::ToothMaterial& material,
                                  ToothModelOptions options) {
  options.geometry.teeth = 3;
  const SolvedSegment s = SolveSegment(gear, material, options);
  const ToothGeometry& g = s.geometry;
  ToothCoupling coupling;
  coupling.nodes = s.mesh.num_nodes();
  const double none = std::numeric_limits<double>::quiet_NaN();
  contact::RimCoupling& rim = coupling.rim;
  for (std::size_t k = 0; k < g.roll.size(); ++k) {
    coupling.compliance.roll.push_back(g.roll[k]);
    coupling.compliance.compliance.push_back(
        Deflection(s, g.centre_point[k], g.load_normal[k], k));
    coupling.compliance.centre_depth.push_back((g.load_point[k] - g.centre_point[k]).norm());
    rim.roll.push_back(g.roll[k]);
    rim.ahead.push_back(
        g.ahead[k].valid ? Deflection(s, g.ahead[k].centre_point, g.load_normal[k], k) : none);
    rim.behind.push_back(
        g.behind[k].valid ? Deflection(s, g.behind[k].centre_point, g.load_normal[k], k) : none);
  }
  return coupling;
}

}  // namespace flexmbs::gear_tooth_fe
