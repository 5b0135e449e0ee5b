#include "io/calib_file.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "io/io_error.h"
#include "io/numbers.h"

namespace slide::io {

CalibEntries readCalibFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw IoError(path, "cannot open file");
  CalibEntries out;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto colon = line.find(':');
    if (colon == std::string::npos || colon == 0)
      throw IoError(path, "line " + std::to_string(n) + ": expected 'KEY: values'");
    std::vector<double> v;
    try {
      v = parseNumberList(line.substr(colon + 1));
    } catch (const std::invalid_argument& e) {
      throw IoError(path, "line " + std::to_string(n) + ": " + e.what());
    }
    out[line.substr(0, colon)] = v;
  }
  return out;
}

void writeCalibFile(const std::string& path, const CalibEntries& entries) {
  std::ofstream out(path);
  if (!out) throw IoError(path, "cannot write file");
  out << std::setprecision(12);
  for (const auto& [key, values] : entries) {
    out << key << ':';
    for (double v : values) out << ' ' << v;
    out << '\n';
  }
  if (!out) throw IoError(path, "write failed");
}

std::vector<double> calibValues(const CalibEntries& calib, const std::string& path, const std::string& key, int n) {
  const auto it = calib.find(key);
  if (it == calib.end()) throw IoError(path, "missing entry '" + key + "'");
  if (static_cast<int>(it->second.size()) != n)
    throw IoError(path, "entry '" + key + "': expected " + std::to_string(n) + " values, got " +
                            std::to_string(it->second.size()));
  return it->second;
}

Pose calibPose(const CalibEntries& calib, const std::string& path, const std::string& key) {
  const std::vector<double> v = calibValues(calib, path, key, 12);
  Pose T = Pose::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) T.matrix()(r, c) = v[4 * r + c];
  return T;
}

std::vector<double> poseToCalib(const Pose& T) {
  std::vector<double> v;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) v.push_back(T.matrix()(r, c));
  return v;
}

}  // namespace slide::io
