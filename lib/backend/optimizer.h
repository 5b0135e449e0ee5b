#pragma once
// The back-end of one robot: validates key-pose bundles (its own and, once an inter-robot
// transform is known, its peers'), associates their objects with landmarks, grows the factor
// graph and keeps it optimized incrementally (local solves per key pose, full solves on loop
// closures, merges and periodically). Everything is in the host robot's frame.
// Full solves run on a snapshot of the graph; with background_solves that happens on one
// worker thread, and the update that finds the solve finished takes its result in (the key
// poses added meanwhile follow their robot's last solved pose, landmarks made meanwhile their
// first observer), so no update waits for a full solve; slide-optimizer runs so by default.
// Without it (BackendConfig's default, for reproducible tests and in-process benchmarks) each
// full solve runs inside the update that asks for it.
#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "backend/backend_config.h"
#include "backend/factor_graph.h"
#include "backend/landmark_grid.h"
#include "objects/class_table.h"
#include "objects/keypose_bundle.h"

namespace slide::backend {

class SolveWorker;

struct TrajectoryPose {
  int seq = 0;
  std::int64_t utime = 0;
  Pose pose = Pose::Identity();
};

struct UpdateResult {
  bool accepted = false;
  bool held = false;        // a peer bundle kept until that peer's transform arrives
  std::string reason;       // why the input was rejected
  std::vector<std::string> warnings;       // objects dropped from an accepted bundle, and why
  std::vector<std::int64_t> landmark_ids;  // per input object: its landmark id, -1 if dropped
  bool full_solve = false;  // a full solve's result entered the estimate in this update
  double full_solve_ms = 0; // that solve's wall time (on the worker when in the background)
  double update_ms = 0;     // wall time of the whole update
  SolveReport solve;
};

class Optimizer {
 public:
  Optimizer(BackendConfig config, ClassTable classes, int host_robot);
  ~Optimizer();
  Optimizer(Optimizer&&) noexcept;
  Optimizer& operator=(Optimizer&&) noexcept;

  int hostRobot() const { return host_; }

  // A key-pose bundle of the host (added at once) or of a peer (held until the peer's
  // transform arrives, then added in the host frame).
  UpdateResult addBundle(const KeyPoseBundle& bundle);
  // T_host_peer maps the peer's frame into the host's. The first one merges the peer's held
  // bundles; later ones close to the transform it was merged through replace its anchor
  // prior, never adding a second, while the peer shares fewer than refine_until_shared
  // landmarks with the host (then the graph aligns the two and they change nothing); one that
  // contradicts it (remerge_* apart) un-merges the
  // peer (its observations leave the graph, which is rebuilt from the recorded inputs) and
  // merges it again through the new transform, when more of the peer's landmarks meet the
  // host's through it than meet them now (else it is rejected: held back). A merge after which
  // some robot's trajectory leaves its odometry envelope is undone and that transform refused
  // from then on.
  UpdateResult addRobotTransform(int peer, const Pose& T_host_peer);
  // Intra-robot loop closure: pose of key pose seq_b's body in key pose seq_a's body.
  // A repeated (robot, seq_a, seq_b) replaces the earlier one. Refused when it is further from
  // the robot's odometry between the two key poses than the odometry envelope allows.
  // It waits for the next full solve to start (at once unless a background solve runs), goes
  // into that solve's snapshot with its error spread along its loop there, and enters the graph
  // with the solve's solution: never before, since a per-key-pose solve would pull the newest
  // key poses alone onto it and bend the trajectory by the whole loop error at one step.
  UpdateResult addLoopClosure(int robot, int seq_a, int seq_b, const Pose& T_a_b);
  // Full solve to convergence over the whole graph (at most final_iterations), in the calling
  // thread (a background solve is cancelled first), then outliers, duplicates and the
  // soundness guard. With max_seconds > 0 it stops after about that long (an iteration may
  // overrun it) and never rebuilds the graph: if the estimate then leaves some robot's odometry
  // envelope, the report says aborted and why (the stop path writes the earlier estimate).
  // With `interruptible`, the stop flag (setStopFlag) ends it at its next iteration and the
  // estimate stays as it was.
  SolveReport fullSolve(double max_seconds = 0, bool interruptible = false);
  // Solves the estimate to convergence once (e.g. when inputs pause): with background_solves
  // a full solve of final_iterations on the worker, taken in by poll() or the next update like
  // any other (outliers, duplicates and the guard follow it; returns at once, an empty
  // report); otherwise fullSolve() here, ended by the stop flag (its report).
  SolveReport settle();
  // Takes a finished background solve into the estimate (updates do this first; call it when
  // idle too). True when one was taken; `r` gets full_solve, its report and any warnings.
  bool poll(UpdateResult* r = nullptr);
  bool solving() const;  // a background solve is running
  // Asks a running background solve to stop and forgets its result; returns at once.
  void cancelSolve();
  // Tests: runs on the worker thread before each background solve (e.g. to hold one).
  void setSolveHook(std::function<void()> hook) { solve_hook_ = std::move(hook); }
  // A flag that, once set (e.g. by a daemon's signal handler), aborts every full solve run
  // inside an update at its next iteration: the estimate stays as it was before that solve.
  // fullSolve() does not look at it.
  void setStopFlag(const std::atomic<bool>* stop) { stop_flag_ = stop; }

  // Landmarks in the host frame (ids are the landmark ids), confirmed ones or all.
  std::vector<Object> landmarks(bool confirmed_only = true) const;
  // The host's own map: landmarks it observed itself at least min_observations times, placed by
  // the joint estimate. Place recognition and the team take this map, not landmarks(): a
  // merged peer's landmarks in it would match the peer's own map at the transform they were
  // merged through, and each refinement would confirm (and drift with) the last one.
  std::vector<Object> ownLandmarks() const;
  // Landmarks observed both by the host and by `peer`.
  int sharedLandmarks(int peer) const;
  std::vector<int> robots() const;  // the host and every merged peer, ascending
  std::vector<TrajectoryPose> trajectory(int robot) const;
  bool merged(int robot) const;
  // The robot's odometry scale as the graph estimates it (1 when it is not estimated).
  double odometryScale(int robot) const;

  int numKeyPoses() const { return static_cast<int>(keyposes_.size()); }
  int numLandmarks(bool confirmed_only = true) const;
  int numPeersMerged() const;
  int numHeld() const;
  int rejected() const { return rejected_; }
  // Key poses never received: gaps in a robot's sequence, bridged with odometry (lost
  // datagrams, or a sender flooding faster than this robot reads).
  std::int64_t missingKeyPoses() const { return missing_keyposes_; }
  int merges() const { return merges_; }
  int detached() const { return detached_; }
  int unmerged() const { return unmerged_; }   // merges undone (contradicted or unsound)
  int rebuilds() const { return rebuilds_; }
  const std::map<std::string, int>& rejections() const { return rejections_; }
  double cost() const { return graph_.cost(); }
  const FactorGraph& graph() const { return graph_; }

  // The same graph solved from scratch (initial values, full convergence), as a baseline.
  struct Batch {
    double ms = 0;
    SolveReport report;
    std::map<int, std::vector<TrajectoryPose>> trajectories;
    std::vector<Object> landmarks;  // confirmed
  };
  Batch solveBatch() const;

 private:
  struct KeyPose {
    int robot, seq;
    std::int64_t utime;
    int var;
    Pose odom_pose;
    OdometryStep step;  // from the previous key pose of the robot (zero for its first)
    int index = 0;          // in its robot's list
    OdometryTotals totals;  // of the robot's steps up to this key pose
  };
  // Every accepted input, in order, so that the graph can be rebuilt without a merge.
  struct Input {
    enum class Kind { Bundle, Transform, Loop } kind = Kind::Bundle;
    KeyPoseBundle bundle;
    int robot = 0, seq_a = 0, seq_b = 0;
    Pose T = Pose::Identity();
  };
  struct Observation {
    int factor;
    int pose_var;
    Object body;  // the measurement, in the key pose's body frame
  };
  struct Landmark {
    std::int64_t id;
    bool alive = true;  // false once merged into another landmark
    std::vector<Observation> seen;
    int class_id;                      // the class with the most votes ...
    std::map<int, double> class_votes; // ... summed observation confidences per class
    Shape shape;
    int var, dims_var = -1;
    int observations = 0;
    int last_step = -1;
    double radius = 0, height = 0, length = 0;  // averages not in the graph
  };
  struct Robot {
    bool merged = false;
    Pose T_host_robot = Pose::Identity();
    int anchor_factor = -1;
    int scale_var = -1;                       // its odometry scale (odometry.scale_sigma > 0)
    std::vector<int> keyposes;                // indices into keyposes_
    std::map<int, KeyPoseBundle> held;        // by seq, before the transform
    // Pairs of its key poses (indices into its list) held together, beyond its odometry, by a
    // loop closure in the graph or a landmark seen from both (association.revisit_sigmas).
    std::vector<std::pair<int, int>> ties;
  };

  const KeyPose& keyPoseOfVar(int var) const;  // of an observation's pose variable
  // Revisits (association.revisit_sigmas). One sigma of the odometry drift between two spans of
  // a robot's key poses (first and last index into its list): along its odometry from the one to
  // the other, or through one of its ties, whichever is less (none when they overlap); the
  // search stops once it is within `enough`.
  using Span = std::pair<int, int>;
  double driftBetween(int robot, Span x, Span y, double enough = 0) const;
  // Per robot, the span of the key poses that observed lm.
  std::map<int, Span> spansOf(const Landmark& lm) const;
  // lm, seen by the robot over x, is now seen over y too (an association or a merge): when its
  // odometry alone would leave the two drifted apart, they are tied (unless a tie within
  // kTieSpacing key poses at both ends holds them already).
  void tie(int robot, Span x, Span y, const Landmark& lm);
  // The least drift, for some robot that observed both, between its observations of a and its
  // observations of b (of a and its key pose `at`, when b is null), or any within which a's gate
  // holds; -1 when no robot did (or revisit_sigmas is 0).
  double driftBetween(const Landmark& a, const Landmark* b, int robot = -1, int at = -1) const;
  // Whether revisit_sigmas of that drift exceed the landmark class's association distance.
  bool driftedApart(const Landmark& lm, double drift) const;
  // Whether nearness can no longer tell that the robot sees lm again (or that `other` is lm):
  // drifted apart, and another landmark of its kind lies within revisit_sigmas of the drift of
  // it, where the robot may as well be seeing that one. A loop closure must first bring the two
  // sightings together (a tie); an object alone of its kind within the drift is still known.
  bool revisitUnsure(const Landmark& lm, double drift, const Landmark* other = nullptr) const;
  UpdateResult reject(UpdateResult r, const std::string& reason);
  std::string checkBundle(const KeyPoseBundle& b, const Robot& robot) const;
  std::vector<Object> usableObjects(const KeyPoseBundle& b, UpdateResult& r) const;
  // Adds the pose, odometry and objects of an already validated bundle; returns the new
  // pose's variable and fills `touched` with the landmarks it observed. Sets `loop` when one
  // of them was last seen long ago.
  int insertBundle(const KeyPoseBundle& b, UpdateResult& r, std::vector<int>& touched, bool& loop);
  // Full solves (optimizer_solve.cpp). A full solve of `iterations` is due: it starts now, or
  // once the running one is taken in. In the calling thread unless background_solves: then
  // returns true, with `r` holding its result.
  struct FullSolveJob;
  bool requestFull(int iterations, UpdateResult& r);
  void startPending(UpdateResult& r);
  std::shared_ptr<FullSolveJob> makeJob(int iterations, double function_tolerance);
  // The job's solution into the graph; false when it is stale (a rebuild) or was cancelled.
  bool adopt(FullSolveJob& job, UpdateResult& r);
  bool background() const { return cfg_.background_solves && !replaying_; }
  // The loop closures waiting for a full solve go into its job (its snapshot, and their
  // spreads); the job's loop factors into the graph when its solution is taken in; a job not
  // taken in (cancelled, aborted) gives its loop closures back to the queue.
  void takePendingLoops(FullSolveJob& job);
  void addLoopFactors(const FullSolveJob& job);
  void requeueLoops(const FullSolveJob& job);
  // A new loop closure cancels a running background solve that brings none (a periodic one or
  // one for re-observed landmarks), so that the closure's solve starts as soon as the worker is
  // free; a solve bringing closures always finishes (closures never starve each other).
  void yieldToLoop();
  int addLandmark(const Object& world);
  void addObservation(int pose_var, const Pose& T_w_b, const Object& body_obj, Landmark& lm);
  // Detections of the landmark read one way only (Object::other_reading unset).
  static int wholeViews(const Landmark& lm);
  // A box read two ways (body frame, key pose T_w_b) takes the reading the map's landmarks of its
  // class within reading_vote_radius, each fixed by kWholeViewsToChooseReading whole views, agree
  // with more (otherReadingAgreesMore): parked cars stand parallel to their neighbours, and the
  // map holds many more cars seen whole than the front-end has in view. Before association.
  void settleReading(Object& seen, const Pose& T_w_b) const;
  Object landmarkObject(const Landmark& lm, const FactorGraph::Values* values = nullptr) const;
  Vector6d odometrySigma(const KeyPoseBundle& b, const Pose& relative, bool bridged) const;
  // A detection's (body frame) range and bearing position sigmas, and the slack its association
  // gate allows beyond its class's association distance: association_sigmas times the larger.
  std::pair<double, double> positionSigmas(const Object& body) const;
  double associationSlack(const Object& body) const;
  void afterSolve(const std::vector<int>& landmarks, bool all);
  // Merges landmarks that turned out to be one object (e.g. after a loop closure corrected
  // the poses, a detector's class confusion made a second one, or a part of the object was
  // seen alone): sameObject() or (one named class) one ellipsoid lying whole within the other; never
  // seen from one key pose, or (one kind, standing inside one another) from at most
  // merge_shared_fraction of the fewer's key poses. Returns merges.
  int mergeDuplicates();
  // a and b are one object: one shape, and associable (same class or family), or (with
  // merge_within_shape) of two classes of that shape associable under each one's thresholds: a
  // detector's class confusion. oa, ob: their current models.
  bool sameObject(const Landmark& a, const Object& oa, const Landmark& b, const Object& ob) const;
  // All of from's observations go to `to`; from ends (merged).
  void moveObservations(Landmark& from, Landmark& to);
  // Adds an observation's vote (its confidence) to the landmark's class.
  static void voteClass(Landmark& lm, int class_id, double confidence);
  // Detaches observations whose residual exceeds outlier_sigmas * sqrt(dimension) from their
  // landmark, or that the solved estimate puts outside the association gate that admitted them
  // (a wrong association made while the poses had drifted): each becomes a new
  // landmark, which mergeDuplicates() may join to the right one. Returns how many. With
  // `norms` (by factor id, as a solved snapshot gave them) only the observations that snapshot
  // held are judged: those made since were placed by key poses that only followed the solve
  // rigidly, and would be found off wherever the solve moved the landmark.
  int detachOutliers(const std::vector<double>* norms = nullptr);
  SolveReport solveAfterInsert(int robot, int pose_var, const std::vector<int>& touched, bool loop, UpdateResult& r);
  const KeyPose* findKeyPose(int robot, int seq) const;
  Vector6d loopSigma() const;  // of an intra-robot loop closure's factor (config)
  Pose poseOf(int var, const FactorGraph::Values* values = nullptr) const;
  // A relative pose the robot's odometry measured, its translation times the robot's estimated
  // odometry scale (unchanged when the scale is not estimated).
  Pose scaledOdometry(int robot, const Pose& odom_a_b) const;
  // Soundness (optimizer_guard.cpp). The odometry envelope check of a robot's key poses
  // (indices into its list) i..j against T_i_j; the frame of a merged peer as the graph holds it.
  EnvelopeCheck envelopeOf(int robot, std::size_t i, std::size_t j, const Pose& T_i_j) const;
  // The first robot whose estimated trajectory (first key pose to each later one) leaves its
  // odometry envelope, or -1.
  int robotOutsideEnvelope(std::string* why = nullptr) const;
  std::optional<Pose> mergedFrame(int peer) const;
  // Landmarks `peer` observed that, moved by C (host frame), lie within their class's
  // association distance of a landmark of that class the host observed (C identity: shared
  // ones meet themselves).
  int landmarksMet(int peer, const Pose& C) const;
  void observedBy(int peer, std::vector<const Landmark*>& host, std::vector<const Landmark*>& other) const;
  // Rebuilds the graph from the recorded inputs, leaving out every transform to `peer` and
  // then (if given) merging it through `T_host_peer`.
  void rebuildWithout(int peer, const std::optional<Pose>& T_host_peer);
  // After a full solve: while some robot left its envelope, undo its merge (a peer) or the
  // newest merge (the host).
  void guard(UpdateResult& r);
  bool refused(int peer, const Pose& T) const;

  BackendConfig cfg_;
  ClassTable classes_;
  int host_;
  FactorGraph graph_;
  std::vector<KeyPose> keyposes_;
  std::vector<int> keypose_of_var_;  // graph variable -> index into keyposes_ (-1: not a key pose)
  std::vector<Landmark> landmarks_;
  std::map<int, Robot> robots_;
  struct LoopFactor {
    int factor;
    Pose T_a_b;
  };
  std::map<std::pair<int, std::pair<int, int>>, LoopFactor> loop_factors_;  // (robot, (seq_a, seq_b))
  LandmarkGrid grid_;
  double max_association_distance_ = 1.0;
  int step_ = 0;                 // key poses inserted so far
  int last_full_step_ = 0;
  bool full_pending_ = false;
  int rejected_ = 0;
  std::int64_t missing_keyposes_ = 0;
  int merges_ = 0;
  int detached_ = 0;
  std::map<std::string, int> rejections_;
  std::vector<Input> inputs_;
  std::vector<int> merge_order_;                 // peers in the order they were merged
  std::map<int, std::vector<Pose>> refused_;     // transforms whose merge was undone
  bool replaying_ = false;
  int unmerged_ = 0, rebuilds_ = 0;
  // Full solves: iterations of the one due (0: none), loop closures it adds to the graph, the
  // one running in the background, the worker, and the graph's generation (a rebuild makes a
  // new one; a solve of an older one is dropped).
  int pending_iterations_ = 0;
  struct PendingLoop {
    int robot, seq_a, seq_b;
    Pose T_a_b;
  };
  std::vector<PendingLoop> pending_loops_;
  std::shared_ptr<FullSolveJob> running_;
  std::unique_ptr<SolveWorker> worker_;
  std::function<void()> solve_hook_;
  const std::atomic<bool>* stop_flag_ = nullptr;
  int epoch_ = 0;
};

}  // namespace slide::backend
