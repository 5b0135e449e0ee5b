#pragma once
// A small JSON value with a strict parser and a writer, enough for benchmark reports and
// evaluation results (objects keep their key order). Not a general-purpose library: numbers
// are doubles, strings are UTF-8 passed through (\uXXXX escapes become UTF-8).
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace slide {

class JsonError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Json {
 public:
  using Array = std::vector<Json>;
  using Object = std::vector<std::pair<std::string, Json>>;

  Json() = default;  // null
  Json(std::nullptr_t) {}
  Json(bool b) : v_(b) {}
  Json(double d) : v_(d) {}
  Json(int i) : v_(static_cast<double>(i)) {}
  Json(long i) : v_(static_cast<double>(i)) {}
  Json(unsigned i) : v_(static_cast<double>(i)) {}
  Json(long long i) : v_(static_cast<double>(i)) {}
  Json(unsigned long i) : v_(static_cast<double>(i)) {}
  Json(unsigned long long i) : v_(static_cast<double>(i)) {}
  Json(const char* s) : v_(std::string(s)) {}
  Json(std::string s) : v_(std::move(s)) {}
  Json(Array a) : v_(std::move(a)) {}
  Json(Object o) : v_(std::move(o)) {}
  static Json array() { return Json(Array{}); }
  static Json object() { return Json(Object{}); }

  bool isNull() const { return v_.index() == 0; }
  bool isBool() const { return v_.index() == 1; }
  bool isNumber() const { return v_.index() == 2; }
  bool isString() const { return v_.index() == 3; }
  bool isArray() const { return v_.index() == 4; }
  bool isObject() const { return v_.index() == 5; }

  // Typed access; throws JsonError naming the expected type.
  bool asBool() const;
  double asNumber() const;
  const std::string& asString() const;
  const Array& asArray() const;
  const Object& asObject() const;

  // Object members: find returns nullptr when absent (or when this is not an object).
  const Json* find(const std::string& key) const;
  // Sets (replacing) or appends a member; turns a null into an object.
  Json& set(const std::string& key, Json value);
  // Appends to an array; turns a null into an array.
  Json& push(Json value);

  // Non-finite numbers are written as null.
  std::string dump(int indent = 2) const;

 private:
  void dumpTo(std::string& out, int indent, int depth) const;
  std::variant<std::nullptr_t, bool, double, std::string, Array, Object> v_{nullptr};
};

// Throws JsonError "<source>: line L, column C: problem".
Json parseJson(const std::string& text, const std::string& source = "JSON");
Json readJsonFile(const std::string& path);
void writeJsonFile(const std::string& path, const Json& value);

}  // namespace slide
