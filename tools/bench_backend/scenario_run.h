#pragma once
// Runs a back-end scenario through the optimizer the way the daemon would see it and
// measures per-update time, accuracy and the batch baseline.
#include <string>
#include <vector>

#include "backend/backend_config.h"
#include "graph_scenario/scenario.h"

namespace slide {

struct ScenarioRunResult {
  std::vector<double> update_ms;      // wall time, one per key pose or transform update
  std::vector<double> update_cpu_ms;  // the same updates in thread CPU time
  double final_solve_ms = 0, final_solve_cpu_ms = 0;
  double batch_ms = 0, batch_cpu_ms = 0;
  double incremental_cost = 0, batch_cost = 0;
  double ate_m = 0, odom_ate_m = 0, batch_ate_m = 0;
  double live_ate_m = 0;  // the estimate as published after the last update, before the final solve
  double landmark_rmse_m = 0;
  int landmarks = 0;
  int true_landmarks_seen = 0;
  int full_solves = 0;
  std::vector<double> full_solve_ms;  // wall time of each full solve taken in (on the worker when in the background)
  int loops_during_solve = 0;         // loop closures that arrived while a background solve ran
  // The live estimate's worst key-pose step: largest difference between an estimated and the
  // true relative translation of consecutive key poses (evaluation against the truth).
  double live_max_step_error_m = 0;
  // Confirmed landmarks whose majority true object is also another confirmed landmark's, as
  // a fraction of the confirmed landmarks (evaluation against the simulator's associations).
  double duplicate_fraction = 0;
  int loop_closures = 0;  // intra-robot closures given (simulated loop closer)
  double wrong_association_fraction = 0;  // detections not of their landmark's majority object
  int keyposes = 0;
  double objects_per_keypose = 0;
  int rejected = 0;
};

// Multi-robot scenarios: the host is robots[0]; bundles are interleaved round-robin, each
// peer's transform arrives half-way (with 0.3 m / 1 deg error) and is refined at
// three quarters (0.05 m / 0.2 deg).
// pace_hz > 0: while a background full solve runs, inputs arrive at most this often (the
// robot's key-pose rate; otherwise they come as fast as the optimizer takes them).
// final_seconds > 0 bounds the final full solve (Optimizer::fullSolve's max_seconds).
// progress_every > 0: every that many key poses of the host (and, at debug level, after every
// full solve taken in), logs the live estimate's ATE so far against the truth and against odometry.
ScenarioRunResult runScenario(const graph_scenario::GraphScenario& s, const backend::BackendConfig& cfg,
                              bool with_batch = true, double pace_hz = 0, double final_seconds = 0,
                              int progress_every = 0);

}  // namespace slide
