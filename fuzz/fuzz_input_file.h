#pragma once
// Fuzz inputs as files: the readers under test take paths, so each input is written to a
// per-process scratch folder in /dev/shm (memory, no disk traffic) before the call.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>

namespace flexmbs::fuzz {

/// This process's scratch folder (/dev/shm/flexmbs-fuzz-<pid>, or under the system's temporary
/// folder without /dev/shm), created on first use and removed at exit.
const std::filesystem::path& ScratchFolder();

/// Writes the `size` bytes at `data` to the file `name` in ScratchFolder(), replacing it, and
/// returns its path.
std::filesystem::path WriteInputFile(std::string_view name, const std::uint8_t* data, std::size_t size);

}  // namespace flexmbs::fuzz
