#include "io/kitti_scan.h"

#include <filesystem>
#include <fstream>

#include "io/io_error.h"

namespace slide::io {

namespace {
std::vector<char> readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw IoError(path, "cannot open file");
  std::vector<char> bytes(static_cast<std::size_t>(in.tellg()));
  in.seekg(0);
  if (!in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()))) throw IoError(path, "read failed");
  return bytes;
}
}  // namespace

LabelledScan readVelodyneBin(const std::string& path) {
  const std::vector<char> bytes = readAll(path);
  if (bytes.size() % 16 != 0)
    throw IoError(path, "truncated: " + std::to_string(bytes.size()) + " bytes is not a multiple of 16 (x y z i floats)");
  const std::size_t n = bytes.size() / 16;
  const float* f = reinterpret_cast<const float*>(bytes.data());
  LabelledScan scan;
  scan.xyz.resize(n);
  scan.intensity.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    scan.xyz[i] = {f[4 * i], f[4 * i + 1], f[4 * i + 2]};
    scan.intensity[i] = f[4 * i + 3];
  }
  return scan;
}

void readLabels(const std::string& path, LabelledScan& scan) {
  const std::vector<char> bytes = readAll(path);
  if (bytes.size() % 4 != 0) throw IoError(path, "truncated: size is not a multiple of 4 bytes");
  const std::size_t n = bytes.size() / 4;
  if (n != scan.size())
    throw IoError(path, "label count " + std::to_string(n) + " does not match " + std::to_string(scan.size()) + " points");
  const uint32_t* l = reinterpret_cast<const uint32_t*>(bytes.data());
  scan.semantic.resize(n);
  scan.instance.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    scan.semantic[i] = static_cast<uint16_t>(l[i] & 0xFFFFu);
    scan.instance[i] = static_cast<uint16_t>(l[i] >> 16);
  }
}

LabelledScan readLabelledScan(const std::string& bin_path) {
  LabelledScan scan = readVelodyneBin(bin_path);
  const std::filesystem::path p(bin_path);
  const std::filesystem::path label = p.parent_path().parent_path() / "labels" / p.filename().replace_extension(".label");
  if (std::filesystem::exists(label)) readLabels(label.string(), scan);
  return scan;
}

void writeVelodyneBin(const std::string& path, const LabelledScan& scan) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw IoError(path, "cannot write file");
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const float v[4] = {scan.xyz[i].x(), scan.xyz[i].y(), scan.xyz[i].z(),
                        scan.intensity.empty() ? 0.f : scan.intensity[i]};
    out.write(reinterpret_cast<const char*>(v), sizeof v);
  }
  if (!out) throw IoError(path, "write failed");
}

void writeLabels(const std::string& path, const LabelledScan& scan) {
  if (scan.semantic.size() != scan.size() || scan.instance.size() != scan.size())
    throw IoError(path, "scan has no labels for every point");
  std::ofstream out(path, std::ios::binary);
  if (!out) throw IoError(path, "cannot write file");
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const uint32_t v = static_cast<uint32_t>(scan.semantic[i]) | (static_cast<uint32_t>(scan.instance[i]) << 16);
    out.write(reinterpret_cast<const char*>(&v), sizeof v);
  }
  if (!out) throw IoError(path, "write failed");
}

}  // namespace slide::io
