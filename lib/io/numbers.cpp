#include "io/numbers.h"

#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace slide::io {

std::optional<double> parseNumber(const std::string& token) {
  if (token.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(token.c_str(), &end);
  if (end != token.c_str() + token.size()) return std::nullopt;
  return v;
}

std::vector<double> parseNumberList(const std::string& text) {
  std::istringstream in(text);
  std::vector<double> out;
  for (std::string token; in >> token;) {
    const std::optional<double> v = parseNumber(token);
    if (!v) throw std::invalid_argument("'" + token + "' is not a number");
    out.push_back(*v);
  }
  return out;
}

}  // namespace slide::io
