// core/h5_file.h: the attributes of groups and datasets, and the UTF-8 string types shared with
// string datasets (declared in h5_detail.h).

#include <fmt/format.h>
#include <hdf5.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/h5_detail.h"
#include "core/h5_file.h"

namespace flexmbs::h5 {

using detail::Check;
using detail::CheckInternal;
using detail::Fail;
using detail::FileState;
using detail::Handle;
using detail::IsBinary64;
using detail::IsInt64;
using detail::Live;
using detail::ReadDoubleAttribute;
using detail::ReadIntegerAttribute;
using detail::ReadStringAttribute;
using detail::StringTypeProblem;
using detail::Utf8StringType;
using detail::Writable;
using detail::WriteStringAttribute;

namespace {

void WriteAttribute(const FileState& file, hid_t object_id, const std::string& object,
                    std::string_view name, hid_t file_type, hid_t memory_type, const void* data) {
  const std::string n(name);
  const std::string what = fmt::format("write attribute '{}'", name);
  if (Check(H5Aexists(object_id, n.c_str()), file, object, what) > 0) {
    Check(H5Adelete(object_id, n.c_str()), file, object, what);
  }
  const Handle space(CheckInternal(H5Screate(H5S_SCALAR), "create a scalar dataspace"), H5Sclose);
  const Handle attribute(Check(H5Acreate2(object_id, n.c_str(), file_type, space.get(),
                                          H5P_DEFAULT, H5P_DEFAULT),
                               file, object, what),
                         H5Aclose);
  Check(H5Awrite(attribute.get(), memory_type, data), file, object, what);
}

std::string_view SingularKind(H5T_class_t type_class) {
  switch (type_class) {
    case H5T_FLOAT: return "a double";
    case H5T_INTEGER: return "an integer";
    case H5T_STRING: return "a string";
    default: return "a value of another HDF5 type";
  }
}

/// Opens the attribute `name` of `object_id` and checks it holds one value of `expected`.
Handle OpenAttribute(const FileState& file, hid_t object_id, const std::string& object,
                     std::string_view name, H5T_class_t expected, Handle* type_out) {
  const std::string n(name);
  const std::string what = fmt::format("read attribute '{}'", name);
  if (Check(H5Aexists(object_id, n.c_str()), file, object, what) <= 0) {
    Fail(file, object, fmt::format("no attribute '{}'", name));
  }
  Handle attribute(Check(H5Aopen(object_id, n.c_str(), H5P_DEFAULT), file, object, what),
                   H5Aclose);
  Handle type(Check(H5Aget_type(attribute.get()), file, object, what), H5Tclose);
  const H5T_class_t type_class = H5Tget_class(type.get());
  const Handle space(Check(H5Aget_space(attribute.get()), file, object, what), H5Sclose);
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (type_class != expected) {
    Fail(file, object, fmt::format("attribute '{}': expected {}, found {}", name,
                                   SingularKind(expected), SingularKind(type_class)));
  }
  if (count != 1) {
    Fail(file, object,
         fmt::format("attribute '{}': expected one value, found {}", name, std::max<hssize_t>(count, 0)));
  }
  const std::size_t size = H5Tget_size(type.get());
  std::string problem;
  if (expected == H5T_FLOAT && !IsBinary64(type.get())) {
    problem = fmt::format("expected an 8-byte IEEE double, found a {}-byte floating-point value", size);
  } else if (expected == H5T_INTEGER && !IsInt64(type.get())) {
    problem = fmt::format("expected an 8-byte signed integer, found a {}-byte integer", size);
  } else if (expected == H5T_STRING) {
    problem = StringTypeProblem(type.get());
  }
  if (!problem.empty()) Fail(file, object, fmt::format("attribute '{}': {}", name, problem));
  *type_out = std::move(type);
  return attribute;
}

}  // namespace

namespace detail {

std::vector<std::string> ReadStringData(const FileState& file, const std::string& object,
                                        hid_t file_type, std::size_t count, const StringReader& read) {
  const std::string problem = StringTypeProblem(file_type);
  if (!problem.empty()) Fail(file, object, problem);
  std::vector<std::string> out;
  if (count == 0) return out;
  out.reserve(count);
  const std::size_t size = H5Tget_size(file_type);
  Handle memory_type(CheckInternal(H5Tcopy(H5T_C_S1), "copy the string type"), H5Tclose);
  CheckInternal(H5Tset_size(memory_type.get(), size), "make a string type");
  CheckInternal(H5Tset_cset(memory_type.get(), H5Tget_cset(file_type)), "set the character set");
  CheckInternal(H5Tset_strpad(memory_type.get(), H5T_STR_NULLPAD), "set the string padding");
  std::vector<char> buffer(count * size, '\0');
  Check(read(memory_type.get(), static_cast<void*>(buffer.data())), file, object, "read the strings");
  for (std::size_t i = 0; i < count; ++i) {
    const char* begin = buffer.data() + i * size;
    out.emplace_back(begin, std::find(begin, begin + size, '\0'));
  }
  return out;
}

std::string ReadStringAttribute(const FileState& file, hid_t object_id, const std::string& object,
                                std::string_view name) {
  Handle type(H5I_INVALID_HID, H5Tclose);
  const Handle attribute = OpenAttribute(file, object_id, object, name, H5T_STRING, &type);
  return ReadStringData(file, object, type.get(), 1, [&](hid_t memory_type, void* buffer) {
    return H5Aread(attribute.get(), memory_type, buffer);
  }).front();
}

void WriteStringAttribute(const FileState& file, hid_t object_id, const std::string& object,
                          std::string_view name, std::string_view value) {
  FLEXMBS_CHECK(value.find('\0') == std::string_view::npos,
                fmt::format("{}: attribute '{}': strings cannot hold '\\0'", object, name));
  const Handle type = Utf8StringType(value.size());
  const std::string text = value.empty() ? std::string(1, '\0') : std::string(value);
  WriteAttribute(file, object_id, object, name, type.get(), type.get(), text.data());
}

double ReadDoubleAttribute(const FileState& file, hid_t object_id, const std::string& object,
                           std::string_view name) {
  Handle type(H5I_INVALID_HID, H5Tclose);
  const Handle attribute = OpenAttribute(file, object_id, object, name, H5T_FLOAT, &type);
  double value = 0.0;
  Check(H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value), file, object,
        fmt::format("read attribute '{}'", name));
  return value;
}

std::int64_t ReadIntegerAttribute(const FileState& file, hid_t object_id, const std::string& object,
                                  std::string_view name) {
  Handle type(H5I_INVALID_HID, H5Tclose);
  const Handle attribute = OpenAttribute(file, object_id, object, name, H5T_INTEGER, &type);
  std::int64_t value = 0;
  Check(H5Aread(attribute.get(), H5T_NATIVE_INT64, &value), file, object,
        fmt::format("read attribute '{}'", name));
  return value;
}

}  // namespace detail

void Group::SetStringAttribute(std::string_view name, std::string_view value) {
  WriteStringAttribute(Writable(file_), id_, path_, name, value);
}

void Group::SetDoubleAttribute(std::string_view name, double value) {
  WriteAttribute(Writable(file_), id_, path_, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void Group::SetIntegerAttribute(std::string_view name, std::int64_t value) {
  WriteAttribute(Writable(file_), id_, path_, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
}

bool Group::HasAttribute(std::string_view name) const {
  const FileState& file = Live(file_);
  const std::string n(name);
  return Check(H5Aexists(id_, n.c_str()), file, path_, "look up the attribute") > 0;
}

std::string Group::GetStringAttribute(std::string_view name) const {
  return ReadStringAttribute(Live(file_), id_, path_, name);
}

double Group::GetDoubleAttribute(std::string_view name) const {
  return ReadDoubleAttribute(Live(file_), id_, path_, name);
}

std::int64_t Group::GetIntegerAttribute(std::string_view name) const {
  return ReadIntegerAttribute(Live(file_), id_, path_, name);
}

}  // namespace flexmbs::h5
