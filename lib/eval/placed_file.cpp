#include "eval/placed_file.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace slide {

PlacedFile parsePlacedFile(const std::string& arg) {
  PlacedFile f;
  const auto at = arg.rfind('@');
  f.path = arg.substr(0, at);
  if (at == std::string::npos) return f;
  std::stringstream s(arg.substr(at + 1));
  std::vector<double> v;
  std::string tok;
  while (std::getline(s, tok, ',')) {
    try {
      std::size_t used = 0;
      v.push_back(std::stod(tok, &used));
      if (used != tok.size() || !std::isfinite(v.back())) throw std::invalid_argument(tok);
    } catch (const std::exception&) {
      throw std::invalid_argument("'" + arg + "': placement after '@' must be x,y,z,yaw_deg");
    }
  }
  if (v.size() != 4 || f.path.empty()) throw std::invalid_argument("'" + arg + "': placement after '@' must be x,y,z,yaw_deg");
  f.placement = poseFromXyzYaw(v[0], v[1], v[2], v[3] * M_PI / 180.0);
  return f;
}

}  // namespace slide
