#include "contact/pcm/stl_file.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"

namespace flexmbs::contact {
namespace {

using Point = std::array<double, 3>;

/// Bytes of a binary STL: 80 header, a 4-byte triangle count, then 50 per triangle.
constexpr std::size_t kBinaryHeader = 84, kBinaryTriangle = 50;

[[noreturn]] void Fail(const std::filesystem::path& file, std::string_view problem) {
  throw InputError(fmt::format("STL file '{}': {}", file.string(), problem));
}

/// The corners of the binary file's triangles, three per triangle.
std::vector<Point> BinaryCorners(const std::filesystem::path& file, const std::string& bytes) {
  if (bytes.size() < kBinaryHeader) {
    Fail(file, fmt::format("{} bytes: truncated (a binary STL has an 84-byte header)", bytes.size()));
  }
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, sizeof(count));  // little endian, as the hosts flexmbs runs on
  const std::size_t expected = kBinaryHeader + kBinaryTriangle * static_cast<std::size_t>(count);
  if (bytes.size() < expected) {
    Fail(file, fmt::format("truncated: {} triangles need {} bytes, the file has {}", count, expected, bytes.size()));
  }
  std::vector<Point> corners;
  corners.reserve(3 * static_cast<std::size_t>(count));
  for (std::size_t t = 0; t < count; ++t) {
    const char* record = bytes.data() + kBinaryHeader + kBinaryTriangle * t + 12;  // past the normal
    for (int c = 0; c < 3; ++c) {
      Point p;
      for (int k = 0; k < 3; ++k) {
        float value = 0.0f;
        std::memcpy(&value, record + 4 * (3 * c + k), sizeof(value));
        p[static_cast<std::size_t>(k)] = value;
      }
      corners.push_back(p);
    }
  }
  return corners;
}

/// The corners of the ASCII file's facets: `facet normal nx ny nz / outer loop / vertex x y z` x 3
/// `/ endloop / endfacet`, between `solid [name]` and `endsolid [name]`.
std::vector<Point> AsciiCorners(const std::filesystem::path& file, const std::string& text) {
  std::istringstream lines(text);
  std::string line;
  int line_number = 0, state = 0;  // 0 outside a facet, 1 facet, 2 outer loop, 3..5 vertices read
  bool in_solid = false;
  std::vector<Point> corners;
  const auto fail = [&](std::string_view what) {
    Fail(file, fmt::format("line {}: {} (got '{}')", line_number, what, line));
  };
  while (std::getline(lines, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string word;
    if (!(words >> word)) continue;
    if (word == "solid" && !in_solid) {
      in_solid = true;
    } else if (!in_solid) {
      fail("expected 'solid'");
    } else if (word == "endsolid" && state == 0) {
      in_solid = false;
    } else if (word == "facet" && state == 0) {
      state = 1;
    } else if (word == "outer" && state == 1) {
      state = 2;
    } else if (word == "vertex" && state >= 2 && state < 5) {
      Point p;
      for (double& value : p) {  // strtod: also nan and inf, refused with the triangle below
        std::string number;
        char* end = nullptr;
        if (!(words >> number) || (value = std::strtod(number.c_str(), &end), *end != '\0')) {
          fail("expected 'vertex x y z'");
        }
      }
      if (std::string rest; words >> rest) fail("expected 'vertex x y z'");
      corners.push_back(p);
      ++state;
    } else if (word == "endloop" && state == 5) {
      state = 6;
    } else if (word == "endfacet" && state == 6) {
      state = 0;
    } else {
      fail("unexpected");
    }
  }
  if (in_solid) Fail(file, fmt::format("ends inside a solid or facet at line {}", line_number));
  return corners;
}

}  // namespace

PolygonMesh ReadStlFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) Fail(file, "cannot be read");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) Fail(file, "cannot be read");
  bool binary = true;
  if (bytes.compare(0, 5, "solid") == 0) {
    std::uint32_t count = 0;
    if (bytes.size() >= kBinaryHeader) std::memcpy(&count, bytes.data() + 80, sizeof(count));
    binary = bytes.size() >= kBinaryHeader && bytes.size() == kBinaryHeader + kBinaryTriangle * std::size_t{count};
  }
  const std::vector<Point> corners = binary ? BinaryCorners(file, bytes) : AsciiCorners(file, bytes);
  if (corners.empty()) Fail(file, "no triangles");
  PolygonMesh mesh;
  std::map<Point, int> index;  // exact coordinates -> merged vertex
  std::vector<Point> vertices;
  for (std::size_t c = 0; c < corners.size(); ++c) {
    const Point& p = corners[c];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      Fail(file, fmt::format("triangle {} has a non-finite coordinate ({}, {}, {})", c / 3, p[0], p[1], p[2]));
    }
    const auto [it, inserted] = index.emplace(p, static_cast<int>(vertices.size()));
    if (inserted) vertices.push_back(p);
    mesh.face_vertices.push_back(it->second);
  }
  mesh.face_sizes.assign(corners.size() / 3, 3);
  mesh.vertices_W.resize(3, static_cast<Eigen::Index>(vertices.size()));
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    mesh.vertices_W.col(static_cast<Eigen::Index>(v)) << vertices[v][0], vertices[v][1], vertices[v][2];
  }
  return mesh;
}

}  // namespace flexmbs::contact
