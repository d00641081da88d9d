#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "fem/mass_properties.h"

namespace flexmbs::reduction {

/// The `.sid.h5` schema this code writes and reads (bumped when the layout changes).
inline constexpr int kSidSchemaVersion = 1;

/// A reduced flexible body as stored in `.sid.h5` (layout in docs/sid.md): the FE nodes, the
/// basis u = Phi q over every FE DOF, the reduced matrices, and where it came from. Version 1
/// holds the reduction result; the SID invariants are added by the SID stage.
struct ReducedBody {
  std::string name;
  fem::MassProperties mass_properties;  ///< of the full FE model, in the body frame B
  Eigen::Matrix3Xd node_positions;       ///< p_BoN_B of every FE node [m]
  std::map<std::string, std::vector<int>> node_sets;  ///< named FE node indices
  /// 3 n_nodes x n_modes: DOF 3 node + axis per unit modal coordinate [m per unit q].
  Eigen::MatrixXd phi;
  std::vector<std::string> mode_names;  ///< one per column, unique
  std::vector<std::string> mode_kinds;  ///< "rigid", "normal", "constraint", "static_correction"
  Eigen::VectorXd frequency_hz;        ///< eigenfrequency of normal modes, NaN for other kinds
  Eigen::VectorXd relative_residuals;  ///< eigen-residual of normal modes, NaN for other kinds
  Eigen::MatrixXd stiffness_reduced;   ///< Phi^T K Phi [N/m per unit q^2]
  Eigen::MatrixXd mass_reduced;        ///< Phi^T M Phi [kg per unit q^2]
  /// n_modes x 6: Phi^T M R, R the unit rigid translations along and rotations about B's axes
  /// through Bo (fem::RigidBodyModes) [kg, kg m per unit q]: modal participation factors.
  Eigen::MatrixXd participation;
  /// Free-form provenance: source files, mesh counts, material, reduction settings, solver,
  /// timings, tool version.
  std::map<std::string, std::string> provenance;
};

/// Writes `body` to `path` atomically (a temporary renamed into place only when complete).
/// Throws InputError naming `path` if it cannot be written; InternalError if the columns of
/// the basis and its per-mode data disagree.
void WriteReducedBody(const std::filesystem::path& path, const ReducedBody& body);

/// Reads a `.sid.h5` file. Throws InputError (one line, naming `path`) for a missing,
/// foreign (not flexmbs), truncated or wrong-version file, or a missing or malformed dataset.
ReducedBody ReadReducedBody(const std::filesystem::path& path);

}  // namespace flexmbs::reduction
