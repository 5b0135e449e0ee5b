#include "segment_diagnosis.h"

#include <cstdio>
#include <cstring>
#include <unordered_map>

namespace slide {

namespace {
std::uint64_t keyOf(const Eigen::Vector3f& p) {
  std::uint32_t b[3];
  std::memcpy(b, p.data(), sizeof b);
  return (std::uint64_t(b[0]) * 0x9e3779b97f4a7c15ULL) ^ (std::uint64_t(b[1]) * 0xc2b2ae3d27d4eb4fULL) ^ b[2];
}

std::string labelName(int label) {
  switch (label) {
    case 0: return "unlabelled";
    case 10: return "car";
    case 40: case 44: case 48: case 49: case 72: return "ground";
    case 50: return "building";
    case 51: return "fence";
    case 52: return "other-structure";
    case 70: return "vegetation";
    case 71: return "trunk";
    case 80: return "pole";
    case 99: return "other-object";
    case 100: return "chair";
    case 101: return "table";
    case 102: return "monitor";
    default: return "label " + std::to_string(label);
  }
}
}  // namespace

void SegmentDiagnosis::addFrame(const io::LabelledScan& truth, const std::vector<frontend::Instance>& instances) {
  ++frame_;
  std::unordered_multimap<std::uint64_t, int> index;
  index.reserve(truth.size());
  std::map<int, int> returns;  // object -> returns within range
  for (std::size_t i = 0; i < truth.size(); ++i) {
    index.emplace(keyOf(truth.xyz[i]), static_cast<int>(i));
    if (truth.xyz[i].head<2>().norm() <= max_range_) ++returns[truth.instance[i]];
  }
  // Composition of each instance: object id (> 0) or -(semantic label) for background.
  std::vector<std::map<int, int>> comp(instances.size());
  for (std::size_t k = 0; k < instances.size(); ++k)
    for (const auto& p : instances[k].points) {
      auto [a, b] = index.equal_range(keyOf(p));
      for (auto it = a; it != b; ++it)
        if (truth.xyz[it->second] == p) {
          const int i = it->second;
          const int obj = truth.instance[i];
          ++comp[k][obj > 0 && object_class_.count(obj) ? obj : -int(truth.semantic[i])];
          break;
        }
    }
  for (const auto& [obj, n] : returns) {
    const auto oc = object_class_.find(obj);
    if (obj <= 0 || oc == object_class_.end() || n < min_points_) continue;
    const int bucket = n < 60 ? 0 : n < 150 ? 1 : 2;
    int holders = 0, best = -1, best_n = 0;
    for (std::size_t k = 0; k < instances.size(); ++k) {
      const auto it = comp[k].find(obj);
      if (it == comp[k].end()) continue;
      if (instances[k].class_id == oc->second && it->second >= 15) ++holders;
      if (it->second > best_n) best_n = it->second, best = static_cast<int>(k);
    }
    std::string outcome;
    if (best < 0 || best_n < std::max(10, n / 5)) outcome = "missed";
    else if (instances[best].class_id != oc->second) outcome = "wrong class (" + std::to_string(instances[best].class_id) + ")";
    else if (holders >= 2) outcome = "fragmented";
    else {
      int other_obj = 0, background = 0, total = 0;
      for (const auto& [src, c] : comp[best]) {
        total += c;
        if (src == obj) continue;
        if (src > 0) other_obj = std::max(other_obj, c);
        else if (src != -40 && src != -44 && src != -48 && src != -49 && src != -72) background += c;
      }
      if (other_obj >= 15) outcome = "joined with an object";
      else if (background >= std::max(15, total / 4)) outcome = "joined with background";
      else outcome = "ok";
    }
    ++objects_[oc->second][bucket][outcome];
  }
  for (std::size_t k = 0; k < instances.size(); ++k) {
    int right = 0, total = 0, src = 0, src_n = 0;
    for (const auto& [s, c] : comp[k]) {
      total += c;
      if (s > 0 && object_class_.at(s) == instances[k].class_id) right += c;
      if (c > src_n) src_n = c, src = s;
    }
    if (2 * right >= total) continue;
    const std::string where = src > 0 ? "object of class " + std::to_string(object_class_.at(src)) : labelName(-src);
    ++false_[instances[k].class_id][where];
    auto& samples = false_samples_[instances[k].class_id][where];
    if (samples.size() < kSamples) {  // where it stood and what it looked like (sensor frame)
      Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e9f), hi = -lo, c = Eigen::Vector3f::Zero();
      for (const auto& p : instances[k].points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p), c += p;
      c /= static_cast<float>(std::max<std::size_t>(1, instances[k].points.size()));
      char buf[200];
      std::snprintf(buf, sizeof buf, "frame %d range %.1f m, %zu points, box %.2f x %.2f, z %.2f to %.2f, confidence %.2f",
                    frame_, c.head<2>().norm(), instances[k].points.size(), hi.x() - lo.x(), hi.y() - lo.y(), lo.z(),
                    hi.z(), instances[k].confidence);
      samples.emplace_back(buf);
    }
  }
}

void SegmentDiagnosis::print(const std::string& mode, const std::map<int, std::string>& class_names) const {
  static const char* buckets[3] = {"30-59 returns", "60-149 returns", ">= 150 returns"};
  for (const auto& [c, per_bucket] : objects_) {
    const auto name = class_names.count(c) ? class_names.at(c) : std::to_string(c);
    for (int b = 0; b < 3; ++b) {
      int total = 0;
      for (const auto& [o, n] : per_bucket[b]) total += n;
      if (!total) continue;
      std::printf("  diagnose %s %s %s: %d object-frames:", mode.c_str(), name.c_str(), buckets[b], total);
      for (const auto& [o, n] : per_bucket[b]) std::printf(" %s %d (%.0f%%);", o.c_str(), n, 100.0 * n / total);
      std::printf("\n");
    }
  }
  for (const auto& [c, where] : false_) {
    const auto name = class_names.count(c) ? class_names.at(c) : std::to_string(c);
    std::printf("  diagnose %s false %s instances (frames), mostly from:", mode.c_str(), name.c_str());
    for (const auto& [w, n] : where) std::printf(" %s %d;", w.c_str(), n);
    std::printf("\n");
    for (const auto& [w, samples] : false_samples_.at(c))
      for (const auto& line : samples) std::printf("    false %s from %s: %s\n", name.c_str(), w.c_str(), line.c_str());
  }
}

}  // namespace slide
