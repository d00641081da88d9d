#include "mbs/surface_contact_force.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <utility>

#include "contact/geometry/sphere_surface.h"
#include "core/error.h"
#include "mbs/multibody_system.h"
#include "mbs/simulation_error.h"
#include "mbs/surface_state.h"
#include "mbs/surface_unilateral.h"

namespace flexmbs::mbs {
namespace {

/// Units of round-off, eps (|p| + |p_plane|), within which a vertex's gap to the plane is a tie.
constexpr double kTieRoundOffs = 4.0;

/// The penetration delta [m] of a vertex at p_W [m] into a plane through p_plane_W [m], zero where
/// it is within the round-off of its own evaluation. A gap that is zero (a face landing flat at
/// the first touch) comes out as +-1e-18 m by the sign of the round-off in the normal (a quarter
/// turn's cosine, 6.1e-17); the theta method's linearisation at the step's start would take the
/// vertices on the one side as springs and not their mirror images (tests/mbs/beam_stop_test.cc).
double TieToZero(double penetration, const Eigen::Vector3d& p_W, const Eigen::Vector3d& p_plane_W) {
  const double round_off =
      kTieRoundOffs * std::numeric_limits<double>::epsilon() * (p_W.norm() + p_plane_W.norm());
  return std::abs(penetration) <= round_off ? 0.0 : penetration;
}

}  // namespace

SphereSurfaceContact::SphereSurfaceContact(std::string name, MarkerRef sphere, double radius, MarkerRef origin,
                                           sid::ContactSurface surface, Eigen::Index num_modes,
                                           CompliantContactLaw law)
    : name_(std::move(name)), sphere_(std::move(sphere)), origin_(std::move(origin)), radius_(radius),
      surface_(std::move(surface)), num_modes_(num_modes), contact_(std::move(law), sphere_, origin_) {
  if (!(radius_ > 0.0) || !std::isfinite(radius_)) {
    throw InputError(fmt::format("force element '{}': radius [m] {:g} must be finite and > 0", name_, radius_));
  }
  ForElement(name_, [&] { CheckSurface(name_, surface_, num_modes_); });
}

ContactPoint SphereSurfaceContact::Geometry(double t, const MultibodySystem& system, const ConstVectorRef& y) const {
  ContactPoint point;
  point.a = system.MarkerState(sphere_, y);
  const SurfaceState surface(system, origin_, surface_, num_modes_, y);
  point.b = surface.frame();
  contact::SphereMeshContact nearest;
  try {
    nearest = contact::SphereMesh({point.a.p_WM_W, radius_}, surface.mesh());
  } catch (const contact::DegenerateContactError& e) {
    throw SimulationError(t, fmt::format("t = {:.9g} s: force element '{}': {}", t, name_, e.what()));
  }
  point.n_W = nearest.n_W;
  point.penetration = -nearest.g_N;
  point.p_Wc_W = nearest.p_WB_W;
  point.modal_b = surface.ModalJacobian(nearest.vertices, nearest.weights);
  point.modal_velocity_b_W = point.modal_b * surface.modal_velocities();
  return point;
}

void SphereSurfaceContact::AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                                     Eigen::Ref<Eigen::VectorXd> h) const {
  contact_.AddForces(system, Geometry(t, system, y), h);
}

double SphereSurfaceContact::PotentialEnergy(double t, const MultibodySystem& system, const ConstVectorRef& y) const {
  return contact_.PotentialEnergy(Geometry(t, system, y));
}

void SphereSurfaceContact::AddForceJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                                            Eigen::Ref<Eigen::MatrixXd> dh_dx,
                                            Eigen::Ref<Eigen::MatrixXd> dh_du) const {
  contact_.AddForceJacobian(system, Geometry(t, system, y), dh_dx, dh_du);
}

double SphereSurfaceContact::NormalForce(double t, const MultibodySystem& system, const ConstVectorRef& y) const {
  return contact_.NormalForce(Geometry(t, system, y));
}

SurfacePlaneContact::SurfacePlaneContact(std::string name, MarkerRef origin, sid::ContactSurface surface,
                                         Eigen::Index num_modes, MarkerRef plane, CompliantContactLaw law)
    : CompliantPointsContact(std::move(name), std::move(law), origin, plane), origin_(std::move(origin)),
      plane_(std::move(plane)), surface_(std::move(surface)), num_modes_(num_modes) {
  ForElement(this->name(), [&] { CheckSurface(this->name(), surface_, num_modes_); });
}

std::vector<ContactPoint> SurfacePlaneContact::Points(const MultibodySystem& system, const ConstVectorRef& y) const {
  const SurfaceState surface(system, origin_, surface_, num_modes_, y);
  const MarkerKinematics plane = system.MarkerState(plane_, y);
  std::vector<ContactPoint> points(static_cast<std::size_t>(surface_.vertices.rows()));
  for (std::size_t v = 0; v < points.size(); ++v) {
    ContactPoint& point = points[v];
    point.a = surface.frame();
    point.b = plane;
    point.n_W = plane.R_WM.col(2);
    point.p_Wc_W = surface.mesh().vertices_W.col(static_cast<Eigen::Index>(v));
    point.penetration = TieToZero(-point.n_W.dot(point.p_Wc_W - plane.p_WM_W), point.p_Wc_W, plane.p_WM_W);
    if (point.penetration > 0.0) {
      point.modal_a = surface.ModalJacobian(static_cast<int>(v));
      point.modal_velocity_a_W = point.modal_a * surface.modal_velocities();
    }
  }
  return points;
}

std::vector<ContactLoad> SphereSurfaceContact::ContactLoads(double t, const MultibodySystem& system,
                                                            const ConstVectorRef& y) const {
  std::vector<ContactLoad> loads;
  contact_.AppendLoad(Geometry(t, system, y), &loads);
  return loads;
}

}  // namespace flexmbs::mbs
