#include "real_data.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <algorithm>

#include "clock/thread_cpu.h"
#include "eval/labelled_scan_score.h"
#include "eval/reference_circle.h"
#include "frontend/circle_fit.h"
#include "frontend/geometric_segmenter.h"
#include "frontend/grid_clustering.h"
#include "frontend/xyz_cloud.h"
#include "io/kitti_scan.h"

namespace slide {

TlsResult evaluateTls(const std::string& data_dir, const ClassTable& classes, const frontend::FrontendConfig& cfg) {
  TlsResult r;
  const frontend::Cloud slice = frontend::readXyzCloud(data_dir + "/tls/dbh_slice.xyz");
  std::vector<Eigen::Vector2d> xy;
  for (const auto& p : slice) xy.emplace_back(p.x(), p.y());
  const auto lsq = frontend::fitCircleAlgebraic(xy);
  if (!lsq) throw std::runtime_error("dbh_slice.xyz: algebraic circle fit failed");
  r.algebraic_radius = lsq->radius;

  // The slice seen from far outside (a TLS scanner sees the whole trunk from several stations).
  const Eigen::Vector3d view = frontend::centroidOf(slice) + Eigen::Vector3d(50, 0, 0);
  const auto cyl = frontend::fitCylinder(slice, cfg.fit.cylinder, view);
  r.fitted_radius = cyl ? cyl->radius : std::nan("");
  // Reference on the trunk's bark, independent of the fit scored (eval/reference_circle.h): the
  // slice also holds a branch, which pulls an all-points least-squares circle off the trunk.
  r.trunk_radius = std::nan("");
  if (const auto ref = eval::referenceCircle(xy)) r.trunk_radius = ref->radius, r.trunk_points = ref->inliers;

  io::LabelledScan plot;
  plot.xyz = frontend::readXyzCloud(data_dir + "/tls/pine_plot.xyz");
  frontend::GeometricSegmenterParams gp = cfg.geometric;
  gp.emit_other = false;
  const frontend::GeometricSegmenter seg(classes, gp);
  frontend::InputIssues issues;
  const Eigen::Vector3d plot_view = frontend::centroidOf(plot.xyz);
  for (const auto& inst : seg.segment(plot, issues)) {
    if (classes.at(inst.class_id).shape != Shape::Cylinder) continue;
    const auto c = frontend::fitCylinder(inst.points, cfg.fit.cylinder, plot_view);
    if (!c) continue;
    ++r.pine_trunks;
    r.pine_radii.push_back(c->radius);
    r.pine_positions.push_back(c->root.head<2>());
  }
  return r;
}

KittiScanResult evaluateKittiScan(const std::string& bin_path, const frontend::LidarSegmenter& segmenter,
                                  const ClassTable& classes, const frontend::FrontendConfig& cfg, int runs) {
  const io::LabelledScan scan = io::readLabelledScan(bin_path);
  KittiScanResult r;
  r.scan = bin_path.substr(bin_path.find_last_of('/') + 1);
  r.mode = segmenter.name();
  std::vector<Object> objects;
  for (int run = 0; run < runs; ++run) {
    frontend::InputIssues issues;
    const double c0 = clock::threadCpuMs();
    const auto t0 = std::chrono::steady_clock::now();
    const auto instances = segmenter.segment(scan, issues);
    std::vector<Object> fitted;
    for (const auto& inst : instances)
      if (auto o = frontend::fitObject(inst.points, inst.class_id, classes, cfg.fit, Eigen::Vector3d::Zero(), nullptr,
                                       nullptr, &inst.free_space))
        fitted.push_back(*o);
    r.segment_fit_wall_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    r.segment_fit_ms.push_back(clock::threadCpuMs() - c0);
    objects = std::move(fitted);
  }
  r.score = eval::scoreScanAgainstLabels(scan, objects, classes);
  for (const auto& t : r.score.targets) {
    KittiTarget k;
    k.class_id = t.class_id;
    k.instance = t.instance;
    k.points = t.points;
    k.centroid = t.centroid;
    k.found = t.estimate >= 0;
    if (k.found) {
      const Eigen::Vector3d e = objects[t.estimate].extent();
      char buf[128];
      std::snprintf(buf, sizeof buf, "%s %.2fx%.2fx%.2f at %.1f m", shapeName(objects[t.estimate].shape()), e.x(), e.y(),
                    e.z(), t.distance);
      k.fitted = buf;
    }
    r.targets.push_back(k);
  }
  for (std::size_t k = 0; k < objects.size(); ++k) {
    const Shape s = objects[k].shape();
    r.cuboids += s == Shape::Cuboid;
    r.cylinders += s == Shape::Cylinder;
    r.ellipsoids += s == Shape::Ellipsoid;
    if (s != Shape::Ellipsoid && r.score.verdicts[k] != eval::EstimateVerdict::Matched) {
      const Eigen::Vector3d p = objects[k].position(), e = objects[k].extent();
      char buf[160];
      std::snprintf(buf, sizeof buf, "%s %s at (%.1f %.1f %.1f) %.2fx%.2fx%.2f", eval::verdictName(r.score.verdicts[k]),
                    shapeName(s), p.x(), p.y(), p.z(), e.x(), e.y(), e.z());
      r.unmatched.push_back(buf);
    }
  }
  return r;
}

std::vector<double> evaluateLearnedLabels(const std::string& bin_path, const frontend::PointLabeler& labeler, int runs,
                                          eval::LabelIou& iou) {
  const io::LabelledScan truth = io::readLabelledScan(bin_path);
  if (!truth.hasLabels()) throw std::runtime_error(bin_path + ": no labels beside the scan");
  io::LabelledScan scan;
  scan.xyz = truth.xyz;
  scan.intensity = truth.intensity;
  std::vector<double> ms;
  for (int run = 0; run < runs; ++run) {
    io::LabelledScan s = scan;
    const double c0 = clock::threadCpuMs();
    labeler.label(s);
    ms.push_back(clock::threadCpuMs() - c0);
    if (run + 1 == runs) iou.add(truth.semantic, s.semantic);
  }
  return ms;
}

}  // namespace slide
