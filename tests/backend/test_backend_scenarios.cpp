// Long runs (LABELS scenario): the benchmark scenarios through the optimizer, checking
// accuracy only (speed is reported by slide-bench-backend, never tested).
#include <gtest/gtest.h>

#include "scenario_run.h"

using namespace slide;

TEST(BackendScenarios, UrbanBeatsOdometryAndMapsEachObjectOnce) {
  const ScenarioRunResult r = runScenario(graph_scenario::makeUrbanScenario(), backend::BackendConfig{});
  EXPECT_LT(r.ate_m, r.odom_ate_m / 3.0);
  EXPECT_LT(r.batch_ate_m, r.odom_ate_m / 3.0);
  EXPECT_NEAR(r.incremental_cost, r.batch_cost, 1e-6 * r.batch_cost);
  EXPECT_NEAR(r.landmarks, r.true_landmarks_seen, 0.05 * r.true_landmarks_seen);
  EXPECT_LT(r.wrong_association_fraction, 0.01);
}

TEST(BackendScenarios, ForestClosesItsLoops) {
  const ScenarioRunResult r = runScenario(graph_scenario::makeForestScenario(), backend::BackendConfig{}, false);
  EXPECT_LT(r.ate_m, r.odom_ate_m / 3.0);
  EXPECT_NEAR(r.landmarks, r.true_landmarks_seen, 0.1 * r.true_landmarks_seen);
}

TEST(BackendScenarios, Kitti07ThreeRobotsMerge) {
  const std::string data = SLIDE_DATA_DIR;
  const ScenarioRunResult r = runScenario(
      graph_scenario::makeKittiScenario("kitti07", data + "/kitti/poses/07.txt", data + "/kitti/poles/07.csv", 3),
      backend::BackendConfig{}, false);
  EXPECT_EQ(r.keyposes, 292);
  EXPECT_LT(r.ate_m, r.odom_ate_m);
  EXPECT_LT(r.ate_m, 0.962);  // the paper's figure on 07
}
