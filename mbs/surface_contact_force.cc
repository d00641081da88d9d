#include "mbs/surface_contact_force.h"

#include <fmt/format.h>

#include <cmath>
#include <utility>

#include "contact/geometry/sphere_surface.h"
#include "core/error.h"
#include "mbs/multibody_system.h"
#include "mbs/simulation_error.h"
#include "mbs/surface_state.h"
#include "mbs/surface_unilateral.h"

namespace flexmbs::mbs {

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

}  // namespace flexmbs::mbs
