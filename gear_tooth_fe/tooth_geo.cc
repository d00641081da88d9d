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
  if (!(o.segment_pitches >= 0.5 &&
        o.segment_pitches * 2.0 * std::numbers::pi / z < std::numbers::pi / 2.0)) {
    throw InputError(fmt::format(
        "FE tooth segment {} pitches must be >= 0.5 and span less than 90 deg on {} teeth",
        o.segment_pitches, z));
  }
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
  GeoScript geo(options.mesh_size * m);
  const Eigen::Vector2d cut(std::sin(g.segment_angle), std::cos(g.segment_angle));
  const int centre = geo.Point(Eigen::Vector2d::Zero());
  const int bore_right = geo.Point(g.bore_radius * cut);
  const int root_right = geo.Point(gear.root_radius * cut);
  const int fillet_right = geo.Point(profile.fillet.front());
  std::vector<int> loop{geo.Curve("Line", {bore_right, root_right}),
                        geo.Curve("Circle", {root_right, centre, fillet_right})};
  std::vector<int> load_tags{geo.Point(g.load_point.front())};
  loop.push_back(geo.Spline(fillet_right, {profile.fillet.begin() + 1, profile.fillet.end() - 1},
                            load_tags.back()));
  for (int k = 1; k < loads; ++k) {
    load_tags.push_back(geo.Point(g.load_point[static_cast<std::size_t>(k)]));
    loop.push_back(geo.Spline(load_tags[load_tags.size() - 2],
                              InvoluteBetween(gear, g.roll[static_cast<std::size_t>(k - 1)],
                                              g.roll[static_cast<std::size_t>(k)], 4),
                              load_tags.back()));
  }
  // The left flank: the mirror image, tip to root.
  const int tip_left = geo.Point(Mirror(g.load_point.back()));
  loop.push_back(geo.Curve("Circle", {load_tags.back(), centre, tip_left}));
  std::vector<Eigen::Vector2d> left_involute =
      InvoluteBetween(gear, profile.form_roll, gear.tip_roll, 4 * loads);
  std::reverse(left_involute.begin(), left_involute.end());
  for (Eigen::Vector2d& p : left_involute) p = Mirror(p);
  const int form_left = geo.Point(Mirror(g.load_point.front()));
  loop.push_back(geo.Spline(tip_left, left_involute, form_left));
  std::vector<Eigen::Vector2d> left_fillet(profile.fillet.rbegin() + 1, profile.fillet.rend() - 1);
  for (Eigen::Vector2d& p : left_fillet) p = Mirror(p);
  const int fillet_left = geo.Point(Mirror(profile.fillet.front()));
  loop.push_back(geo.Spline(form_left, left_fillet, fillet_left));
  const int root_left = geo.Point(gear.root_radius * Mirror(cut));
  const int bore_left = geo.Point(g.bore_radius * Mirror(cut));
  loop.push_back(geo.Curve("Circle", {fillet_left, centre, root_left}));
  loop.push_back(geo.Curve("Line", {root_left, bore_left}));
  loop.push_back(geo.Curve("Circle", {bore_left, centre, bore_right}));
  geo.Add(
      fmt::format("Curve Loop(1) = {{{}}};\nPlane Surface(1) = {{1}};\n", fmt::join(loop, ", ")));
  std::vector<int> inner;
  for (const Eigen::Vector2d& c : g.centre_point) inner.push_back(geo.Point(c));
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
