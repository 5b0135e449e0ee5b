#include "perception.h"

#include <stdexcept>

namespace slide {

std::string toString(DetectionSource s) {
  switch (s) {
    case DetectionSource::Emulated: return "emulated";
    case DetectionSource::Oracle: return "oracle";
    default: return "none";
  }
}

DetectionSource parseDetectionSource(const std::string& name) {
  if (name == "none") return DetectionSource::None;
  if (name == "emulated") return DetectionSource::Emulated;
  if (name == "oracle") return DetectionSource::Oracle;
  throw std::invalid_argument("unknown detection source '" + name + "' (expected none, emulated or oracle)");
}

LabelledScan FramePerception::scan(const std::string& bin, int frame) const {
  if (source_ == DetectionSource::None) return readVelodyneBin(bin);  // labels stay on disk, unread
  LabelledScan truth = readLabelledScan(bin);
  if (source_ == DetectionSource::Oracle) return truth;
  return emulateLidarLabels(truth, config_.lidar, detectionSeed(config_.seed, robot_, frame));
}

std::optional<FramePerception::Masks> FramePerception::masks(const std::filesystem::path& dir, const std::string& rgb,
                                                             const cv::Mat& depth, double depth_scale, int frame) const {
  if (source_ == DetectionSource::None) return std::nullopt;
  const std::filesystem::path png = dir / "instances" / std::filesystem::path(rgb).filename();
  if (!std::filesystem::exists(png)) return std::nullopt;
  InstanceMask truth = readInstanceMask(png.string());
  if (source_ == DetectionSource::Oracle) {
    Masks m{std::move(truth), {}};
    m.confidence.assign(m.masks.class_id.size(), 1.0f);
    return m;
  }
  EmulatedMasks e = emulateRgbdDetections(truth, depth, depth_scale, config_.rgbd, detectionSeed(config_.seed, robot_, frame));
  return Masks{std::move(e.masks), std::move(e.confidence)};
}

}  // namespace slide
