#pragma once
// The optimizer daemon's logic without the LCM loop: decodes input messages, feeds the
// back-end, journals every accepted input (team/journal.h: checksummed records, one per input,
// its type the input channel and its payload the LCM bytes; replayed at start, so a restarted
// daemon rebuilds the same state), and publishes map, trajectories and status.
#include <chrono>
#include <functional>
#include <memory>
#include <string>

#include "app/channels.h"
#include "backend/optimizer.h"
#include "msg/publisher.h"
#include "slide/keypose_bundle_t.hpp"
#include "slide/loop_closure_t.hpp"
#include "team/journal.h"

namespace slide {

struct OptimizerChannels {
  std::string bundle = app::channels::kKeyPoseBundle;
  std::string peer_bundle = app::channels::kPeerBundle;
  std::string loop_closure = app::channels::kLoopClosure;
  std::string object_map = app::channels::kObjectMap;
  std::string own_map = app::channels::kOwnMap;
  std::string trajectory = app::channels::kTrajectory;
  std::string status = app::channels::kOptimizerStatus;
};

class OptimizerNode {
 public:
  // Publishes through `publish(channel, bytes)`; an empty function publishes nothing.
  using Publisher = msg::Publisher;

  OptimizerNode(const backend::BackendConfig& config, const ClassTable& classes, int robot, OptimizerChannels channels,
                Publisher publish, int publish_every = 1);
  ~OptimizerNode();

  // Replays the journal at `path` (if it exists) through the same handlers without
  // publishing, then keeps appending accepted inputs to it. Returns the inputs replayed. A
  // damaged tail is cut and saved aside (<path>.damaged-<offset>); a record that is not an
  // input or whose replay throws is skipped, counted (replaySkipped) and logged. Throws
  // std::runtime_error naming the path when it cannot be opened or written, or when it holds
  // the LCM log of versions before the checksummed journal.
  int openJournal(const std::string& path);
  // The inputs of the journal at `path` as (channel, LCM bytes), the file unchanged (for tools);
  // a damaged tail is reported in `recovery`. Throws like openJournal.
  struct JournalInput {
    std::string channel;
    std::vector<uint8_t> bytes;
  };
  static std::vector<JournalInput> readJournal(const std::string& path, team::JournalRecovery* recovery = nullptr);

  // Raw LCM input on `channel` (one of the three input channels). Undecodable data and
  // rejected inputs are counted and logged as warnings.
  void handle(const std::string& channel, const void* data, int size);

  void publishAll();
  // Outputs: TUM files <dir>/trajectory_robot<N>.txt for every robot and the (merged) object
  // map <dir>/map_robot<host>.txt (io/object_map_text.h), each written whole or not at all. Written
  // every `period_s` seconds by poll() when the estimate changed (0: never), by writeOutputs()
  // and at stop(). An empty dir writes nothing.
  void setOutputs(const std::string& dir, double period_s);
  // The current estimate to the outputs (no solve); false (logged) when a file cannot be written.
  bool writeOutputs();
  // Between messages: takes a finished background solve into the estimate (then publishes
  // it), settles the estimate when no input came for the settle period, and writes the
  // outputs when their period has passed.
  void poll(std::chrono::steady_clock::time_point now = std::chrono::steady_clock::now());
  // Full solves on the update path run one or two iterations each, so an estimate converges
  // only while inputs keep coming. After `idle_s` seconds without an accepted input the estimate
  // changed since, poll() has it solved to convergence once (Optimizer::settle: on the worker
  // with background solves, then taken in and published like any other; 0: never).
  void setSettle(double idle_s) { settle_after_s_ = idle_s; }
  // Asked to stop: cancels a running solve without waiting for it and writes the current
  // estimate at once; then refines it with a full solve of at most `budget_s` seconds (an
  // iteration may overrun it) and writes and publishes that unless it left an odometry envelope.
  void stop(double budget_s = 1.0);
  // Messages the bus layer dropped before they reached handle() (size cap, handler
  // exceptions): added to the status message's dropped_messages.
  void setBusDrops(std::function<std::uint64_t()> count) { bus_drops_ = std::move(count); }
  const backend::Optimizer& optimizer() const { return optimizer_; }
  backend::Optimizer& optimizer() { return optimizer_; }
  int decodeErrors() const { return decode_errors_; }
  // Accepted inputs the journal could not take (a full disk): an alarm in every status.
  int unjournalled() const { return unjournalled_; }
  // Journal records skipped at the last openJournal (not an input, or their replay threw).
  int replaySkipped() const { return replay_skipped_; }
  const team::JournalRecovery& journalRecovery() const { return journal_recovery_; }

 private:
  enum class Input { Bundle, PeerBundle, LoopClosure };
  bool process(Input kind, const void* data, int size);
  void journal(Input kind, const void* data, int size);
  void publishStatus(const backend::UpdateResult& r);
  void logSettled(const backend::SolveReport& s) const;

  backend::Optimizer optimizer_;
  ClassTable classes_;
  OptimizerChannels channels_;
  Publisher publish_;
  int publish_every_;
  int updates_ = 0;
  int decode_errors_ = 0;
  std::function<std::uint64_t()> bus_drops_;
  int unjournalled_ = 0;
  std::chrono::steady_clock::time_point last_alarm_{};
  bool replaying_ = false;
  int replay_skipped_ = 0;
  team::JournalRecovery journal_recovery_;
  std::unique_ptr<team::Journal> journal_;
  std::string out_dir_;
  double write_period_s_ = 0;
  std::chrono::steady_clock::time_point last_write_{};
  int written_updates_ = -1;  // updates_ when the outputs were last written
  double settle_after_s_ = 0;
  std::chrono::steady_clock::time_point last_input_ = std::chrono::steady_clock::now();
  int settled_updates_ = 0;  // updates_ after the last settling solve
  bool settling_ = false;    // a settling solve runs on the worker
};

}  // namespace slide
