#include "core/atomic_file.h"

#include <fmt/format.h>
#include <fstream>
#include <system_error>
#include <unistd.h>

#include "core/error.h"

namespace flexmbs {

std::filesystem::path TemporaryPathFor(const std::filesystem::path& path) {
  return std::filesystem::path(fmt::format("{}.tmp.{}", path.string(), ::getpid()));
}

void CommitTemporaryFile(const std::filesystem::path& temporary, const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::filesystem::remove(temporary, ec);
    throw InputError(fmt::format("{}: cannot write the file: {}", path.string(), ec.message()));
  }
}

void WriteFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write) {
  const std::filesystem::path temporary = TemporaryPathFor(path);
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(fmt::format("{}: cannot open the file for writing", path.string()));
    try {
      write(out);
    } catch (...) {
      out.close();
      std::error_code ec;
      std::filesystem::remove(temporary, ec);
      throw;
    }
    out.flush();
    if (!out) {
      std::error_code ec;
      std::filesystem::remove(temporary, ec);
      throw InputError(fmt::format("{}: writing the file failed", path.string()));
    }
  }
  CommitTemporaryFile(temporary, path);
}

}  // namespace flexmbs
