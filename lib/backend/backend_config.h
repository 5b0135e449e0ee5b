#pragma once
// Parameters of the back-end (config/backend.yaml): noise models, association, confirmation,
// incremental solving and input gates.
#include <string>

#include "backend/odometry_envelope.h"
#include "geometry/pose.h"

namespace slide::backend {

struct BackendConfig {
  // Odometry noise, used when a bundle's odom_sigma is missing (zeros) or
  // use_message_sigma is false: sigma = max(floor, per_metre * step length).
  bool use_message_sigma = true;
  double odom_translation_per_m = 0.01;
  double odom_rotation_per_m = 0.001;
  double odom_translation_floor = 0.005;
  double odom_rotation_floor = 0.0005;
  // Each robot's odometry scale (true distance over measured: wheel radius, visual scale) is
  // estimated with this prior sigma about 1; 0: the odometry's translation is taken as it is.
  double odom_scale_sigma = 0.0;
  // Input gates: steps longer or turns larger than these are rejected as absurd.
  double max_step_m = 25.0;
  double max_step_rad = 1.2;

  // Prior on the first own pose; prior on a merged peer's first pose from the inter-robot
  // transform; intra-robot loop closures.
  double prior_translation_sigma = 0.001;
  double prior_rotation_sigma = 0.001;
  double peer_translation_sigma = 1.0;  // horizontal
  // Vertical: place recognition takes the height offset from many matched landmarks' height
  // differences, much better than the horizontal one; peers' heights are otherwise only
  // weakly held (trunk feet along their axes), and a loose anchor let a peer's frame sink.
  double peer_vertical_sigma = 0.3;
  double peer_rotation_sigma = 0.05;
  double loop_translation_sigma = 0.05;
  double loop_rotation_sigma = 0.005;
  // Roll and pitch of every key pose from the odometry's attitude (an IMU's gravity
  // direction does not drift), radians.
  double gravity_sigma = 0.005;

  // Object measurement noise (range-bearing model for positions).
  double range_sigma = 0.1;
  double bearing_sigma = 0.05;
  double vertical_sigma = 0.2;
  double position_sigma_floor = 0.05;
  // An ellipsoid's centroid comes from the part of the object in view; the fit completes it
  // behind the visible side by a guess of the hidden depth. Its range sigma is at least this
  // times the measured horizontal radius (indoors, p10-p90 of the furniture's detections along
  // the line of sight: chairs +-0.03 m, monitors -0.05..+0.09, tables -0.11..+0.26 m).
  double ellipsoid_partial_view = 0.3;
  double cuboid_rotation_sigma = 0.1;
  double cuboid_dims_sigma = 0.3;
  double cylinder_along_axis_sigma = 2.0;
  double cylinder_axis_sigma = 0.1;
  double cylinder_radius_sigma = 0.05;

  // A transform between two robots' odometry origins must be within max_robot_offset_m before
  // it is journalled or touches the graph. (Loop closures are checked against the odometry
  // envelope: backend/odometry_envelope.h, the `soundness:` section.)
  double max_robot_offset_m = 1e5;
  double ellipsoid_size_ema = 0.2;  // weight of a new measurement in radius/height averages
  double robust_loss_scale = 1.5;   // Huber threshold: this * sqrt(residual count) (whitened)
  // Objects farther than this from their key pose (body frame) are dropped: no sensor of the
  // team sees that far, and such values would make association scan huge areas.
  double max_object_range_m = 200.0;

  // Peers' bundles held until their transform arrives: at most max_peers robots besides this
  // one, and max_held_bundles per peer; more is rejected and counted (status rejected_inputs).
  int max_peers = 16;
  int max_held_bundles = 20000;

  // Association and confirmation. The class table's distance threshold is widened by
  // association_sigmas times the detection's own position sigma (range-bearing model).
  int min_observations = 3;
  double association_sigmas = 2.0;
  double association_gate = 0.0;   // > 0: Mahalanobis gate (sigmas) with the detection's covariance
  double outlier_sigmas = 4.0;     // after full solves, observations beyond this are detached
  // After full solves, two landmarks never seen from one key pose are merged when associable;
  // merge_within_shape: also two classes of one shape (a detector's class confusion: a chair
  // taken for a table now and then), when associable under the stricter class's thresholds.
  bool merge_within_shape = true;
  // Two such landmarks of one kind that stand inside one another (the nearer's centre within
  // the larger's radius) may share key poses up to this fraction of the fewer one's observations:
  // a neighbour's or a false object's detection taken now and then, or one object reported in two
  // pieces. (0.25 without the overlap and kind tests cost KITTI 05 a wrong peer merge: team ATE
  // 6.6 -> 11.8 m; with them KITTI 05, 07 and urban are unchanged; BENCHMARKS.md, issue 20.)
  double merge_shared_fraction = 0.35;
  // Revisits: a robot is associated by nearness with a landmark it saw before, and two
  // landmarks it saw at different times are merged, only while this many sigmas of its odometry
  // drift between the two sightings (through a loop closure where one shortens it) stay within
  // the class's association distance, or while no other landmark of its kind lies within that
  // drift of it; beyond, the robot may be seeing any of them, nearness says nothing, and the
  // revisit waits for a loop closure. 0: nearness decides at any drift.
  double revisit_sigmas = 2.0;
  // A box read two ways takes the reading that the landmarks seen whole within this radius (m)
  // agree with (Optimizer::settleReading); 0: the front-end's choice.
  double reading_vote_radius = 30.0;

  // Incremental solving.
  int window_poses = 3;            // own latest poses optimized in each local solve
  int settled_observations = 8;    // landmarks seen this often stay fixed in local solves
  int local_iterations = 3;
  double local_function_tolerance = 1e-3;  // local solves stop once the cost falls by less
  int full_iterations = 2;         // full solves during updates (warm-started)
  int loop_iterations = 1;         // full solves when a loop closure or peer transform arrives
  bool spread_loops = true;        // spread a loop closure's error along its loop before that solve
  int final_iterations = 100;      // full solves on request / at the end (to convergence)
  int full_every = 250;            // key poses between periodic full solves
  int loop_gap = 40;               // a landmark unseen for this many key poses closes a loop
  int min_full_gap = 120;          // key poses between loop-triggered full solves
  double full_function_tolerance = 1e-6;
  double final_function_tolerance = 1e-10;
  // Initial Levenberg-Marquardt trust region of full solves (all start from the last solution).
  double full_trust_region_radius = 1e8;
  int num_threads = 2;  // Ceres threads of full solves (per-key-pose solves use one)
  // Full solves on a worker thread, taken in by the first update after they finish. Not read
  // from YAML: the optimizer daemon turns it on (unless --inline-solves); in-process runs
  // (tests, benchmarks) keep each full solve inside its update, so their figures are
  // reproducible (a background solve's result depends on when the worker finishes).
  bool background_solves = false;

  // Soundness: an intra-robot loop closure, or an estimate of any robot's trajectory after a
  // merge or full solve, that leaves that robot's odometry envelope is refused or undone.
  OdometryEnvelope envelope;
  bool guard_estimate = true;       // check every robot's trajectory after full solves
  // A transform to an already merged peer this far from the one it was merged through
  // contradicts the merge: the peer is un-merged and merged again through it.
  double remerge_translation_m = 2.0;
  double remerge_yaw_deg = 5.0;
  int refine_until_shared = 10;  // a merged peer's transform follows place recognition's refinements
                                 // until it shares this many landmarks with the host
};

// Loads backend.yaml; every key is optional (defaults above); errors name file and key.
BackendConfig loadBackendConfig(const std::string& path);

}  // namespace slide::backend
