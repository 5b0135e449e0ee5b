#include "config/config.h"

#include <algorithm>
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
  auto usage = std::make_shared<Usage>();
  usage->file = name;
  try {
    YAML::Node root = YAML::Load(text);
    if (!root.IsMap()) throw ConfigError(name + ": expected a map of keys at the top level");
    return ConfigNode(root, usage, "");
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
  throw ConfigError(file() + ": " + keyPath(key) + ": " + what);
}

void ConfigNode::requirePositive(const std::string& key, double v) const {
  if (!(v > 0)) fail(key, "must be positive");
}

void ConfigNode::requireNonNegative(const std::string& key, double v) const {
  if (!(v >= 0)) fail(key, "must not be negative");
}

bool ConfigNode::has(const std::string& key) const {
  ask(key);
  return node_.IsMap() && node_[key] && !node_[key].IsNull();
}

YAML::Node ConfigNode::require(const std::string& key) const {
  if (!node_.IsMap()) fail("", "expected a map" + where(node_));
  ask(key);
  YAML::Node n = node_[key];
  if (!n || n.IsNull()) fail(key, "missing key" + where(node_));
  return n;
}

ConfigNode ConfigNode::child(const std::string& key) const {
  YAML::Node n = require(key);
  if (!n.IsMap() && !n.IsSequence()) fail(key, "expected a map or a list" + where(n));
  ConfigNode c(n, usage_, keyPath(key));
  usage_->asked[c.path_];  // read into: its keys are checked too
  return c;
}

std::size_t ConfigNode::size() const { return node_.IsSequence() ? node_.size() : 0; }

ConfigNode ConfigNode::operator[](std::size_t i) const {
  if (!node_.IsSequence() || i >= node_.size()) fail("[" + std::to_string(i) + "]", "no such list element");
  ConfigNode c(node_[i], usage_, keyPath("[" + std::to_string(i) + "]"));
  usage_->asked[c.path_];
  return c;
}

std::vector<std::string> ConfigNode::keys() const {
  std::vector<std::string> out;
  if (node_.IsMap())
    for (const auto& kv : node_) out.push_back(kv.first.as<std::string>());
  return out;
}

namespace {
std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}
}  // namespace

void ConfigNode::unknownBelow(const YAML::Node& n, const std::string& path, std::vector<std::string>& out) const {
  const auto asked = usage_->asked.find(path);
  if (asked == usage_->asked.end()) return;  // never read into: not ours to judge
  if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i) unknownBelow(n[i], path + "[" + std::to_string(i) + "]", out);
    return;
  }
  if (!n.IsMap()) return;
  for (const auto& kv : n) {
    const std::string key = kv.first.Scalar();
    const std::string key_path = path.empty() ? key : path + "." + key;
    if (asked->second.count(key)) {
      unknownBelow(kv.second, key_path, out);
      continue;
    }
    std::string line = file() + ": " + key_path;
    if (kv.first.Mark().line >= 0) line += " (line " + std::to_string(kv.first.Mark().line + 1) + ")";
    line += ": unknown key";
    const std::string* nearest = nullptr;
    std::size_t best = 0;
    for (const std::string& k : asked->second) {
      const std::size_t d = editDistance(key, k);
      if (!nearest || d < best) nearest = &k, best = d;
    }
    if (nearest) line += "; did you mean '" + *nearest + "'?";
    out.push_back(line);
  }
}

void ConfigNode::known(const std::vector<std::string>& keys) const {
  for (const std::string& k : keys) ask(k);
}

std::vector<std::string> ConfigNode::unknownKeys() const {
  std::vector<std::string> out;
  usage_->asked[path_];  // this node is the caller's own
  unknownBelow(node_, path_, out);
  return out;
}

void ConfigNode::rejectUnknownKeys() const {
  const std::vector<std::string> unknown = unknownKeys();
  if (unknown.empty()) return;
  std::string what = unknown.size() == 1 ? unknown[0] : std::to_string(unknown.size()) + " unknown keys:";
  if (unknown.size() > 1)
    for (const std::string& u : unknown) what += "\n  " + u;
  throw ConfigError(what + " (a misspelled parameter would be ignored; remove or correct it)");
}

}  // namespace slide
