#pragma once
// STL files for the tests of the STL reader (tests/contact/pcm_stl_file_test.cc) and of the
// `pcm_contact` scene entry (tests/app/simulate_pcm_test.cc): triangles written as ASCII or
// binary STL, and a box's and a tetrahedron's triangles.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace flexmbs::testing {

using StlTriangle = std::array<Eigen::Vector3d, 3>;

/// The box [-half, half] centred at `centre` [m]: 12 triangles, counter-clockwise seen from
/// outside (each face's two triangles by the diagonal from its first corner).
inline std::vector<StlTriangle> BoxTriangles(const Eigen::Vector3d& half, const Eigen::Vector3d& centre) {
  std::vector<StlTriangle> triangles;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;  // (u, v, axis) right-handed
    for (const double side : {-1.0, 1.0}) {
      std::array<Eigen::Vector3d, 4> corners;
      const std::array<std::array<double, 2>, 4> uv{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}};  // counter-clockwise about +axis
      for (int c = 0; c < 4; ++c) {
        Eigen::Vector3d p;
        p(axis) = side * half(axis);
        p(u) = uv[c][0] * half(u);
        p(v) = uv[c][1] * half(v);
        corners[c] = centre + p;
      }
      if (side > 0) {
        triangles.push_back({corners[0], corners[1], corners[2]});
        triangles.push_back({corners[0], corners[2], corners[3]});
      } else {
        triangles.push_back({corners[0], corners[2], corners[1]});
        triangles.push_back({corners[0], corners[3], corners[2]});
      }
    }
  }
  return triangles;
}

/// The tetrahedron with corners 0, x, y, z (of length `edge` [m]): 4 triangles, counter-clockwise
/// seen from outside.
inline std::vector<StlTriangle> TetrahedronTriangles(double edge) {
  const Eigen::Vector3d o = Eigen::Vector3d::Zero(), x = edge * Eigen::Vector3d::UnitX(),
                        y = edge * Eigen::Vector3d::UnitY(), z = edge * Eigen::Vector3d::UnitZ();
  return {{o, y, x}, {o, x, z}, {o, z, y}, {x, y, z}};
}

/// Writes `triangles` as an ASCII STL file (each coordinate with 17 significant digits).
inline void WriteAsciiStl(const std::filesystem::path& file, const std::vector<StlTriangle>& triangles) {
  std::ofstream out(file);
  out.precision(17);
  out << "solid test\n";
  for (const StlTriangle& t : triangles) {
    const Eigen::Vector3d n = (t[1] - t[0]).cross(t[2] - t[0]).normalized();
    out << "  facet normal " << n.x() << " " << n.y() << " " << n.z() << "\n    outer loop\n";
    for (const Eigen::Vector3d& p : t) out << "      vertex " << p.x() << " " << p.y() << " " << p.z() << "\n";
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid test\n";
}

/// Writes `triangles` as a binary STL file (little endian; coordinates as float) under an 80-byte
/// header starting with `header` (binary files may start with "solid" too).
inline void WriteBinaryStl(const std::filesystem::path& file, const std::vector<StlTriangle>& triangles,
                           const std::string& header = "binary test") {
  std::string bytes(80, ' ');
  bytes.replace(0, header.size(), header);
  const auto append = [&](const void* data, std::size_t size) { bytes.append(static_cast<const char*>(data), size); };
  const std::uint32_t count = static_cast<std::uint32_t>(triangles.size());
  append(&count, 4);
  for (const StlTriangle& t : triangles) {
    const Eigen::Vector3f n = (t[1] - t[0]).cross(t[2] - t[0]).normalized().cast<float>();
    append(n.data(), 12);
    for (const Eigen::Vector3d& p : t) {
      const Eigen::Vector3f q = p.cast<float>();
      append(q.data(), 12);
    }
    const std::uint16_t attributes = 0;
    append(&attributes, 2);
  }
  std::ofstream(file, std::ios::binary) << bytes;
}

}  // namespace flexmbs::testing
