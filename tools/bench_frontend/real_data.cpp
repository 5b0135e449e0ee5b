#include "real_data.h"

#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <map>
#include <algorithm>

#include "frontend/circle_fit.h"
#include "frontend/geometric_segmenter.h"
#include "frontend/grid_clustering.h"
#include "frontend/xyz_cloud.h"
#include "io/kitti_scan.h"

namespace slide {

TlsResult evaluateTls(const std::string& data_dir, const ClassTable& classes, const FrontendConfig& cfg) {
  TlsResult r;
  const Cloud slice = readXyzCloud(data_dir + "/tls/dbh_slice.xyz");
  std::vector<Eigen::Vector2d> xy;
  for (const auto& p : slice) xy.emplace_back(p.x(), p.y());
  const auto lsq = fitCircleAlgebraic(xy);
  if (!lsq) throw std::runtime_error("dbh_slice.xyz: algebraic circle fit failed");
  r.algebraic_radius = lsq->radius;

  // The slice seen from far outside (a TLS scanner sees the whole trunk from several stations).
  const Eigen::Vector3d view = centroidOf(slice) + Eigen::Vector3d(50, 0, 0);
  const auto cyl = fitCylinder(slice, cfg.fit.cylinder, view);
  r.fitted_radius = cyl ? cyl->radius : std::nan("");
  // Reference on the trunk's bark: algebraic LS of the points within 5 cm of the fitted circle
  // (a trimmed LS from all points does not converge to the trunk: the branch dominates).
  r.trunk_radius = std::nan("");
  if (cyl) {
    std::vector<Eigen::Vector2d> bark;
    for (const auto& q : xy)
      if (std::abs((q - cyl->root.head<2>()).norm() - cyl->radius) <= 0.05) bark.push_back(q);
    r.trunk_points = static_cast<int>(bark.size());
    if (const auto c = fitCircleAlgebraic(bark)) r.trunk_radius = c->radius;
  }

  LabelledScan plot;
  plot.xyz = readXyzCloud(data_dir + "/tls/pine_plot.xyz");
  GeometricSegmenterParams gp = cfg.geometric;
  gp.emit_other = false;
  const GeometricSegmenter seg(classes, gp);
  InputIssues issues;
  const Eigen::Vector3d plot_view = centroidOf(plot.xyz);
  for (const auto& inst : seg.segment(plot, issues)) {
    if (classes.at(inst.class_id).shape != Shape::Cylinder) continue;
    const auto c = fitCylinder(inst.points, cfg.fit.cylinder, plot_view);
    if (!c) continue;
    ++r.pine_trunks;
    r.pine_radii.push_back(c->radius);
    r.pine_positions.push_back(c->root.head<2>());
  }
  return r;
}

namespace {
// CPU time of the calling thread: one core's work, unaffected by other processes on the machine.
double threadCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

std::vector<KittiTarget> kittiTargets(const LabelledScan& scan, const ClassTable& classes) {
  std::vector<KittiTarget> out;
  std::map<int, std::vector<int>> cars;                // instance -> points
  std::map<int, std::vector<int>> columns;             // class -> points (no instance ids)
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const auto cls = classes.fromSemanticKitti(scan.semantic[i]);
    if (!cls || !scan.xyz[i].allFinite()) continue;
    if (classes.at(*cls).shape == Shape::Cuboid) cars[scan.instance[i]].push_back(static_cast<int>(i));
    else if (classes.at(*cls).shape == Shape::Cylinder) columns[*cls].push_back(static_cast<int>(i));
  }
  auto add = [&](int class_id, int instance, const std::vector<int>& idx) {
    KittiTarget t;
    t.class_id = class_id;
    t.instance = instance;
    t.points = static_cast<int>(idx.size());
    for (int i : idx) t.centroid += scan.xyz[i].cast<double>();
    t.centroid /= idx.size();
    out.push_back(t);
  };
  for (const auto& [inst, idx] : cars)
    if (idx.size() >= 200) add(10, inst, idx);
  for (const auto& [cls, idx] : columns)
    for (const auto& cl : clusterGrid(scan.xyz, idx, {0.3, false, 30})) add(cls, 0, cl);
  return out;
}
}  // namespace

KittiScanResult evaluateKittiScan(const std::string& bin_path, const LidarSegmenter& segmenter,
                                  const ClassTable& classes, const FrontendConfig& cfg, int runs) {
  const LabelledScan scan = readLabelledScan(bin_path);
  KittiScanResult r;
  r.scan = bin_path.substr(bin_path.find_last_of('/') + 1);
  r.mode = segmenter.name();
  r.targets = kittiTargets(scan, classes);
  std::vector<Object> objects;
  for (int run = 0; run < runs; ++run) {
    InputIssues issues;
    const double c0 = threadCpuMs();
    const auto t0 = std::chrono::steady_clock::now();
    const auto instances = segmenter.segment(scan, issues);
    std::vector<Object> fitted;
    for (const auto& inst : instances)
      if (auto o = fitObject(inst.points, inst.class_id, classes, cfg.fit, Eigen::Vector3d::Zero())) fitted.push_back(*o);
    r.segment_fit_wall_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    r.segment_fit_ms.push_back(threadCpuMs() - c0);
    objects = std::move(fitted);
  }
  std::vector<char> used(objects.size(), 0);
  for (auto& t : r.targets) {
    const Shape want = classes.at(t.class_id).shape;
    double best = want == Shape::Cuboid ? 2.0 : 1.0;
    int best_k = -1;
    for (std::size_t k = 0; k < objects.size(); ++k) {
      if (used[k] || objects[k].shape() != want) continue;
      const double d = (objects[k].position() - t.centroid).head<2>().norm();
      if (d < best) best = d, best_k = static_cast<int>(k);
    }
    if (best_k < 0) continue;
    t.found = true;
    used[best_k] = 1;
    const Eigen::Vector3d e = objects[best_k].extent();
    char buf[128];
    std::snprintf(buf, sizeof buf, "%s %.2fx%.2fx%.2f at %.1f m", shapeName(objects[best_k].shape()), e.x(), e.y(), e.z(), best);
    t.fitted = buf;
  }
  for (std::size_t k = 0; k < objects.size(); ++k) {
    const Shape s = objects[k].shape();
    r.cuboids += s == Shape::Cuboid;
    r.cylinders += s == Shape::Cylinder;
    r.ellipsoids += s == Shape::Ellipsoid;
    if (!used[k]) {
      r.unmatched_cuboids += s == Shape::Cuboid;
      r.unmatched_cylinders += s == Shape::Cylinder;
    }
  }
  return r;
}

}  // namespace slide
