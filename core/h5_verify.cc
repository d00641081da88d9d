// core/h5_file.h: Group::VerifyAll, which reads everything under a group through the checked
// readers and hashes what it read.

#include <fmt/format.h>
#include <hdf5.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/h5_detail.h"
#include "core/h5_file.h"
#include "core/sha256.h"

namespace flexmbs::h5 {

using detail::Check;
using detail::Fail;
using detail::FileState;
using detail::Handle;
using detail::Live;

namespace {

/// Adds a string to `sha` with its length first, so that no two sequences hash alike.
void HashText(Sha256& sha, std::string_view text) {
  const auto size = static_cast<std::uint64_t>(text.size());
  sha.Update(&size, sizeof size);
  sha.Update(text.data(), text.size());
}

/// Adds a matrix's dims and its values' bytes (bit-exact: NaNs and signed zeros count).
template <typename Matrix>
void HashMatrix(Sha256& sha, const Matrix& m) {
  const std::int64_t dims[2] = {m.rows(), m.cols()};
  sha.Update(dims, sizeof dims);
  sha.Update(m.data(), static_cast<std::size_t>(m.size()) * sizeof(typename Matrix::Scalar));
}

/// Reads every attribute of the object `id` (named `object`) and adds name and value to `sha`.
void VerifyAttributes(const FileState& file, hid_t id, const std::string& object, Sha256& sha,
                      VerifyReport& report) {
  H5O_info_t info;
  Check(H5Oget_info2(id, &info, H5O_INFO_NUM_ATTRS), file, object, "list the attributes");
  for (hsize_t i = 0; i < info.num_attrs; ++i) {
    const ssize_t length = Check(H5Aget_name_by_idx(id, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT),
                                 file, object, "list the attributes");
    std::string name(static_cast<std::size_t>(length) + 1, '\0');
    Check(H5Aget_name_by_idx(id, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(), H5P_DEFAULT), file,
          object, "list the attributes");
    name.resize(static_cast<std::size_t>(length));
    const std::string what = fmt::format("read attribute '{}'", name);
    const Handle attribute(Check(H5Aopen(id, name.c_str(), H5P_DEFAULT), file, object, what), H5Aclose);
    const Handle type(Check(H5Aget_type(attribute.get()), file, object, what), H5Tclose);
    HashText(sha, name);
    switch (H5Tget_class(type.get())) {
      case H5T_STRING: HashText(sha, detail::ReadStringAttribute(file, id, object, name)); break;
      case H5T_FLOAT: {
        const double value = detail::ReadDoubleAttribute(file, id, object, name);
        sha.Update(&value, sizeof value);
        break;
      }
      case H5T_INTEGER: {
        const std::int64_t value = detail::ReadIntegerAttribute(file, id, object, name);
        sha.Update(&value, sizeof value);
        break;
      }
      default: Fail(file, object, fmt::format("attribute '{}' is neither a string nor a number", name));
    }
    ++report.attributes;
    ++report.values;
  }
}

/// Reads the dataset `name` of `group` through the reader of its rank and type.
void VerifyDataset(const Group& group, const FileState& file, hid_t group_id, const std::string& name, Sha256& sha,
                   VerifyReport& report) {
  const std::string object = detail::Join(group.path(), name);
  const detail::DatasetView view = detail::InspectDataset(file, group_id, object, name);
  detail::RequireChecksum(file, view, object);
  HashText(sha, name);
  if (view.type_class == H5T_FLOAT && view.rank == 0) {
    const double value = group.ReadScalar(name);
    sha.Update(&value, sizeof value);
  } else if (view.type_class == H5T_FLOAT && view.rank == 1) {
    HashMatrix(sha, group.ReadVector(name));
  } else if (view.type_class == H5T_FLOAT && view.rank == 2) {
    HashMatrix(sha, group.ReadMatrix(name));
  } else if (view.type_class == H5T_INTEGER && view.rank == 1) {
    const std::vector<std::int64_t> values = group.ReadIntegers(name);
    sha.Update(values.data(), values.size() * sizeof(std::int64_t));
  } else if (view.type_class == H5T_INTEGER && view.rank == 2) {
    HashMatrix(sha, group.ReadIntegerMatrix(name));
  } else if (view.type_class == H5T_STRING && view.rank == 1) {
    for (const std::string& s : group.ReadStrings(name)) HashText(sha, s);
  } else {
    Fail(file, object, fmt::format("a dataset of rank {} and HDF5 type class {}, which flexmbs does not write",
                                   view.rank, static_cast<int>(view.type_class)));
  }
  VerifyAttributes(file, view.dataset.get(), object, sha, report);
  ++report.datasets;
  report.values += static_cast<std::int64_t>(view.count);
}

}  // namespace

VerifyReport Group::VerifyAll() const {
  const FileState& file = Live(file_);
  VerifyReport report;
  report.groups = 1;
  Sha256 sha;
  VerifyAttributes(file, id_, path_, sha, report);
  for (const std::string& name : ChildNames()) {
    // A damaged link table can give a name no writer can make (HasGroup would take it for a
    // path or refuse it as a bug): found by fuzz_results_reader.
    if (name.empty() || name == "." || name.find('/') != std::string::npos) {
      Fail(file, path_, fmt::format("a link named '{}' (not an object name: the link table is damaged)", name));
    }
    if (HasGroup(name)) {
      const VerifyReport child = OpenGroup(name).VerifyAll();
      HashText(sha, name);
      HashText(sha, child.content_sha256);
      report.groups += child.groups;
      report.datasets += child.datasets;
      report.attributes += child.attributes;
      report.values += child.values;
    } else if (HasDataset(name)) {
      VerifyDataset(*this, file, id_, name, sha, report);
    } else {
      Fail(file, detail::Join(path_, name), "neither a group nor a dataset");
    }
  }
  report.content_sha256 = sha.HexDigest();
  return report;
}

}  // namespace flexmbs::h5
