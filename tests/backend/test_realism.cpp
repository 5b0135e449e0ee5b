// The realistic detections laid over a back-end scenario (lib/graph_scenario/realism.h).
#include <gtest/gtest.h>

#include "graph_scenario/realism.h"

namespace slide {
namespace {

struct Counts {
  std::size_t detections = 0, false_detections = 0, confused = 0;
};

Counts count(const graph_scenario::GraphScenario& s) {
  Counts c;
  for (const graph_scenario::ScenarioRobot& r : s.robots)
    for (std::size_t k = 0; k < r.bundles.size(); ++k)
      for (std::size_t i = 0; i < r.seen[k].size(); ++i) {
        ++c.detections;
        if (r.seen[k][i] < 0) ++c.false_detections;
        else if (r.bundles[k].objects[i].class_id != s.landmarks[r.seen[k][i]].class_id) ++c.confused;
      }
  return c;
}

TEST(ScenarioRealism, NoneKeepsEveryDetectionOfEveryTrueObject) {
  const graph_scenario::GraphScenario ideal = graph_scenario::makeIndoorScenario();
  const graph_scenario::GraphScenario same = graph_scenario::withRealism(ideal, {}, ClassTable::loadDefault());
  const Counts a = count(ideal), b = count(same);
  EXPECT_EQ(a.detections, b.detections);
  EXPECT_EQ(b.false_detections, 0u);
  EXPECT_EQ(b.confused, 0u);
}

TEST(ScenarioRealism, MissesFalseObjectsAndConfusionComeAtTheirRates) {
  const graph_scenario::GraphScenario ideal = graph_scenario::makeIndoorScenario();
  const ClassTable classes = ClassTable::loadDefault();
  graph_scenario::ScenarioRealism r;
  r.miss_rate = 0.2;
  r.clutter_fraction = 0.15;
  r.confusion_rate = 0.1;
  const graph_scenario::GraphScenario s = graph_scenario::withRealism(ideal, r, classes);
  const Counts a = count(ideal), b = count(s);
  const double true_kept = static_cast<double>(b.detections - b.false_detections) / a.detections;
  EXPECT_NEAR(true_kept, 0.8, 0.03);
  EXPECT_NEAR(static_cast<double>(b.false_detections) / b.detections, 0.15, 0.04);
  // Confusion picks another class of the same shape: indoors every class is an ellipsoid.
  EXPECT_NEAR(static_cast<double>(b.confused) / (b.detections - b.false_detections), 0.1, 0.03);
  for (const graph_scenario::ScenarioRobot& robot : s.robots)
    for (std::size_t k = 0; k < robot.bundles.size(); ++k) {
      ASSERT_EQ(robot.bundles[k].objects.size(), robot.seen[k].size());
      for (const Object& o : robot.bundles[k].objects) EXPECT_EQ(o.id, -1);
    }
}

TEST(ScenarioRealism, NoiseTheEstimatorIsNotToldOf) {
  const graph_scenario::GraphScenario ideal = graph_scenario::makeUrbanScenario();
  graph_scenario::ScenarioRealism r;
  r.noise_scale = 2.0;
  const graph_scenario::GraphScenario s = graph_scenario::withRealism(ideal, r, ClassTable::loadDefault());
  ASSERT_EQ(s.robots[0].bundles.size(), ideal.robots[0].bundles.size());
  // The bundles report the nominal odometry sigmas while the steps' errors are twice as large.
  double sq_ideal = 0, sq = 0;
  for (std::size_t k = 1; k < s.robots[0].bundles.size(); ++k) {
    EXPECT_EQ(s.robots[0].bundles[k].odom_sigma, ideal.robots[0].bundles[k].odom_sigma);
    const Pose step = s.robots[0].truth[k - 1].inverse() * s.robots[0].truth[k];
    sq_ideal += (ideal.robots[0].bundles[k].relative_odom.translation() - step.translation()).squaredNorm();
    sq += (s.robots[0].bundles[k].relative_odom.translation() - step.translation()).squaredNorm();
  }
  EXPECT_NEAR(std::sqrt(sq / sq_ideal), 2.0, 0.2);
}

TEST(ScenarioRealism, RatesOutsideTheirRangeAreRefused) {
  const graph_scenario::GraphScenario ideal = graph_scenario::makeIndoorScenario();
  const ClassTable classes = ClassTable::loadDefault();
  graph_scenario::ScenarioRealism r;
  r.miss_rate = 1.0;
  EXPECT_THROW(graph_scenario::withRealism(ideal, r, classes), std::invalid_argument);
  r = {};
  r.noise_scale = 0;
  EXPECT_THROW(graph_scenario::withRealism(ideal, r, classes), std::invalid_argument);
  r = {};
  r.clutter_fraction = -0.1;
  EXPECT_THROW(graph_scenario::withRealism(ideal, r, classes), std::invalid_argument);
}

}  // namespace
}  // namespace slide
