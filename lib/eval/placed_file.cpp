#include "eval/placed_file.h"

#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "io/numbers.h"

namespace slide::eval {

PlacedFile parsePlacedFile(const std::string& arg) {
  PlacedFile f;
  const auto at = arg.rfind('@');
  // An '@' inside a directory name is part of the path, not a placement.
  if (at == std::string::npos || arg.find('/', at) != std::string::npos) {
    f.path = arg;
    return f;
  }
  f.path = arg.substr(0, at);
  std::stringstream s(arg.substr(at + 1));
  std::vector<double> v;
  std::string tok;
  while (std::getline(s, tok, ',')) {
    const std::optional<double> x = io::parseNumber(tok);
    if (!x || !std::isfinite(*x)) throw std::invalid_argument("'" + arg + "': placement after '@' must be x,y,z,yaw_deg");
    v.push_back(*x);
  }
  if (v.size() != 4 || f.path.empty()) throw std::invalid_argument("'" + arg + "': placement after '@' must be x,y,z,yaw_deg");
  f.placement = poseFromXyzYaw(v[0], v[1], v[2], v[3] * M_PI / 180.0);
  return f;
}

}  // namespace slide::eval
