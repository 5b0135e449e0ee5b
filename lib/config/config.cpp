#include "config/config.h"

#include <fstream>
#include <sstream>

namespace slide {

template <> const char* configTypeName<int>() { return "an integer"; }
template <> const char* configTypeName<long>() { return "an integer"; }
template <> const char* configTypeName<unsigned>() { return "a non-negative integer"; }
template <> const char* configTypeName<unsigned long>() { return "a non-negative integer"; }
template <> const char* configTypeName<double>() { return "a number"; }
template <> const char* configTypeName<float>() { return "a number"; }
template <> const char* configTypeName<bool>() { return "true or false"; }
template <> const char* configTypeName<std::string>() { return "a string"; }

ConfigNode ConfigNode::load(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open file");
  std::stringstream text;
  text << in.rdbuf();
  return parse(text.str(), path);
}

ConfigNode ConfigNode::parse(const std::string& text, const std::string& name) {
  auto file = std::make_shared<const std::string>(name);
  try {
    YAML::Node root = YAML::Load(text);
    if (!root.IsMap()) throw ConfigError(name + ": expected a map of keys at the top level");
    return ConfigNode(root, file, "");
  } catch (const YAML::ParserException& e) {
    throw ConfigError(name + ": YAML syntax error at line " + std::to_string(e.mark.line + 1) + ", column " +
                      std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
}

std::string ConfigNode::keyPath(const std::string& key) const {
  if (key.empty()) return path_.empty() ? "(top level)" : path_;
  if (path_.empty()) return key;
  return key.front() == '[' ? path_ + key : path_ + "." + key;
}

std::string ConfigNode::where(const YAML::Node& n) const {
  const YAML::Mark m = n.Mark();
  if (m.line < 0) return "";
  return " (line " + std::to_string(m.line + 1) + ", column " + std::to_string(m.column + 1) + ")";
}

void ConfigNode::fail(const std::string& key, const std::string& what) const {
  throw ConfigError(*file_ + ": " + keyPath(key) + ": " + what);
}

void ConfigNode::requirePositive(const std::string& key, double v) const {
  if (!(v > 0)) fail(key, "must be positive");
}

void ConfigNode::requireNonNegative(const std::string& key, double v) const {
  if (!(v >= 0)) fail(key, "must not be negative");
}

bool ConfigNode::has(const std::string& key) const {
  return node_.IsMap() && node_[key] && !node_[key].IsNull();
}

YAML::Node ConfigNode::require(const std::string& key) const {
  if (!node_.IsMap()) fail("", "expected a map" + where(node_));
  YAML::Node n = node_[key];
  if (!n || n.IsNull()) fail(key, "missing key" + where(node_));
  return n;
}

ConfigNode ConfigNode::child(const std::string& key) const {
  YAML::Node n = require(key);
  if (!n.IsMap() && !n.IsSequence()) fail(key, "expected a map or a list" + where(n));
  return ConfigNode(n, file_, keyPath(key));
}

std::size_t ConfigNode::size() const { return node_.IsSequence() ? node_.size() : 0; }

ConfigNode ConfigNode::operator[](std::size_t i) const {
  if (!node_.IsSequence() || i >= node_.size()) fail("[" + std::to_string(i) + "]", "no such list element");
  return ConfigNode(node_[i], file_, keyPath("[" + std::to_string(i) + "]"));
}

std::vector<std::string> ConfigNode::keys() const {
  std::vector<std::string> out;
  if (node_.IsMap())
    for (const auto& kv : node_) out.push_back(kv.first.as<std::string>());
  return out;
}

}  // namespace slide
