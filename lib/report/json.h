#pragma once
// JSON for benchmark reports and evaluation results: nlohmann's ordered_json (objects keep
// their key order), with parse errors that name the source, line and column. NaN and
// infinite numbers are written as null.
#include <nlohmann/json.hpp>

#include <stdexcept>
#include <string>

namespace slide::report {

using Json = nlohmann::ordered_json;

class JsonError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The member `key` of an object, or nullptr when absent (or when j is not an object).
inline const Json* member(const Json& j, const std::string& key) {
  if (!j.is_object()) return nullptr;
  const auto it = j.find(key);
  return it == j.end() ? nullptr : &*it;
}

// Throws JsonError "<source>: line L, column C: problem".
Json parseJson(const std::string& text, const std::string& source = "JSON");
Json readJsonFile(const std::string& path);
// Written with an indent of 2 and a final newline.
void writeJsonFile(const std::string& path, const Json& value);

}  // namespace slide::report
