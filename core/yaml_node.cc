#include "core/yaml_node.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fstream>
#include <map>
#include <sstream>
#include <yaml-cpp/yaml.h>

#include "core/error.h"

namespace flexmbs {
namespace {

// A map key as a string; keys that are lists or maps are an input error at `map`'s location.
std::string KeyOf(const YAML::Node& key, const YamlNode& map) {
  if (!key.IsScalar()) map.Fail("every key must be a plain name, not a list or a map");
  return key.Scalar();
}

// yaml-cpp accepts a key twice and lookups see only the first: reject the second.
void RejectDuplicateKeys(const YAML::Node& node, const YamlNode& map) {
  std::map<std::string, YAML::Mark> seen;
  for (const auto& entry : node) {
    const std::string key = KeyOf(entry.first, map);
    const auto [it, inserted] = seen.emplace(key, entry.first.Mark());
    if (!inserted) {
      const YAML::Mark mark = entry.first.Mark();
      throw InputError(fmt::format("{}:{}:{}: {}: duplicate key '{}' (first at line {})",
                                   map.file().string(), mark.line + 1, mark.column + 1,
                                   map.item().empty() ? key : map.item() + "." + key, key,
                                   it->second.line + 1));
    }
  }
}

}  // namespace

YamlNode::YamlNode(std::filesystem::path file, std::string item, const YAML::Node& node)
    : file_(std::move(file)), item_(std::move(item)), node_(std::make_unique<YAML::Node>(node)) {}

YamlNode::~YamlNode() = default;

YamlNode::YamlNode(const YamlNode& other)
    : file_(other.file_), item_(other.item_), node_(std::make_unique<YAML::Node>(*other.node_)) {}

YamlNode& YamlNode::operator=(const YamlNode& other) {
  file_ = other.file_;
  item_ = other.item_;
  node_ = std::make_unique<YAML::Node>(*other.node_);
  return *this;
}

YamlNode YamlNode::LoadFile(const std::filesystem::path& file) {
  // Read the whole file first, so that I/O errors and YAML errors get their own messages.
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) {
    throw InputError(fmt::format("{}: is a directory, not a YAML file", file.string()));
  }
  std::string text;
  {
    errno = 0;
    std::ifstream in(file, std::ios::binary);
    if (!in) {
      throw InputError(fmt::format("{}: cannot open the file: {}", file.string(),
                                   errno != 0 ? std::strerror(errno) : "unknown error"));
    }
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (in.bad()) throw InputError(fmt::format("{}: cannot read the file", file.string()));
    text = std::move(buffer).str();
  }
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    std::string message = e.msg;
    std::replace(message.begin(), message.end(), '\n', ' ');
    if (e.mark.is_null()) {
      throw InputError(fmt::format("{}: malformed YAML: {}", file.string(), message));
    }
    throw InputError(fmt::format("{}:{}:{}: malformed YAML: {}", file.string(), e.mark.line + 1,
                                 e.mark.column + 1, message));
  }
  if (!root.IsDefined() || root.IsNull()) {
    throw InputError(fmt::format("{}: the file is empty", file.string()));
  }
  if (!root.IsMap()) {
    const YAML::Mark mark = root.Mark();
    throw InputError(fmt::format("{}:{}:{}: expected a map of keys at the top level",
                                 file.string(), mark.line + 1, mark.column + 1));
  }
  return YamlNode(file, "", root);
}

std::string YamlNode::Where() const {
  const YAML::Mark mark = node_->Mark();
  std::string where = file_.string();
  if (!mark.is_null()) where += fmt::format(":{}:{}", mark.line + 1, mark.column + 1);
  if (!item_.empty()) where += ": " + item_;
  return where;
}

void YamlNode::Fail(std::string_view problem) const {
  throw InputError(fmt::format("{}: {}", Where(), problem));
}

bool YamlNode::Has(std::string_view key) const {
  return node_->IsMap() && (*node_)[std::string(key)].IsDefined();
}

bool YamlNode::IsScalar() const { return node_->IsScalar(); }

YamlNode YamlNode::Required(std::string_view key) const {
  if (!node_->IsMap()) Fail("expected a map");
  const YAML::Node child = (*node_)[std::string(key)];
  const std::string item = item_.empty() ? std::string(key) : item_ + "." + std::string(key);
  if (!child.IsDefined() || child.IsNull()) {
    Fail(fmt::format("missing key '{}'", key));
  }
  return YamlNode(file_, item, child);
}

double YamlNode::AsDouble() const {
  if (!node_->IsScalar()) Fail("expected a number");
  double value;
  if (!YAML::convert<double>::decode(*node_, value) || !std::isfinite(value)) {
    Fail(fmt::format("'{}' is not a finite number", node_->Scalar()));
  }
  return value;
}

int YamlNode::AsChoice(const std::vector<std::string_view>& names) const {
  const std::string value = AsString();
  const auto it = std::find(names.begin(), names.end(), value);
  if (it == names.end()) Fail(fmt::format("'{}' must be one of: {}", value, fmt::join(names, ", ")));
  return static_cast<int>(it - names.begin());
}

int YamlNode::AsInt() const {
  if (!node_->IsScalar()) Fail("expected an integer");
  int value;
  if (!YAML::convert<int>::decode(*node_, value)) {
    Fail(fmt::format("'{}' is not an integer", node_->Scalar()));
  }
  return value;
}

std::string YamlNode::AsString() const {
  if (!node_->IsScalar()) Fail("expected a string");
  return node_->Scalar();
}

bool YamlNode::AsBool() const {
  if (!node_->IsScalar()) Fail("expected true or false");
  bool value;
  if (!YAML::convert<bool>::decode(*node_, value)) {
    Fail(fmt::format("'{}' is not true or false", node_->Scalar()));
  }
  return value;
}

std::vector<YamlNode> YamlNode::AsList() const {
  if (!node_->IsSequence()) Fail("expected a list");
  std::vector<YamlNode> out;
  for (std::size_t i = 0; i < node_->size(); ++i) {
    out.push_back(YamlNode(file_, fmt::format("{}[{}]", item_, i), (*node_)[i]));
  }
  return out;
}

std::vector<std::string> YamlNode::AsStringList() const {
  if (node_->IsScalar()) return {node_->Scalar()};
  if (!node_->IsSequence()) Fail("expected a list of names");
  std::vector<std::string> out;
  for (const YamlNode& element : AsList()) out.push_back(element.AsString());
  return out;
}

std::vector<std::pair<std::string, YamlNode>> YamlNode::AsMap() const {
  if (!node_->IsMap()) Fail("expected a map");
  RejectDuplicateKeys(*node_, *this);
  std::vector<std::pair<std::string, YamlNode>> out;
  for (const auto& entry : *node_) {
    const std::string key = KeyOf(entry.first, *this);
    out.emplace_back(key, YamlNode(file_, item_.empty() ? key : item_ + "." + key, entry.second));
  }
  return out;
}

void YamlNode::RejectUnknownKeys(std::initializer_list<std::string_view> known) const {
  if (!node_->IsMap()) Fail("expected a map");
  RejectDuplicateKeys(*node_, *this);
  for (const auto& entry : *node_) {
    const std::string key = KeyOf(entry.first, *this);
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      std::string list;
      for (std::string_view k : known) list += (list.empty() ? "" : ", ") + std::string(k);
      YamlNode(file_, item_.empty() ? key : item_ + "." + key, entry.first)
          .Fail(fmt::format("unknown key '{}' (expected one of: {})", key, list));
    }
  }
}

}  // namespace flexmbs
