#include "perception.h"

#include <spdlog/spdlog.h>

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

io::LabelledScan FramePerception::scan(io::LabelledScan read, int frame) const {
  if (source_ == DetectionSource::Oracle) return read;
  if (source_ == DetectionSource::Emulated && read.hasLabels())
    return emulator::emulateLidarLabels(read, config_.lidar, emulator::detectionSeed(config_.seed, robot_, frame));
  read.semantic.clear();  // none (or nothing to emulate from): ground truth is never published
  read.instance.clear();
  return read;
}

std::optional<FramePerception::Masks> FramePerception::masks(std::optional<io::InstanceMask> truth,
                                                             const cv::Mat& depth, double depth_scale,
                                                             int frame) const {
  if (source_ == DetectionSource::None || !truth) return std::nullopt;
  if (source_ == DetectionSource::Oracle) {
    Masks m{std::move(*truth), {}};
    m.confidence.assign(m.masks.class_id.size(), 1.0f);
    return m;
  }
  emulator::EmulatedMasks e = emulator::emulateRgbdDetections(*truth, depth, depth_scale, config_.rgbd,
                                                              emulator::detectionSeed(config_.seed, robot_, frame));
  return Masks{std::move(e.masks), std::move(e.confidence)};
}

FramePerception openPerception(DetectionSource source, const std::string& detection_config, int robot) {
  emulator::DetectionEmulatorConfig emulator;
  if (source == DetectionSource::Emulated) emulator = emulator::loadDetectionEmulatorConfig(detection_config);
  if (source == DetectionSource::Oracle)
    spdlog::warn("ORACLE: publishing the dataset's GROUND-TRUTH labels / masks (--detections oracle); a real robot "
                 "has none, so every figure from this run is an upper bound");
  else if (source == DetectionSource::Emulated)
    spdlog::info("detections: emulated from ground truth inside the driver ({}, seed {}); no ground truth is published",
                 detection_config, emulator.seed);
  else
    spdlog::info("detections: none (raw data only; ground-truth labels / masks stay on disk)");
  return FramePerception(source, emulator, robot);
}

}  // namespace slide
