#include "optimizer_node.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "app/clock.h"
#include "bundle_messages.h"
#include "io/tum_trajectory.h"
#include "io/object_map_text.h"
#include "slide/optimizer_status_t.hpp"

namespace slide {

namespace {
// Journal record types are the inputs' fixed channel names, whatever the bus calls them.
constexpr int kInputs = 3;
const char* journalChannel(int kind) {
  static const char* names[kInputs] = {"KEYPOSE_BUNDLE", "PEER_BUNDLE", "LOOP_CLOSURE"};
  return names[kind];
}
std::uint8_t recordType(int kind) { return static_cast<std::uint8_t>(kind + 1); }

// The journal of versions before checksums was an LCM log: refused, not cut as damage.
void checkJournalFile(const std::string& path) {
  if (!std::filesystem::exists(path)) return;
  // A device or pipe would feed the reader without end.
  if (!std::filesystem::is_regular_file(path)) throw std::runtime_error("journal " + path + " is not a regular file");
  if (!team::Journal::looksLikeJournal(path))
    throw std::runtime_error("journal " + path + " is not a slide journal (an LCM log of an optimizer before "
                             "checksummed journals?): move it aside to start afresh; slide-journal-replay --journal " +
                             path + " still reads an LCM log");
}

void logResult(const backend::UpdateResult& r, const std::string& what) {
  for (const auto& w : r.warnings) spdlog::warn("{}", w);
  if (!r.accepted) spdlog::warn("rejected {}: {}", what, r.reason);
}
}  // namespace

OptimizerNode::OptimizerNode(const backend::BackendConfig& config, const ClassTable& classes, int robot,
                             OptimizerChannels channels, Publisher publish, int publish_every)
    : optimizer_(config, classes, robot),
      classes_(classes),
      channels_(std::move(channels)),
      publish_(std::move(publish)),
      publish_every_(std::max(1, publish_every)) {}

OptimizerNode::~OptimizerNode() = default;

std::vector<OptimizerNode::JournalInput> OptimizerNode::readJournal(const std::string& path,
                                                                   team::JournalRecovery* recovery) {
  checkJournalFile(path);
  std::vector<JournalInput> out;
  for (auto& r : team::Journal::read(path, recovery))
    if (r.type >= 1 && r.type <= kInputs) out.push_back({journalChannel(r.type - 1), std::move(r.payload)});
  return out;
}

int OptimizerNode::openJournal(const std::string& path) {
  checkJournalFile(path);
  std::vector<team::JournalRecord> records;
  journal_.reset();
  journal_ = std::make_unique<team::Journal>(path, &records, &journal_recovery_);
  if (journal_recovery_.dropped_bytes)
    spdlog::warn("journal {}: cut a damaged tail of {} bytes after {} good records ({})", path,
                 journal_recovery_.dropped_bytes, journal_recovery_.records,
                 journal_recovery_.not_saved.empty() ? "saved to " + journal_recovery_.damaged_copy
                                                     : journal_recovery_.not_saved);
  replaying_ = true;
  // Whatever one record does (not an input, its replay throws), the others are still replayed.
  const int replayed = static_cast<int>(team::replayRecords(
      records,
      [this](const team::JournalRecord& r) -> std::string {
        if (r.type < 1 || r.type > kInputs) return "unknown record type " + std::to_string(r.type);
        process(static_cast<Input>(r.type - 1), r.payload.data(), static_cast<int>(r.payload.size()));
        return {};
      },
      journal_recovery_));
  replaying_ = false;
  replay_skipped_ = static_cast<int>(journal_recovery_.skipped);
  if (replay_skipped_)
    spdlog::warn("journal {}: skipped {} records it cannot replay (first: {})", path, replay_skipped_,
                 journal_recovery_.first_skipped);
  spdlog::info("journal {}: replayed {} inputs ({} key poses, {} landmarks)", path, replayed, optimizer_.numKeyPoses(),
               optimizer_.numLandmarks());
  return replayed;
}

void OptimizerNode::journal(Input kind, const void* data, int size) {
  if (!journal_ || replaying_) return;
  // A failed write (a full disk) is an alarm, not a reason to stop: the input is in the graph
  // but would be lost at a restart. Counted, logged as an error, shown in every status. The
  // journal cuts a torn record back off, so later records stay reachable.
  try {
    const auto* p = static_cast<const std::uint8_t*>(data);
    journal_->append(recordType(static_cast<int>(kind)), team::Bytes(p, p + size));
    return;
  } catch (const std::exception& e) {
    ++unjournalled_;
    const auto t = std::chrono::steady_clock::now();
    if (unjournalled_ == 1 || t - last_alarm_ > std::chrono::seconds(10)) {
      spdlog::error("JOURNAL WRITE FAILED ({}): {} accepted inputs so far are not in the journal and would be lost "
                    "at a restart",
                    e.what(), unjournalled_);
      last_alarm_ = t;
    }
  }
}

void OptimizerNode::handle(const std::string& channel, const void* data, int size) {
  Input kind;
  if (channel == channels_.bundle) kind = Input::Bundle;
  else if (channel == channels_.peer_bundle) kind = Input::PeerBundle;
  else if (channel == channels_.loop_closure) kind = Input::LoopClosure;
  else return;
  if (process(kind, data, size)) {
    journal(kind, data, size);
    last_input_ = std::chrono::steady_clock::now();
  }
}

bool OptimizerNode::process(Input kind, const void* data, int size) {
  backend::UpdateResult r;
  if (kind == Input::LoopClosure) {
    loop_closure_t m;
    if (m.decode(data, 0, size) < 0) {
      ++decode_errors_;
      spdlog::warn("undecodable loop_closure_t on {} ({} bytes)", channels_.loop_closure, size);
      return false;
    }
    const Pose T = poseFromXyzYaw(m.x, m.y, m.z, m.yaw);
    const int host = optimizer_.hostRobot();
    if (m.robot_a == m.robot_b) {
      r = optimizer_.addLoopClosure(m.robot_a, m.keypose_a, m.keypose_b, T);
    } else if (m.robot_a == host) {
      r = optimizer_.addRobotTransform(m.robot_b, T);
    } else if (m.robot_b == host) {
      r = optimizer_.addRobotTransform(m.robot_a, T.inverse());
    } else {
      spdlog::debug("loop closure between robots {} and {} does not involve robot {}", m.robot_a, m.robot_b, host);
      return false;
    }
    logResult(r, "loop closure " + std::to_string(m.robot_a) + "/" + std::to_string(m.robot_b));
  } else {
    keypose_bundle_t m;
    const std::string& channel = kind == Input::Bundle ? channels_.bundle : channels_.peer_bundle;
    if (m.decode(data, 0, size) < 0) {
      ++decode_errors_;
      spdlog::warn("undecodable keypose_bundle_t on {} ({} bytes)", channel, size);
      return false;
    }
    const bool own = m.header.robot == optimizer_.hostRobot();
    if (own != (kind == Input::Bundle)) {
      spdlog::warn("ignored bundle of robot {} on {}: {} carries {} bundles only", m.header.robot, channel, channel,
                   kind == Input::Bundle ? "this robot's" : "peers'");
      return false;
    }
    std::vector<std::string> dropped;
    const KeyPoseBundle b = msg::fromLcm(m, &dropped);
    for (const auto& w : dropped) spdlog::warn("malformed object dropped: robot {} key pose {}: {}", b.robot, b.seq, w);
    r = optimizer_.addBundle(b);
    logResult(r, "bundle of robot " + std::to_string(b.robot) + " key pose " + std::to_string(b.seq));
  }
  if (!r.accepted) {
    if (!replaying_) publishStatus(r);
    if (r.full_solve) ++updates_;  // a background solve was taken in: the estimate changed
    if (!replaying_ && r.full_solve) publishAll();
    return false;
  }
  ++updates_;
  if (!replaying_) {
    publishStatus(r);
    if (updates_ % publish_every_ == 0 || r.full_solve) publishAll();
  }
  return true;
}

void OptimizerNode::publishStatus(const backend::UpdateResult& r) {
  if (!publish_) return;
  optimizer_status_t s;
  s.utime = app::wallMicros();
  s.robot = optimizer_.hostRobot();
  s.num_keyposes = optimizer_.numKeyPoses();
  s.num_landmarks = optimizer_.numLandmarks();
  s.num_peers_merged = optimizer_.numPeersMerged();
  s.full_solve = r.full_solve;
  s.update_ms = r.update_ms;
  s.final_cost = r.solve.final_cost;
  s.rejected_inputs = optimizer_.rejected();
  const std::uint64_t dropped = static_cast<std::uint64_t>(decode_errors_) + (bus_drops_ ? bus_drops_() : 0);
  s.dropped_messages = static_cast<std::int32_t>(std::min<std::uint64_t>(dropped, INT32_MAX));
  s.unjournalled_inputs = unjournalled_;
  s.missing_keyposes = static_cast<std::int32_t>(std::min<std::int64_t>(optimizer_.missingKeyPoses(), INT32_MAX));
  publish_(channels_.status, msg::encodeLcm(s));
}

void OptimizerNode::publishAll() {
  if (!publish_) return;
  const std::int64_t t = app::wallMicros();
  const int host = optimizer_.hostRobot();
  publish_(channels_.object_map, msg::encodeLcm(objectMapMsg(t, host, optimizer_.landmarks())));
  publish_(channels_.own_map, msg::encodeLcm(objectMapMsg(t, host, optimizer_.ownLandmarks())));
  for (int r : optimizer_.robots()) publish_(channels_.trajectory, msg::encodeLcm(trajectoryMsg(t, r, host, optimizer_.trajectory(r))));
}

void OptimizerNode::setOutputs(const std::string& dir, double period_s) {
  out_dir_ = dir;
  write_period_s_ = std::max(0.0, period_s);
  last_write_ = std::chrono::steady_clock::now();
}

bool OptimizerNode::writeOutputs() {
  if (out_dir_.empty()) return true;
  // A full disk or a removed folder is logged, never fatal: the next write tries again.
  try {
    std::filesystem::create_directories(out_dir_);
    for (int r : optimizer_.robots()) {
      std::vector<StampedPose> poses;
      for (const backend::TrajectoryPose& p : optimizer_.trajectory(r)) poses.push_back({p.utime * 1e-6, p.pose});
      io::writeTum(out_dir_ + "/trajectory_robot" + std::to_string(r) + ".txt", poses);
    }
    const ObjectMap objects(optimizer_.landmarks());
    io::writeObjectMapText(out_dir_ + "/map_robot" + std::to_string(optimizer_.hostRobot()) + ".txt", objects,
                           classes_);
    spdlog::debug("wrote {} key poses and {} objects to {}", optimizer_.numKeyPoses(), objects.size(), out_dir_);
  } catch (const std::exception& e) {
    spdlog::error("outputs not written: {}", e.what());
    return false;
  }
  written_updates_ = updates_;
  return true;
}

void OptimizerNode::poll(std::chrono::steady_clock::time_point now) {
  backend::UpdateResult r;
  if (optimizer_.poll(&r)) {
    ++updates_;
    logResult(r, "background solve");
    if (settling_) {
      settled_updates_ = updates_;
      logSettled(r.solve);
    }
    publishAll();
  }
  if (!optimizer_.solving()) settling_ = false;  // taken in above, or by an update (input came)
  if (settle_after_s_ > 0 && updates_ != settled_updates_ && optimizer_.numKeyPoses() > 0 && !optimizer_.solving() &&
      now - last_input_ >= std::chrono::duration<double>(settle_after_s_)) {
    const backend::SolveReport s = optimizer_.settle();
    if (optimizer_.solving()) {
      settling_ = true;  // on the worker: a later poll() takes it in
    } else {
      ++updates_;
      settled_updates_ = updates_;
      logSettled(s);
      publishAll();
    }
  }
  if (write_period_s_ > 0 && updates_ != written_updates_ &&
      now - last_write_ >= std::chrono::duration<double>(write_period_s_)) {
    last_write_ = now;
    writeOutputs();
  }
}

void OptimizerNode::logSettled(const backend::SolveReport& s) const {
  spdlog::info("no input for {:.0f} s: settled the estimate ({} iterations, {:.0f} ms, cost {:.4g} -> {:.4g})",
               settle_after_s_, s.iterations, s.wall_ms, s.initial_cost, s.final_cost);
}

void OptimizerNode::stop(double budget_s) {
  optimizer_.cancelSolve();
  if (writeOutputs() && !out_dir_.empty())
    spdlog::info("wrote the estimate of {} key poses to {}", optimizer_.numKeyPoses(), out_dir_);
  const backend::SolveReport s = optimizer_.fullSolve(budget_s);
  if (s.aborted) {
    spdlog::warn("final solve not used: {}", s.message);
    return;
  }
  if (writeOutputs() && !out_dir_.empty())
    spdlog::info("wrote the final solve ({} iterations, {}) to {}", s.iterations, s.message, out_dir_);
  publishAll();
}

}  // namespace slide
