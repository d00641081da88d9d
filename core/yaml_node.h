#pragma once

#include <filesystem>
#include <initializer_list>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace YAML {
class Node;
}

namespace flexmbs {

/// A node of a YAML input file that knows its file and its item path ("materials.steel"), so
/// that every error is one line: "<file>:<line>:<column>: <item>: <problem>".
class YamlNode {
 public:
  /// Parses `file`; throws InputError for an unreadable file or malformed YAML (with the line
  /// and column of the syntax error).
  static YamlNode LoadFile(const std::filesystem::path& file);

  ~YamlNode();
  YamlNode(const YamlNode& other);
  YamlNode& operator=(const YamlNode& other);

  /// True if this map node has `key`.
  bool Has(std::string_view key) const;
  /// True for a scalar (a number or a string), false for a map, a sequence or null.
  bool IsScalar() const;
  /// The child `key` of this map; throws InputError if it is missing.
  YamlNode Required(std::string_view key) const;

  /// Scalars, converted or an InputError naming the item and the value.
  double AsDouble() const;
  int AsInt() const;
  bool AsBool() const;
  std::string AsString() const;
  /// The index of this scalar among `names` (the file's spellings); else InputError
  /// "'<value>' must be one of: a, b, c".
  int AsChoice(const std::vector<std::string_view>& names) const;
  /// A sequence of strings (a single string counts as a one-element list).
  std::vector<std::string> AsStringList() const;
  /// The elements of a sequence node, each knowing its item path ("interfaces[1]").
  std::vector<YamlNode> AsList() const;
  /// The entries of a map node, in file order; throws InputError for a key given twice.
  std::vector<std::pair<std::string, YamlNode>> AsMap() const;

  /// Throws InputError naming the first key of this map not in `known`, or a key given twice.
  void RejectUnknownKeys(std::initializer_list<std::string_view> known) const;
  /// Throws InputError "<file>:<line>:<col>: <item>: <problem>".
  [[noreturn]] void Fail(std::string_view problem) const;

  const std::filesystem::path& file() const { return file_; }
  const std::string& item() const { return item_; }

 private:
  YamlNode(std::filesystem::path file, std::string item, const YAML::Node& node);
  std::string Where() const;

  std::filesystem::path file_;
  std::string item_;
  std::unique_ptr<YAML::Node> node_;
};

}  // namespace flexmbs
