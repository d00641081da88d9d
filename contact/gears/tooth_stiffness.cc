#include "contact/gears/tooth_stiffness.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "contact/laws/law_checks.h"
#include "core/error.h"

namespace flexmbs::contact {
namespace {

/// ISO 6336-1:2019 Table 8: C1 ... C9 of q' [mm um / N].
constexpr std::array<double, 9> kIsoC = {0.04723,  0.15551,  0.25791, -0.00635, -0.11654,
                                         -0.00193, -0.24188, 0.00529, 0.00182};

/// 1 N/(mm um) in N/m^2.
constexpr double kNewtonPerMmMicron = 1e9;

/// ISO 6336-1's C_B of one wheel's basic rack.
double RackFactor(const SpurGearSpec& g) {
  const double alpha_deg = g.pressure_angle * 180.0 / std::numbers::pi;
  return (1.0 + 0.5 * (1.2 - g.dedendum_coefficient)) * (1.0 - 0.02 * (20.0 - alpha_deg));
}

}  // namespace

IsoMeshStiffness IsoSinglePairStiffness(const SpurGearSpec& g1, const SpurGearSpec& g2) {
  const double z1 = g1.teeth, z2 = g2.teeth, x1 = g1.profile_shift, x2 = g2.profile_shift;
  const auto& c = kIsoC;
  const double q = c[0] + c[1] / z1 + c[2] / z2 + c[3] * x1 + c[4] * x1 / z1 + c[5] * x2 +
                   c[6] * x2 / z2 + c[7] * x1 * x1 + c[8] * x2 * x2;
  IsoMeshStiffness iso;
  iso.theoretical = kNewtonPerMmMicron / q;
  iso.c_b = 0.5 * (RackFactor(g1) + RackFactor(g2));
  iso.single_pair = iso.theoretical * iso.c_m * iso.c_r * iso.c_b;
  return iso;
}

double WeberFlattening(double load_per_width, double rho1, double rho2, double h1, double h2,
                       const ToothMaterial& material) {
  FLEXMBS_CHECK(load_per_width > 0.0 && rho1 > 0.0 && rho2 > 0.0 && h1 > 0.0 && h2 > 0.0,
                "WeberFlattening needs a load, radii and depths > 0");
  const double nu = material.poisson_ratio;
  const double soft = (1.0 - nu * nu) / (std::numbers::pi * material.youngs_modulus);
  const double radius = rho1 * rho2 / (rho1 + rho2);
  const double half_width = std::sqrt(8.0 * load_per_width * radius * soft);
  return 2.0 * load_per_width * soft *
         (std::log(2.0 * h1 / half_width) + std::log(2.0 * h2 / half_width) - nu / (1.0 - nu));
}

void CheckToothCompliance(const ToothCompliance& tooth, const char* item) {
  const std::size_t n = tooth.roll.size();
  if (n < 2 || tooth.compliance.size() != n || tooth.centre_depth.size() != n) {
    throw InputError(fmt::format(
        "{}: the compliance table needs two or more samples and as many of each column (roll {}, "
        "compliance {}, centre_depth {})",
        item, n, tooth.compliance.size(), tooth.centre_depth.size()));
  }
  for (std::size_t k = 0; k < n; ++k) {
    const double previous = k == 0 ? 0.0 : tooth.roll[k - 1];
    if (!(tooth.roll[k] > previous) || !std::isfinite(tooth.roll[k])) {
      throw InputError(fmt::format("{}: roll[{}] {} rad must be finite, > 0 and above roll[{}]",
                                   item, k, tooth.roll[k], k == 0 ? 0 : k - 1));
    }
    if (!(tooth.compliance[k] > 0.0 && std::isfinite(tooth.compliance[k]))) {
      throw InputError(fmt::format("{}: compliance[{}] {} m^2/N must be finite and > 0", item, k,
                                   tooth.compliance[k]));
    }
    if (!(tooth.centre_depth[k] > 0.0 && std::isfinite(tooth.centre_depth[k]))) {
      throw InputError(fmt::format("{}: centre_depth[{}] {} m must be finite and > 0", item, k,
                                   tooth.centre_depth[k]));
    }
  }
}

void CheckToothMaterial(const ToothMaterial& material, double reference_load) {
  RequirePositive("Young's modulus [Pa]", material.youngs_modulus);
  const double nu = material.poisson_ratio;
  if (!(nu >= 0.0 && nu < 0.5)) {
    throw InputError(fmt::format("Poisson's ratio {} must be in [0, 0.5)", nu));
  }
  RequirePositive("reference load [N/m]", reference_load);
}

void CheckElasticTeeth(const ElasticTeeth& teeth) {
  CheckToothMaterial(teeth.material, teeth.reference_load);
  CheckToothCompliance(teeth.tooth1, "gear 1 tooth");
  CheckToothCompliance(teeth.tooth2, "gear 2 tooth");
}

ToothComplianceAt InterpolateCompliance(const ToothCompliance& tooth, double roll) {
  const std::vector<double>& t = tooth.roll;
  FLEXMBS_CHECK(
      t.size() >= 2 && tooth.compliance.size() == t.size() && tooth.centre_depth.size() == t.size(),
      "a tooth compliance table needs two or more samples of each column");
  const double clamped = std::clamp(roll, t.front(), t.back());
  const auto upper = std::upper_bound(t.begin() + 1, t.end() - 1, clamped);
  const auto k = static_cast<std::size_t>(upper - t.begin()) - 1;
  FLEXMBS_CHECK(t[k + 1] > t[k], "a tooth compliance table's roll angles must increase");
  const double s = (clamped - t[k]) / (t[k + 1] - t[k]);
  return {(1.0 - s) * tooth.compliance[k] + s * tooth.compliance[k + 1],
          (1.0 - s) * tooth.centre_depth[k] + s * tooth.centre_depth[k + 1]};
}

double RimCouplingAt(const std::vector<double>& roll, const std::vector<double>& values, double t) {
  std::vector<double> x, y;
  for (std::size_t k = 0; k < roll.size() && k < values.size(); ++k) {
    if (std::isfinite(values[k])) x.push_back(roll[k]), y.push_back(values[k]);
  }
  FLEXMBS_CHECK(x.size() >= 2, "a rim coupling column needs two or more finite samples");
  std::size_t k = 0;
  while (k + 2 < x.size() && t > x[k + 1]) ++k;
  return y[k] + (y[k + 1] - y[k]) * (t - x[k]) / (x[k + 1] - x[k]);
}

double FlatteningCompliance(const ElasticTeeth& teeth, const GearPair& pair, double roll1,
                            double roll2) {
  const double w = teeth.reference_load;
  return WeberFlattening(w, pair.gear1.base_radius * roll1, pair.gear2.base_radius * roll2,
                         InterpolateCompliance(teeth.tooth1, roll1).centre_depth,
                         InterpolateCompliance(teeth.tooth2, roll2).centre_depth, teeth.material) /
         w;
}

double TeethPairStiffness(const ElasticTeeth& teeth, const GearPair& pair, double roll1,
                          double roll2) {
  return 1.0 / (InterpolateCompliance(teeth.tooth1, roll1).compliance +
                InterpolateCompliance(teeth.tooth2, roll2).compliance +
                FlatteningCompliance(teeth, pair, roll1, roll2));
}

}  // namespace flexmbs::contact
