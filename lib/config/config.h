#pragma once
// YAML configuration with errors that name the file, the key path, its line and column, and
// what was expected. A ConfigNode is a view into one loaded file; every key a reader asks for
// (has, get, read, child, ...) is remembered for the file, so that a reader can reject the keys
// it never asked for (misspellings) once it has read its part: rejectUnknownKeys.
// Vocabulary: in namespace slide itself, not slide::config, as every area uses it (README).
#include <yaml-cpp/yaml.h>

#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace slide {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ConfigNode {
 public:
  // Loads a YAML file; throws ConfigError for a missing or unparsable file.
  static ConfigNode load(const std::string& path);
  // Parses YAML text; `name` stands in for the file name in errors.
  static ConfigNode parse(const std::string& text, const std::string& name);

  // Required scalar; throws if missing or not convertible to T.
  template <typename T>
  T get(const std::string& key) const;
  // Optional scalar: `fallback` when missing, error when present but of the wrong type.
  template <typename T>
  T get(const std::string& key, const T& fallback) const;
  // Required fixed-length or any-length list of scalars (n < 0: any length).
  template <typename T>
  std::vector<T> getList(const std::string& key, int n = -1) const;

  // Optional scalar into `value`, which keeps what it holds when the key is missing.
  template <typename T>
  void read(const std::string& key, T& value) const {
    value = get<T>(key, value);
  }
  // Throw a ConfigError at `key` unless v > 0 (v >= 0).
  void requirePositive(const std::string& key, double v) const;
  void requireNonNegative(const std::string& key, double v) const;

  bool has(const std::string& key) const;
  ConfigNode child(const std::string& key) const;  // required map or list
  std::size_t size() const;                        // list length (0 for others)
  ConfigNode operator[](std::size_t i) const;      // list element
  std::vector<std::string> keys() const;           // map keys in file order

  const std::string& file() const { return usage_->file; }
  const std::string& path() const { return path_; }
  // Throws a ConfigError located at `key` (or at this node when key is empty).
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

  // Keys at or below this node that no reader has asked for: a map key nobody asked for, or
  // one inside a map / list element that was read (child, [i]). Maps and lists a reader only
  // tested with has() or read whole (getList) are not searched. One line per key:
  // "<file>: <key path> (line L): unknown key; did you mean '<nearest asked-for key>'?".
  std::vector<std::string> unknownKeys() const;
  // Marks keys as known without reading them: values the command line overrides, which the
  // reader then skips.
  void known(const std::vector<std::string>& keys) const;
  // Throws a ConfigError listing unknownKeys() when there are any. Call it on the part of a
  // file one reader owns (the root of its own file, or its section of a shared file), after
  // everything it knows has been read.
  void rejectUnknownKeys() const;

 private:
  struct Usage {  // one per loaded file, shared by its nodes
    std::string file;
    std::map<std::string, std::set<std::string>> asked;  // node path -> keys asked for there
  };
  ConfigNode(YAML::Node node, std::shared_ptr<Usage> usage, std::string path)
      : node_(std::move(node)), usage_(std::move(usage)), path_(std::move(path)) {}
  void ask(const std::string& key) const { usage_->asked[path_].insert(key); }
  void unknownBelow(const YAML::Node& n, const std::string& path, std::vector<std::string>& out) const;
  std::string keyPath(const std::string& key) const;
  std::string where(const YAML::Node& n) const;
  YAML::Node require(const std::string& key) const;
  template <typename T>
  T convert(const YAML::Node& n, const std::string& key) const;

  YAML::Node node_;
  std::shared_ptr<Usage> usage_;
  std::string path_;
};

// Human-readable name of the scalar type T in error messages.
template <typename T>
const char* configTypeName();

template <typename T>
T ConfigNode::convert(const YAML::Node& n, const std::string& key) const {
  if (!n.IsScalar()) fail(key, std::string("expected ") + configTypeName<T>() + where(n));
  try {
    return n.as<T>();
  } catch (const YAML::Exception&) {
    fail(key, std::string("expected ") + configTypeName<T>() + ", got '" + n.Scalar() + "'" + where(n));
  }
}

template <typename T>
T ConfigNode::get(const std::string& key) const {
  return convert<T>(require(key), key);
}

template <typename T>
T ConfigNode::get(const std::string& key, const T& fallback) const {
  return has(key) ? get<T>(key) : fallback;
}

template <typename T>
std::vector<T> ConfigNode::getList(const std::string& key, int n) const {
  const YAML::Node list = require(key);
  if (!list.IsSequence()) fail(key, std::string("expected a list of ") + configTypeName<T>() + where(list));
  if (n >= 0 && static_cast<int>(list.size()) != n)
    fail(key, "expected " + std::to_string(n) + " values, got " + std::to_string(list.size()) + where(list));
  std::vector<T> out;
  for (std::size_t i = 0; i < list.size(); ++i) out.push_back(convert<T>(list[i], key + "[" + std::to_string(i) + "]"));
  return out;
}

}  // namespace slide
