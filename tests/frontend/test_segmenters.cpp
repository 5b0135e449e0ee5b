// Labelled and geometric LiDAR segmenters on hand-made and real SemanticKITTI scans, grid
// clustering, ground removal, and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <stdexcept>

#include "frontend/frontend_config.h"
#include "frontend/geometric_segmenter.h"
#include "frontend/grid_clustering.h"
#include "frontend/label_vote.h"
#include "frontend/labelled_segmenter.h"
#include "emulator/detection_emulator.h"
#include "synthetic_scene.h"

using namespace slide;
using slide::synth::SceneObject;

namespace {
const std::string kScan720 = std::string(SLIDE_DATA_DIR) + "/semantickitti/sequences/08/velodyne/000720.bin";

const frontend::Instance* nearest(const std::vector<frontend::Instance>& v, int class_id, const Eigen::Vector2d& xy,
                                  double max_d) {
  const frontend::Instance* best = nullptr;
  for (const auto& i : v) {
    if (i.class_id != class_id) continue;
    const double d = (frontend::centroidOf(i.points).head<2>() - xy).norm();
    if (d < max_d) max_d = d, best = &i;
  }
  return best;
}

// One return of a hand-made labelled scan (no instance id).
void addLabelledPoint(io::LabelledScan& scan, double x, double y, double z, std::uint16_t label) {
  scan.xyz.emplace_back(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
  scan.intensity.push_back(0.5f);
  scan.semantic.push_back(label);
  scan.instance.push_back(0);
}
}  // namespace

TEST(GridClustering, SplitsSeparatedBlobsAndDropsSmallOnes) {
  frontend::Cloud c;
  for (int i = 0; i < 50; ++i) c.emplace_back(0.02f * i, 0, 0);
  for (int i = 0; i < 30; ++i) c.emplace_back(5 + 0.02f * i, 0, 0);
  for (int i = 0; i < 3; ++i) c.emplace_back(-10, 0.01f * i, 0);
  c.emplace_back(std::numeric_limits<float>::quiet_NaN(), 0, 0);
  const auto cl = frontend::clusterGrid(c, {}, {0.3, false, 5});
  ASSERT_EQ(cl.size(), 2u);
  EXPECT_EQ(cl[0].size(), 50u);
  EXPECT_EQ(cl[1].size(), 30u);
  // Planar clustering ignores height.
  frontend::Cloud stack{{0, 0, 0}, {0, 0, 5}};
  EXPECT_EQ(frontend::clusterGrid(stack, {}, {0.3, true, 1}).size(), 1u);
  EXPECT_EQ(frontend::clusterGrid(stack, {}, {0.3, false, 1}).size(), 2u);
}

// Brute-force reference: points whose cells differ by at most one in every axis are joined.
std::vector<std::vector<int>> clusterByPairs(const frontend::Cloud& c, double cell, int min_points) {
  const int n = static_cast<int>(c.size());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> root = [&](int i) { return parent[i] == i ? i : parent[i] = root(parent[i]); };
  auto cellOf = [&](const Eigen::Vector3f& p) { return (p.cast<double>() / cell).array().floor().eval(); };
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if ((cellOf(c[i]) - cellOf(c[j])).abs().maxCoeff() <= 1) parent[root(j)] = root(i);
  std::map<int, std::vector<int>> groups;
  for (int i = 0; i < n; ++i) groups[root(i)].push_back(i);
  std::vector<std::vector<int>> out;
  for (auto& [r, g] : groups)
    if (static_cast<int>(g.size()) >= min_points) out.push_back(g);
  std::sort(out.begin(), out.end());
  return out;
}

TEST(GridClustering, MatchesPairwiseCellAdjacencyWithNegativeAndFarCoordinates) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  frontend::Cloud c;
  // Blobs around negative and positive coordinates, some touching only at cell corners.
  for (const Eigen::Vector3f& centre : {Eigen::Vector3f(-3.1f, -2.2f, -0.4f), Eigen::Vector3f(-2.5f, -1.6f, 0.2f),
                                       Eigen::Vector3f(4.0f, 0.0f, 1.0f), Eigen::Vector3f(0.0f, 6.0f, -1.0f)})
    for (int i = 0; i < 40; ++i) c.push_back(centre + 0.25f * Eigen::Vector3f(u(rng), u(rng), u(rng)));
  for (int i = 0; i < 60; ++i) c.emplace_back(10 * u(rng), 10 * u(rng), 2 * u(rng));  // scattered singles
  const auto reference = clusterByPairs(c, 0.3, 3);
  auto sorted = [](std::vector<std::vector<int>> v) {  // clusters as sets
    for (auto& cl : v) std::sort(cl.begin(), cl.end());
    std::sort(v.begin(), v.end());
    return v;
  };
  const auto near = frontend::clusterGrid(c, {}, {0.3, false, 3});
  EXPECT_EQ(sorted(near), reference);
  // Two lone points 100 km away in every axis widen the cell box past one 64-bit word (the
  // other sorting path); the clusters must not change.
  frontend::Cloud wide = c;
  wide.emplace_back(1e5f, 1e5f, 1e5f);
  wide.emplace_back(-1e5f, -1e5f, -1e5f);
  EXPECT_EQ(sorted(frontend::clusterGrid(wide, {}, {0.3, false, 3})), reference);
}

TEST(GroundRemoval, CarRoofIsNotGround) {
  const auto scan = synth::syntheticScan({{10, {8, 0, 0}, 0, 0, 0, {4.4, 1.8, 1.5}}},
                                           poseFromXyzYaw(0, 0, 1.5, 0));
  const auto h = frontend::heightAboveGround(scan.xyz, {});
  for (std::size_t i = 0; i < scan.size(); ++i) {
    if (scan.semantic[i] == 40) {
      EXPECT_LT(std::abs(h[i]), 0.1);
    }
    if (scan.semantic[i] == 10 && scan.xyz[i].z() > -0.5) {
      EXPECT_GT(h[i], 0.9);
    }
  }
}

TEST(LabelledSegmenter, InstancesFromClassesAloneAndBadInput) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::LabelledSegmenter seg(classes, {});
  auto scan = synth::syntheticScan({{71, {6, 2, 0}}, {10, {9, -3, 0}, 0, 0, 0.3}}, poseFromXyzYaw(0, 0, 1.5, 0));
  scan.instance.clear();  // a detector gives classes only
  scan.xyz[0] = Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity());
  frontend::InputIssues issues;
  const auto inst = seg.segment(scan, issues);
  ASSERT_EQ(inst.size(), 2u);
  EXPECT_TRUE(nearest(inst, 71, {6, 2}, 0.5));
  EXPECT_TRUE(nearest(inst, 10, {9, -3}, 1.0));
  EXPECT_EQ(issues.get("non-finite point"), 1);

  frontend::InputIssues empty_issues;
  EXPECT_TRUE(seg.segment(io::LabelledScan{}, empty_issues).empty());
  EXPECT_EQ(empty_issues.get("empty scan"), 1);
  io::LabelledScan unlabelled;
  unlabelled.xyz = scan.xyz;
  EXPECT_TRUE(seg.segment(unlabelled, empty_issues).empty());
  EXPECT_EQ(empty_issues.get("scan without labels"), 1);
}

// Two chairs 0.35 m apart (label 100): one 0.3 m grid joins them, the chair's own 0.15 m cell
// keeps them apart; a cell for a class the table lacks is a configuration error.
TEST(LabelledSegmenter, ClassCellKeepsCloseChairsApart) {
  io::LabelledScan scan;
  for (double x0 : {4.0, 4.75})  // 0.4 m wide seats: a 0.35 m gap between them
    for (double x = 0; x <= 0.4; x += 0.03)
      for (double z = -1.0; z <= -0.2; z += 0.05) {
        scan.xyz.emplace_back(static_cast<float>(x0 + x), 1.0f, static_cast<float>(z));
        scan.intensity.push_back(0.5f);
        scan.semantic.push_back(100);
        scan.instance.push_back(0);
      }
  const ClassTable classes = ClassTable::loadDefault();
  frontend::LabelledSegmenterParams p = frontend::loadDefaultFrontendConfig().labelled;
  frontend::InputIssues issues;
  EXPECT_EQ(frontend::LabelledSegmenter(classes, p).segment(scan, issues).size(), 2u);
  p.cluster_cell_by_class.clear();
  EXPECT_EQ(frontend::LabelledSegmenter(classes, p).segment(scan, issues).size(), 1u) << "0.3 m cells join the chairs";
  p.cluster_cell_by_class["sofa"] = 0.1;
  EXPECT_THROW(frontend::LabelledSegmenter(classes, p), std::invalid_argument);
}

// Two trunks (label trunk, radius 0.18 m) whose near halves stand 0.37 m apart across the line
// of sight: 0.3 m cells join them (one cylinder fitted across both), the cylinder classes' own
// 0.2 m cells keep them apart. Trunk and pole points are clustered together and take the finest
// of the cylinder classes' cells.
TEST(LabelledSegmenter, CylinderCellKeepsCloseTrunksApart) {
  io::LabelledScan scan;
  for (double yc : {0.0, 0.73})
    for (double a = M_PI / 2; a <= 3 * M_PI / 2 + 1e-9; a += M_PI / 18)  // the half facing the sensor at the origin
      for (double z = -1.0; z <= 2.0; z += 0.1) addLabelledPoint(scan, 6.0 + 0.18 * std::cos(a), yc + 0.18 * std::sin(a), z, 71);
  const ClassTable classes = ClassTable::loadDefault();
  frontend::LabelledSegmenterParams p = frontend::loadDefaultFrontendConfig().labelled;
  ASSERT_TRUE(p.merge_cylinders);
  frontend::InputIssues issues;
  EXPECT_EQ(frontend::LabelledSegmenter(classes, p).segment(scan, issues).size(), 2u);
  p.cluster_cell_by_class.erase("trunk");
  p.cluster_cell_by_class.erase("pole");
  EXPECT_EQ(frontend::LabelledSegmenter(classes, p).segment(scan, issues).size(), 1u) << "0.3 m cells join the trunks";
}

// Two cars' end faces side by side (label car, each 1.8 m wide, 0.6 m apart along y = 4), seen
// far off: one return every 0.05 m along a beam, beams 0.35 m apart in height, so each face
// falls into strips of 37 returns on 3-D gap cells, every one under gap_cluster.min_points. Two
// mixed returns in the gap (a beam grazing both edges) join the faces on 0.3 m cells. The gap
// split works on the footprint (the gap between two cars is a vertical slot): two clusters.
TEST(LabelledSegmenter, TwoEndFacesSideBySideSeenFarOffAreTwoClusters) {
  io::LabelledScan scan;
  for (double x0 : {5.0, 7.4})
    for (double x = x0; x <= x0 + 1.8 + 1e-9; x += 0.05)
      for (double z = -1.0; z <= 0.45; z += 0.35) {
        scan.xyz.emplace_back(static_cast<float>(x), 4.0f, static_cast<float>(z));
        scan.intensity.push_back(0.5f);
        scan.semantic.push_back(10);
        scan.instance.push_back(0);
      }
  for (float z : {-0.65f, -0.3f}) {
    scan.xyz.emplace_back(7.1f, 4.0f, z);
    scan.intensity.push_back(0.5f);
    scan.semantic.push_back(10);
    scan.instance.push_back(0);
  }
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::LabelledSegmenterParams p = frontend::loadDefaultFrontendConfig().labelled;
  ASSERT_GT(p.gap_cluster.min_points, 37) << "a strip alone is no part";
  frontend::InputIssues issues;
  const auto instances = frontend::LabelledSegmenter(classes, p).segment(scan, issues);
  ASSERT_EQ(instances.size(), 2u);
  for (const auto& inst : instances) {
    float lo = 1e9f, hi = -1e9f;
    for (const auto& q : inst.points) lo = std::min(lo, q.x()), hi = std::max(hi, q.x());
    EXPECT_LT(hi - lo, 1.9f);
  }
}

// A car's end face (label car, 1.8 m wide, x 5.0 to 6.8 at y = 4) and, 0.35 m past its corner, a
// stripe of the next car's side (0.8 m deep at x = 7.15) join on 0.3 m cells into one car-sized
// cluster; on gap_cluster cells they are two, and the car is the face alone.
TEST(LabelledSegmenter, AnEndFaceAndAStripeOfTheNextCarsSideAreTwoClusters) {
  io::LabelledScan scan;
  auto face = [&](double x0, double y0, double x1, double y1) {
    const double len = std::hypot(x1 - x0, y1 - y0);
    for (double t = 0; t <= len + 1e-9; t += 0.05)
      for (double z = -1.0; z <= 0.4; z += 0.1) {
        const double x = x0 + (x1 - x0) * t / len, y = y0 + (y1 - y0) * t / len;
        scan.xyz.emplace_back(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
        scan.intensity.push_back(0.5f);
        scan.semantic.push_back(10);
        scan.instance.push_back(0);
      }
  };
  face(5.0, 4.0, 6.8, 4.0);
  face(7.15, 4.2, 7.15, 5.0);
  const ClassTable classes = ClassTable::loadDefault();
  frontend::LabelledSegmenterParams p = frontend::loadDefaultFrontendConfig().labelled;
  ASSERT_GT(p.gap_cluster.cell, 0.0) << "on by default";
  frontend::InputIssues issues;
  auto widest = [&](const frontend::LabelledSegmenterParams& params) {
    float most = 0;
    for (const auto& inst : frontend::LabelledSegmenter(classes, params).segment(scan, issues)) {
      float lo = 1e9f, hi = -1e9f;
      for (const auto& q : inst.points) lo = std::min(lo, q.x()), hi = std::max(hi, q.x());
      most = std::max(most, hi - lo);
    }
    return most;
  };
  EXPECT_LT(widest(p), 1.9f) << "the face alone";
  p.gap_cluster.cell = 0;
  EXPECT_GT(widest(p), 2.1f) << "the face with the stripe";
}

TEST(LabelledSegmenter, RealScanCarBecomesCarSizedCuboid) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  const io::LabelledScan scan = io::readLabelledScan(kScan720);
  frontend::InputIssues issues;
  const auto inst = frontend::LabelledSegmenter(classes, cfg.labelled).segment(scan, issues);
  const frontend::Instance* car = nearest(inst, 10, {-14.7, -6.8}, 1.0);
  ASSERT_TRUE(car);
  EXPECT_GT(car->points.size(), 500u);  // labelled instance: 600+ points; clustering of the class drops a few strays
  const auto o = frontend::fitObject(car->points, 10, classes, cfg.fit, Eigen::Vector3d::Zero());
  ASSERT_TRUE(o);
  EXPECT_TRUE(classes.sizePlausible(*o));
  int cylinders = 0;
  for (const auto& i : inst)
    if (classes.at(i.class_id).shape == Shape::Cylinder)
      cylinders += frontend::fitObject(i.points, i.class_id, classes, cfg.fit, Eigen::Vector3d::Zero()).has_value();
  EXPECT_GE(cylinders, 7);
}

TEST(GeometricSegmenter, SyntheticTrunkAndCar) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::GeometricSegmenter seg(classes, frontend::loadDefaultFrontendConfig().geometric);
  auto scan = synth::syntheticScan({{71, {6, 3, 0}, 0.25, 6.0}, {10, {9, -4, 0}, 0, 0, 0.2}}, poseFromXyzYaw(0, 0, 1.5, 0));
  scan.semantic.clear();
  scan.instance.clear();
  frontend::InputIssues issues;
  const auto inst = seg.segment(scan, issues);
  EXPECT_TRUE(nearest(inst, 71, {6, 3}, 0.5));
  EXPECT_TRUE(nearest(inst, 10, {9, -4}, 1.0));
  EXPECT_EQ(issues.total(), 0);
}

TEST(GeometricSegmenter, RealScanFindsTheLabelledCar) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  io::LabelledScan scan = io::readLabelledScan(kScan720);
  scan.semantic.clear();
  scan.instance.clear();
  frontend::InputIssues issues;
  const auto inst = frontend::GeometricSegmenter(classes, cfg.geometric).segment(scan, issues);
  const frontend::Instance* car = nearest(inst, 10, {-14.7, -6.8}, 1.5);
  ASSERT_TRUE(car);
  EXPECT_TRUE(frontend::fitObject(car->points, 10, classes, cfg.fit, Eigen::Vector3d::Zero()));
}

// Emulated detector labels (config/detections.yaml: bled boundaries, point noise, confusions,
// no instance ids) still give one trunk, one pole and one car where they stand, over many seeds.
TEST(LabelledSegmenter, RobustToEmulatedDetectorErrors) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::LabelledSegmenter seg(classes, frontend::loadDefaultFrontendConfig().labelled);
  const emulator::DetectionEmulatorConfig emu =
      emulator::loadDetectionEmulatorConfig(std::string(SLIDE_SOURCE_DIR) + "/config/detections.yaml");
  const auto truth = synth::syntheticScan({{71, {6, 2, 0}, 0.2, 6.0}, {80, {7, -5, 0}, 0.08, 5.0}, {10, {12, -1, 0}, 0, 0, 0.3}},
                                          poseFromXyzYaw(0, 0, 1.5, 0));
  int trunk = 0, pole_or_trunk = 0, car = 0, extra = 0;
  const int runs = 20;
  for (int k = 0; k < runs; ++k) {
    const io::LabelledScan scan =
        emulator::emulateLidarLabels(truth, emu.lidar, emulator::detectionSeed(emu.seed, 0, k));
    frontend::InputIssues issues;
    const auto inst = seg.segment(scan, issues);
    const bool t = nearest(inst, 71, {6, 2}, 0.5), c = nearest(inst, 10, {12, -1}, 1.0);
    const bool p = nearest(inst, 80, {7, -5}, 0.5) || nearest(inst, 71, {7, -5}, 0.5);
    trunk += t, pole_or_trunk += p, car += c;
    extra += static_cast<int>(inst.size()) - t - p - c;
  }
  // The emulator misses near objects with probability 0.01-0.05 and confuses 2-5 % of them.
  EXPECT_GE(trunk, runs - 3);
  EXPECT_GE(pole_or_trunk, runs - 3);
  EXPECT_GE(car, runs - 2);
  EXPECT_LE(extra, runs / 2) << "bled or shadowed points formed extra objects";
}

// A wall 3 m behind a table, seen over it: a range-image labeller blurs the table's label onto
// every third wall return along the table's upper outline (a band 1.2 m wide, 0.3 m high), as
// the detection emulator's boundary bleeding does. Those 48 returns stand a table high and make
// a second table 3 m behind the first; voted on by the returns in the cells around them, they
// are wall again and one table is left. A table return among table returns keeps its label.
TEST(LabelledSegmenter, LabelsBledOntoAWallBehindATableMakeNoSecondTable) {
  io::LabelledScan scan;
  for (double y = -0.5; y <= 0.5 + 1e-9; y += 0.05)  // the table's near face, x = 5
    for (double z = -1.0; z <= -0.3 + 1e-9; z += 0.05) addLabelledPoint(scan, 5.0, y, z, 101);
  const std::size_t table_points = scan.size();
  int bled = 0, k = 0;
  for (double y = -1.0; y <= 1.0 + 1e-9; y += 0.05)  // the wall, x = 8
    for (double z = -1.0; z <= 0.5 + 1e-9; z += 0.05, ++k) {
      const bool band = std::abs(y) <= 0.6 && z >= -0.3 && z <= 0.0 && k % 3 == 0;
      addLabelledPoint(scan, 8.0, y, z, band ? 101 : 50);
      bled += band;
    }
  ASSERT_GE(bled, 45);
  const ClassTable classes = ClassTable::loadDefault();
  const auto is_table = [](std::uint16_t l) { return l == 101; };
  const std::vector<std::uint16_t> voted = frontend::voteLabels(scan, is_table, {0.1, 80.0});
  ASSERT_EQ(voted.size(), scan.size());
  EXPECT_EQ(std::count(voted.begin(), voted.end(), 101), static_cast<long>(table_points));
  EXPECT_TRUE(std::all_of(voted.begin(), voted.begin() + table_points, [](std::uint16_t l) { return l == 101; }));
  EXPECT_EQ(frontend::voteLabels(scan, is_table, {0.0, 80.0}), scan.semantic) << "cell 0: off";
  io::LabelledScan hostile = scan;  // a return no cell holds (a broken driver): keeps its label, votes for nothing
  addLabelledPoint(hostile, 5.0, 0.0, 3e38, 101);
  const std::vector<std::uint16_t> hostile_voted = frontend::voteLabels(hostile, is_table, {0.1, 80.0});
  EXPECT_EQ(hostile_voted.back(), 101);
  EXPECT_TRUE(std::equal(voted.begin(), voted.end(), hostile_voted.begin()));

  frontend::LabelledSegmenterParams p = frontend::loadDefaultFrontendConfig().labelled;
  ASSERT_GT(p.vote_cell, 0.0);
  frontend::InputIssues issues;
  const auto voted_inst = frontend::LabelledSegmenter(classes, p).segment(scan, issues);
  ASSERT_EQ(voted_inst.size(), 1u);
  EXPECT_NEAR(frontend::centroidOf(voted_inst[0].points).x(), 5.0, 0.1);
  p.vote_cell = 0;
  EXPECT_EQ(frontend::LabelledSegmenter(classes, p).segment(scan, issues).size(), 2u) << "the bled band is a table of its own";
}

// A chair in front of a table hides the table's middle: the table's two visible pieces, 0.7 m
// apart, are two clusters on the table's cells. With the returns between them (in azimuth, at
// their height) on the chair, nearer, they are one table; with a wall seen between them, farther,
// they stay two (nothing says they are one), as they do with the join off.
TEST(LabelledSegmenter, ATableCutInTwoByAChairInFrontOfItIsOneTable) {
  auto scene = [](bool chair) {
    io::LabelledScan scan;
    const double chair_half_width = 0.25, chair_x = 3.5;  // hides |y / x| < 0.25 / 3.5
    for (double y = -0.6; y <= 0.6 + 1e-9; y += 0.05)     // the table's near face, x = 5
      for (double z = -1.0; z <= -0.3 + 1e-9; z += 0.05)
        if (std::abs(y) / 5.0 >= chair_half_width / chair_x) addLabelledPoint(scan, 5.0, y, z, 101);
        else if (!chair) addLabelledPoint(scan, 8.0, y * 8.0 / 5.0, z, 50);  // a wall seen through the gap
    if (chair)
      for (double y = -chair_half_width; y <= chair_half_width + 1e-9; y += 0.05)
        for (double z = -1.05; z <= -0.2 + 1e-9; z += 0.05) addLabelledPoint(scan, chair_x, y, z, 100);
    return scan;
  };
  const ClassTable classes = ClassTable::loadDefault();
  frontend::LabelledSegmenterParams p = frontend::loadDefaultFrontendConfig().labelled;
  ASSERT_GT(p.ellipsoid_join.max_gap, 0.7);
  frontend::InputIssues issues;
  auto tables = [&](const io::LabelledScan& scan, const frontend::LabelledSegmenterParams& params) {
    std::vector<Eigen::Vector3d> centres;
    for (const auto& inst : frontend::LabelledSegmenter(classes, params).segment(scan, issues))
      if (inst.class_id == 2) centres.push_back(frontend::centroidOf(inst.points));
    return centres;
  };
  const auto joined = tables(scene(true), p);
  ASSERT_EQ(joined.size(), 1u);
  EXPECT_NEAR(joined[0].y(), 0.0, 0.05);
  EXPECT_EQ(tables(scene(false), p).size(), 2u) << "a wall behind the gap hides nothing";
  p.ellipsoid_join.max_gap = 0;
  EXPECT_EQ(tables(scene(true), p).size(), 2u) << "join off";
}

// A chair's seat (its front and top) and its back, 0.35 m above the seat with nothing labelled
// between, are two clusters on the chair's cells; one above the other, and together the size of
// a chair, they are one.
TEST(LabelledSegmenter, AChairsSeatAndBackAreOneChair) {
  io::LabelledScan scan;
  for (double y = -0.25; y <= 0.25 + 1e-9; y += 0.05) {
    for (double x = 4.0; x <= 4.5 + 1e-9; x += 0.05) addLabelledPoint(scan, x, y, -0.8, 100);      // the seat's top
    for (double z = -1.1; z <= -0.8 + 1e-9; z += 0.05) addLabelledPoint(scan, 4.0, y, z, 100);     // its front
    for (double z = -0.45; z <= -0.1 + 1e-9; z += 0.05) addLabelledPoint(scan, 4.5, y, z, 100);    // the back
  }
  const ClassTable classes = ClassTable::loadDefault();
  frontend::LabelledSegmenterParams p = frontend::loadDefaultFrontendConfig().labelled;
  ASSERT_GT(p.ellipsoid_join.stacked_overlap, 0.0);
  frontend::InputIssues issues;
  EXPECT_EQ(frontend::LabelledSegmenter(classes, p).segment(scan, issues).size(), 1u);
  p.ellipsoid_join.stacked_overlap = 0;
  EXPECT_EQ(frontend::LabelledSegmenter(classes, p).segment(scan, issues).size(), 2u) << "join off";
}

// A labeller's catch-all ("other-object", 99) scattered over a table's points (one point in
// four, the vote off so it survives) clusters into a table-sized "other": dropped as debris, as
// every one of its points has table points around it. A bin standing alone by a wall is an
// "other" and votes with other_confidence. With the debris rule off the scattered labels make a
// second "other".
TEST(LabelledSegmenter, CatchAllLabelsScatteredOverATableAreNoObject) {
  io::LabelledScan scan;
  int k = 0;
  for (double y = -0.5; y <= 0.5 + 1e-9; y += 0.05) {
    for (double x = 4.0; x <= 5.0 + 1e-9; x += 0.05) addLabelledPoint(scan, x, y, -0.75, ++k % 4 ? 101 : 99);  // top
    for (double z = -1.5; z < -0.75; z += 0.05) addLabelledPoint(scan, 4.0, y, z, ++k % 4 ? 101 : 99);        // front
  }
  for (double a = 0; a < 2 * M_PI; a += 0.1)
    for (double z = -1.5; z <= -0.7 + 1e-9; z += 0.05) addLabelledPoint(scan, 4.5 + 0.25 * std::cos(a), 3.0 + 0.25 * std::sin(a), z, 99);
  for (double x = 3.0; x <= 6.0 + 1e-9; x += 0.05)
    for (double z = -1.5; z <= 1.0 + 1e-9; z += 0.1) addLabelledPoint(scan, x, 3.4, z, 50);  // the wall behind the bin
  const ClassTable classes = ClassTable::loadDefault();
  ASSERT_TRUE(classes.at(0).catch_all);
  frontend::LabelledSegmenterParams p = frontend::loadDefaultFrontendConfig().labelled;
  ASSERT_GT(p.catch_all_debris.radius, 0.0);
  ASSERT_LT(p.other_confidence, 1.0);
  p.vote_cell = 0;
  frontend::InputIssues issues;
  const auto out = frontend::LabelledSegmenter(classes, p).segment(scan, issues);
  std::vector<const frontend::Instance*> others;
  int tables = 0;
  for (const auto& i : out) {
    if (i.class_id == 0) others.push_back(&i);
    tables += i.class_id == 2;
  }
  EXPECT_EQ(tables, 1);
  ASSERT_EQ(others.size(), 1u);
  EXPECT_NEAR(frontend::centroidOf(others[0]->points).y(), 3.0, 0.1) << "the bin";
  EXPECT_FLOAT_EQ(others[0]->confidence, static_cast<float>(p.other_confidence));
  p.catch_all_debris.radius = 0;
  int others_off = 0;
  for (const auto& i : frontend::LabelledSegmenter(classes, p).segment(scan, issues)) others_off += i.class_id == 0;
  EXPECT_EQ(others_off, 2) << "debris rule off";
}

// Two cars parked side by side 0.4 m apart join on 0.3 m cells into one cluster wider than a
// car; re-clustered on 0.15 m cells they are two, in both segmenters. With re-clustering off
// (min_split_cell = cell, or max_split_length shorter than the pair) the labelled segmenter
// gives one instance, the geometric one none (too wide for a car).
TEST(Segmenters, TwoCarsParkedCloseAreTwoCars) {
  const ClassTable classes = ClassTable::loadDefault();
  const frontend::FrontendConfig cfg = frontend::loadDefaultFrontendConfig();
  const std::vector<SceneObject> cars{{10, {9.0, -5, 0}, 0, 0, M_PI / 2, {4.4, 1.8, 1.5}},
                                      {10, {11.2, -5, 0}, 0, 0, M_PI / 2, {4.4, 1.8, 1.5}}};
  const io::LabelledScan labelled = synth::syntheticScan(cars, poseFromXyzYaw(0, 0, 1.5, 0));
  io::LabelledScan unlabelled = labelled;
  unlabelled.semantic.clear();
  unlabelled.instance.clear();
  for (bool split : {true, false}) {
    frontend::FrontendConfig c = cfg;
    if (!split) c.labelled.min_split_cell = c.labelled.cluster.cell, c.geometric.car.min_split_cell = c.geometric.car.cell;
    frontend::InputIssues issues;
    int labelled_cars = 0, geometric_cars = 0;
    for (const auto& i : frontend::LabelledSegmenter(classes, c.labelled).segment(labelled, issues))
      labelled_cars += i.class_id == 10;
    const auto geo = frontend::GeometricSegmenter(classes, c.geometric).segment(unlabelled, issues);
    for (const auto& i : geo) geometric_cars += i.class_id == 10;
    EXPECT_EQ(labelled_cars, split ? 2 : 1) << split;
    EXPECT_EQ(geometric_cars, split ? 2 : 0) << split;
    if (split) {
      EXPECT_TRUE(nearest(geo, 10, {9.0, -5}, 1.2));
      EXPECT_TRUE(nearest(geo, 10, {11.2, -5}, 1.2));
    }
  }
  frontend::FrontendConfig c = cfg;  // a cluster longer than max_split_length (a wall's base) is left whole
  c.geometric.car.max_split_length = 3.0;
  frontend::InputIssues issues;
  for (const auto& i : frontend::GeometricSegmenter(classes, c.geometric).segment(unlabelled, issues))
    EXPECT_NE(i.class_id, 10);
}

namespace {
// The car points of a synthetic scan seen from the origin, and their instance ids.
std::pair<frontend::Cloud, std::vector<int>> carPoints(const std::vector<SceneObject>& cars) {
  const io::LabelledScan s = synth::syntheticScan(cars, poseFromXyzYaw(0, 0, 1.5, 0));
  std::pair<frontend::Cloud, std::vector<int>> out;
  for (std::size_t i = 0; i < s.xyz.size(); ++i)
    if (s.semantic[i] == 10) out.first.push_back(s.xyz[i]), out.second.push_back(s.instance[i]);
  return out;
}
std::vector<int> allOf(const frontend::Cloud& c) {
  std::vector<int> idx(c.size());
  std::iota(idx.begin(), idx.end(), 0);
  return idx;
}
}  // namespace

TEST(ViewNotch, SplitsTwoCarsNoseOutAndKeepsOneCarWhole) {
  const frontend::NotchSplitParams p;
  // Two cars parked nose out 0.3 m apart, seen from the aisle: the rays into the gap hit their
  // facing sides, metres beyond the two fronts.
  const auto [pair, inst] = carPoints({{10, {12.0, -1.05, 0}, 0, 0, 0, {4.4, 1.8, 1.5}},
                                       {10, {12.0, 1.05, 0}, 0, 0, 0, {4.4, 1.8, 1.5}}});
  const auto parts = frontend::splitAtNotch(pair, allOf(pair), p);
  ASSERT_TRUE(parts);
  for (const auto* part : {&parts->first, &parts->second}) {
    std::map<int, int> ids;
    for (int i : *part) ++ids[inst[i]];
    ASSERT_EQ(ids.size(), 1u) << "each part holds one car's points";
  }
  EXPECT_NE(inst[parts->first.front()], inst[parts->second.front()]);
  // One car: seen at its corner (an L, nearest in the middle), broadside, or end on.
  for (const double yaw : {0.6, M_PI / 2, 0.0}) {
    const auto [one, ids] = carPoints({{10, {12.0, 2.0, 0}, 0, 0, yaw, {4.4, 1.8, 1.5}}});
    EXPECT_FALSE(frontend::splitAtNotch(one, allOf(one), p)) << "yaw " << yaw;
  }
  frontend::NotchSplitParams off = p;
  off.depth = 0;
  EXPECT_FALSE(frontend::splitAtNotch(pair, allOf(pair), off));
}

// A car's side (x = 10, 4.4 m long, 1.4 m tall) over ground labelled road, and a strip of the
// ground in front of it (x 9.0 to 10) whose labels bled into "car", as a range-image network's
// boundary errors do: left in, the strip stretches the car's footprint 1 m towards the sensor.
TEST(LabelledSegmenter, GroundLabelledCarAtACarsFootIsLeftOut) {
  io::LabelledScan scan;
  auto point = [&](double x, double y, double z, std::uint16_t label) { addLabelledPoint(scan, x, y, z, label); };
  for (double y = -2.2; y <= 2.2 + 1e-9; y += 0.05) {
    for (double z = -0.9; z <= 0.4 + 1e-9; z += 0.1) point(10.0, y, z, 10);
    for (double x = 4.0; x < 10.0; x += 0.1) point(x, y, -1.0, x >= 9.0 ? 10 : 40);
  }
  point(3.0e6, -2.0e6, -1.0, 40);  // a stray far return labelled ground must not size the ground grid
  const ClassTable classes = ClassTable::loadDefault();
  frontend::LabelledSegmenterParams p = frontend::loadDefaultFrontendConfig().labelled;
  ASSERT_GT(p.cuboid_ground_strip, 0.0) << "on by default";
  frontend::InputIssues issues;
  auto nearest = [&](const frontend::LabelledSegmenterParams& params) {
    float x = 1e9f;
    for (const auto& inst : frontend::LabelledSegmenter(classes, params).segment(scan, issues))
      if (inst.class_id == 10)
        for (const auto& q : inst.points) x = std::min(x, q.x());
    return x;
  };
  EXPECT_NEAR(nearest(p), 10.0f, 1e-3f) << "the car's side alone";
  p.cuboid_ground_strip = 0;
  EXPECT_LT(nearest(p), 9.2f) << "the bled ground strip in the car";
}

// A car's side 10 m off (labelled car, y -2.2 to 2.2), the road in front of it and, 15-20 m off,
// beyond both of its ends (labelled road): with free_space on, the car carries the cells that
// lines of sight crossed in its body's height band (in front of it and past its ends), none
// within its body; the tracker then completes it and judges its motion from them.
TEST(LabelledSegmenter, ACarCarriesTheCellsSeenThroughNearItNoneInItsBody) {
  io::LabelledScan scan;
  auto point = [&](double x, double y, double z, std::uint16_t label) { addLabelledPoint(scan, x, y, z, label); };
  for (double y = -2.2; y <= 2.2 + 1e-9; y += 0.05)
    for (double z = -0.9; z <= 0.4 + 1e-9; z += 0.1) point(10.0, y, z, 10);
  for (double x = 4.0; x < 10.0; x += 0.1)
    for (double y = -2.2; y <= 2.2 + 1e-9; y += 0.1) point(x, y, -1.0, 40);
  for (double x = 15.0; x <= 20.0; x += 0.1)  // seen past the car's ends: |y| / x > 2.2 / 10
    for (double y = 0.25 * x; y <= 0.25 * x + 2.5; y += 0.05) point(x, y, -1.0, 40), point(x, -y, -1.0, 40);
  const ClassTable classes = ClassTable::loadDefault();
  frontend::LabelledSegmenterParams p = frontend::loadDefaultFrontendConfig().labelled;
  ASSERT_GT(p.free_space.cell, 0.0) << "on by default";
  for (double cell : {p.free_space.cell, 0.0}) {
    p.free_space.cell = cell;
    frontend::InputIssues issues;
    int cars = 0;
    for (const auto& inst : frontend::LabelledSegmenter(classes, p).segment(scan, issues)) {
      if (inst.class_id != 10) continue;
      ++cars;
      if (cell == 0) {
        EXPECT_TRUE(inst.free_space.empty());
        continue;
      }
      int in_body = 0, in_front = 0, past_ends = 0;
      for (const auto& q : inst.free_space) {
        in_body += q.x() > 10.1f && q.x() < 11.8f && std::abs(q.y()) < 2.0f;
        in_front += q.x() < 9.8f && std::abs(q.y()) < 2.0f;
        past_ends += q.x() > 10.5f && std::abs(q.y()) > 2.6f;
      }
      EXPECT_EQ(in_body, 0);
      EXPECT_GT(in_front, 10);
      EXPECT_GT(past_ends, 10);
    }
    EXPECT_EQ(cars, 1) << cell;
  }
}
