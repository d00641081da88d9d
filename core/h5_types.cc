// core/h5_detail.h: the element types flexmbs writes and the only ones its readers accept.

#include <fmt/format.h>
#include <hdf5.h>

#include <cstddef>
#include <string>

#include "core/h5_detail.h"

namespace flexmbs::h5::detail {

namespace {

/// True if `type` equals one of the predefined types `a`, `b` (H5Tequal fails as "not equal").
bool EqualsEither(hid_t type, hid_t a, hid_t b) { return H5Tequal(type, a) > 0 || H5Tequal(type, b) > 0; }

/// Longest fixed-length string a reader takes (a damaged size could ask for gigabytes per value).
constexpr std::size_t kMaxStringBytes = std::size_t{1} << 20;

}  // namespace

bool IsBinary64(hid_t type) { return EqualsEither(type, H5T_IEEE_F64LE, H5T_IEEE_F64BE); }

bool IsInt64(hid_t type) { return EqualsEither(type, H5T_STD_I64LE, H5T_STD_I64BE); }

std::string StringTypeProblem(hid_t type) {
  if (H5Tget_class(type) != H5T_STRING) return "not a string type";
  if (H5Tis_variable_str(type) != 0) {
    return "variable-length strings are not read (flexmbs writes fixed-length ones; a damaged "
           "variable-length string can make HDF5 read out of bounds)";
  }
  const std::size_t size = H5Tget_size(type);
  if (size == 0 || size > kMaxStringBytes) return fmt::format("a string size of {} bytes", size);
  const H5T_cset_t cset = H5Tget_cset(type);
  if (cset != H5T_CSET_ASCII && cset != H5T_CSET_UTF8) return "a character set other than ASCII or UTF-8";
  return {};
}

Handle Utf8StringType(std::size_t size) {
  Handle type(CheckInternal(H5Tcopy(H5T_C_S1), "copy the string type"), H5Tclose);
  CheckInternal(H5Tset_size(type.get(), size == 0 ? 1 : size), "size a string type");
  CheckInternal(H5Tset_cset(type.get(), H5T_CSET_UTF8), "make a UTF-8 string type");
  CheckInternal(H5Tset_strpad(type.get(), H5T_STR_NULLPAD), "pad a string type with zeros");
  return type;
}

}  // namespace flexmbs::h5::detail
