#include "mbs/gear_mesh_element.h"

#include <Eigen/Geometry>

namespace flexmbs::mbs {

void AddPairTorques(const GearPairFrame& f, const ContactPoint& point, double force,
                    GearMeshElement::Readout* readout) {
  const Eigen::Vector3d f_W = force * point.n_W;  // on wheel 2; wheel 1 takes -f_W
  readout->torque1 += (point.p_Wc_W - f.wheel1.p_WM_W).cross(-f_W).dot(f.wheel1.R_WM.col(2));
  readout->torque2 += (point.p_Wc_W - f.wheel2.p_WM_W).cross(f_W).dot(f.wheel2.R_WM.col(2));
}

}  // namespace flexmbs::mbs
