#pragma once
// Reduced bodies of random data in the shapes of docs/sid.md: a small one with every part of the
// `.sid.h5` layout, for the tests of the file (tests/sid/sid_file_test.cc) and of its damage
// (tests/integrity/), and the blocks of any size that bench/sid_file_bench.cc generates.

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "sid/reduced_body.h"

namespace flexmbs::testing {

using sid::ReducedBody;
using sid::ContactSurface;
using sid::Node;
using sid::TaylorMatrix;

/// A Taylor block of random entries with `order` for n modes.
inline TaylorMatrix RandomTaylor(Eigen::Index rows, Eigen::Index cols, Eigen::Index n, int order) {
  TaylorMatrix block;
  block.m0 = Eigen::MatrixXd::Random(rows, cols);
  if (order >= 1) {
    for (Eigen::Index j = 0; j < n; ++j) block.m1.push_back(Eigen::MatrixXd::Random(rows, cols));
  }
  if (order >= 2) {
    for (Eigen::Index j = 0; j < n * n; ++j) block.m2.push_back(Eigen::MatrixXd::Random(rows, cols));
  }
  return block;
}

/// The SID invariants of n modes, random, each block in its shape and order of docs/sid.md:
/// mdCM, J (order 2), Ct, Cr, Gr, Oe (order 1), Me, Ge, Ke, De, ksigma (order 0).
inline void SetRandomInvariants(Eigen::Index n, ReducedBody* body) {
  body->mdCM = RandomTaylor(3, 1, n, 1);
  body->J = RandomTaylor(3, 3, n, 2);
  body->Ct = RandomTaylor(n, 3, n, 1);
  body->Cr = RandomTaylor(n, 3, n, 1);
  body->Me = RandomTaylor(n, n, n, 0);
  body->Gr = RandomTaylor(3, 3 * n, n, 1);
  body->Ge = RandomTaylor(n, 3 * n, n, 0);
  body->Oe = RandomTaylor(n, 6, n, 1);
  body->Ke = RandomTaylor(n, n, n, 0);
  body->De = RandomTaylor(n, n, n, 0);
  body->ksigma = RandomTaylor(n, 1, n, 0);
}

/// A marker node `name` on `fe_nodes` with `coupling` ("rigid", "node", ...) and random order-1
/// origin, phi, psi and AP blocks for n modes.
inline Node RandomNode(std::string name, std::vector<int> fe_nodes, std::string coupling, Eigen::Index n) {
  Node node;
  node.name = std::move(name);
  node.fe_nodes = std::move(fe_nodes);
  node.coupling = std::move(coupling);
  node.origin = RandomTaylor(3, 1, n, 1);
  node.phi = RandomTaylor(3, n, n, 1);
  node.psi = RandomTaylor(3, n, n, 1);
  node.AP = RandomTaylor(3, 3, n, 1);
  return node;
}

/// The modes and FE nodes of SampleBody().
inline constexpr Eigen::Index kSampleModes = 3;
inline constexpr Eigen::Index kSampleNodes = 5;

/// A body of kSampleModes modes on kSampleNodes FE nodes with every part of the layout filled:
/// random invariants of every order, stiffening, a rigid marker, a contact surface, a visual
/// surface, provenance.
inline ReducedBody SampleBody() {
  const Eigen::Index n = kSampleModes;
  const Eigen::Index nodes = kSampleNodes;
  ReducedBody body;
  body.name = "bracket";
  body.mass = 1.25;
  body.center_of_mass = Eigen::Vector3d(0.1, -0.2, 0.3);
  body.inertia_about_center_of_mass << 1, 0.1, 0.2, 0.1, 2, 0.3, 0.2, 0.3, 3;
  body.mode_names = {"constraint_tip_tx", "normal_1", "normal_2"};
  body.mode_kinds = {"constraint", "normal", "normal"};
  body.frequency_hz = Eigen::Vector3d(std::nan(""), 12.5, 80.25);
  body.relative_residuals = Eigen::Vector3d(std::nan(""), 1e-12, 3e-11);
  body.damping = "modal 2 %";
  SetRandomInvariants(n, &body);
  for (auto* cases : {&body.stiffening.K0t, &body.stiffening.K0r}) {
    for (Eigen::MatrixXd& K : *cases) K = Eigen::MatrixXd::Random(n, n);
  }
  for (Eigen::MatrixXd& K : body.stiffening.K0omega) K = Eigen::MatrixXd::Random(n, n);
  body.node_positions = Eigen::Matrix3Xd::Random(3, nodes);
  body.node_sets = {{"clamp", {0, 1}}, {"tip", {3, 4}}};
  body.phi = Eigen::MatrixXd::Random(3 * nodes, n);
  body.nodes = {RandomNode("tip", {3, 4}, "rigid", n)};
  ContactSurface pad;
  pad.name = "pad";
  pad.fe_nodes = {1, 2, 3, 4};
  pad.vertices = Eigen::MatrixX3d::Random(4, 3);
  pad.face_sizes = {3, 3};
  pad.face_vertices = {0, 1, 2, 0, 2, 3};
  pad.face_normals = Eigen::MatrixX3d::Random(2, 3);
  pad.phi = Eigen::MatrixXd::Random(12, n);
  body.surfaces = {pad};
  body.visual_surface.face_sizes = {3, 4};
  body.visual_surface.face_nodes = {0, 1, 2, 1, 2, 3, 4};
  body.provenance = {{"mesh", "bracket.msh"}, {"eigensolver", "spectra"}};
  return body;
}

}  // namespace flexmbs::testing
