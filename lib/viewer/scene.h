#pragma once
// What the live viewer shows, kept as versioned state so that every browser gets only what
// changed since it was last served (viewer::Scene), and drawn from each robot's point of view:
// a view is one robot's bus, in that robot's frame (its map, its trajectory and the peers'
// trajectories it merged, its current key pose and last instances, the loop closures it found,
// its optimizer's and sensor driver's status, the team links it hears).
//
// Every change takes a new version number; delta(since) lists what has a newer one, and
// removed objects as tombstones. A browser that fell behind further than the tombstones kept
// (or an older epoch, after reset()) gets a full snapshot instead. Numbers are rounded to what
// a picture needs (centimetres, milliradians), and a change smaller than that is no change, so
// a map re-published unchanged costs nothing. No LCM and no HTTP: the daemon feeds it decoded,
// checked values. Not thread-safe (the daemon holds a lock).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geometry/pose.h"
#include "objects/object.h"
#include "viewer/thin.h"

namespace slide::viewer {

// A few points of one instance of the last scan, already in the view's frame.
struct InstanceView {
  int class_id = 0;
  std::vector<Eigen::Vector3f> points;
};

struct LoopView {
  int robot_a = 0, robot_b = 0, keypose_a = -1, keypose_b = -1;
  std::string method;  // "slidegraph" | "slidematch"
  double x = 0, y = 0, z = 0, yaw = 0, score = 0;
  std::vector<std::int64_t> inliers_a, inliers_b;  // object ids in robot_a's / robot_b's map
};

struct OptimizerView {
  int keyposes = 0, landmarks = 0, peers_merged = 0;
  double update_ms = 0;
  bool full_solve = false;
  int rejected = 0, dropped = 0;
};

struct SensorView {
  std::string state;  // running | finished | failed
  int frames_sent = 0, frames_total = 0;
  std::string source, detections, reason;
};

struct SceneLimits {
  std::size_t max_tombstones = 4096;        // older ones fall off; a client that far behind resyncs
  std::size_t max_trajectory_points = 2000; // longer trajectories are sent evenly thinned
  std::size_t max_loops = 8;                // latest loop closures kept per view
  double link_timeout_s = 5.0;              // a peer heard less recently than this is unlinked
  double rate_window_s = 5.0;               // team traffic rate averaged over this
};

class Scene {
 public:
  explicit Scene(SceneLimits limits = {});

  // The whole map of `view` (objects not in it are removed); `t` in seconds (log or wall time).
  void setObjectMap(int view, const std::vector<Object>& objects, double t);
  // The key-pose positions of `robot` in the frame of `view`.
  void setTrajectory(int view, int robot, const std::vector<Eigen::Vector3d>& positions, double t);
  void setKeyPose(int view, int seq, const Pose& T_view_body, double t);
  void setInstances(int view, const std::vector<InstanceView>& instances, double t);
  void addLoopClosure(int view, const LoopView& lc, double t);
  void setOptimizer(int view, const OptimizerView& s, double t);
  void setSensor(int view, const SensorView& s, double t);
  // A team-bus message from `sender`, heard by `listener` (a robot id, or -1 for this host).
  void noteTeamMessage(int listener, int sender, std::size_t bytes, double t);
  // Advances the scene's clock: peers not heard for link_timeout_s are unlinked, rates decay.
  void tick(double t);
  // Forgets everything (a replay jumping back): a new epoch, so every client resyncs.
  void reset();

  std::uint64_t epoch() const { return epoch_; }
  std::uint64_t version() const { return version_; }
  double time() const { return time_; }
  // What changed after (epoch, since): {"epoch", "version", "reset", "time", "views": {...},
  // "team": {...}}; "reset": true (a full snapshot) when `epoch` is not the current one or
  // `since` is older than the oldest tombstone kept. Format: docs in daemons/viewer/web/viewer.js.
  nlohmann::json delta(std::uint64_t epoch, std::uint64_t since) const;

  // Counts for status lines and tests.
  std::size_t objectCount(int view) const;
  std::size_t viewCount() const { return views_.size(); }

 private:
  template <class T>
  struct Versioned {
    T value{};
    std::uint64_t version = 0;  // 0: never set
  };
  struct ObjectEntry {
    std::vector<double> row;  // rounded: [class, shape, params...]
    std::uint64_t version = 0;
  };
  struct View {
    std::map<std::int64_t, ObjectEntry> objects;
    std::map<int, Versioned<std::vector<double>>> trajectories;  // robot -> rounded x,y,z,...
    Versioned<nlohmann::json> keypose, instances, optimizer, sensor, loops;
    std::vector<LoopView> loop_list;
  };
  struct Listener {
    std::map<int, double> last_heard;            // sender -> t
    std::vector<std::pair<double, std::size_t>> traffic;  // (t, bytes) inside the rate window
    Versioned<nlohmann::json> summary;
  };
  struct Tombstone {
    int view;
    std::int64_t id;
    std::uint64_t version;
  };

  View& view(int v);
  std::uint64_t bump() { return ++version_; }
  void setJson(Versioned<nlohmann::json>& slot, nlohmann::json value);
  void updateListener(int listener, Listener& l);
  void advance(double t);

  SceneLimits limits_;
  std::uint64_t epoch_ = 1, version_ = 0, tombstone_floor_ = 0;
  double time_ = 0;
  std::map<int, View> views_;
  std::map<int, Listener> listeners_;
  std::vector<Tombstone> tombstones_;
};

}  // namespace slide::viewer
