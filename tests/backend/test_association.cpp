// Data association: class and threshold gates, at most one detection per landmark, and an
// optimal (not greedy) assignment.
#include <gtest/gtest.h>

#include "backend/data_association.h"
#include "objects/association.h"

using namespace slide;

namespace {
Object chair(double x, double y, double radius = 0.3) {
  Object o;
  o.class_id = 1;
  o.model = Ellipsoid{{x, y, 0.45}, radius, 0.9};
  return o;
}
Object car(double x, double y, double yaw) {
  Object o;
  o.class_id = 10;
  o.model = Cuboid{poseFromXyzYaw(x, y, 0.75, yaw), {4.5, 1.8, 1.5}};
  return o;
}
Object table(double x, double y) {
  Object o;
  o.class_id = 2;
  o.model = Ellipsoid{{x, y, 0.4}, 0.6, 0.75};
  return o;
}
}  // namespace

TEST(BackendAssociation, GatesOnClassDistanceAndModel) {
  const ClassTable classes = ClassTable::loadDefault();
  EXPECT_GE(backend::associationCost(chair(0, 0), chair(0.3, 0), classes), 0.0);
  EXPECT_LT(backend::associationCost(chair(0, 0), chair(0.9, 0), classes), 0.0);        // chair threshold 0.6 m
  EXPECT_GE(backend::associationCost(chair(0, 0), chair(0.9, 0), classes, 0.5), 0.0);   // widened by slack
  EXPECT_LT(backend::associationCost(chair(0, 0), table(0.1, 0), classes), 0.0);        // other class
  EXPECT_LT(backend::associationCost(chair(0, 0, 0.3), chair(0, 0, 1.0), classes), 0.0);  // model differs by 0.7 > 0.5
}

TEST(BackendAssociation, OneDetectionPerLandmarkOptimally) {
  const ClassTable classes = ClassTable::loadDefault();
  const Object l0 = chair(0, 0), l1 = chair(1.0, 0);
  const std::vector<backend::LandmarkCandidate> landmarks = {{10, &l0}, {11, &l1}};
  // Detection a is nearest to landmark 10 but b can only be landmark 10; the optimum gives
  // a to 11 and b to 10 (greedy first-match would leave b unmatched).
  const std::vector<backend::Detection> dets = {{chair(0.45, 0), 0}, {chair(-0.2, 0), 0}};
  const std::vector<int> m = backend::associateDetections(dets, landmarks, classes);
  EXPECT_EQ(m[0], 11);
  EXPECT_EQ(m[1], 10);
  // Two detections of one landmark: only one gets it, the other starts a new landmark.
  const std::vector<backend::LandmarkCandidate> one = {{5, &l0}};
  const std::vector<int> m2 = backend::associateDetections({{chair(0.05, 0), 0}, {chair(0.2, 0), 0}}, one, classes);
  EXPECT_EQ(m2[0], 5);
  EXPECT_EQ(m2[1], -1);
}

TEST(BackendAssociation, ABoxReadTwoWaysIsTakenAsTheReadingTheLandmarkAgreesWith) {
  const ClassTable classes = ClassTable::loadDefault();
  // A car along y at (0, 0); its end face seen alone, read as a car across (centre 1.35 m to
  // the side and 1.5 m short) and as a car along y (the other reading, 0.2 m off). Association
  // weighs the front-end's reading (the other one never reaches a neighbour's landmark); the
  // observation then takes the reading that fits.
  const Object landmark = car(0, 0, M_PI / 2);
  Object seen = car(1.35, -1.5, 0);
  const double alone = backend::associationCost(seen, landmark, classes);
  seen.other_reading = std::get<Cuboid>(car(0, 0.2, M_PI / 2).model);
  EXPECT_DOUBLE_EQ(backend::associationCost(seen, landmark, classes), alone);
  const Object chosen = nearestReading(seen, landmark);
  EXPECT_NEAR(chosen.position().y(), 0.2, 1e-9);
  ASSERT_TRUE(chosen.other_reading.has_value());  // the reading not taken is kept
  EXPECT_NEAR(chosen.other_reading->pose.translation().x(), 1.35, 1e-9);
  seen.other_reading.reset();
  EXPECT_NEAR(nearestReading(seen, landmark).position().x(), 1.35, 1e-9);  // one reading: itself
}

TEST(BackendAssociation, CarsParkedSideBySideAreNotOneLandmark) {
  const ClassTable classes = ClassTable::loadDefault();
  // Parked nose in, 2.5 m apart (1.8 m wide): the neighbour is within the car's 3 m but its
  // footprint does not touch the landmark's. The same car seen 2 m further along its length
  // (a partial view completed the other way) or read across (length and width swapped) is.
  const Object landmark = car(0, 0, M_PI / 2);
  EXPECT_LT(backend::associationCost(car(2.5, 0, M_PI / 2), landmark, classes), 0.0);
  EXPECT_GE(backend::associationCost(car(0, 2.0, M_PI / 2), landmark, classes), 0.0);
  EXPECT_GE(backend::associationCost(car(1.2, -1.4, 0), landmark, classes), 0.0);
  // A detection far out carries slack for its own uncertainty, for cars at most 0.5 m of it
  // (association_max_slack): the same car 3.2 m along its length is associable with it, the
  // neighbour still is not (uncapped, 1.6 m of slack would widen the footprints enough).
  ASSERT_DOUBLE_EQ(classes.at(10).association_max_slack, 0.5);
  EXPECT_LT(backend::associationCost(car(0, 3.2, M_PI / 2), landmark, classes), 0.0);
  EXPECT_GE(backend::associationCost(car(0, 3.2, M_PI / 2), landmark, classes, 1.6), 0.0);
  EXPECT_LT(backend::associationCost(car(2.5, 0, M_PI / 2), landmark, classes, 1.6), 0.0);
  const std::vector<backend::LandmarkCandidate> one = {{7, &landmark}};
  EXPECT_EQ(backend::associateDetections({{car(2.5, 0, M_PI / 2), 0}}, one, classes)[0], -1);
}
