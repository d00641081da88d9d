#include "fem/gmsh_import.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gmsh.h>
#include <iostream>
#include <map>
#include <mutex>
#include <unistd.h>

#include "core/error.h"
#include "fem/gmsh_mesh_arrays.h"

namespace flexmbs::fem {
namespace {

namespace fs = std::filesystem;

constexpr double kGmshNoSizeLimit = 1e22;  // gmsh's default Mesh.MeshSizeMax

// While alive, the process's stdout and stderr (file descriptors 1 and 2) go to /dev/null.
// gmsh itself is quiet with General.Terminal = 0, but OpenCASCADE's STEP reader prints its
// parse errors straight to stdout; flexmbs reports gmsh's errors itself, as one line.
class SilenceStdStreams {
 public:
  SilenceStdStreams() {
    std::fflush(nullptr);
    std::cout.flush();
    std::cerr.flush();
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null < 0) return;
    for (int i = 0; i < 2; ++i) {
      saved_[i] = ::dup(i + 1);
      if (saved_[i] >= 0) ::dup2(null, i + 1);
    }
    ::close(null);
  }
  ~SilenceStdStreams() {
    std::fflush(nullptr);
    std::cout.flush();
    std::cerr.flush();
    for (int i = 0; i < 2; ++i) {
      if (saved_[i] < 0) continue;
      ::dup2(saved_[i], i + 1);
      ::close(saved_[i]);
    }
  }
  SilenceStdStreams(const SilenceStdStreams&) = delete;
  SilenceStdStreams& operator=(const SilenceStdStreams&) = delete;

 private:
  int saved_[2] = {-1, -1};
};

// gmsh is one global state: initialise it once per process, quietly, without reading the
// command line (it would exit on options it does not know).
std::mutex& GmshMutex() {
  static std::mutex mutex;
  return mutex;
}

void EnsureGmshInitialized() {
  static const bool initialized = [] {
    const SilenceStdStreams silence;
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    // gmsh 4.8's API default (2) throws std::string out of the .geo parser on the first
    // error and leaves gmsh locked: every later gmsh::open in the process is then ignored
    // ("I'm busy! Ask me that later..."). With 0 gmsh only logs errors, and CallGmsh reads
    // them from the logger.
    gmsh::option::setNumber("General.AbortOnError", 0);
    return true;
  }();
  (void)initialized;
}

// Runs a gmsh call, turning gmsh's errors (logged, or thrown as strings) into one InputError
// "<path>: gmsh could not <action>: <first error> (and N more errors)".
template <typename F>
void CallGmsh(const fs::path& path, std::string_view action, F&& f) {
  std::vector<std::string> errors;
  bool locked = false;
  {
    const SilenceStdStreams silence;
    gmsh::logger::start();
    try {
      f();
    } catch (const std::string& error) {
      errors.push_back(error);
    } catch (const std::exception& error) {
      errors.push_back(error.what());
    } catch (...) {
      errors.push_back("unknown gmsh error");
    }
    std::vector<std::string> log;
    gmsh::logger::get(log);
    gmsh::logger::stop();
    constexpr std::string_view kError = "Error: ";
    std::vector<std::string> logged;
    for (const std::string& line : log) {
      if (line.starts_with(kError)) logged.push_back(line.substr(kError.size()));
      if (line.find("I'm busy!") != std::string::npos) locked = true;
    }
    // The logged errors come first: a thrown one repeats the last of them.
    if (!logged.empty()) errors.insert(errors.begin(), logged.begin(), logged.end());
    if (errors.size() > 1 && errors.back() == errors[errors.size() - 2]) errors.pop_back();
  }
  if (locked) {
    throw InternalError(fmt::format("{}: gmsh refused to {}: it is locked by an earlier error",
                                    path.string(), action));
  }
  if (errors.empty()) return;
  std::string message = errors.front();
  // "'<path>', line 3: syntax error (1)": the path is already at the front of the message.
  const std::string quoted_path = fmt::format("'{}', ", path.string());
  if (message.starts_with(quoted_path)) message.erase(0, quoted_path.size());
  std::replace(message.begin(), message.end(), '\n', ' ');
  std::replace(message.begin(), message.end(), '\r', ' ');
  if (errors.size() > 1) {
    message += fmt::format(" (and {} more error{})", errors.size() - 1,
                           errors.size() > 2 ? "s" : "");
  }
  throw InputError(fmt::format("{}: gmsh could not {}: {}", path.string(), action, message));
}

std::string PhysicalName(int dim, int tag) {
  std::string name;
  gmsh::model::getPhysicalName(dim, tag, name);
  return name;
}

// Named physical groups of every dimension: name -> (dim, tag).
std::map<std::string, std::pair<int, int>> NamedGroups() {
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups);
  std::map<std::string, std::pair<int, int>> named;
  for (const auto& [dim, tag] : groups) {
    const std::string name = PhysicalName(dim, tag);
    if (!name.empty()) named[name] = {dim, tag};
  }
  return named;
}

// The volume entities to mesh and their region names.
std::vector<std::pair<int, std::string>> VolumeRegions() {
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, 3);
  std::vector<std::pair<int, std::string>> regions;
  if (groups.empty()) {
    gmsh::vectorpair volumes;
    gmsh::model::getEntities(volumes, 3);
    for (const auto& [dim, tag] : volumes) regions.emplace_back(tag, fmt::format("volume {}", tag));
    return regions;
  }
  for (const auto& [dim, tag] : groups) {
    std::string name = PhysicalName(dim, tag);
    if (name.empty()) name = fmt::format("physical volume {}", tag);
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(dim, tag, entities);
    for (int entity : entities) regions.emplace_back(entity, name);
  }
  return regions;
}

std::vector<GmshElementBlock> ReadVolumeElements() {
  std::vector<GmshElementBlock> blocks;
  for (const auto& [entity, region] : VolumeRegions()) {
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> element_tags, node_tags;
    gmsh::model::mesh::getElements(types, element_tags, node_tags, 3, entity);
    for (std::size_t k = 0; k < types.size(); ++k) {
      if (element_tags[k].empty()) continue;
      blocks.push_back({types[k], region, std::move(element_tags[k]), std::move(node_tags[k])});
    }
  }
  return blocks;
}

// Why a model has no volume elements, for the message: "the mesh has no elements" or "the
// mesh is 2-D (24 surface elements, no volume elements)".
std::string DescribeMeshWithoutVolumes() {
  constexpr std::string_view kKinds[] = {"point", "line", "surface"};
  for (int dim = 2; dim >= 0; --dim) {
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> element_tags, node_tags;
    gmsh::model::mesh::getElements(types, element_tags, node_tags, dim, -1);
    std::size_t count = 0;
    for (const auto& tags : element_tags) count += tags.size();
    if (count > 0) {
      return fmt::format("the mesh is {}-D ({} {} element{}, no volume elements)", dim, count,
                         kKinds[dim], count == 1 ? "" : "s");
    }
  }
  return "the mesh has no elements";
}

// The mesh of the model's volume elements `blocks` with the node sets `node_set_names`, from
// gmsh's arrays checked by MeshFromGmshArrays.
Mesh BuildMesh(const fs::path& path, std::vector<GmshElementBlock> blocks,
               const std::vector<std::string>& node_set_names) {
  if (blocks.empty()) {
    throw InputError(fmt::format("{}: {}; flexmbs needs a solid (3-D) mesh", path.string(),
                                 DescribeMeshWithoutVolumes()));
  }
  GmshNodes all_nodes;
  std::vector<double> parametric;
  gmsh::model::mesh::getNodes(all_nodes.tags, all_nodes.coords, parametric, -1, -1, false, false);
  Mesh mesh = MeshFromGmshArrays(path, std::move(blocks), all_nodes);

  const auto groups = NamedGroups();
  for (const std::string& name : node_set_names) {
    const auto it = groups.find(name);
    if (it == groups.end()) {
      std::vector<std::string> available;
      for (const auto& [n, g] : groups) available.push_back(n);
      throw InputError(fmt::format("{}: node set '{}': no physical group of that name (the file has: {})",
                                   path.string(), name,
                                   available.empty() ? "none" : fmt::format("{}", fmt::join(available, ", "))));
    }
    std::vector<std::size_t> tags;
    std::vector<double> xyz;
    gmsh::model::mesh::getNodesForPhysicalGroup(it->second.first, it->second.second, tags, xyz);
    std::vector<int> nodes = MeshNodesOfTags(mesh, tags);
    if (nodes.empty()) {
      throw InputError(fmt::format("{}: node set '{}': the physical group has no nodes on the solid mesh",
                                   path.string(), name));
    }
    mesh.node_sets[name] = std::move(nodes);
  }
  return mesh;
}

}  // namespace

Mesh ImportMesh(const fs::path& path, const MeshingOptions& options,
                const std::vector<std::string>& node_set_names) {
  // gmsh 4.8 silently opens nothing for a missing or unreadable .geo: check first.
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    throw InputError(fmt::format("{}: is a directory, not a geometry or mesh file", path.string()));
  }
  if (!fs::exists(path, ec)) throw InputError(fmt::format("{}: no such file", path.string()));
  if (std::FILE* file = std::fopen(path.c_str(), "rb")) {
    std::fclose(file);
  } else {
    throw InputError(
        fmt::format("{}: cannot open the file: {}", path.string(), std::strerror(errno)));
  }
  if (options.element_order != 1 && options.element_order != 2) {
    throw InputError(fmt::format("{}: element order {} must be 1 or 2", path.string(),
                                 options.element_order));
  }
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const bool is_mesh = extension == ".msh";
  if (!is_mesh && extension != ".geo" && extension != ".step" && extension != ".stp") {
    throw InputError(fmt::format("{}: unsupported geometry file type '{}' (use .geo, .step, .stp or .msh)",
                                 path.string(), extension));
  }

  const std::lock_guard lock(GmshMutex());
  EnsureGmshInitialized();
  // Leave gmsh empty however this ends: the model can be large.
  struct ClearGmsh {
    ~ClearGmsh() {
      try {
        gmsh::clear();
      } catch (...) {  // nothing left to report: the import already succeeded or failed
      }
    }
  } clear_on_exit;
  gmsh::clear();
  CallGmsh(path, "read the file", [&] { gmsh::open(path.string()); });
  if (!is_mesh) {
    CallGmsh(path, "mesh the geometry", [&] {
      // Options persist in gmsh's global state: set every one on each call.
      gmsh::option::setNumber("Mesh.MeshSizeMax",
                              options.mesh_size_m > 0.0 ? options.mesh_size_m : kGmshNoSizeLimit);
      gmsh::option::setNumber("Mesh.ElementOrder", options.element_order);
      gmsh::option::setNumber("Mesh.SecondOrderIncomplete", 1);
      gmsh::model::mesh::generate(3);
    });
  }
  return BuildMesh(path, ReadVolumeElements(), node_set_names);
}

}  // namespace flexmbs::fem
