#include <gtest/gtest.h>

#include <cmath>

#include "eval/bandwidth.h"
#include "eval/label_iou.h"
#include "eval/object_matching.h"
#include "eval/stage_timing.h"

using namespace slide;

namespace {
Object at(int cls, double x, double y, double z = 0) {
  Object o;
  o.class_id = cls;
  o.model = Ellipsoid{{x, y, z}, 0.3, 0.5};
  return o;
}
}  // namespace

TEST(ObjectMatching, HandComputedPrecisionRecallF1) {
  // Truth: three cars (10) and two trunks (71).
  const std::vector<Object> gt{at(10, 0, 0), at(10, 10, 0), at(10, 20, 0), at(71, 0, 5), at(71, 5, 5)};
  // Estimate: car near gt0 (0.3 m), car near gt1 (0.4 m), a car far from everything,
  // a trunk near gt3 (0.5 m), and a trunk standing where a car is (wrong class).
  const std::vector<Object> est{at(10, 0.3, 0), at(10, 10, 0.4), at(10, 50, 0), at(71, 0, 5.5), at(71, 20, 0)};
  const eval::ObjectMappingScore s = eval::scoreObjectMap(est, gt, {1.0});
  EXPECT_EQ(s.overall.true_positives, 3u);
  EXPECT_NEAR(s.overall.precision, 3.0 / 5, 1e-12);
  EXPECT_NEAR(s.overall.recall, 3.0 / 5, 1e-12);
  EXPECT_NEAR(s.overall.f1, 0.6, 1e-12);
  EXPECT_NEAR(s.overall.position_rmse, std::sqrt((0.09 + 0.16 + 0.25) / 3), 1e-12);
  ASSERT_EQ(s.per_class.size(), 2u);
  const eval::ClassScore& cars = s.per_class[0];
  EXPECT_EQ(cars.class_id, 10);
  EXPECT_NEAR(cars.precision, 2.0 / 3, 1e-12);
  EXPECT_NEAR(cars.recall, 2.0 / 3, 1e-12);
  const eval::ClassScore& trunks = s.per_class[1];
  EXPECT_NEAR(trunks.precision, 0.5, 1e-12);
  EXPECT_NEAR(trunks.recall, 0.5, 1e-12);
  EXPECT_NEAR(trunks.f1, 0.5, 1e-12);
  EXPECT_NEAR(trunks.position_rmse, 0.5, 1e-12);
  // Ignoring classes, the trunk at (20, 0) matches the third car.
  eval::ObjectMatchOptions any{1.0};
  any.match_classes = false;
  EXPECT_EQ(eval::scoreObjectMap(est, gt, any).overall.true_positives, 4u);
}

TEST(ObjectMatching, OneToOneGreedyByDistance) {
  // Two estimates near one truth: only the nearer one matches; the other is a false positive.
  const std::vector<Object> gt{at(1, 0, 0)};
  const std::vector<Object> est{at(1, 0.6, 0), at(1, 0.2, 0)};
  const eval::ObjectMappingScore s = eval::scoreObjectMap(est, gt, {1.0});
  ASSERT_EQ(s.matches.size(), 1u);
  EXPECT_EQ(s.matches[0].est, 1u);
  EXPECT_NEAR(s.overall.precision, 0.5, 1e-12);
  EXPECT_NEAR(s.overall.recall, 1.0, 1e-12);
  EXPECT_NEAR(s.overall.f1, 2 * 0.5 / 1.5, 1e-12);
}

// An unmatched estimate within the threshold of a true object of its class that another
// estimate took is the object mapped twice; one of another class there, or one far from every
// truth, is a false object.
TEST(ObjectMatching, SecondEstimatesOfATakenObject) {
  const std::vector<Object> gt{at(71, 0, 0), at(71, 10, 0)};
  const std::vector<Object> est{at(71, 0.2, 0), at(71, 0.7, 0), at(0, 0.5, 0), at(71, 30, 0), at(71, 10.5, 0)};
  const eval::ObjectMappingScore s = eval::scoreObjectMap(est, gt, {1.0});
  const std::vector<char> second = eval::secondEstimates(est, gt, s, {1.0});
  // Estimate 4 takes truth 1 itself; the "other" at 0.5 m and the trunk 30 m off are false.
  EXPECT_EQ(second, (std::vector<char>{0, 1, 0, 0, 0}));
  EXPECT_EQ(eval::secondEstimates({}, gt, eval::scoreObjectMap({}, gt, {1.0}), {1.0}).size(), 0u);
}

TEST(ObjectMatching, ThresholdPlanarAndEmptyMaps) {
  const std::vector<Object> gt{at(1, 0, 0, 0)};
  const std::vector<Object> est{at(1, 0.5, 0, 2.0)};  // 0.5 m away in x-y, 2.06 m in 3D
  EXPECT_EQ(eval::scoreObjectMap(est, gt, {1.0}).overall.true_positives, 0u);
  eval::ObjectMatchOptions planar{1.0};
  planar.planar = true;
  EXPECT_EQ(eval::scoreObjectMap(est, gt, planar).overall.true_positives, 1u);
  EXPECT_EQ(eval::scoreObjectMap(est, gt, {0.4, true}).overall.true_positives, 0u);
  const eval::ObjectMappingScore none = eval::scoreObjectMap({}, gt, {1.0});
  EXPECT_EQ(none.overall.precision, 0.0);
  EXPECT_EQ(none.overall.recall, 0.0);
  EXPECT_EQ(none.overall.f1, 0.0);
  EXPECT_THROW(eval::scoreObjectMap(est, gt, {0.0}), std::invalid_argument);
}

TEST(Bandwidth, PerLandmarkAndPerMetre) {
  const eval::BandwidthFigures f = eval::bandwidthFigures(12000, 40, 300);
  EXPECT_DOUBLE_EQ(f.bytes_per_landmark, 300);
  EXPECT_DOUBLE_EQ(f.bytes_per_metre, 40);
  EXPECT_TRUE(std::isnan(eval::bandwidthFigures(10, 0, 0).bytes_per_landmark));
  EXPECT_TRUE(std::isnan(eval::bandwidthFigures(10, 0, 0).bytes_per_metre));
  EXPECT_THROW(eval::bandwidthFigures(-1, 1, 1), std::invalid_argument);
}

TEST(StageTiming, MedianAndP99) {
  std::vector<double> v;
  for (int i = 1; i <= 101; ++i) v.push_back(i);  // 1..101 ms
  const auto t = eval::stageTimings({{"update", v}, {"fit", {2.0, 4.0}}});
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].stage, "fit");
  EXPECT_DOUBLE_EQ(t[0].median, 3.0);
  EXPECT_DOUBLE_EQ(t[1].median, 51.0);
  EXPECT_DOUBLE_EQ(t[1].p99, 100.0);  // 1 + 0.99 * 100
  EXPECT_DOUBLE_EQ(t[1].max, 101.0);
  EXPECT_EQ(t[1].count, 101u);
}

// Point IoU per label group: tp / (tp + fp + fn), labels outside every group count for none.
TEST(LabelIou, CountsTruePositivesFalsePositivesAndMissesPerGroup) {
  eval::LabelIou iou;
  //          truth:  car car  car  trunk pole sign road terrain veg  50 (no group)
  iou.add({10, 252, 10, 71, 80, 81, 40, 72, 70, 50}, {10, 10, 71, 71, 81, 0, 72, 40, 50, 70});
  EXPECT_EQ(iou.counts("car"), (std::array<long, 3>{2, 0, 1}));
  EXPECT_DOUBLE_EQ(*iou.iou("car"), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(*iou.iou("trunk"), 1.0 / 2.0);   // one hit, one car called trunk
  EXPECT_DOUBLE_EQ(*iou.iou("pole"), 1.0 / 2.0);    // sign called pole counts; sign missed
  EXPECT_DOUBLE_EQ(*iou.iou("ground"), 1.0);        // road and terrain are one group
  EXPECT_DOUBLE_EQ(*iou.iou("vegetation"), 0.0);    // missed once, predicted once on a building
  EXPECT_THROW(iou.add({10}, {}), std::invalid_argument);
  eval::LabelIou other({{"a", {1}}});
  EXPECT_FALSE(other.iou("a").has_value());
  EXPECT_THROW(eval::LabelIou({{"a", {1}}, {"b", {1}}}), std::invalid_argument);
}
