// The mode rule's factor for Polygonal Contact Model pairs (docs/contact.md, "Which modes a contact
// needs"): a steel sphere's lower cap striking a steel plate clamped at its sides (20 x 20 x 2
// hex8, 0.2 x 0.2 x 0.01 m) through stiff layers, so that the contact time is near the plate's
// lowest periods; the plate keeps its N lowest fixed-interface modes, N from 1 to the most, and a
// rigid flat in its top face's place stands for N = 0. Per run: the highest kept frequency times
// the advice's contact time (mbs/contact_mode_advice.h), the peak force and its error against the
// run with the most modes, and the CPU time against that run's. The factor is the least f t_c
// from which every run keeps the peak within 1 %. With `correction`, each run's plate is reduced
// anew to its N modes and the attachment modes of the top nodes within a cell of the struck point
// (a unit force at each alone, residual to those N modes: the static response to any load there,
// as a correction mode carries it); N = 0 is left out then.
//
//   bench_pcm_mode_rule [most modes, default 40] [layer modulus E in Pa, default 1e10] [correction]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "mbs/contact_mode_advice.h"
#include "mbs/flexible_body.h"
#include "mbs/multibody_system.h"
#include "mbs/pcm_contact_force.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation.h"
#include "tests/contact/pcm_meshes.h"
#include "tests/mbs/pcm_flexible_bodies.h"
#include "tests/support/test_problems.h"

namespace {

using namespace flexmbs;
using Eigen::Vector3d;
using Eigen::VectorXd;

constexpr double kSide = 0.2, kThickness = 0.01, kRadius = 0.02, kSpeed = 0.3;
const Vector3d kCentre(0.5 * kSide + 1.3e-3, 0.5 * kSide + 0.7e-3, 0.0);  // off the nodes, as tests/mbs/pcm_plate_test.cc

struct Run {
  double peak = 0.0, cpu = 0.0, contact_time = 0.0, cutoff_hz = 0.0;
};

/// The strike on `plate` (null: a rigid flat in the plate's top face's place), explicit at 1e-9 /
/// 1e-12, outputs every 2 us for 2 ms; the advice from its start.
Run Strike(const sid::ReducedBody* plate, const contact::ElasticLayer& layer) {
  const double mass = 7850.0 * 4.0 / 3.0 * M_PI * std::pow(kRadius, 3);
  mbs::MultibodySystem system(Vector3d::Zero());
  const int ball = system.AddBody(std::make_unique<mbs::RigidBody>(
      "ball", mass, Vector3d::Zero(), (0.4 * mass * kRadius * kRadius * Eigen::Matrix3d::Identity()).eval(),
      std::vector<mbs::RigidBodyMarker>{{"centre", Vector3d::Zero(), Eigen::Matrix3d::Identity()}}));
  mbs::PcmSurface B;
  if (plate) {
    const int body = system.AddBody(std::make_unique<mbs::FlexibleBody>("plate", *plate, false));
    const mbs::MarkerRef origin = mbs::MarkerRef::OnBody(body, system.body(body).FindMarker(mbs::FlexibleBody::kOriginMarker));
    system.AddJoint(mbs::Joint("clamp", mbs::JointType::kFixed, mbs::MarkerRef::Ground(Vector3d::Zero()), origin));
    B = mbs::ModalPcmSurface(origin, plate->surfaces.at(0), plate->num_modes(), layer, false);
  } else {
    contact::PolygonMesh flat{Eigen::Matrix3Xd(3, 4), {3, 3}, {0, 1, 2, 0, 2, 3}};
    flat.vertices_W << 0, kSide, kSide, 0, 0, 0, kSide, kSide, kThickness, kThickness, kThickness, kThickness;
    B = mbs::PcmSurface{"flat", mbs::MarkerRef::Ground(Vector3d::Zero()), flat, layer, false};
  }
  system.AddForceElement(std::make_unique<mbs::PcmContactForce>(
      "strike",
      mbs::PcmSurface{"cap", mbs::MarkerRef::OnBody(ball, 0),
                      contact::testing::LowerCap(kRadius, 4), layer, false},
      std::move(B), 0.0, contact::RegularisedCoulomb{0.0, 1e-3}, 3e-3));
  VectorXd y = system.NeutralState(), x_ball(7), u_ball = VectorXd::Zero(6);
  x_ball << kCentre + Vector3d(0.0, 0.0, kThickness + kRadius + 1e-5), 1.0, 0.0, 0.0, 0.0;
  u_ball(2) = -kSpeed;
  system.SetBodyState(ball, x_ball, u_ball, y);
  Run run;
  if (plate) {
    const std::vector<mbs::ContactModeAdvice> advice = mbs::AdviseContactModes(system, y);
    if (!advice.empty()) {
      run.contact_time = advice.front().contact_time;
      run.cutoff_hz = advice.front().cutoff_hz;
    }
  }
  mbs::SimulationOptions options;
  options.end_time = 2e-3;
  options.output_interval = 2e-6;
  options.integrator.relative_tolerance = 1e-9;
  options.integrator.absolute_tolerance = 1e-12;
  const std::clock_t start = std::clock();
  mbs::Simulate(system, options, y, [&](double, const VectorXd& s, const VectorXd&) {
    double force = 0.0;
    for (const mbs::ContactLoad& load : system.force_element(0).ContactLoads(0.0, system, s)) force += load.f_W.z();
    run.peak = std::max(run.peak, force);
  });
  run.cpu = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  return run;
}

}  // namespace

int main(int argc, char** argv) {
  const int most = argc > 1 ? std::stoi(argv[1]) : 40;
  const double modulus = argc > 2 ? std::stod(argv[2]) : 1e10;
  const bool correction = argc > 3 && std::string(argv[3]) == "correction";
  const contact::ElasticLayer layer{modulus, 2e-3};
  // The plate with its n lowest fixed-interface modes (and, with `correction`, the attachment modes).
  const auto make_plate = [&](int n) {
    return mbs::testing::MakeClampedBox(
        "plate", Eigen::Vector3i(20, 20, 2), Vector3d(kSide, kSide, kThickness),
        [](const fem::Mesh& mesh) { return mbs::testing::SideFaceNodes(mesh, kSide, kSide); }, "top",
        [](const fem::Mesh& mesh) { return flexmbs::testing::NodesOnPlane(mesh, 2, kThickness); },
        [&](const fem::Mesh& mesh) {
          if (!correction) return std::vector<int>();
          const double cell = kSide / 20.0;
          return mbs::testing::NodesInBox(mesh, Vector3d(0.5 * kSide - cell, 0.5 * kSide - cell, kThickness),
                                          Vector3d(0.5 * kSide + cell, 0.5 * kSide + cell, kThickness));
        },
        n);
  };
  const mbs::testing::ClampedBox box = make_plate(most);
  const Eigen::Index attachments = box.fe.basis.num_modes() - most;
  std::vector<int> counts{0, 1, 2, 3, 4, 6, 8, 12, 16, 24, 32};
  counts.erase(std::remove_if(counts.begin(), counts.end(), [&](int n) { return n >= most || (correction && n == 0); }),
               counts.end());
  counts.push_back(most);
  const Run reference = Strike(&box.fe.body, layer);
  std::printf("layers E = %.3g Pa, h = 2 mm each (c = %.3g N/m^3); advice with %d modes and %ld attachment modes: "
              "t_c = %.4g s, cut-off %.4g Hz (%.3g / t_c); reference peak %.6g N, CPU %.3g s\n",
              modulus, modulus / (2.0 * 2e-3), most, static_cast<long>(attachments), reference.contact_time,
              reference.cutoff_hz, reference.cutoff_hz * reference.contact_time, reference.peak, reference.cpu);
  std::printf("%6s %12s %10s %12s %12s %10s\n", "modes", "f_max [Hz]", "f t_c", "peak [N]", "peak error", "CPU ratio");
  for (const int n : counts) {
    std::vector<Eigen::Index> keep(static_cast<std::size_t>(n));
    std::iota(keep.begin(), keep.end(), 0);
    sid::ReducedBody plate;
    if (correction && n < most) {
      plate = make_plate(n).fe.body;
    } else if (n > 0) {
      plate = mbs::testing::Reduce(box.fe, mbs::testing::KeepColumns(box.fe.basis, keep));
      plate.name = "plate";
    }
    const Run run = n == most ? reference : Strike(n > 0 ? &plate : nullptr, layer);
    const double f_max = n > 0 ? box.fe.body.frequency_hz(n - 1) : 0.0;
    std::printf("%6d %12.1f %10.3f %12.6g %12.3e %10.3f\n", n, f_max, f_max * reference.contact_time, run.peak,
                run.peak / reference.peak - 1.0, run.cpu / reference.cpu);
    std::fflush(stdout);
  }
  return 0;
}
