#include "fuzz/fuzz_input_file.h"

#include <cstdlib>
#include <fstream>
#include <string>
#include <unistd.h>

namespace flexmbs::fuzz {
namespace {

/// Removes the scratch folder (registered with std::atexit).
void RemoveScratchFolder() {
  std::error_code ignored;
  std::filesystem::remove_all(ScratchFolder(), ignored);
}

/// Creates the scratch folder.
std::filesystem::path MakeScratchFolder() {
  const std::filesystem::path shm = "/dev/shm";
  const std::filesystem::path base = std::filesystem::is_directory(shm) ? shm : std::filesystem::temp_directory_path();
  std::filesystem::path folder = base / ("flexmbs-fuzz-" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  return folder;
}

}  // namespace

const std::filesystem::path& ScratchFolder() {
  static const std::filesystem::path folder = MakeScratchFolder();
  // Registered after `folder` is made, so it runs before `folder` is destroyed.
  [[maybe_unused]] static const int removal = std::atexit(RemoveScratchFolder);
  return folder;
}

std::filesystem::path WriteInputFile(std::string_view name, const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path path = ScratchFolder() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace flexmbs::fuzz
