#pragma once
// The sensor driver's logic without the LCM loop: replay of one robot's dataset (which frames,
// at what pace) into a sink, which publishes through an injected publisher and/or writes an LCM
// log; the stream status (RUNNING, FINISHED, FAILED) goes the same way.
#include <functional>
#include <memory>
#include <string>

#include <lcm/lcm-cpp.hpp>

#include "app/channels.h"
#include "io/robot_dataset.h"
#include "msg/publisher.h"
#include "perception.h"

namespace slide {

struct ReplayOptions {
  int robot = 0;
  double rate = 1.0;          // real-time factor; <= 0: as fast as possible
  int start_frame = 0;        // skip the first K frames ...
  double start_time = 0.0;    // ... or the first S seconds of data (whichever skips more)
  int max_frames = 0;         // > 0: stop after this many frames
  std::string scan_channel = app::channels::kScan, rgbd_channel = app::channels::kRgbd,
              odom_channel = app::channels::kOdom;
  std::string status_channel = app::channels::kSensorStatus;
  bool progress = true;       // progress bar on stderr
  double max_gap_s = 10.0;    // a longer pause between two frames' times is replayed as this long
};

// Where encoded messages go: the bus (an empty publisher: none) and/or an LCM log (an empty
// path: none). Throws IoError when the log cannot be opened.
class MessageSink {
 public:
  MessageSink(msg::Publisher bus, const std::string& log_path);
  // data: an encoded message; dataset_utime stamps log events (the log keeps data time).
  void send(const std::string& channel, const std::vector<uint8_t>& data, int64_t dataset_utime);
  template <class Msg>
  void send(const std::string& channel, const Msg& msg, int64_t dataset_utime) {
    send(channel, msg::encodeLcm(msg), dataset_utime);
  }

 private:
  msg::Publisher bus_;
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

// Before the driver exits on an error: FAILED with `reason` on the status channel (bus and log),
// opening the bus (when `publish`, at `url`) or the log first when the error came before them.
// Never throws.
void publishFailed(std::unique_ptr<lcm::LCM>& bus, std::unique_ptr<MessageSink>& sink, bool publish,
                   const std::string& url, const std::string& log_path, const ReplayOptions& options,
                   const StreamProgress& progress, const std::string& reason);

// Replays frames [start, end) of `dataset` into `sink`, with the labels or masks `perception`
// gives; returns frames sent. Publishes a RUNNING status (naming the detection source) about
// once a second and FINISHED at the end of data; `progress` follows it (FAILED is the caller's
// to send, from progress, when this throws). `stop` is polled between frames and at least
// every 100 ms while waiting (interrupts end the replay early, without FINISHED). A frame that
// cannot be read is dropped, logged and counted; the replay goes on.
int replayDataset(const io::RobotDataset& dataset, const ReplayOptions& options, const FramePerception& perception,
                  MessageSink& sink, const std::function<bool()>& stop, StreamProgress& progress);

}  // namespace slide
