// Tracker and key-pose bundles on synthetic instances: one track per static object, objects
// only after the minimum age, moving objects rejected, deletion after missed frames, key
// poses by travelled distance with relative odometry.
#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <limits>

#include "config/config.h"
#include "frontend/frontend_config.h"
#include "frontend/keypose.h"
#include "frontend/labelled_segmenter.h"
#include "frontend/odometry_buffer.h"
#include "objects/association.h"
#include "synthetic_scene.h"

using namespace slide;
using slide::synth::SceneObject;

namespace {
struct Pipeline {
  ClassTable classes = ClassTable::loadDefault();
  frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  frontend::LabelledSegmenter seg{classes, cfg.labelled};
  frontend::KeyPoseBundler bundler{frontend::Tracker(classes, cfg.tracker, cfg.fit), cfg.keypose};
  frontend::InputIssues issues;

  // The robot drives along x at 0.5 m per frame; objects may move with `car_velocity` per frame.
  std::vector<KeyPoseBundle> run(std::vector<SceneObject> objects, int frames, double car_step = 0) {
    std::vector<KeyPoseBundle> out;
    for (int k = 0; k < frames; ++k) {
      const Pose T = poseFromXyzYaw(0.5 * k, 0, 1.5, 0.02 * k);
      frontend::FrameInstances f;
      f.utime = k * 100000;
      f.odom_pose = T;
      f.instances = seg.segment(synth::syntheticScan(objects, T, 0.08, k + 1), issues);
      if (auto b = bundler.process(f, issues)) out.push_back(*b);
      for (auto& o : objects)
        if (o.semantic == 10) o.center.x() += car_step;
    }
    return out;
  }
};
}  // namespace

TEST(Tracker, StaticObjectsKeepOneTrackAndAppearAfterMinAge) {
  Pipeline p;
  const auto bundles = p.run({{71, {8, 4, 0}, 0.3, 6.0}, {10, {10, -5, 0}, 0, 0, 0.4}}, 12);
  ASSERT_GE(bundles.size(), 5u);
  for (std::size_t i = 0; i < bundles.size(); ++i) EXPECT_EQ(bundles[i].seq, static_cast<int>(i));
  EXPECT_TRUE(bundles[0].objects.empty()) << "no track is old enough at the first key pose";
  EXPECT_TRUE(bundles[0].relative_odom.isApprox(Pose::Identity()));
  EXPECT_EQ(p.bundler.tracker().tracks().size(), 2u);
  const KeyPoseBundle& last = bundles.back();
  ASSERT_EQ(last.objects.size(), 2u);
  for (const auto& o : last.objects) {
    const Eigen::Vector3d world = last.odom_pose * o.position();
    if (o.class_id == 71) {
      EXPECT_NEAR((world.head<2>() - Eigen::Vector2d(8, 4)).norm(), 0, 0.1);
      EXPECT_NEAR(std::get<Cylinder>(o.model).radius, 0.3, 0.05);
    } else {
      EXPECT_EQ(o.class_id, 10);
      EXPECT_NEAR((world.head<2>() - Eigen::Vector2d(10, -5)).norm(), 0, 0.4);
    }
    EXPECT_GE(o.num_observations, 3);
  }
  // Relative odometry chains the key poses.
  for (std::size_t i = 1; i < bundles.size(); ++i)
    EXPECT_TRUE((bundles[i - 1].odom_pose * bundles[i].relative_odom).isApprox(bundles[i].odom_pose, 1e-9));
  EXPECT_GE(bundles[1].odom_pose.translation().x() - bundles[0].odom_pose.translation().x(), 1.0 - 1e-9);
}

TEST(Tracker, MovingCarIsRejected) {
  Pipeline p;
  // 1 m per frame (10 m/s at 10 Hz): its track smears beyond a car's length.
  const auto bundles = p.run({{71, {8, 4, 0}, 0.3, 6.0}, {10, {6, -5, 0}, 0, 0, 0.0}}, 12, 1.0);
  for (const auto& o : bundles.back().objects) EXPECT_NE(o.class_id, 10);
  bool moving = false;
  for (const auto& [id, t] : p.bundler.tracker().tracks()) moving |= t.moving;
  EXPECT_TRUE(moving);
}

TEST(Tracker, TracksAreDeletedAfterMissedFramesAndUnknownClassesCounted) {
  const ClassTable classes = ClassTable::loadDefault();
  frontend::TrackerParams tp;
  tp.max_missed = 2;
  frontend::Tracker tracker(classes, tp, {});
  frontend::FrameInstances f;
  frontend::Instance inst;
  inst.class_id = 71;
  for (int i = 0; i < 30; ++i) inst.points.emplace_back(5 + 0.01f * i, 0, 0.1f * i);
  f.instances = {inst};
  frontend::InputIssues issues;
  tracker.update(f, issues);
  EXPECT_EQ(tracker.tracks().size(), 1u);
  frontend::FrameInstances empty;
  for (int k = 0; k < 3; ++k) tracker.update(empty, issues);
  EXPECT_TRUE(tracker.tracks().empty());
  frontend::Instance unknown = inst;
  unknown.class_id = 4242;
  f.instances = {unknown};
  tracker.update(f, issues);
  EXPECT_EQ(issues.get("unknown class"), 1);
  f.odom_pose.matrix()(0, 3) = std::nan("");
  tracker.update(f, issues);
  EXPECT_EQ(issues.get("non-finite odometry pose"), 1);
}

TEST(OdometryBuffer, InterpolatesAndKnowsWhenToGiveUp) {
  frontend::OdometryBuffer buf(100, 20000);
  EXPECT_FALSE(buf.at(0));
  buf.add(1000000, poseFromXyzYaw(0, 0, 0, 0));
  buf.add(1100000, poseFromXyzYaw(1, 0, 0, 0.2));
  const auto mid = buf.at(1050000);
  ASSERT_TRUE(mid);
  EXPECT_NEAR(mid->translation().x(), 0.5, 1e-9);
  EXPECT_NEAR(yawOf(mid->linear()), 0.1, 1e-9);
  EXPECT_TRUE(buf.at(1110000));   // within tolerance after the newest
  EXPECT_FALSE(buf.at(1200000));  // not yet known
  EXPECT_FALSE(buf.hopeless(1200000));
  EXPECT_TRUE(buf.hopeless(500000));  // before the oldest: will never come
}

TEST(FrontendConfig, DefaultLoadsAndErrorsNameTheKey) {
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  EXPECT_EQ(cfg.lidar_mode, "auto");
  EXPECT_DOUBLE_EQ(cfg.keypose.distance, 1.0);
  const std::string path = std::string(SLIDE_BINARY_DIR) + "/bad_frontend.yaml";
  {
    std::ofstream(path) << "tracker:\n  min_age: many\n";
  }
  try {
    frontend::loadFrontendConfig(path);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("min_age"), std::string::npos) << e.what();
  }
  {
    std::ofstream(path) << "segmenter:\n  lidar_mode: magic\n";
  }
  EXPECT_THROW(frontend::loadFrontendConfig(path), ConfigError);
  // A per-class map given as a list would have been read as empty.
  for (const char* bad : {"tracker:\n  report_max_range_by_class: [car, 40]\n",
                          "segmenter:\n  labelled:\n    cluster_cell_by_class: [0.15]\n",
                          "tracker:\n  report_max_range_by_class: {car: -1}\n"}) {
    std::ofstream(path) << bad;
    try {
      frontend::loadFrontendConfig(path);
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("_by_class"), std::string::npos) << e.what();
    }
  }
}

// Objects beyond report_max_range are tracked but not reported; once nearer, the report carries
// every observation, the far ones included.
TEST(Tracker, AnObjectBeyondTheReportRangeIsTrackedButReportedOnlyOnceNearer) {
  Pipeline p;
  p.cfg.tracker.report_max_range = 25;
  p.bundler = frontend::KeyPoseBundler{frontend::Tracker(p.classes, p.cfg.tracker, p.cfg.fit), p.cfg.keypose};
  const auto bundles = p.run({{71, {34, 2, 0}, 0.3, 6.0}}, 36);  // from 34 m to 16.5 m off
  ASSERT_GE(bundles.size(), 10u);
  int far = 0, near = 0;
  for (const KeyPoseBundle& b : bundles) {
    const double range = (Eigen::Vector2d(34, 2) - b.odom_pose.translation().head<2>()).norm();
    if (range > 25.5 && p.bundler.tracker().tracks().size() == 1) {
      EXPECT_TRUE(b.objects.empty()) << "key pose " << b.seq << " reported the trunk " << range << " m off";
      far += b.seq > 1;  // the track is old enough from the second key pose on
    } else if (range < 24.5) {
      ASSERT_EQ(b.objects.size(), 1u) << "key pose " << b.seq << ", the trunk " << range << " m off";
      EXPECT_EQ(b.objects[0].class_id, 71);
      ++near;
    }
  }
  EXPECT_GE(far, 2);
  EXPECT_GE(near, 3);
  ASSERT_EQ(p.bundler.tracker().tracks().size(), 1u);
  EXPECT_GE(bundles.back().objects.at(0).num_observations, 30) << "the far observations count too (17 frames see it within 25 m)";
}

// A class of its own report range: a car 30 m off is reported where a trunk as far is not; a
// class name that is not in the table is an error that names it.
TEST(Tracker, AClassWithItsOwnReportRangeIsReportedFartherOff) {
  Pipeline p;
  p.cfg.tracker.report_max_range = 25;
  p.cfg.tracker.report_max_range_by_class = {{"car", 40.0}};
  p.bundler = frontend::KeyPoseBundler{frontend::Tracker(p.classes, p.cfg.tracker, p.cfg.fit), p.cfg.keypose};
  const auto bundles = p.run({{71, {30, 3, 0}, 0.3, 6.0}, {10, {30, -4, 0}, 0, 0, 0.4}}, 8);  // 26.5-30 m off
  ASSERT_GE(bundles.size(), 3u);
  ASSERT_EQ(bundles.back().objects.size(), 1u);
  EXPECT_EQ(bundles.back().objects[0].class_id, 10);
  EXPECT_EQ(p.bundler.tracker().tracks().size(), 2u);
  frontend::TrackerParams bad;
  bad.report_max_range_by_class = {{"lamp", 10.0}};
  try {
    frontend::Tracker t(p.classes, bad, p.cfg.fit);
    FAIL() << "an unknown class name was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'lamp'"), std::string::npos) << e.what();
  }
}

TEST(Tracker, ClassFlipsBetweenTrunkAndPoleKeepOneTrack) {
  const ClassTable classes = ClassTable::loadDefault();
  frontend::Tracker tracker(classes, {}, {});
  frontend::InputIssues issues;
  for (int k = 0; k < 5; ++k) {
    frontend::FrameInstances f;
    frontend::Instance inst;
    inst.class_id = k == 2 ? 80 : 71;  // one frame calls the trunk a pole
    for (int i = 0; i < 30; ++i) inst.points.emplace_back(5 + 0.01f * i, 0, 0.1f * i);
    f.instances = {inst};
    tracker.update(f, issues);
  }
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_EQ(tracker.tracks().begin()->second.class_id, 71);
  EXPECT_EQ(tracker.tracks().begin()->second.hits, 5);
}

namespace {
// Frames at 3 Hz, from `first`: each frame's instances, none with free cells (no line of sight is
// known to pass anywhere: the vacated test cannot tell).
void feedAt3Hz(frontend::Tracker& tracker, int first, const std::vector<std::vector<frontend::Instance>>& frames) {
  frontend::InputIssues issues;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    frontend::FrameInstances f;
    f.utime = (first + static_cast<std::int64_t>(k)) * 333333;
    f.instances = frames[k];
    tracker.update(f, issues);
  }
}

}  // namespace

// A trunk seen as two instances in one frame (its halves either side of an occluder) starts a
// second track, which follows the same trunk: the two are merged. A second trunk 0.6 m away
// keeps its own track.
TEST(Tracker, TwoTracksOfOneTrunkAreMergedANeighbourIsNot) {
  const ClassTable classes = ClassTable::loadDefault();
  auto column = [](float x, float y, float z0) {
    frontend::Instance inst;
    inst.class_id = 71;
    for (int i = 0; i < 30; ++i) inst.points.emplace_back(x + 0.005f * (i % 3), y, z0 + 0.05f * i);
    return inst;
  };
  for (double merge : {0.25, 0.0}) {
    frontend::TrackerParams p;
    p.column_merge_distance = merge;
    frontend::Tracker tracker(classes, p, {});
    std::vector<std::vector<frontend::Instance>> frames(6, {column(5, 0, 0.3f), column(5.6f, 0, 0.3f)});
    frames[2].push_back(column(5.1f, 0, 2.5f));  // upper half of the first trunk, apart
    feedAt3Hz(tracker, 0, frames);
    ASSERT_EQ(tracker.tracks().size(), merge > 0 ? 2u : 3u) << merge;
    if (merge > 0) {
      EXPECT_EQ(tracker.tracks().begin()->second.hits, 7) << "the piece's observation is kept";
      EXPECT_EQ(tracker.tracks().begin()->second.missed, 0);
    }
  }
}

// A chair the detector calls "other" (a catch-all) in its first frames has an "other" track;
// when one frame names its seat a chair and leaves its back "other", the chair instance starts a
// track of its own beside it. The two follow one object: merged, and named by the votes (the
// catch-all's weigh other_confidence). A bin 1 m off keeps its own "other" track.
TEST(Tracker, ACatchAllTrackAndANamedOneOnOneObjectAreMergedABinBesideIsNot) {
  const ClassTable classes = ClassTable::loadDefault();
  auto blob = [](int class_id, float x, float y, float z0, float confidence) {
    frontend::Instance inst;
    inst.class_id = class_id;
    inst.confidence = confidence;
    for (int i = 0; i < 30; ++i) inst.points.emplace_back(x + 0.01f * (i % 5), y + 0.01f * (i / 5), z0 + 0.02f * i);
    return inst;
  };
  for (double merge : {0.5, 0.0}) {
    frontend::TrackerParams p;
    p.catch_all_merge_distance = merge;
    frontend::Tracker tracker(classes, p, {});
    std::vector<std::vector<frontend::Instance>> frames(6, {blob(0, 5, 1.0f, 0, 0.2f)});  // the bin
    for (int k = 0; k < 6; ++k) {
      if (k < 3) frames[k].push_back(blob(0, 5, 0, 0, 0.2f));      // the chair, missed
      if (k == 3) frames[k].push_back(blob(0, 5, 0, 0.4f, 0.2f));  // its back, missed
      if (k >= 3) frames[k].push_back(blob(1, 5, 0, 0, 1.0f));     // the chair, named
    }
    feedAt3Hz(tracker, 0, frames);
    ASSERT_EQ(tracker.tracks().size(), merge > 0 ? 2u : 3u) << merge;
    int chairs = 0, others = 0;
    for (const auto& [id, t] : tracker.tracks()) (t.class_id == 1 ? chairs : others) += 1;
    EXPECT_EQ(chairs, 1) << merge;
    EXPECT_EQ(others, merge > 0 ? 1 : 2) << merge;
  }
}

TEST(Tracker, PartlySeenCarIsCompletedAwayFromWhereItWasSeen) {
  // The near side of a car (4.4 m long along x, 1.8 m wide, centre (10, 5.9)) seen from the
  // aisle at y = 0; the fit is asked for from a body pose past it, on the car's far side
  // (y = 10): the hidden width still grows away from the aisle.
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  frontend::Tracker tracker(classes, cfg.tracker, cfg.fit);
  frontend::InputIssues issues;
  for (int k = 0; k < 4; ++k) {
    const Pose T = poseFromXyzYaw(8.0 + 0.5 * k, 0, 0, 0);
    frontend::Instance inst;
    inst.id = 1;
    inst.class_id = 10;
    inst.confidence = 1;
    for (double x = 7.8; x <= 12.2; x += 0.05)
      for (double z = 0.1; z <= 1.5; z += 0.1) inst.points.push_back((T.inverse() * Eigen::Vector3d(x, 5.0, z)).cast<float>());
    frontend::FrameInstances f;
    f.utime = k * 100000;
    f.odom_pose = T;
    f.instances.push_back(inst);
    tracker.update(f, issues);
  }
  const Pose T_far = poseFromXyzYaw(10.0, 10.0, 0, M_PI);
  const auto objects = tracker.objectsInBody(T_far);
  ASSERT_EQ(objects.size(), 1u);
  const Eigen::Vector3d world = T_far * objects[0].position();
  EXPECT_NEAR(world.x(), 10.0, 0.1);
  EXPECT_NEAR(world.y(), 5.9, 0.1) << "grown away from the aisle, not from the current pose";
}

namespace {
// Car-labelled points on an axis-aligned vertical face from (x0, y0) to (x1, y1), z 0.1 to 1.5.
void addFace(frontend::Instance& inst, double x0, double y0, double x1, double y1) {
  const double len = std::hypot(x1 - x0, y1 - y0);
  for (double s = 0; s <= len + 1e-9; s += 0.05)
    for (double z = 0.1; z <= 1.5; z += 0.1)
      inst.points.emplace_back(static_cast<float>(x0 + (x1 - x0) * s / len), static_cast<float>(y0 + (y1 - y0) * s / len),
                               static_cast<float>(z));
}

frontend::Instance carInstance() {
  frontend::Instance inst;
  inst.class_id = 10;
  inst.confidence = 1;
  return inst;
}

// Frames at the odometry origin, 0.1 s apart.
struct FrameFeed {
  explicit FrameFeed(frontend::Tracker& t) : tracker(t) {}
  frontend::Tracker& tracker;
  int k = 0;
  frontend::InputIssues issues;
  void operator()(const std::vector<frontend::Instance>& instances) {
    frontend::FrameInstances f;
    f.utime = 100000 * k++;
    f.instances = instances;
    tracker.update(f, issues);
  }
};

// The noses of cars A and B parked side by side, their lengths along y (A x 9.1 to 10.9, B x 11.6
// to 13.4, noses at y = -2.8), each alone and both as one cluster.
std::array<frontend::Instance, 3> twoNoses() {
  std::array<frontend::Instance, 3> n = {carInstance(), carInstance(), carInstance()};
  addFace(n[0], 9.1, -2.8, 10.9, -2.8);
  addFace(n[1], 11.6, -2.8, 13.4, -2.8);
  addFace(n[2], 9.1, -2.8, 10.9, -2.8);
  addFace(n[2], 11.6, -2.8, 13.4, -2.8);
  return n;
}

// Four frames at the odometry origin, each with the same instances.
void feedFourFrames(frontend::Tracker& tracker, const std::vector<frontend::Instance>& instances) {
  frontend::InputIssues issues;
  for (int k = 0; k < 4; ++k) {
    frontend::FrameInstances f;
    f.utime = k * 100000;
    f.instances = instances;
    tracker.update(f, issues);
  }
}
}  // namespace

// Car A (4.4 x 1.8 m, its length along y, x 9.1 to 10.9, nose at y = -2.8) is seen as an L (its
// end face and the near part of its side) plus, 2 m on, a stripe of the side seen at a grazing
// angle: two instances beyond the tracker's gate, two tracks, which follow one car and are
// merged. Car B, parked beside A 0.6 m away, seen end-on, keeps its own track (A and B together
// are too wide for one car).
TEST(Tracker, AStripeOfACarsSideIsMergedIntoItsTrackTheNeighbourIsNot) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  for (double width : {cfg.tracker.box_merge_width, 0.0}) {
    frontend::TrackerParams p = cfg.tracker;
    p.box_merge_width = width;
    frontend::Tracker tracker(classes, p, cfg.fit);
    frontend::Instance a = carInstance(), stripe = carInstance(), b = carInstance();
    addFace(a, 9.1, -2.8, 10.9, -2.8);
    addFace(a, 9.1, -2.8, 9.1, -5.0);
    addFace(stripe, 9.1, -5.0, 9.1, -5.4);
    addFace(b, 11.5, -2.8, 13.3, -2.8);
    feedFourFrames(tracker, {a, stripe, b});
    ASSERT_EQ(tracker.tracks().size(), width > 0 ? 2u : 3u) << width;
    const auto objects = tracker.objectsInBody(Pose::Identity());
    ASSERT_EQ(objects.size(), 2u) << "the stripe alone is too short for a box";
    for (const auto& o : objects)
      EXPECT_EQ(o.num_observations, o.position().x() < 11 && width > 0 ? 8 : 4) << "the stripe's observations are kept";
  }
}

// Car A (4.4 x 1.8 m, its length along y, x 9.1 to 10.9, y -2.8 to -7.2) seen as its end face
// and, 1.8 m on, a 2.6 m stripe of its far side: two tracks (beyond the gate, and too far apart
// along the side for one to hold the other). Each alone is completed away from the sensor and
// the stripe's box lands 2 m off the car; their boxes overlap by more than half, so they are
// reported as one box fitted to both tracks' points, on the car.
TEST(Tracker, TwoOverlappingBoxesOfOneCarAreReportedAsOne) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  ASSERT_GT(cfg.tracker.box_overlap, 0.0) << "on by default";
  for (double overlap : {cfg.tracker.box_overlap, 0.0}) {
    frontend::TrackerParams p = cfg.tracker;
    p.box_overlap = overlap;
    p.box_across = overlap > 0 ? cfg.tracker.box_across : 0.0;  // off with it: the two boxes stand on each other
    frontend::Tracker tracker(classes, p, cfg.fit);
    frontend::Instance face = carInstance(), stripe = carInstance();
    addFace(face, 9.1, -2.8, 10.9, -2.8);
    addFace(stripe, 9.1, -4.6, 9.1, -7.2);
    feedFourFrames(tracker, {face, stripe});
    ASSERT_EQ(tracker.tracks().size(), 2u);
    const auto objects = tracker.objectsInBody(Pose::Identity());
    if (overlap > 0) {
      ASSERT_EQ(objects.size(), 1u);
      EXPECT_NEAR((objects[0].position().head<2>() - Eigen::Vector2d(10.0, -5.0)).norm(), 0, 0.25);
      EXPECT_EQ(objects[0].num_observations, 8);
    } else {
      ASSERT_EQ(objects.size(), 2u);
      double worst = 0;
      for (const auto& o : objects) worst = std::max(worst, (o.position().head<2>() - Eigen::Vector2d(10.0, -5.0)).norm());
      EXPECT_GT(worst, 1.5) << "the stripe alone is completed the wrong way";
    }
  }
}

// Cars A and B parked side by side, their lengths along y (A x 9.1 to 10.9, B x 11.6 to 13.4,
// noses at y = -2.8), seen end-on from far off: A's nose alone for five frames, then one view in
// which both noses come as one cluster (A's track takes it: B has none yet), then each nose on its
// own. A's track now holds B's nose among its points, but no single view of A but the one shows
// it: B keeps a track of its own (box_merge_view_quantile), where all of A's points together
// would have taken B's nose in, frame after frame.
TEST(Tracker, OneViewJoiningTwoNeighboursDoesNotMakeATrackHoldTheOther) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  ASSERT_LT(cfg.tracker.box_merge_view_quantile, 1.0) << "the default leaves out a track's rarest views";
  for (double quantile : {cfg.tracker.box_merge_view_quantile, 1.0}) {
    frontend::TrackerParams p = cfg.tracker;
    p.box_merge_view_quantile = quantile;
    p.split_distance = 0;  // the view quantile alone: the joined view stays whole
    frontend::Tracker tracker(classes, p, cfg.fit);
    const auto [a, b, both] = twoNoses();
    FrameFeed frame{tracker};
    for (int i = 0; i < 5; ++i) frame({a});
    frame({both});
    ASSERT_EQ(tracker.tracks().size(), 1u) << "A's track took the joined view";
    for (int i = 0; i < 4; ++i) frame({a, b});
    EXPECT_EQ(tracker.tracks().size(), quantile < 1 ? 2u : 1u) << quantile;
    if (quantile < 1) {
      int hits_b = 0;
      for (const auto& [id, t] : tracker.tracks()) hits_b = std::max(hits_b, t.last_centroid.x() > 11.5 ? t.hits : 0);
      EXPECT_EQ(hits_b, 4) << "B's track has every view of B";
    }
  }
}

// Cars A and B parked side by side, their lengths along y (A x 9.1 to 10.9, B x 11.6 to 13.4,
// noses at y = -2.8), seen end-on from far off: each nose on its own for two frames (two tracks),
// then one view in which both noses come as one cluster, then each on its own again. The joined
// view is split between the two tracks, which keep a view each; unsplit, one track takes it, holds
// both noses, takes the other track in and is reported as a box laid across both cars.
// The joined view seen first, before B has a track, is split in A's track once B's is seen beside
// it. A car's side seen in two stripes (two tracks) and then whole is not split: no gap in it.
TEST(Tracker, AViewJoiningTwoTrackedNeighboursIsSplitBetweenThemOneCarsWholeSideIsNot) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  ASSERT_GT(cfg.tracker.split_distance, 0.0) << "on by default";
  const auto [a, b, both] = twoNoses();
  // A tracker with the given split_distance after the given frames.
  auto tracked = [&](double split, const std::vector<std::vector<frontend::Instance>>& frames) {
    frontend::TrackerParams p = cfg.tracker;
    p.split_distance = split;
    frontend::Tracker tracker(classes, p, cfg.fit);
    FrameFeed frame{tracker};
    for (const auto& f : frames) frame(f);
    return tracker;
  };
  for (double split : {cfg.tracker.split_distance, 0.0}) {
    const frontend::Tracker tracker = tracked(split, {{a, b}, {a, b}, {both}, {a, b}, {a, b}, {a, b}});
    if (split > 0) {
      ASSERT_EQ(tracker.tracks().size(), 2u);
      for (const auto& [id, t] : tracker.tracks()) EXPECT_EQ(t.hits, 6) << "every view of its own car, the joined one too";
      const auto objects = tracker.objectsInBody(Pose::Identity());
      ASSERT_EQ(objects.size(), 2u);
      for (const auto& o : objects)
        EXPECT_GT(std::abs(std::remainder(headingOf(std::get<Cuboid>(o.model)), M_PI)), 1.2) << "length along y";
    } else {
      bool across = false;
      for (const auto& o : tracker.objectsInBody(Pose::Identity()))
        across |= std::abs(std::remainder(headingOf(std::get<Cuboid>(o.model)), M_PI)) < 0.3;
      EXPECT_TRUE(across) << "one track took both noses, merged the other's and reads them as one car's side";
    }
  }
  // The joined view first, when B has no track yet: A's track takes it whole, and keeps only A's
  // nose of it once B's track is seen beside it.
  for (double split : {cfg.tracker.split_distance, 0.0}) {
    const frontend::Tracker tracker = tracked(split, {{both}, {a}, {a, b}, {a, b}, {a, b}});
    ASSERT_EQ(tracker.tracks().size(), 2u);
    int of_b_in_a = 0;
    for (const auto& [id, t] : tracker.tracks())
      if (t.last_centroid.x() < 11.2)
        for (const auto& o : t.observations)
          for (const auto& q : o.points) of_b_in_a += q.x() > 11.2f;
    if (split > 0) EXPECT_EQ(of_b_in_a, 0) << "A's first view keeps A's nose only";
    else EXPECT_GT(of_b_in_a, 0);
  }
  for (double gap : {cfg.tracker.split_min_gap, 0.0}) {
    frontend::TrackerParams p = cfg.tracker;
    p.split_min_gap = gap;
    frontend::Tracker tracker(classes, p, cfg.fit);
    frontend::Instance near = carInstance(), far = carInstance(), side = carInstance();
    addFace(near, 9.1, -2.8, 9.1, -4.3);
    addFace(far, 9.1, -5.7, 9.1, -7.2);
    addFace(side, 9.1, -2.8, 9.1, -7.2);
    FrameFeed frame{tracker};
    for (int k = 0; k < 4; ++k) frame({near, far});
    frame({side});
    int hits = 0;
    for (const auto& [id, t] : tracker.tracks()) hits += t.hits;
    EXPECT_EQ(hits, gap > 0 ? 9 : 10) << (gap > 0 ? "the whole side went to one track, unsplit" : "split without the gap test");
  }
}

// Cars A and B parked side by side, their lengths along y (A x 9.1 to 10.9, B x 11.6 to 13.4,
// noses at y = -2.8): A's nose seen whole and B's left part (x 11.6 to 12.3) for three frames,
// then A's nose cut in two by the segmenter (a gap of 0.15 m at x 10.1) while B goes unseen.
// Given to tracks one by one, A's right piece lies within the gate of B's track and continues
// it; joined first (both pieces lie on A's last view and on no other), A's track takes the whole
// nose and B's track keeps B's points only.
TEST(Tracker, PiecesOfOneCarsViewAreJoinedBeforeAssociationNotGivenToTheNeighbour) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  ASSERT_GT(cfg.tracker.join_share, 0.0) << "on by default";
  frontend::Instance a = carInstance(), b = carInstance(), left = carInstance(), right = carInstance();
  addFace(a, 9.1, -2.8, 10.9, -2.8);
  addFace(b, 11.6, -2.8, 12.3, -2.8);
  addFace(left, 9.1, -2.8, 10.05, -2.8);
  addFace(right, 10.2, -2.8, 10.9, -2.8);
  for (double share : {cfg.tracker.join_share, 0.0}) {
    frontend::TrackerParams p = cfg.tracker;
    p.join_share = share;
    frontend::Tracker tracker(classes, p, cfg.fit);
    FrameFeed frame{tracker};
    for (int k = 0; k < 3; ++k) frame({a, b});
    frame({left, right});
    int of_a_in_b = 0, hits_a = 0;
    for (const auto& [id, t] : tracker.tracks()) {
      if (t.observations.front().points.front().x() > 11.2f) {
        for (const auto& o : t.observations)
          for (const auto& q : o.points) of_a_in_b += q.x() < 11.2f;
      } else {
        hits_a = t.hits;
      }
    }
    if (share > 0) {
      EXPECT_EQ(tracker.tracks().size(), 2u);
      EXPECT_EQ(of_a_in_b, 0) << "B's track holds none of A's nose";
      EXPECT_EQ(hits_a, 4) << "A's track took the joined view";
    } else {
      EXPECT_GT(of_a_in_b, 0) << "A's right piece continued B's track";
    }
  }
}

// Cars A and B parked side by side, their lengths along y (A x 9.1 to 10.9, B x 11.6 to 13.4,
// noses at y = -2.8), each seen as an L (its nose and the near part of its side). A third track
// holds the inner parts of both noses seen as one face (x 9.9 to 12.6): a car's side, its box
// laid across both cars. That box is not reported; A's and B's are.
TEST(Tracker, ABoxLaidAcrossTwoParkedCarsIsNotReported) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  ASSERT_GT(cfg.tracker.box_across, 0.0) << "on by default";
  for (double across : {cfg.tracker.box_across, 0.0}) {
    frontend::TrackerParams p = cfg.tracker;
    p.box_across = across;
    frontend::Tracker tracker(classes, p, cfg.fit);
    frontend::Instance a = carInstance(), b = carInstance(), noses = carInstance();
    addFace(a, 9.1, -2.8, 10.9, -2.8);
    addFace(a, 9.1, -2.8, 9.1, -5.8);
    addFace(b, 11.6, -2.8, 13.4, -2.8);
    addFace(b, 11.6, -2.8, 11.6, -5.8);
    addFace(noses, 9.9, -2.75, 12.6, -2.75);
    feedFourFrames(tracker, {a, b, noses});
    ASSERT_EQ(tracker.tracks().size(), 3u);
    const auto objects = tracker.objectsInBody(Pose::Identity());
    ASSERT_EQ(objects.size(), across > 0 ? 2u : 3u) << across;
    int along_y = 0;
    for (const auto& o : objects) along_y += std::abs(std::remainder(headingOf(std::get<Cuboid>(o.model)), M_PI)) > 1.2;
    EXPECT_EQ(along_y, 2) << "A and B keep their boxes, lengths along y";
  }
}

namespace {
// Cars each seen as one face (x0, y0, x1, y1) in four frames: each reported box's x and how far
// its length turns from the x axis (0 to pi / 2).
std::vector<std::pair<double, double>> headingsAcross(const ClassTable& classes, const frontend::TrackerParams& p,
                                                      const frontend::FitParams& fit,
                                                      const std::vector<std::array<double, 4>>& faces) {
  frontend::Tracker tracker(classes, p, fit);
  std::vector<frontend::Instance> cars;
  for (const auto& f : faces) {
    cars.push_back(carInstance());
    addFace(cars.back(), f[0], f[1], f[2], f[3]);
  }
  feedFourFrames(tracker, cars);
  std::vector<std::pair<double, double>> out;
  for (const auto& o : tracker.objectsInBody(Pose::Identity())) {
    out.emplace_back(o.position().x(), std::abs(std::remainder(headingOf(std::get<Cuboid>(o.model)), M_PI)));
  }
  return out;
}
}  // namespace

// Two cars seen along their sides (length along x, at y = 5 and y = 12) and, between them, a
// 1.8 m stretch of a third one's side seen through a gap (x 20 to 21.8 at y = 8.5: a lone face
// with the width of a car). Alone, the fit takes that face for the car's end (its length across
// the face, along y); with parallel neighbours within parallel_radius it takes their heading.
TEST(Tracker, ABoxWhoseLengthWasNotSeenTakesTheHeadingOfItsParallelNeighbours) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  ASSERT_GT(cfg.tracker.parallel_radius, 0.0) << "on by default";
  for (double radius : {cfg.tracker.parallel_radius, 0.0}) {
    frontend::TrackerParams p = cfg.tracker;
    p.parallel_radius = radius;
    const auto headings = headingsAcross(classes, p, cfg.fit, {{8.0, 5.0, 12.4, 5.0}, {28.0, 12.0, 32.4, 12.0}, {20.0, 8.5, 21.8, 8.5}});
    ASSERT_EQ(headings.size(), 3u);
    for (const auto& [x, across] : headings) {
      const bool stretch = std::abs(x - 21) < 2.5;
      if (!stretch || radius > 0) {
        EXPECT_LT(across, 0.1) << "radius " << radius << " at x " << x;
      } else {
        EXPECT_NEAR(across, M_PI / 2, 0.1) << "alone, the lone face is taken for an end";
      }
    }
  }
}

// Cars A and B parked side by side, their lengths along y (A x 9.1 to 10.9, B x 11.6 to 13.4,
// noses at y = -2.8), between two cars seen whole along their sides (length along y, at x = 6.5
// and 16.5). Only a metre of each nose is seen (A x 9.9 to 10.9, B x 11.6 to 12.6): too short
// for a width, each box is first read with its length across the nose, and the two readings
// overlap by more than half. The neighbours settle both along y before boxes are joined: two
// cars, each along y, not one box laid across both noses.
TEST(Tracker, ReadingsAreSettledByParallelNeighboursBeforeOverlappingBoxesAreJoined) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  const auto headings = headingsAcross(classes, cfg.tracker, cfg.fit,
                                       {{6.5, -3.0, 6.5, -7.4}, {16.5, -3.0, 16.5, -7.4}, {9.9, -2.8, 10.9, -2.8}, {11.6, -2.8, 12.6, -2.8}});
  ASSERT_EQ(headings.size(), 4u) << "A and B reported apart";
  for (const auto& [x, across] : headings) EXPECT_NEAR(across, M_PI / 2, 0.1) << "length along y, at x " << x;
}

// A car's side (x 18-22.5 at y = 8.5, length along x) seen in two halves, split by a pole in
// front (x 18-20.1 and 20.4-22.5), between two cars seen whole along x. Each half is a lone face
// as wide as a car's end: read across, its box stands on its own stretch, beside the other's
// (not joined). Its other reading, along x, is completed where the sensor did not see through
// (cells seen empty beyond both ends of the side): over the whole car, for either half. Once the
// neighbours settle both halves into that reading, the two boxes stand on one centre and are
// reported as one car; without settling they stay two.
TEST(Tracker, TwoHalvesOfACarSettledIntoOneReadingAreReportedAsOne) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  for (double radius : {cfg.tracker.parallel_radius, 0.0}) {
    frontend::TrackerParams p = cfg.tracker;
    p.parallel_radius = radius;
    frontend::Tracker tracker(classes, p, cfg.fit);
    frontend::Instance a = carInstance(), b = carInstance(), left = carInstance(), right = carInstance();
    addFace(a, 12.0, 5.0, 16.4, 5.0);
    addFace(b, 26.0, 12.0, 30.4, 12.0);
    addFace(left, 18.0, 8.5, 20.1, 8.5);
    addFace(right, 20.4, 8.5, 22.5, 8.5);
    frontend::Cloud free;  // in front of the side, and beyond its ends
    for (double x = 15.1; x <= 25.5; x += 0.2)
      for (double y = 6.5; y <= 10.3; y += 0.2)
        if (y < 8.3 || x < 17.8 || x > 22.7) free.emplace_back(static_cast<float>(x), static_cast<float>(y), 0.6f);
    left.free_space = right.free_space = free;
    feedFourFrames(tracker, {a, b, left, right});
    ASSERT_EQ(tracker.tracks().size(), 4u);
    const auto objects = tracker.objectsInBody(Pose::Identity());
    int middle = 0;
    for (const auto& o : objects)
      if (std::abs(o.position().x() - 20.25) < 2.5) {
        ++middle;
        if (radius > 0) {
          EXPECT_LT((o.position().head<2>() - Eigen::Vector2d(20.25, 9.4)).norm(), 0.3) << o.position().transpose();
        }
      }
    EXPECT_EQ(middle, radius > 0 ? 1 : 2) << "radius " << radius;
  }
}

// Two cars side by side joined into one instance (3.8 x 4.4 m: wider than any car) in one
// frame: without the size check on single instances the car's track takes it and counts as
// moving (no object); with it the instance is dropped and counted, the car stays.
TEST(Tracker, AnInstanceLargerThanItsClassIsDroppedNotTakenAsMotion) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  for (bool drop : {true, false}) {
    frontend::TrackerParams p = cfg.tracker;
    p.drop_oversized = drop;
    frontend::Tracker tracker(classes, p, cfg.fit);
    frontend::InputIssues issues;
    for (int k = 0; k < 5; ++k) {
      frontend::Instance car = carInstance();
      addFace(car, 9.1, -2.8, 10.9, -2.8);
      addFace(car, 9.1, -2.8, 9.1, -7.2);
      if (k == 2) addFace(car, 11.1, -2.8, 12.9, -2.8);  // the end of the neighbour beside it joined in
      frontend::FrameInstances f;
      f.utime = k * 100000;
      f.instances = {car};
      tracker.update(f, issues);
    }
    EXPECT_EQ(tracker.objectsInBody(Pose::Identity()).size(), drop ? 1u : 0u) << drop;
    EXPECT_EQ(issues.total(), drop ? 1 : 0);
  }
}

namespace {
// A solid upright disc of points (radius r, height h) around (x, y), class `class_id`.
frontend::Instance discInstance(int class_id, double x, double y, double r, double h, double z0 = 0) {
  frontend::Instance inst;
  inst.class_id = class_id;
  for (double a = 0; a < 2 * M_PI; a += 0.2)
    for (double z = z0; z <= z0 + h; z += 0.1)
      inst.points.emplace_back(static_cast<float>(x + r * std::cos(a)), static_cast<float>(y + r * std::sin(a)),
                               static_cast<float>(z));
  return inst;
}
}  // namespace

// One chair instance 3 m wide (a mask spread along a wall) is a segmentation error: dropped
// and counted; the chair's track is not judged moving and is still reported.
TEST(Tracker, AnInstanceWiderThanItsClassIsDroppedNotMadeAMovingTrack) {
  const ClassTable classes = ClassTable::loadDefault();
  frontend::Tracker tracker(classes, {}, {});
  frontend::InputIssues issues;
  frontend::FrameInstances f;
  f.instances = {discInstance(1, 3.0, 0.0, 0.28, 0.9)};
  for (int k = 0; k < 3; ++k) tracker.update(f, issues);
  frontend::Instance smear = discInstance(1, 3.0, 0.0, 0.28, 0.9);
  for (int i = 0; i <= 30; ++i) smear.points.emplace_back(1.5f + 0.1f * i, 0.3f, 0.5f);  // 1.5 .. 4.5 m
  f.instances = {smear};
  tracker.update(f, issues);
  EXPECT_EQ(issues.get("instance larger than its class"), 1);
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_FALSE(tracker.tracks().begin()->second.moving);
  f.instances = {discInstance(1, 3.0, 0.0, 0.28, 0.9)};
  tracker.update(f, issues);
  EXPECT_EQ(tracker.objectsInBody(Pose::Identity()).size(), 1u);
}

// Key poses every 1 m at 0.25 m per frame (frames 0, 4, 8): a chair seen in frames 0-2 only is
// confirmed in frame 2 (min_age 3) and missed in frames 3 and 4, the next key pose. It is
// reported there once (seen since the previous key pose; report_max_missed 1 alone dropped
// it), and not again at frame 8.
TEST(KeyPoseBundler, ATrackConfirmedBetweenKeyPosesIsReportedOnce) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  frontend::KeyPoseBundler bundler(frontend::Tracker(classes, cfg.tracker, cfg.fit), cfg.keypose);
  frontend::InputIssues issues;
  std::vector<KeyPoseBundle> bundles;
  for (int k = 0; k <= 8; ++k) {
    frontend::FrameInstances f;
    f.utime = k * 100000;
    f.odom_pose = poseFromXyzYaw(0.25 * k, 0, 0.5, 0);
    if (k <= 2) f.instances = {discInstance(1, 4.0 - 0.25 * k, 1.0, 0.28, 0.9)};  // static at (4, 1) in odom
    if (auto b = bundler.process(f, issues)) bundles.push_back(*b);
  }
  ASSERT_EQ(bundles.size(), 3u);
  EXPECT_TRUE(bundles[0].objects.empty());
  ASSERT_EQ(bundles[1].objects.size(), 1u);
  EXPECT_EQ(bundles[1].objects[0].class_id, 1);
  EXPECT_TRUE(bundles[2].objects.empty());
}

// An instance may carry any number of free cells, anywhere (a hostile or broken segmenter): each
// observation keeps a bounded share of them, spread over all, and the car is not judged moving.
TEST(Tracker, AnInstancesFreeCellsAreBounded) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  frontend::Tracker tracker(classes, cfg.tracker, cfg.fit);
  frontend::Instance car = carInstance();
  addFace(car, 8.0, 5.0, 12.4, 5.0);
  for (int k = 0; k < 200000; ++k) car.free_space.emplace_back(0.01f * (k % 1000), 7.0f + 0.01f * (k / 1000), 0.6f);
  // Cells as far apart as the bus encoding reaches (±3.2 km), and one not finite: the moving test
  // rasterises only the cells around the track's own points (these took gigabytes).
  car.free_space.emplace_back(-3200.0f, -3200.0f, 0.6f);
  car.free_space.emplace_back(3200.0f, 3200.0f, 0.6f);
  car.free_space.emplace_back(std::numeric_limits<float>::quiet_NaN(), 1.0f, 0.6f);
  feedFourFrames(tracker, {car});
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_FALSE(tracker.tracks().begin()->second.moving);
  EXPECT_EQ(tracker.objectsInBody(Pose::Identity()).size(), 1u);
  for (const auto& o : tracker.tracks().begin()->second.observations) {
    EXPECT_LE(o.free_space.size(), 4u * static_cast<std::size_t>(cfg.tracker.max_points_per_observation));
    EXPECT_GT(o.free_space.size(), 1000u);
  }
}

namespace {
// Free cells (0.2 m, as the segmenter's) filling the rectangle [x0, x1] x [y0, y1] at band height.
void addFreeCells(frontend::Instance& inst, double x0, double y0, double x1, double y1) {
  for (double x = x0 + 0.1; x < x1; x += 0.2)
    for (double y = y0 + 0.1; y < y1; y += 0.2)
      inst.free_space.emplace_back(static_cast<float>(x), static_cast<float>(y), 0.6f);
}
}  // namespace

// A car seen side on from the origin (its near side at x = 10, 4.4 m long along y) drives along
// y at 0.5 m per frame: too slowly for its track's points to outgrow a car by the minimum age.
// The lines of sight of each frame pass through where it stood a frame earlier (free cells from
// the sensor to 3 m beyond its side, over y where it no longer is): it is judged moving and never
// reported. A parked car whose free cells reach up to 0.1 m from its faces (lines of sight
// grazing them, and those in front) is not.
TEST(Tracker, ACarWhoseEarlierPlaceWasSeenThroughIsMovingAParkedOneIsNot) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  ASSERT_GT(cfg.tracker.moving_vacated_share, 0) << "on by default";
  for (double step : {0.5, 0.0}) {
    for (bool check : {true, false}) {
      frontend::TrackerParams p = cfg.tracker;
      if (!check) p.moving_vacated_share = 0;
      p.moving_shift = 0;  // the vacated test alone (the car's whole side shifts too)
      frontend::Tracker tracker(classes, p, cfg.fit);
      frontend::InputIssues issues;
      for (int k = 0; k < 5; ++k) {
        const double y0 = -2.2 + step * k;  // the car's rear end
        frontend::Instance car = carInstance();
        addFace(car, 10.0, y0, 10.0, y0 + 4.4);
        addFreeCells(car, 5.0, y0 - 4.0, 9.9, y0 + 8.4);  // in front of its side
        addFreeCells(car, 9.9, y0 - 4.0, 13.0, y0 - 0.1);  // behind it, beyond its rear end
        addFreeCells(car, 9.9, y0 + 4.5, 13.0, y0 + 8.4);  // beyond its front end
        frontend::FrameInstances f;
        f.utime = k * 100000;
        f.instances = {car};
        tracker.update(f, issues);
      }
      ASSERT_EQ(tracker.tracks().size(), 1u);
      const bool moving = step > 0 && check;
      EXPECT_EQ(tracker.tracks().begin()->second.moving, moving) << "step " << step << " check " << check;
      EXPECT_EQ(tracker.objectsInBody(Pose::Identity()).size(), moving ? 0u : 1u) << "step " << step << " check " << check;
    }
  }
}

namespace {
// A car's side along x at y = 20 (`length` m), its rear end at x0.
frontend::Instance carSide(double x0, double length = 4.4) {
  frontend::Instance car = carInstance();
  addFace(car, x0, 20.0, x0 + length, 20.0);
  return car;
}
}  // namespace

// A small car (3.6 m) seen side on drives along its length at 1.2 m per frame (3.6 m/s at 3 Hz),
// within the tracker's gate: by the minimum age its points together are 6.0 m long, no longer
// than a car may be, and no free cell says where it stood. Its whole side shifted: moving, never
// reported. With the shift test off it is reported as a parked car. A parked car seen more of
// each frame (its side 1.5, 3.0, then 4.4 m long from one end) is not moving.
TEST(Tracker, ACarWhoseWholeSideShiftedIsMovingOneSeenMoreOfIsNot) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  ASSERT_GT(cfg.tracker.moving_shift, 0) << "on by default";
  ASSERT_LT(cfg.tracker.moving_shift, 1.2);
  ASSERT_GT(cfg.tracker.gate_scale * classes.at(10).association_distance, 1.2);
  for (bool check : {true, false}) {
    frontend::TrackerParams p = cfg.tracker;
    if (!check) p.moving_shift = 0;
    frontend::Tracker tracker(classes, p, cfg.fit);
    feedAt3Hz(tracker, 0, {{carSide(0.0, 3.6)}, {carSide(1.2, 3.6)}, {carSide(2.4, 3.6)}});
    ASSERT_EQ(tracker.tracks().size(), 1u) << "check " << check;
    ASSERT_EQ(tracker.tracks().begin()->second.hits, cfg.tracker.min_age);
    EXPECT_EQ(tracker.tracks().begin()->second.moving, check);
    EXPECT_EQ(tracker.objectsInBody(Pose::Identity()).size(), check ? 0u : 1u) << "check " << check;
  }
  frontend::Tracker parked(classes, cfg.tracker, cfg.fit);
  std::vector<std::vector<frontend::Instance>> frames;
  for (double len : {1.5, 3.0, 4.4, 4.4}) {
    frontend::Instance car = carInstance();
    addFace(car, 0.0, 20.0, len, 20.0);
    frames.push_back({car});
  }
  feedAt3Hz(parked, 0, frames);
  ASSERT_EQ(parked.tracks().size(), 1u);
  EXPECT_FALSE(parked.tracks().begin()->second.moving);
  EXPECT_EQ(parked.objectsInBody(Pose::Identity()).size(), 1u);
}

// Three cars pass one after another at 2.4 m per frame (7.2 m/s at 3 Hz), beyond the gate: each
// frame's view is too far from the last for the gate. Without moving_shift_reach every view starts
// a track, and each car passing later feeds the tracks the one before left at the same places: at
// the minimum age they are reported as parked cars (the far lane's traffic in the urban worlds).
// With it each car's views continue one track, judged moving; nothing is reported. The end faces
// of a row of parked cars (1.8 m wide, 2.6 m apart), one glimpsed per frame, are not moving: a
// face's jump to the next is across its width.
TEST(Tracker, CarsPassingBeyondTheGateAreMovingARowGlimpsedEndOnIsNot) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  ASSERT_GT(cfg.tracker.moving_shift_reach, 2.6);
  ASSERT_LT(cfg.tracker.gate_scale * classes.at(10).association_distance, 2.4);
  for (bool reach : {true, false}) {
    frontend::TrackerParams p = cfg.tracker;
    if (!reach) p.moving_shift_reach = 0;
    frontend::Tracker tracker(classes, p, cfg.fit);
    for (int pass = 0; pass < 3; ++pass)
      feedAt3Hz(tracker, 6 * pass, {{carSide(0.0)}, {carSide(2.4)}, {carSide(4.8)}, {carSide(7.2)}});
    std::size_t moving = 0;
    for (const auto& [id, t] : tracker.tracks()) moving += t.moving;
    if (reach) {
      EXPECT_EQ(moving, tracker.tracks().size());
      EXPECT_TRUE(tracker.objectsInBody(Pose::Identity()).empty());
    } else {
      EXPECT_EQ(moving, 0u);
      EXPECT_FALSE(tracker.objectsInBody(Pose::Identity()).empty()) << "the failure the reach mends";
    }
  }
  frontend::Tracker row(classes, cfg.tracker, cfg.fit);
  std::vector<std::vector<frontend::Instance>> frames;
  for (int k = 0; k < 9; ++k) {
    const double x = 2.6 * (k % 3);
    frontend::Instance face = carInstance();
    addFace(face, x, 10.0, x + 1.8, 10.0);
    frames.push_back({face});
  }
  feedAt3Hz(row, 0, frames);
  ASSERT_EQ(row.tracks().size(), 3u);
  for (const auto& [id, t] : row.tracks()) EXPECT_FALSE(t.moving) << "track " << id;
}

// A small car (its 3.6 m side along x at y = 20) drives on at 1.2 m per frame at 3 Hz; a track
// another car left 1 m ahead of where this one was last seen (a 1 m piece of a side at y = 20.3,
// seen once) waits there. The car's fourth view lies 0.2 m from that track and 1.2 m from its own
// (both within the gate): looked for where it was, the car's view feeds the other track; looked
// for where its velocity (3.6 m/s) carries it, it continues its own.
TEST(Tracker, AMovingCarIsLookedForWhereItsVelocityCarriesIt) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  ASSERT_TRUE(cfg.tracker.moving_predict) << "on by default";
  for (bool predict : {true, false}) {
    frontend::TrackerParams p = cfg.tracker;
    p.moving_predict = predict;
    frontend::Tracker tracker(classes, p, cfg.fit);
    frontend::Instance piece = carInstance();
    addFace(piece, 5.1, 20.3, 6.1, 20.3);
    std::vector<std::vector<frontend::Instance>> frames;
    for (int k = 0; k < 4; ++k) frames.push_back({carSide(1.2 * k, 3.6)});
    frames[0].push_back(piece);
    feedAt3Hz(tracker, 0, frames);
    ASSERT_EQ(tracker.tracks().size(), 2u) << "predict " << predict;
    const frontend::Track& car = tracker.tracks().begin()->second;  // the lower id: the car's
    const frontend::Track& left = std::next(tracker.tracks().begin())->second;
    EXPECT_TRUE(car.moving);
    EXPECT_EQ(car.hits, predict ? 4 : 3) << "predict " << predict;
    EXPECT_EQ(left.hits, predict ? 1 : 2) << "predict " << predict;
  }
}

// Frame times off a bus may be anything. A car 1.2 m on from one frame to the next, at times near
// the two ends of int64 whose integer difference would wrap to +0.5 s (a shift within the
// moving test's interval): the times lie 1.8e13 s apart the other way, so the views are not
// compared, the car is not moving and no velocity is taken. Times that run backwards or jump
// between the extremes afterwards fault nothing.
TEST(Tracker, FrameTimesAtTheExtremesNeitherOverflowNorMoveACar) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  ASSERT_LT(cfg.tracker.moving_shift_interval, 0.5);
  ASSERT_GT(cfg.tracker.moving_shift_max_interval, 0.5);
  frontend::Tracker tracker(classes, cfg.tracker, cfg.fit);
  frontend::InputIssues issues;
  constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max(), kMin = std::numeric_limits<std::int64_t>::min();
  const std::int64_t times[] = {kMax - 249999, kMin + 250000, 0, kMax, -1};
  for (int k = 0; k < 5; ++k) {
    frontend::FrameInstances f;
    f.utime = times[k];
    f.instances = {carSide(k < 2 ? 1.2 * k : 1.2, 3.6)};
    tracker.update(f, issues);
    if (k == 1) {
      ASSERT_EQ(tracker.tracks().size(), 1u);
      EXPECT_FALSE(tracker.tracks().begin()->second.moving);
    }
  }
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_FALSE(tracker.tracks().begin()->second.moving);
  EXPECT_EQ(tracker.tracks().begin()->second.hits, 5);
  EXPECT_TRUE(tracker.tracks().begin()->second.velocity.isZero());
}

// A car driving away from the sensor, seen end-on (its 1.8 m rear face across x at y = 10, then
// 11.6): it moved 1.6 m, beyond the 1.5 m gate, so the second view starts a track of its own,
// and the box merge joins the two (together 1.8 x 1.6 m, one holding the other). The second
// view's lines of sight passed through where the face stood: the joint track is moving. With
// the vacated test off it is not.
TEST(Tracker, ACarTrackedAnewEachFrameIsMovingOnceItsTracksJoin) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  ASSERT_GT(cfg.tracker.moving_vacated_share, 0) << "on by default";
  ASSERT_LT(cfg.tracker.gate_scale * classes.at(10).association_distance, 1.6);
  ASSERT_GT(cfg.tracker.box_merge_width, 1.6);
  for (bool check : {true, false}) {
    frontend::TrackerParams p = cfg.tracker;
    if (!check) p.moving_vacated_share = 0;
    frontend::Tracker tracker(classes, p, cfg.fit);
    frontend::InputIssues issues;
    for (int k = 0; k < 2; ++k) {
      const double y = 10.0 + 1.6 * k;
      frontend::Instance car = carInstance();
      addFace(car, -0.9, y, 0.9, y);
      addFreeCells(car, -2.0, 1.0, 2.0, y - 0.1);  // from the sensor to the face
      frontend::FrameInstances f;
      f.utime = k * 100000;
      f.instances = {car};
      tracker.update(f, issues);
    }
    ASSERT_EQ(tracker.tracks().size(), 1u) << "check " << check;
    EXPECT_EQ(tracker.tracks().begin()->second.hits, 2);
    EXPECT_EQ(tracker.tracks().begin()->second.moving, check) << "check " << check;
  }
}

// The lone 1.8 m face of the test above, its neighbours seen along their sides now 12-15 m off
// (x 4 to 8.4 and 33 to 37.4 at y = 8.5): beyond parallel_radius, within
// parallel_fallback_radius. With the fallback it takes their heading; without it (fallback no
// wider than the radius) the fit's own guess, an end face.
TEST(Tracker, ABoxWithNoParallelNeighbourNearTakesTheHeadingOfThoseFartherOff) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  ASSERT_GT(cfg.tracker.parallel_fallback_radius, 16.0) << "on by default";
  ASSERT_LT(cfg.tracker.parallel_radius, 12.0);
  for (double fallback : {cfg.tracker.parallel_fallback_radius, cfg.tracker.parallel_radius}) {
    frontend::TrackerParams p = cfg.tracker;
    p.parallel_fallback_radius = fallback;
    const auto headings = headingsAcross(classes, p, cfg.fit, {{4.0, 8.5, 8.4, 8.5}, {33.0, 8.5, 37.4, 8.5}, {20.0, 8.5, 21.8, 8.5}});
    ASSERT_EQ(headings.size(), 3u);
    for (const auto& [x, across] : headings) {
      if (std::abs(x - 21) < 2.5) {
        EXPECT_NEAR(across, fallback > cfg.tracker.parallel_radius ? 0.0 : M_PI / 2, 0.1) << "fallback " << fallback;
      }
    }
  }
}

// A table (1.0 m across, centre (4, 0)) tracked over six frames; in frame 2 the labeller also
// named the monitor standing beside it "table" (0.6 m more to one side), and that wide view joins
// the track. The report leaves it out (ellipsoid_view_growth): the table keeps its size and centre;
// without, the fit grows towards the monitor.
TEST(Tracker, AnEllipsoidsReportLeavesOutAViewMuchWiderThanItsOthers) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  ASSERT_GT(cfg.tracker.ellipsoid_view_growth, 0) << "on by default";
  auto disc = [](float cx, float radius) {
    frontend::Instance inst;
    inst.class_id = 2;  // table
    for (int i = 0; i < 40; ++i)
      for (float z : {0.05f, 0.3f, 0.55f, 0.75f}) {
        const float a = static_cast<float>(i) * 0.157f;
        inst.points.emplace_back(cx + radius * std::cos(a), radius * std::sin(a), z);
      }
    return inst;
  };
  auto reported = [&](double growth) {
    frontend::TrackerParams p = cfg.tracker;
    p.ellipsoid_view_growth = growth;
    frontend::Tracker tracker(classes, p, cfg.fit);
    frontend::InputIssues issues;
    for (int k = 0; k < 6; ++k) {
      frontend::FrameInstances f;
      f.utime = k * 100000;
      frontend::Instance table = disc(4.0f, 0.5f);
      if (k == 2) {
        const frontend::Instance monitor_too = disc(4.3f, 0.8f);  // the table and the monitor beside it
        table.points.insert(table.points.end(), monitor_too.points.begin(), monitor_too.points.end());
      }
      f.instances = {table};
      tracker.update(f, issues);
    }
    const std::vector<Object> out = tracker.objectsInBody(Pose::Identity());
    EXPECT_EQ(out.size(), 1u);
    return out.empty() ? Object{} : out[0];
  };
  const Object table = reported(cfg.tracker.ellipsoid_view_growth);
  ASSERT_TRUE(std::holds_alternative<Ellipsoid>(table.model));
  const double kept = std::get<Ellipsoid>(table.model).radius;
  const Object blob = reported(0.0);
  ASSERT_TRUE(std::holds_alternative<Ellipsoid>(blob.model));
  const double all = std::get<Ellipsoid>(blob.model).radius;
  EXPECT_NEAR(kept, 0.5, 0.05);
  EXPECT_NEAR(table.position().x(), 4.0, 0.05);
  EXPECT_GT(all, kept + 0.2) << "the wide view was taken in";
}
