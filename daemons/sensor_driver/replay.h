#pragma once
// Replay of one robot's dataset: which frames, at what pace, and where the messages go.
#include <functional>
#include <memory>
#include <string>

#include <lcm/lcm-cpp.hpp>

#include "io/robot_dataset.h"
#include "perception.h"

namespace slide {

struct ReplayOptions {
  int robot = 0;
  double rate = 1.0;          // real-time factor; <= 0: as fast as possible
  int start_frame = 0;        // skip the first K frames ...
  double start_time = 0.0;    // ... or the first S seconds of data (whichever skips more)
  int max_frames = 0;         // > 0: stop after this many frames
  std::string scan_channel = "SCAN", rgbd_channel = "RGBD", odom_channel = "ODOM", status_channel = "SENSOR_STATUS";
  bool progress = true;       // progress bar on stderr
  double max_gap_s = 10.0;    // a longer pause between two frames' times is replayed as this long
};

// Where encoded messages go: the bus and/or an LCM log.
class MessageSink {
 public:
  MessageSink(lcm::LCM* bus, const std::string& log_path);
  // data: an encoded message; dataset_utime stamps log events (the log keeps data time).
  void send(const std::string& channel, const std::vector<uint8_t>& data, int64_t dataset_utime);
  template <class Msg>
  void send(const std::string& channel, const Msg& msg, int64_t dataset_utime) {
    std::vector<uint8_t> buf(static_cast<std::size_t>(msg.getEncodedSize()));
    msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
    send(channel, buf, dataset_utime);
  }

 private:
  lcm::LCM* bus_;
  std::unique_ptr<lcm::LogFile> log_;
  int64_t log_origin_ = 0;  // wall-clock utime of the first log event
  int64_t first_utime_ = -1;
  int64_t event_num_ = 0;
};

// What the status channel last said: kept up to date by replayDataset, so that a driver that
// stops on an error can publish FAILED with how far it got.
struct StreamProgress {
  std::string source;      // dataset path
  std::string detections;  // none | emulated | oracle
  int sent = 0, total = 0;
  int64_t data_utime = 0;  // stamps log events
};

// Sends a stream_status_t with `state` (RUNNING, FINISHED, FAILED) and, for FAILED, `reason`.
void sendStatus(MessageSink& sink, const ReplayOptions& options, const StreamProgress& progress, int8_t state,
                const std::string& reason = "");

// Replays frames [start, end) of `dataset` into `sink`, with the labels or masks `perception`
// gives; returns frames sent. Publishes a RUNNING status (naming the detection source) about
// once a second and FINISHED at the end of data; `progress` follows it (FAILED is the caller's
// to send, from progress, when this throws). `stop` is polled between frames and at least
// every 100 ms while waiting (interrupts end the replay early, without FINISHED). A frame that
// cannot be read is dropped, logged and counted; the replay goes on.
int replayDataset(const RobotDataset& dataset, const ReplayOptions& options, const FramePerception& perception,
                  MessageSink& sink, const std::function<bool()>& stop, StreamProgress& progress);

}  // namespace slide
