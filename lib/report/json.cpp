#include "report/json.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace slide {

bool Json::asBool() const {
  if (!isBool()) throw JsonError("JSON value is not a boolean");
  return std::get<bool>(v_);
}
double Json::asNumber() const {
  if (!isNumber()) throw JsonError("JSON value is not a number");
  return std::get<double>(v_);
}
const std::string& Json::asString() const {
  if (!isString()) throw JsonError("JSON value is not a string");
  return std::get<std::string>(v_);
}
const Json::Array& Json::asArray() const {
  if (!isArray()) throw JsonError("JSON value is not an array");
  return std::get<Array>(v_);
}
const Json::Object& Json::asObject() const {
  if (!isObject()) throw JsonError("JSON value is not an object");
  return std::get<Object>(v_);
}

const Json* Json::find(const std::string& key) const {
  if (!isObject()) return nullptr;
  for (const auto& [k, v] : std::get<Object>(v_))
    if (k == key) return &v;
  return nullptr;
}

Json& Json::set(const std::string& key, Json value) {
  if (isNull()) v_ = Object{};
  if (!isObject()) throw JsonError("set('" + key + "') on a JSON value that is not an object");
  auto& o = std::get<Object>(v_);
  for (auto& [k, v] : o)
    if (k == key) return v = std::move(value);
  o.emplace_back(key, std::move(value));
  return o.back().second;
}

Json& Json::push(Json value) {
  if (isNull()) v_ = Array{};
  if (!isArray()) throw JsonError("push on a JSON value that is not an array");
  auto& a = std::get<Array>(v_);
  a.push_back(std::move(value));
  return a.back();
}

namespace {
void dumpString(std::string& out, const std::string& s) {
  out += '"';
  for (unsigned char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  out += '"';
}

std::string number(double d) {
  if (!std::isfinite(d)) return "null";
  if (d == std::floor(d) && std::abs(d) < 1e15) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f", d);
    return buf;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", d);
  return buf;
}

class Parser {
 public:
  Parser(const std::string& text, const std::string& source) : s_(text), source_(source) {}

  Json document() {
    Json v = value();
    skipSpace();
    if (pos_ != s_.size()) fail("unexpected text after the JSON value");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    int line = 1, col = 1;
    for (std::size_t i = 0; i < pos_ && i < s_.size(); ++i) {
      if (s_[i] == '\n') {
        ++line;
        col = 1;
      } else {
        ++col;
      }
    }
    throw JsonError(source_ + ": line " + std::to_string(line) + ", column " + std::to_string(col) + ": " + problem);
  }

  void skipSpace() {
    while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\n' || s_[pos_] == '\t' || s_[pos_] == '\r')) ++pos_;
  }

  bool consume(const char* word) {
    const std::size_t n = std::char_traits<char>::length(word);
    if (s_.compare(pos_, n, word) != 0) return false;
    pos_ += n;
    return true;
  }

  Json value() {
    if (++depth_ > 200) fail("nesting too deep");
    skipSpace();
    if (pos_ >= s_.size()) fail("unexpected end of input");
    Json out;
    const char c = s_[pos_];
    if (c == '{') out = object();
    else if (c == '[') out = array();
    else if (c == '"') out = Json(string());
    else if (consume("true")) out = Json(true);
    else if (consume("false")) out = Json(false);
    else if (consume("null")) out = Json();
    else if (c == '-' || (c >= '0' && c <= '9')) out = Json(numberValue());
    else fail(std::string("unexpected character '") + c + "'");
    --depth_;
    return out;
  }

  Json object() {
    ++pos_;
    Json out = Json::object();
    skipSpace();
    if (pos_ < s_.size() && s_[pos_] == '}') {
      ++pos_;
      return out;
    }
    while (true) {
      skipSpace();
      if (pos_ >= s_.size() || s_[pos_] != '"') fail("expected a string key");
      std::string key = string();
      skipSpace();
      if (pos_ >= s_.size() || s_[pos_] != ':') fail("expected ':' after key \"" + key + "\"");
      ++pos_;
      out.set(key, value());
      skipSpace();
      if (pos_ < s_.size() && s_[pos_] == ',') {
        ++pos_;
        continue;
      }
      if (pos_ < s_.size() && s_[pos_] == '}') {
        ++pos_;
        return out;
      }
      fail("expected ',' or '}' in object");
    }
  }

  Json array() {
    ++pos_;
    Json out = Json::array();
    skipSpace();
    if (pos_ < s_.size() && s_[pos_] == ']') {
      ++pos_;
      return out;
    }
    while (true) {
      out.push(value());
      skipSpace();
      if (pos_ < s_.size() && s_[pos_] == ',') {
        ++pos_;
        continue;
      }
      if (pos_ < s_.size() && s_[pos_] == ']') {
        ++pos_;
        return out;
      }
      fail("expected ',' or ']' in array");
    }
  }

  static void appendUtf8(std::string& out, unsigned cp) {
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xC0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xE0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (cp >> 18));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    }
  }

  unsigned hex4() {
    if (pos_ + 4 > s_.size()) fail("truncated \\u escape");
    unsigned v = 0;
    for (int i = 0; i < 4; ++i) {
      const char c = s_[pos_++];
      v <<= 4;
      if (c >= '0' && c <= '9') v |= c - '0';
      else if (c >= 'a' && c <= 'f') v |= c - 'a' + 10;
      else if (c >= 'A' && c <= 'F') v |= c - 'A' + 10;
      else fail("bad hex digit in \\u escape");
    }
    return v;
  }

  std::string string() {
    ++pos_;  // opening quote
    std::string out;
    while (true) {
      if (pos_ >= s_.size()) fail("unterminated string");
      const char c = s_[pos_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) fail("control character in string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (pos_ >= s_.size()) fail("unterminated escape");
      const char e = s_[pos_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          unsigned cp = hex4();
          if (cp >= 0xD800 && cp < 0xDC00 && s_.compare(pos_, 2, "\\u") == 0) {
            pos_ += 2;
            const unsigned lo = hex4();
            cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
          }
          appendUtf8(out, cp);
          break;
        }
        default: fail(std::string("bad escape \\") + e);
      }
    }
  }

  double numberValue() {
    const std::size_t start = pos_;
    if (s_[pos_] == '-') ++pos_;
    auto digits = [&] {
      const std::size_t d = pos_;
      while (pos_ < s_.size() && s_[pos_] >= '0' && s_[pos_] <= '9') ++pos_;
      return pos_ - d;
    };
    if (digits() == 0) fail("bad number");
    if (pos_ < s_.size() && s_[pos_] == '.') {
      ++pos_;
      if (digits() == 0) fail("bad number: digits expected after '.'");
    }
    if (pos_ < s_.size() && (s_[pos_] == 'e' || s_[pos_] == 'E')) {
      ++pos_;
      if (pos_ < s_.size() && (s_[pos_] == '+' || s_[pos_] == '-')) ++pos_;
      if (digits() == 0) fail("bad number: exponent digits expected");
    }
    std::istringstream in(s_.substr(start, pos_ - start));
    in.imbue(std::locale::classic());
    double d = 0;
    in >> d;
    return d;
  }

  const std::string& s_;
  std::string source_;
  std::size_t pos_ = 0;
  int depth_ = 0;
};
}  // namespace

void Json::dumpTo(std::string& out, int indent, int depth) const {
  const std::string pad = indent > 0 ? "\n" + std::string((depth + 1) * indent, ' ') : "";
  const std::string end = indent > 0 ? "\n" + std::string(depth * indent, ' ') : "";
  switch (v_.index()) {
    case 0: out += "null"; break;
    case 1: out += std::get<bool>(v_) ? "true" : "false"; break;
    case 2: out += number(std::get<double>(v_)); break;
    case 3: dumpString(out, std::get<std::string>(v_)); break;
    case 4: {
      const auto& a = std::get<Array>(v_);
      if (a.empty()) {
        out += "[]";
        break;
      }
      out += '[';
      for (std::size_t i = 0; i < a.size(); ++i) {
        out += (i ? "," : "") + pad;
        a[i].dumpTo(out, indent, depth + 1);
      }
      out += end + "]";
      break;
    }
    case 5: {
      const auto& o = std::get<Object>(v_);
      if (o.empty()) {
        out += "{}";
        break;
      }
      out += '{';
      for (std::size_t i = 0; i < o.size(); ++i) {
        out += (i ? "," : "") + pad;
        dumpString(out, o[i].first);
        out += indent > 0 ? ": " : ":";
        o[i].second.dumpTo(out, indent, depth + 1);
      }
      out += end + "}";
      break;
    }
  }
}

std::string Json::dump(int indent) const {
  std::string out;
  dumpTo(out, indent, 0);
  return out;
}

Json parseJson(const std::string& text, const std::string& source) { return Parser(text, source).document(); }

Json readJsonFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw JsonError(path + ": cannot open file");
  std::ostringstream s;
  s << in.rdbuf();
  return parseJson(s.str(), path);
}

void writeJsonFile(const std::string& path, const Json& value) {
  std::ofstream out(path);
  if (!out) throw JsonError(path + ": cannot write file");
  out << value.dump() << "\n";
  if (!out) throw JsonError(path + ": write failed");
}

}  // namespace slide
