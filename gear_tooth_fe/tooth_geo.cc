#include "gear_tooth_fe/tooth_geo.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "contact/gears/tooth_profile.h"
#include "contact/laws/law_checks.h"
#include "core/error.h"

namespace flexmbs::gear_tooth_fe {
namespace {

/// Builds a built-in-kernel .geo script entity by entity.
class GeoScript {
 public:
  explicit GeoScript(double size) : size_(size) {}
  /// A point at p [m] in the plane z = 0; its tag.
  int Point(const Eigen::Vector2d& p) {
    text_ += fmt::format("Point({}) = {{{:.17g}, {:.17g}, 0, {:.17g}}};\n", ++points_, p.x(), p.y(),
                         size_);
    return points_;
  }
  /// A curve of `kind` ("Line", "Spline", "Circle") through the point tags; its tag.
  int Curve(const char* kind, const std::vector<int>& through) {
    text_ += fmt::format("{}({}) = {{{}}};\n", kind, ++curves_, fmt::join(through, ", "));
    return curves_;
  }
  /// A spline through the points, the first and last given as tags.
  int Spline(int first, const std::vector<Eigen::Vector2d>& inner, int last) {
    std::vector<int> tags{first};
    for (const Eigen::Vector2d& p : inner) tags.push_back(Point(p));
    tags.push_back(last);
    return Curve("Spline", tags);
  }
  void Add(const std::string& line) { text_ += line; }
  const std::string& text() const { return text_; }

 private:
  double size_;
  int points_ = 0, curves_ = 0;
  std::string text_;
};

Eigen::Vector2d Mirror(const Eigen::Vector2d& p) { return {-p.x(), p.y()}; }

/// Right flank points strictly between roll angles t0 and t1.
std::vector<Eigen::Vector2d> InvoluteBetween(const contact::SpurGear& gear, double t0, double t1,
                                             int count) {
  std::vector<Eigen::Vector2d> points;
  for (int i = 1; i <= count; ++i)
    points.push_back(contact::ToothFlankPoint(gear, t0 + (t1 - t0) * i / (count + 1.0)));
  return points;
}

void CheckOptions(const ToothGeometryOptions& o, int z) {
  contact::RequirePositive("FE tooth rim depth / m", o.rim_depth);
  contact::RequirePositive("FE tooth mesh size / m", o.mesh_size);
  if (o.teeth != 1 && o.teeth != 3) {
    throw InputError(fmt::format("FE tooth segment: {} teeth must be 1 or 3", o.teeth));
  }
  const double half = o.segment_pitches + (o.teeth - 1) / 2;
  if (!(o.segment_pitches >= 0.5 && half * 2.0 * std::numbers::pi / z < std::numbers::pi / 2.0)) {
    throw InputError(fmt::format(
        "FE tooth segment {} pitches must be >= 0.5 and span less than 90 deg on {} teeth",
        o.segment_pitches, z));
  }
}

/// p turned by angle a [rad] about the wheel's centre.
Eigen::Vector2d Turned(const Eigen::Vector2d& p, double a) {
  return {std::cos(a) * p.x() - std::sin(a) * p.y(), std::sin(a) * p.x() + std::cos(a) * p.y()};
}

/// Where the line p + s n crosses the centre line of the tooth turned by `angle` (ToothGeometry's
/// NeighbourPoint), for the neighbour's roll `roll` on [form_roll, tip_roll].
NeighbourPoint Neighbour(const Eigen::Vector2d& p, const Eigen::Vector2d& n, double angle,
                         double roll, double form_roll, double tip_roll) {
  NeighbourPoint point;
  point.roll = roll;
  point.valid = roll >= form_roll && roll <= tip_roll;
  const Eigen::Vector2d axis = Turned(Eigen::Vector2d::UnitY(), angle);  // its centre line
  const Eigen::Vector2d across(axis.y(), -axis.x());
  point.centre_point = p - (p.dot(across) / n.dot(across)) * n;
  return point;
}

}  // namespace

ToothGeometry MakeToothGeometry(const contact::SpurGear& gear, const ToothGeometryOptions& options,
                                int loads) {
  FLEXMBS_CHECK(loads >= 2, "MakeToothGeometry needs two or more load points");
  const int z = gear.spec.teeth;
  CheckOptions(options, z);
  const double m = gear.spec.module;
  const contact::ToothFlankProfile profile =
      contact::RightFlankProfile(gear, options.rack_tip_radius, 16);
  ToothGeometry g;
  g.face_width = options.mesh_size * m;
  g.bore_radius = std::max(gear.root_radius - options.rim_depth * m, 0.2 * gear.root_radius);
  g.segment_angle = options.segment_pitches * 2.0 * std::numbers::pi / z;
  for (int k = 0; k < loads; ++k) {
    const double t = profile.form_roll + (gear.tip_roll - profile.form_roll) * k / (loads - 1.0);
    const Eigen::Vector2d p = contact::ToothFlankPoint(gear, t);
    const Eigen::Vector2d n = contact::ToothFlankNormal(gear, t);
    g.roll.push_back(t);
    g.load_point.push_back(p);
    g.load_normal.push_back(n);
    g.centre_point.push_back(p - (p.x() / n.x()) * n);
  }
  const double pitch = 2.0 * std::numbers::pi / z;
  const double side_teeth = (options.teeth - 1) / 2;  // neighbours on either side
  g.segment_angle += side_teeth * pitch;
  if (options.teeth == 3) {
    for (int k = 0; k < loads; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      g.ahead.push_back(Neighbour(g.load_point[kk], g.load_normal[kk], -pitch, g.roll[kk] + pitch,
                                  profile.form_roll, gear.tip_roll));
      g.behind.push_back(Neighbour(g.load_point[kk], g.load_normal[kk], pitch, g.roll[kk] - pitch,
                                   profile.form_roll, gear.tip_roll));
    }
  }
  GeoScript geo(options.mesh_size * m);
  const Eigen::Vector2d cut(std::sin(g.segment_angle), std::cos(g.segment_angle));
  const int centre = geo.Point(Eigen::Vector2d::Zero());
  const int bore_right = geo.Point(g.bore_radius * cut);
  const int root_right = geo.Point(gear.root_radius * cut);
  std::vector<int> loop;
  // The teeth from +x (turned by -pitch) to -x, each from its right fillet to its left; the
  // loaded one (angle 0) with its right flank split at the load points.
  int previous = root_right;
  for (int j = 0; j < options.teeth; ++j) {
    const double angle = (j - side_teeth) * pitch;
    const auto at = [&](const Eigen::Vector2d& p) { return Turned(p, angle); };
    const int fillet_right = geo.Point(at(profile.fillet.front()));
    if (j == 0) loop.push_back(geo.Curve("Line", {bore_right, root_right}));
    loop.push_back(geo.Curve("Circle", {previous, centre, fillet_right}));
    std::vector<Eigen::Vector2d> fillet;
    for (auto p = profile.fillet.begin() + 1; p != profile.fillet.end() - 1; ++p)
      fillet.push_back(at(*p));
    int flank = geo.Point(at(g.load_point.front()));
    loop.push_back(geo.Spline(fillet_right, fillet, flank));
    if (angle == 0.0) {
      for (int k = 1; k < loads; ++k) {
        const int next = geo.Point(g.load_point[static_cast<std::size_t>(k)]);
        loop.push_back(geo.Spline(flank,
                                  InvoluteBetween(gear, g.roll[static_cast<std::size_t>(k - 1)],
                                                  g.roll[static_cast<std::size_t>(k)], 4),
                                  next));
        flank = next;
      }
    } else {
      std::vector<Eigen::Vector2d> involute =
          InvoluteBetween(gear, profile.form_roll, gear.tip_roll, 4 * loads);
      for (Eigen::Vector2d& p : involute) p = at(p);
      const int tip = geo.Point(at(g.load_point.back()));
      loop.push_back(geo.Spline(flank, involute, tip));
      flank = tip;
    }
    // The left flank: the mirror image, tip to root.
    const int tip_left = geo.Point(at(Mirror(g.load_point.back())));
    loop.push_back(geo.Curve("Circle", {flank, centre, tip_left}));
    std::vector<Eigen::Vector2d> left_involute =
        InvoluteBetween(gear, profile.form_roll, gear.tip_roll, 4 * loads);
    std::reverse(left_involute.begin(), left_involute.end());
    for (Eigen::Vector2d& p : left_involute) p = at(Mirror(p));
    const int form_left = geo.Point(at(Mirror(g.load_point.front())));
    loop.push_back(geo.Spline(tip_left, left_involute, form_left));
    std::vector<Eigen::Vector2d> left_fillet(profile.fillet.rbegin() + 1,
                                             profile.fillet.rend() - 1);
    for (Eigen::Vector2d& p : left_fillet) p = at(Mirror(p));
    previous = geo.Point(at(Mirror(profile.fillet.front())));
    loop.push_back(geo.Spline(form_left, left_fillet, previous));
  }
  const int root_left = geo.Point(gear.root_radius * Mirror(cut));
  const int bore_left = geo.Point(g.bore_radius * Mirror(cut));
  loop.push_back(geo.Curve("Circle", {previous, centre, root_left}));
  loop.push_back(geo.Curve("Line", {root_left, bore_left}));
  loop.push_back(geo.Curve("Circle", {bore_left, centre, bore_right}));
  geo.Add(
      fmt::format("Curve Loop(1) = {{{}}};\nPlane Surface(1) = {{1}};\n", fmt::join(loop, ", ")));
  std::vector<int> inner;
  for (const Eigen::Vector2d& c : g.centre_point) inner.push_back(geo.Point(c));
  for (const std::vector<NeighbourPoint>* side : {&g.ahead, &g.behind}) {
    for (const NeighbourPoint& c : *side)
      if (c.valid) inner.push_back(geo.Point(c.centre_point));
  }
  geo.Add(fmt::format("Point{{{}}} In Surface{{1}};\n", fmt::join(inner, ", ")));
  geo.Add(
      fmt::format("Recombine Surface{{1}};\nExtrude {{0, 0, {:.17g}}} {{ Surface{{1}}; "
                  "Layers{{1}}; Recombine; }}\n",
                  g.face_width));
  g.geo =
      "// One spur gear tooth on its rim segment (flexmbs gear_tooth_fe). Unit: m.\n" + geo.text();
  return g;
}

}  // namespace flexmbs::gear_tooth_fe
