#include "pcl_reference.h"

#include <pcl/ModelCoefficients.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>
#include <pcl/segmentation/sac_segmentation.h>

#include "bench/stats.h"
#include "clock/thread_cpu.h"
#include "frontend/circle_fit.h"
#include "frontend/grid_clustering.h"
#include "frontend/ground_removal.h"
#include "frontend/xyz_cloud.h"
#include "io/kitti_scan.h"

namespace slide {

namespace {
template <typename F>
double medianMs(int runs, F&& f) {
  std::vector<double> ms;
  for (int r = 0; r < runs; ++r) {
    const double t0 = clock::threadCpuMs();
    f();
    ms.push_back(clock::threadCpuMs() - t0);
  }
  return bench::median(ms);
}

bool groundLabel(int l) { return l == 40 || l == 44 || l == 48 || l == 49 || l == 60 || l == 72; }
bool objectLabel(int l) { return l == 10 || l == 71 || l == 80 || l == 81; }
}  // namespace

PclComparison comparePcl(const std::string& kitti_bin, const std::string& tls_slice,
                         const frontend::FrontendConfig& cfg, int runs) {
  PclComparison r;
  const io::LabelledScan scan = io::readLabelledScan(kitti_bin);
  frontend::GroundParams gp = cfg.geometric.ground;
  gp.max_range = cfg.geometric.max_range;
  const double r2 = gp.max_range * gp.max_range;

  // Ground. Ours: height above the grid estimate <= threshold. PCL: inliers of one RANSAC plane
  // with the same threshold as distance, 200 iterations.
  std::vector<float> h;
  r.ours_ground_ms = medianMs(runs, [&] { h = frontend::heightAboveGround(scan.xyz, gp); });
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  std::vector<int> in_range;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const auto& p = scan.xyz[i];
    if (!p.allFinite() || double(p.x()) * p.x() + double(p.y()) * p.y() > r2) continue;
    cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
    in_range.push_back(static_cast<int>(i));
  }
  pcl::PointIndices plane;
  r.pcl_ground_ms = medianMs(runs, [&] {
    pcl::SACSegmentation<pcl::PointXYZ> seg;
    seg.setModelType(pcl::SACMODEL_PLANE);
    seg.setMethodType(pcl::SAC_RANSAC);
    seg.setDistanceThreshold(gp.threshold);
    seg.setMaxIterations(200);
    seg.setInputCloud(cloud);
    pcl::ModelCoefficients coeff;
    seg.segment(plane, coeff);
  });
  std::vector<char> pcl_ground(scan.size(), 0);
  for (int k : plane.indices) pcl_ground[in_range[k]] = 1;
  long ground = 0, objects = 0, ours_kept = 0, pcl_kept = 0, ours_lost = 0, pcl_lost = 0;
  for (int i : in_range) {
    const bool ours = std::isfinite(h[i]) && h[i] <= gp.threshold;
    if (groundLabel(scan.semantic[i])) ++ground, ours_kept += ours, pcl_kept += pcl_ground[i];
    if (objectLabel(scan.semantic[i])) ++objects, ours_lost += ours, pcl_lost += pcl_ground[i];
  }
  r.ours_ground_kept = double(ours_kept) / std::max(1L, ground);
  r.pcl_ground_kept = double(pcl_kept) / std::max(1L, ground);
  r.ours_object_lost = double(ours_lost) / std::max(1L, objects);
  r.pcl_object_lost = double(pcl_lost) / std::max(1L, objects);

  // Clustering of our above-ground points. Ours joins points whose 0.3 m voxels touch
  // (26-neighbourhood: gaps up to 0.3-1.04 m bridge, depending on where points fall); PCL's
  // joins points closer than a tolerance, here 0.5 m (between the two). Both keep >= 30 points.
  std::vector<int> above;
  for (int i : in_range)
    if (std::isfinite(h[i]) && h[i] > gp.threshold) above.push_back(i);
  pcl::PointCloud<pcl::PointXYZ>::Ptr above_cloud(new pcl::PointCloud<pcl::PointXYZ>);
  for (int i : above) above_cloud->push_back(pcl::PointXYZ(scan.xyz[i].x(), scan.xyz[i].y(), scan.xyz[i].z()));
  std::vector<std::vector<int>> ours;
  r.ours_cluster_ms = medianMs(runs, [&] { ours = frontend::clusterGrid(scan.xyz, above, {0.3, false, 30}); });
  std::vector<pcl::PointIndices> theirs;
  r.pcl_cluster_ms = medianMs(runs, [&] {
    theirs.clear();
    pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
    tree->setInputCloud(above_cloud);
    pcl::EuclideanClusterExtraction<pcl::PointXYZ> ec;
    ec.setClusterTolerance(0.5);
    ec.setMinClusterSize(30);
    ec.setSearchMethod(tree);
    ec.setInputCloud(above_cloud);
    ec.extract(theirs);
  });
  r.ours_clusters = static_cast<int>(ours.size());
  r.pcl_clusters = static_cast<int>(theirs.size());

  // Circle on the TLS slice (trunk plus a branch), same inlier distance and iterations.
  const frontend::Cloud slice = frontend::readXyzCloud(tls_slice);
  std::vector<Eigen::Vector2d> xy;
  pcl::PointCloud<pcl::PointXYZ>::Ptr slice_cloud(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : slice) {
    xy.emplace_back(p.x(), p.y());
    slice_cloud->push_back(pcl::PointXYZ(p.x(), p.y(), 0.0f));
  }
  const frontend::CircleRansacParams& cp = cfg.fit.cylinder.ransac;
  std::optional<frontend::Circle> c;
  r.ours_circle_ms = medianMs(runs, [&] { c = frontend::fitCircleRansac(xy, cp); });
  r.ours_radius = c ? c->radius : std::nan("");
  pcl::ModelCoefficients coeff;
  r.pcl_circle_ms = medianMs(runs, [&] {
    pcl::SACSegmentation<pcl::PointXYZ> seg;
    seg.setModelType(pcl::SACMODEL_CIRCLE2D);
    seg.setMethodType(pcl::SAC_RANSAC);
    seg.setDistanceThreshold(cp.inlier_distance);
    seg.setMaxIterations(cp.iterations);
    seg.setRadiusLimits(cp.min_radius, cp.max_radius);
    seg.setOptimizeCoefficients(true);
    seg.setInputCloud(slice_cloud);
    pcl::PointIndices inliers;
    seg.segment(inliers, coeff);
  });
  r.pcl_radius = coeff.values.size() >= 3 ? coeff.values[2] : std::nan("");
  return r;
}

}  // namespace slide
