#pragma once
// YAML configuration with errors that name the file, the key path, its line and column, and
// what was expected. A ConfigNode is a view into one loaded file.
#include <yaml-cpp/yaml.h>

#include <memory>
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

  const std::string& file() const { return *file_; }
  const std::string& path() const { return path_; }
  // Throws a ConfigError located at `key` (or at this node when key is empty).
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

 private:
  ConfigNode(YAML::Node node, std::shared_ptr<const std::string> file, std::string path)
      : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {}
  std::string keyPath(const std::string& key) const;
  std::string where(const YAML::Node& n) const;
  YAML::Node require(const std::string& key) const;
  template <typename T>
  T convert(const YAML::Node& n, const std::string& key) const;

  YAML::Node node_;
  std::shared_ptr<const std::string> file_;
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
