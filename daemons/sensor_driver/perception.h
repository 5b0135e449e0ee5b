#pragma once
// What the sensor driver puts on the robot bus besides raw data: nothing (the default: a real
// robot has no labels), the detection emulator's output made from the dataset's ground truth
// (simulation standing in for a learned detector), or the ground truth itself (an oracle,
// asked for explicitly, for upper-bound runs only). Ground truth never leaves this process
// except in oracle mode.
#include <optional>
#include <string>

#include "io/robot_dataset.h"
#include "emulator/detection_emulator.h"
#include "emulator/rgbd_emulator.h"

namespace slide {

enum class DetectionSource { None, Emulated, Oracle };
// "none", "emulated", "oracle"; parseDetectionSource throws std::invalid_argument otherwise.
std::string toString(DetectionSource s);
DetectionSource parseDetectionSource(const std::string& name);

class FramePerception {
 public:
  FramePerception(DetectionSource source, emulator::DetectionEmulatorConfig config, int robot)
      : source_(source), config_(std::move(config)), robot_(robot) {}
  DetectionSource source() const { return source_; }

  // Scan `read` of dataset frame `frame` (with the recording's ground-truth labels, if it has
  // any) as published: no labels, emulated labels without instance ids, or the ground truth.
  io::LabelledScan scan(io::LabelledScan read, int frame) const;

  struct Masks {
    io::InstanceMask masks;
    std::vector<float> confidence;
  };
  // Instance masks of RGBD frame `frame` as published, from the recording's ground-truth masks
  // `truth`; nullopt when none are published or the recording has none.
  std::optional<Masks> masks(std::optional<io::InstanceMask> truth, const cv::Mat& depth, double depth_scale,
                             int frame) const;

 private:
  DetectionSource source_;
  emulator::DetectionEmulatorConfig config_;
  int robot_;
};

// The perception for `source` (the emulator's parameters read from `detection_config` when
// emulated), once the log says what goes on the bus (an oracle run loudly).
FramePerception openPerception(DetectionSource source, const std::string& detection_config, int robot);

}  // namespace slide
