// The realistic detections laid over a back-end scenario (lib/graph_scenario/realism.h).
#include <cmath>
#include <vector>

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

// Odometry that reads distance wrong: each robot's path length times one factor of its own (the
// factors of a 5 % error differ between robots and from 1), its headings and every detection as
// without the error.
TEST(ScenarioRealism, OdometryThatReadsDistanceWrongByOneFactorPerRobot) {
  graph_scenario::GraphScenario ideal = graph_scenario::makeIndoorScenario();
  ideal.robots.push_back(ideal.robots[0]);
  ideal.robots[1].id = 1;
  const ClassTable classes = ClassTable::loadDefault();
  graph_scenario::ScenarioRealism r;
  const graph_scenario::GraphScenario plain = graph_scenario::withRealism(ideal, r, classes);
  r.odom_scale_error = 0.05;
  const graph_scenario::GraphScenario scaled = graph_scenario::withRealism(ideal, r, classes);
  std::vector<double> factors;
  for (std::size_t i = 0; i < plain.robots.size(); ++i) {
    const auto& a = plain.robots[i].bundles;
    const auto& b = scaled.robots[i].bundles;
    ASSERT_EQ(a.size(), b.size());
    const double factor = b[1].relative_odom.translation().norm() / a[1].relative_odom.translation().norm();
    for (std::size_t k = 1; k < a.size(); ++k) {
      EXPECT_NEAR(b[k].relative_odom.translation().norm(), factor * a[k].relative_odom.translation().norm(), 1e-9);
      EXPECT_TRUE(b[k].relative_odom.linear().isApprox(a[k].relative_odom.linear()));
      EXPECT_TRUE(b[k].odom_pose.isApprox(b[k - 1].odom_pose * b[k].relative_odom, 1e-9));
      ASSERT_EQ(b[k].objects.size(), a[k].objects.size());
      for (std::size_t j = 0; j < a[k].objects.size(); ++j)
        EXPECT_EQ(b[k].objects[j].position(), a[k].objects[j].position());
    }
    factors.push_back(factor);
  }
  EXPECT_GT(std::abs(factors[0] - 1.0), 1e-4);
  EXPECT_NE(factors[0], factors[1]);
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
  r = {};
  r.odom_scale_error = 0.5;
  EXPECT_THROW(graph_scenario::withRealism(ideal, r, classes), std::invalid_argument);
}

}  // namespace
}  // namespace slide
