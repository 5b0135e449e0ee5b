#include "world_eval.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <set>
#include <opencv2/core.hpp>

#include "frontend/geometric_segmenter.h"
#include "assignment/hungarian.h"
#include "frontend/keypose.h"
#include "frontend/labelled_segmenter.h"
#include "frontend/rgbd_segmenter.h"
#include "sim/lidar.h"
#include "sim/ray_caster.h"
#include "sim/rgbd_camera.h"
#include "sim/dataset_writer.h"
#include "sim/scenario.h"
#include "simmap/sensor_rig.h"

namespace slide {

namespace {
// Can `mode` produce objects of this class at all? (Only those classes are evaluated.)
bool producible(const std::string& mode, const ClassInfo& c, const FrontendConfig& cfg) {
  if (mode == "labelled") return !c.semantickitti.empty();
  if (mode == "geometric")
    return c.id == cfg.geometric.car_class || c.id == cfg.geometric.trunk_class || c.id == cfg.geometric.pole_class;
  return c.id != 0;  // rgbd: every detector class but the catch-all
}

// Evaluation group of a class: the geometric mode cannot tell trunks from poles reliably, so
// there both count as one "cylinder" group.
int groupOf(const std::string& mode, int class_id, const FrontendConfig& cfg) {
  if (mode == "geometric" && class_id == cfg.geometric.pole_class) return cfg.geometric.trunk_class;
  return class_id;
}

bool insideFootprint(const Object& box, const Eigen::Vector3d& p) {
  const Cuboid& c = std::get<Cuboid>(box.model);
  const Eigen::Vector3d q = c.pose.inverse() * p;
  return std::abs(q.x()) <= c.dims.x() / 2 && std::abs(q.y()) <= c.dims.y() / 2;
}

struct Runner {
  std::string mode;
  std::unique_ptr<LidarSegmenter> lidar;
  std::unique_ptr<KeyposeBundler> bundler;
  std::map<std::int64_t, Object> latest;  // world frame, by track id
  ModeResult result;
};
}  // namespace

WorldEvalResult evaluateWorld(const WorldEvalSpec& spec, const ClassTable& classes, const FrontendConfig& cfg) {
  ScenarioSpec ss;
  ss.world = spec.world;
  ss.robots = 1;
  ss.seed = spec.seed;
  ss.distance = spec.distance;
  ss.rate = spec.rate;
  ss.data_dir = spec.data_dir;
  ss.forest = spec.forest;
  const Scenario sc = buildScenario(ss);
  const RobotRun& robot = sc.robots.at(0);
  const LidarModel lidar = lidarModel("os1-64");
  const CameraModel camera = cameraModel("d455");

  std::vector<Runner> runners;
  for (const auto& mode : spec.modes) {
    Runner r;
    r.mode = r.result.mode = mode;
    if (mode == "labelled") r.lidar = std::make_unique<LabelledSegmenter>(classes, cfg.labelled);
    else if (mode == "geometric") r.lidar = std::make_unique<GeometricSegmenter>(classes, cfg.geometric);
    else if (mode != "rgbd") throw std::invalid_argument("unknown mode '" + mode + "'");
    r.bundler = std::make_unique<KeyposeBundler>(Tracker(classes, cfg.tracker, cfg.fit), cfg.keypose);
    runners.push_back(std::move(r));
  }
  bool any_moving = false;
  for (const auto& o : sc.world.objects) any_moving |= o.moving();
  bool need_lidar = false, need_rgbd = false;
  for (const auto& r : runners) (r.mode == "rgbd" ? need_rgbd : need_lidar) = true;

  std::map<int, int> seen_lidar, seen_rgbd;
  std::map<std::int64_t, int> max_points;  // object id -> frames with >= min_points
  std::unique_ptr<RayCaster> caster;
  const std::size_t n = robot.ground_truth.size();
  for (std::size_t k = 0; k < n; ++k) {
    const double t = robot.ground_truth.times[k];
    if (!caster || any_moving) caster = std::make_unique<RayCaster>(sc.world, t);
    const Pose& T_world_body = robot.ground_truth.poses[k];
    std::mt19937_64 rng = frameRng(spec.seed, 0, static_cast<int>(k));
    LabelledScan scan, unlabelled;
    RgbdFrame frame;
    std::map<int, int> count;
    if (need_lidar) {
      scan = simulateLidarScan(*caster, T_world_body, lidar, rng);
      unlabelled.xyz = scan.xyz;
      unlabelled.intensity = scan.intensity;
      count.clear();
      for (auto id : scan.instance) ++count[id];
      for (const auto& [id, c] : count) {
        if (id != 0 && c >= spec.min_points) ++seen_lidar[id];
        max_points[id] = std::max(max_points[id], c);
      }
    }
    if (need_rgbd) {
      const RgbdImage img = renderRgbd(*caster, T_world_body, camera, rng);
      frame = rgbdFrameOf(img, camera);
      std::vector<int> pix(img.instance_object.size() + 1, 0);
      for (auto id : frame.mask)
        if (id > 0 && id < pix.size()) ++pix[id];
      for (std::size_t i = 0; i < img.instance_object.size(); ++i)
        if (img.instance_object[i] > 0 && pix[i + 1] >= spec.min_points) ++seen_rgbd[img.instance_object[i]];
    }
    for (auto& r : runners) {
      InputIssues issues;
      const auto t0 = std::chrono::steady_clock::now();
      FrameInstances fi;
      fi.utime = static_cast<std::int64_t>(t * 1e6);
      fi.odom_pose = robot.odometry[k];
      if (r.mode == "rgbd") fi.instances = segmentRgbd(frame, classes, cfg.rgbd, issues);
      else fi.instances = r.lidar->segment(r.mode == "labelled" ? scan : unlabelled, issues);
      const auto bundle = r.bundler->process(fi, issues);
      r.result.frame_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      r.result.issues += issues.total();
      if (bundle)
        for (const auto& o : bundle->objects) r.latest[o.id] = transformObject(T_world_body, o);
    }
  }

  WorldEvalResult out;
  out.world = spec.world;
  out.frames = static_cast<int>(n);
  for (auto& r : runners) {
    const auto& seen = r.mode == "rgbd" ? seen_rgbd : seen_lidar;
    std::map<int, std::vector<const Object*>> gt, est;  // by evaluation group
    for (const auto& g : sc.world.objects) {
      const ClassInfo* c = classes.find(g.object.class_id);
      if (!c || g.moving() || !producible(r.mode, *c, cfg)) continue;
      const auto it = seen.find(static_cast<int>(g.object.id));
      if (it == seen.end() || it->second < spec.min_frames) continue;
      gt[groupOf(r.mode, c->id, cfg)].push_back(&g.object);
    }
    // The map: estimates of one group that are the same landmark (what the back-end's data
    // association does with re-created tracks) are kept once: cuboids whose centre lies in
    // the other's footprint, other shapes closer than half the class's association distance.
    // Best-observed estimates first: they survive as the landmark.
    std::vector<Object> ordered;
    for (const auto& [id, o] : r.latest) ordered.push_back(o);
    std::stable_sort(ordered.begin(), ordered.end(),
                     [](const Object& a, const Object& b) { return a.num_observations > b.num_observations; });
    // The label-free mode is scored on its raw estimates: every re-created track counts.
    const bool merge = r.mode != "geometric";
    std::vector<Object> merged;
    for (const auto& o : ordered) {
      const ClassInfo* c = classes.find(o.class_id);
      if (!c || !producible(r.mode, *c, cfg)) continue;
      bool dup = false;
      if (merge)
      for (const auto& m : merged)
        dup |= groupOf(r.mode, m.class_id, cfg) == groupOf(r.mode, o.class_id, cfg) &&
               ((m.position() - o.position()).head<2>().norm() < 0.5 * c->association_distance ||
                (o.shape() == Shape::Cuboid && m.shape() == Shape::Cuboid &&
                 (insideFootprint(m, o.position()) || insideFootprint(o, m.position()))));
      if (!dup) merged.push_back(o);
    }
    for (const auto& o : merged) est[groupOf(r.mode, o.class_id, cfg)].push_back(&o);
    ModeResult& m = r.result;
    std::set<int> groups;
    for (const auto& [g, v] : gt) groups.insert(g);
    for (const auto& [g, v] : est) groups.insert(g);
    for (int g : groups) {
      const auto& G = gt[g];
      const auto& E = est[g];
      const ClassInfo& info = classes.at(g);
      int matched = 0;
      if (!G.empty() && !E.empty()) {
        Eigen::MatrixXd cost(E.size(), G.size());
        for (std::size_t i = 0; i < E.size(); ++i)
          for (std::size_t j = 0; j < G.size(); ++j)
            cost(i, j) = (E[i]->position() - G[j]->position()).head<2>().norm();
        const auto assign = solveGatedAssignment(cost, info.association_distance);
        std::vector<char> hit(G.size(), 0);
        for (int a : assign)
          if (a >= 0) ++matched, hit[a] = 1;
        // Unmatched estimates within the association distance of a ground-truth object are
        // duplicates (a second track of a mapped object, or a track off its object).
        for (std::size_t i = 0; i < E.size(); ++i) {
          if (assign[i] >= 0) continue;
          bool near = false;
          for (const auto* g : G) near |= (E[i]->position() - g->position()).head<2>().norm() < info.association_distance;
          ++(near ? m.duplicates : m.false_objects);
        }
        if (spec.verbose)
          for (std::size_t i = 0; i < E.size(); ++i) {
            if (assign[i] >= 0) continue;
            const GroundTruthObject* near = nullptr;
            double d = 1e9;
            for (const auto& g : sc.world.objects) {
              const double dg = (g.object.position() - E[i]->position()).head<2>().norm();
              if (dg < d) d = dg, near = &g;
            }
            const auto it = near ? seen.find(static_cast<int>(near->object.id)) : seen.end();
            std::printf("  extra %s %s at (%.1f, %.1f): nearest object %ld (class %d%s, seen in %d frames) at %.2f m\n",
                        r.mode.c_str(), info.name.c_str(), E[i]->position().x(), E[i]->position().y(),
                        near ? static_cast<long>(near->object.id) : -1L, near ? near->object.class_id : -1,
                        near && near->moving() ? ", moving" : "", it == seen.end() ? 0 : it->second, d);
            // Cuboids: this box and the estimates near the same object, against the true box.
            auto describe = [](const Object& o) {
              char buf[160];
              const auto* b = std::get_if<Cuboid>(&o.model);
              if (!b) return std::string();
              std::snprintf(buf, sizeof buf, "(%.1f, %.1f) yaw %.0f deg dims %.1f x %.1f, %d observations", o.position().x(),
                            o.position().y(), yawOf(b->pose.linear()) * 180 / M_PI, b->dims.x(), b->dims.y(), o.num_observations);
              return std::string(buf);
            };
            if (near && std::holds_alternative<Cuboid>(E[i]->model)) {
              std::printf("    this box %s; true box %s\n", describe(*E[i]).c_str(), describe(near->object).c_str());
              for (std::size_t j = 0; j < E.size(); ++j)
                if (j != i && (E[j]->position() - near->object.position()).head<2>().norm() < 4.0)
                  std::printf("    other estimate %s\n", describe(*E[j]).c_str());
            }
          }
        if (spec.verbose)
          for (std::size_t j = 0; j < G.size(); ++j) {
            if (hit[j]) continue;
            double nearest = 1e9;
            for (const auto* e : E) nearest = std::min(nearest, (e->position() - G[j]->position()).head<2>().norm());
            std::printf("  missed %s %s id %ld at (%.1f, %.1f): seen in %d frames, max %d points, nearest estimate %.2f m\n",
                        r.mode.c_str(), info.name.c_str(), static_cast<long>(G[j]->id), G[j]->position().x(),
                        G[j]->position().y(), seen.at(static_cast<int>(G[j]->id)), max_points[G[j]->id], nearest);
          }
      } else {
        m.false_objects += static_cast<int>(E.size());
      }
      if ((G.empty() || E.empty()) && spec.verbose) {
        for (const auto* g : G)
          std::printf("  missed %s %s id %ld: no estimate of the class\n", r.mode.c_str(), info.name.c_str(), static_cast<long>(g->id));
        for (const auto* e : E) {
          const auto* b = std::get_if<Cuboid>(&e->model);
          std::printf("  extra %s %s at (%.1f, %.1f): no ground truth of the class", r.mode.c_str(), info.name.c_str(),
                      e->position().x(), e->position().y());
          if (b) std::printf("; box yaw %.0f deg dims %.1f x %.1f x %.1f, %d observations", yawOf(b->pose.linear()) * 180 / M_PI,
                             b->dims.x(), b->dims.y(), b->dims.z(), e->num_observations);
          std::printf("\n");
        }
      }
      auto& pc = m.per_class[info.name];
      pc = {static_cast<int>(E.size()), static_cast<int>(G.size()), matched};
      m.estimated += static_cast<int>(E.size());
      m.ground_truth += static_cast<int>(G.size());
      m.matched += matched;
    }
    m.precision = m.estimated ? double(m.matched) / m.estimated : 0.0;
    m.recall = m.ground_truth ? double(m.matched) / m.ground_truth : 0.0;
    m.f1 = m.precision + m.recall > 0 ? 2 * m.precision * m.recall / (m.precision + m.recall) : 0.0;
    out.modes.push_back(std::move(m));
  }
  return out;
}

}  // namespace slide
