#include "frontend/xyz_cloud.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "io/io_error.h"

namespace slide::frontend {

Cloud readXyzCloud(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw io::IoError(path, "cannot open");
  Cloud out;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty() || line[0] == '#') continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream s(line);
    double x, y, z;
    if (!(s >> x >> y >> z)) {
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      throw io::IoError(path, "line " + std::to_string(n) + ": expected x y z");
    }
    out.emplace_back(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
  }
  return out;
}

}  // namespace slide::frontend
