#include "sensor_driver_node.h"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <thread>

#include "app/clock.h"
#include "frame_messages.h"
#include "io/io_error.h"
#include "msg/frontend_convert.h"
#include "slide/stream_status_t.hpp"

namespace slide {

namespace {
void drawProgress(int done, int total, double data_t, double rate) {
  const int width = 30, filled = total > 0 ? width * done / total : width;
  std::fprintf(stderr, "\r[%.*s%*s] %d/%d frames  t=%.1f s  %s", filled, "##############################",
               width - filled, "", done, total, data_t, rate > 0 ? ("x" + std::to_string(rate).substr(0, 4)).c_str() : "max");
  std::fflush(stderr);
}
}  // namespace

MessageSink::MessageSink(msg::Publisher bus, const std::string& log_path) : bus_(std::move(bus)) {
  if (!log_path.empty()) {
    log_ = std::make_unique<lcm::LogFile>(log_path, "w");
    if (!log_->good()) throw io::IoError(log_path, "cannot open LCM log for writing");
  }
}

void MessageSink::send(const std::string& channel, const std::vector<uint8_t>& data, int64_t dataset_utime) {
  if (bus_ && !bus_(channel, data))
    spdlog::warn("publishing on {} failed", channel);
  if (log_) {
    if (first_utime_ < 0) first_utime_ = dataset_utime, log_origin_ = app::wallMicros();
    lcm::LogEvent ev;
    ev.eventnum = event_num_++;
    ev.timestamp = log_origin_ + (dataset_utime - first_utime_);
    ev.channel = channel;
    ev.datalen = static_cast<int32_t>(data.size());
    ev.data = const_cast<uint8_t*>(data.data());
    if (log_->writeEvent(&ev) != 0) throw std::runtime_error("writing the LCM log failed");
  }
}

void sendStatus(MessageSink& sink, const ReplayOptions& o, const StreamProgress& p, int8_t state,
                const std::string& reason) {
  stream_status_t s;
  s.utime = app::wallMicros();
  s.robot = o.robot;
  s.state = state;
  s.frames_sent = p.sent;
  s.frames_total = p.total;
  s.source = p.source;
  s.detections = p.detections;
  s.reason = reason;
  sink.send(o.status_channel, s, p.data_utime);
}

int replayDataset(const io::RobotDataset& d, const ReplayOptions& o, const FramePerception& perception,
                  MessageSink& sink, const std::function<bool()>& stop, StreamProgress& progress) {
  const int n = static_cast<int>(d.size());
  int first = std::clamp(o.start_frame, 0, n);
  while (first < n && d.times[first] - d.times.front() < o.start_time) ++first;
  int last = o.max_frames > 0 ? std::min(n, first + o.max_frames) : n;
  const int total = last - first;
  spdlog::info("replaying {} frames [{}, {}) of {} ({}), rate {}", total, first, last, d.path,
               d.sensor == io::RobotDataset::Sensor::Lidar ? "lidar" : "rgbd",
               o.rate > 0 ? std::to_string(o.rate) : "max");
  for (const std::string& w : d.warnings) spdlog::warn("{}: {}", d.path, w);
  if (d.dropped.total() > 0)
    spdlog::warn("{}: {} frames dropped without an odometry pose ({} outside its time span, {} in gaps)", d.path,
                 d.dropped.total(), d.dropped.outside_span, d.dropped.gap);

  const bool bar = o.progress && isatty(STDERR_FILENO);
  const auto wall0 = std::chrono::steady_clock::now();
  auto last_status = wall0;
  progress.source = d.path;
  progress.detections = toString(perception.source());
  progress.total = total;
  auto status = [&](int8_t state, int sent) {
    progress.sent = sent;
    progress.data_utime = first < n ? static_cast<int64_t>(1e6 * (d.times[std::min(first + sent, n - 1)])) : 0;
    sendStatus(sink, o, progress, state);
  };
  status(stream_status_t::RUNNING, 0);
  int sent = 0, unreadable = 0;
  double skipped_s = 0;  // data time not waited for: pauses longer than max_gap_s
  const auto interrupted = [&] {
    if (!stop || !stop()) return false;
    if (bar) std::fprintf(stderr, "\n");
    spdlog::warn("interrupted after {} of {} frames", sent, total);
    return true;
  };
  auto sendOdometry = [&](int i, int64_t utime, int seq) {
    const Pose* prev = i > 0 ? &d.odometry[i - 1].pose : nullptr;
    const double dt = i > 0 ? d.times[i] - d.times[i - 1] : 0.0;
    sink.send(o.odom_channel, toOdometryMessage(d.odometry[i].pose, prev, dt, utime, o.robot, seq), utime);
  };
  for (int i = first; i < last; ++i) {
    if (interrupted()) return sent;
    if (i > first && d.times[i] - d.times[i - 1] > o.max_gap_s) {
      spdlog::warn("{}: frame times jump {:.1f} s between frames {} and {}; replayed as a {:.1f} s pause", d.path,
                   d.times[i] - d.times[i - 1], i - 1, i, o.max_gap_s);
      skipped_s += d.times[i] - d.times[i - 1] - o.max_gap_s;
    }
    const double rel = d.times[i] - d.times[first];
    if (o.rate > 0) {
      const auto due = wall0 + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                   std::chrono::duration<double>((rel - skipped_s) / o.rate));
      while (std::chrono::steady_clock::now() < due) {  // in slices, so a stop request is seen
        std::this_thread::sleep_until(std::min(due, std::chrono::steady_clock::now() + std::chrono::milliseconds(100)));
        if (interrupted()) return sent;
      }
    }
    const int64_t utime = static_cast<int64_t>(std::llround(d.times[i] * 1e6));
    const int seq = i - first;
    try {  // a frame that cannot be read is dropped and counted; the replay goes on
      if (d.sensor == io::RobotDataset::Sensor::Lidar) {
        const lidar_scan_t scan = msg::toLcm(perception.scan(d.scan(i), i), frameHeader(utime, o.robot, seq));
        sendOdometry(i, utime, seq);
        sink.send(o.scan_channel, scan, utime);
      } else {
        io::RgbdImages f = d.rgbd(i);
        const auto masks = perception.masks(std::move(f.mask), f.depth, d.camera.depth_scale, i);
        const rgbd_frame_t frame = toRgbdMessage(f.color, f.depth, masks ? &masks->masks : nullptr,
                                                 masks ? &masks->confidence : nullptr, d.camera, utime, o.robot, seq);
        sendOdometry(i, utime, seq);
        sink.send(o.rgbd_channel, frame, utime);
      }
    } catch (const io::IoError& e) {
      if (bar) std::fprintf(stderr, "\n");
      spdlog::warn("frame {} dropped: {}", i, e.what());
      ++unreadable;
      continue;
    }
    ++sent;
    progress.sent = sent;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_status > std::chrono::seconds(1)) {
      status(stream_status_t::RUNNING, sent);
      last_status = now;
    }
    if (bar) drawProgress(sent, total, rel, o.rate);
    else if (o.progress && total >= 10 && sent % (total / 10) == 0) spdlog::info("{}/{} frames", sent, total);
  }
  if (bar) std::fprintf(stderr, "\n");
  status(stream_status_t::FINISHED, sent);
  spdlog::info("end of data: {} frames sent", sent);
  if (unreadable > 0) spdlog::warn("{} frames could not be read and were dropped", unreadable);
  if (const std::string drops = d.reader->dropSummary(); !drops.empty()) spdlog::info("{}: {}", d.path, drops);
  return sent;
}

void publishFailed(std::unique_ptr<lcm::LCM>& bus, std::unique_ptr<MessageSink>& sink, bool publish,
                   const std::string& url, const std::string& log_path, const ReplayOptions& opt,
                   const StreamProgress& progress, const std::string& reason) {
  try {
    if (!sink) {
      if (publish && !bus) {
        auto b = std::make_unique<lcm::LCM>(url);
        if (b->good()) bus = std::move(b);
      }
      try {
        sink = std::make_unique<MessageSink>(msg::lcmPublisher(bus.get()), log_path);
      } catch (const std::exception&) {  // the log is what failed: the bus alone
        sink = std::make_unique<MessageSink>(msg::lcmPublisher(bus.get()), "");
      }
    }
    sendStatus(*sink, opt, progress, stream_status_t::FAILED, reason);
  } catch (const std::exception& e) {
    spdlog::warn("could not publish the FAILED status on {}: {}", opt.status_channel, e.what());
  }
}

}  // namespace slide
