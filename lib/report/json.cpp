#include "report/json.h"

#include <fstream>
#include <sstream>

namespace slide::report {

Json parseJson(const std::string& text, const std::string& source) {
  try {
    return Json::parse(text);
  } catch (const Json::parse_error& e) {
    // e.byte: 1-based offset of the byte where parsing stopped.
    const std::size_t at = std::min<std::size_t>(e.byte, text.size() + 1);
    std::size_t line = 1, col = 1;
    for (std::size_t i = 0; i + 1 < at; ++i) {
      if (text[i] == '\n') ++line, col = 1;
      else ++col;
    }
    std::string what = e.what();
    const std::size_t colon = what.find(": ");  // keep nlohmann's description after its position
    if (colon != std::string::npos) what = what.substr(colon + 2);
    throw JsonError(source + ": line " + std::to_string(line) + ", column " + std::to_string(col) + ": " + what);
  }
}

Json readJsonFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw JsonError(path + ": cannot open file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parseJson(ss.str(), path);
}

void writeJsonFile(const std::string& path, const Json& value) {
  std::ofstream out(path);
  if (!out) throw JsonError(path + ": cannot write file");
  out << value.dump(2) << "\n";
  if (!out) throw JsonError(path + ": write failed");
}

}  // namespace slide::report
