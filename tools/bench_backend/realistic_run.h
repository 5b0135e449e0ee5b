#pragma once
// A back-end scenario run as the daemons chain it, with nothing taken from the truth on the
// robot's side: every robot's optimizer publishes its own map, its loop closer (place
// recognition on those maps, config/loop_closer.yaml) finds intra-robot closures and, on the
// host, the transforms to its peers; the host's optimizer takes them as the daemon does.
// The truth only scores the result.
#include <vector>

#include "backend/backend_config.h"
#include "place/loop_closer.h"
#include "graph_scenario/scenario.h"

namespace slide {

struct RealisticRunResult {
  std::vector<double> update_ms, update_cpu_ms;  // the host optimizer's updates (bundles, closures, transforms)
  double place_cpu_s = 0;                        // every robot's loop closer (place recognition), thread CPU
  double ate_m = 0, odom_ate_m = 0;              // host and merged peers, after a final solve
  double host_ate_m = 0, host_odom_ate_m = 0;    // the host's own trajectory and odometry
  int peers = 0, peers_merged = 0;
  int intra_closures = 0, inter_transforms = 0;  // given to the host's optimizer
  // Scored by the simulator's truth: intra-robot closures given more than 1 m or 2 deg from the
  // true relative pose of their two key poses, and of those the host's optimizer accepted.
  int wrong_intra = 0, intra_accepted = 0, wrong_intra_accepted = 0;
  struct IntraClosure {
    int seq_a = 0, seq_b = 0;
    double error_m = 0, error_deg = 0;  // against truth[a]^-1 truth[b]
    bool accepted = false;              // by the host's optimizer (odometry envelope)
    double host_ate_m = 0;              // the host's ATE so far (SE3), just before this closure
  };
  std::vector<IntraClosure> intra;
  struct AteSoFar {
    int keyposes = 0;
    double host_ate_m = 0, odom_ate_m = 0;  // over the host's key poses so far, SE3-aligned
  };
  std::vector<AteSoFar> ate_trace;  // every 50 key poses
  int wrong_inter = 0;  // of those: > 1 m or > 2 deg from the two maps' alignment, or maps sharing no object
  // Per transform given: its error against the least-squares alignment of the two own maps over
  // the true objects both hold (the truth for bent maps), and against the robots' true frames.
  std::vector<double> map_error_m, frame_error_m;
  // Maps bent by drift that share several places admit no one rigid alignment: the same, with
  // the truth the alignment over the true objects both hold within kPlaceRadius of the
  // transform's inliers in the host's map (the place it was found at).
  static constexpr double kPlaceRadius = 60.0;
  int wrong_inter_at_place = 0;
  std::vector<double> place_error_m;
  int landmarks = 0, false_landmarks = 0;        // confirmed; false: most detections from false objects
  double duplicate_fraction = 0;  // confirmed landmarks beyond the first whose detections are mostly of one true object
  double landmark_rmse_m = 0;
  int keyposes = 0;
};

// keypose_period_s: the simulated time between key poses (the loop closer's periods are in
// seconds); map_every: key poses between own-map publications.
RealisticRunResult runRealistic(const graph_scenario::GraphScenario& s, const backend::BackendConfig& cfg,
                                const place::LoopCloserParams& closer, double keypose_period_s = 1.0,
                                int map_every = 5);

}  // namespace slide
