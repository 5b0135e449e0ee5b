#include "world_eval.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <set>
#include <opencv2/core.hpp>

#include "frontend/geometric_segmenter.h"
#include "assignment/hungarian.h"
#include "backend/data_association.h"
#include "objects/association.h"
#include "frontend/keypose.h"
#include "eval/label_iou.h"
#include "frontend/labelled_segmenter.h"
#include "frontend/range_net_labeler.h"
#include "frontend/rgbd_segmenter.h"
#include "simulator/lidar.h"
#include "simulator/ray_caster.h"
#include "simulator/rgbd_camera.h"
#include "simulator/dataset_writer.h"
#include "emulator/rgbd_emulator.h"
#include "simulator/scenario.h"
#include "simulator/semantic_labels.h"
#include "mapped_robot/sensor_rig.h"
#include "segment_diagnosis.h"

namespace slide {

namespace {
// Can `mode` produce objects of this class at all? (Only those classes are evaluated.)
bool producible(const std::string& mode, const ClassInfo& c, const frontend::FrontendConfig& cfg) {
  if (mode == "emulated" || mode == "oracle" || mode == "learned") return !c.semantickitti.empty();
  if (mode == "geometric")  // trunks and poles are scored apart: a trunk called a pole is wrong
    return c.id == cfg.geometric.car_class || c.id == cfg.geometric.trunk_class || c.id == cfg.geometric.pole_class ||
           (cfg.geometric.emit_other && c.id == cfg.geometric.other_class);
  return c.id != 0;  // rgbd: every detector class but the catch-all
}

// The class a real object of class c is scored as in `mode`, none when the mode cannot find it.
// The label-free mode names no furniture: a chair, table or monitor it finds is an ellipsoid of
// class "other", and is scored so (an "other" there is right; a car or trunk there is not).
std::optional<int> scoreGroup(const std::string& mode, const ClassInfo& c, const frontend::FrontendConfig& cfg) {
  if (producible(mode, c, cfg)) return c.id;
  if (mode == "geometric" && cfg.geometric.emit_other && c.shape == Shape::Ellipsoid) return cfg.geometric.other_class;
  return std::nullopt;
}

bool isRgbd(const std::string& mode) { return mode.rfind("rgbd", 0) == 0; }

// Point IoU accumulators of the emulated labels per class (tp, fp, fn).
using IouCounts = std::map<int, std::array<long, 3>>;
void countIou(const io::LabelledScan& truth, const io::LabelledScan& emulated, IouCounts& counts) {
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const int t = simulator::label::classIdOfLabel(truth.semantic[i]),
              e = simulator::label::classIdOfLabel(emulated.semantic[i]);
    if (t == e && t != 0) ++counts[t][0];
    if (t != e) {
      if (e != 0) ++counts[e][1];
      if (t != 0) ++counts[t][2];
    }
  }
}

frontend::RgbdFrame emulatedFrame(const simulator::RgbdImage& img, const simulator::CameraModel& camera,
                                  const emulator::RgbdEmulatorParams& p, uint64_t seed) {
  io::InstanceMask truth;
  truth.mask = img.instance;
  truth.class_id = img.instance_class;
  truth.object_id = img.instance_object;
  const emulator::EmulatedMasks e = emulator::emulateRgbdDetections(truth, img.depth, 0.001, p, seed);
  frontend::RgbdFrame f = mapped_robot::rgbdFrameOf(img, camera);
  f.mask.assign(e.masks.mask.begin<std::uint16_t>(), e.masks.mask.end<std::uint16_t>());
  f.instance_class = e.masks.class_id;
  f.instance_confidence = e.confidence;
  return f;
}

// What the map holds about one landmark beyond its current estimate.
struct LandmarkEvidence {
  std::map<int, double> votes;              // class -> confidence-weighted votes
  std::vector<Eigen::Vector3d> centres;     // every associated detection's centre
  int whole_views = 0;                      // detections with one reading
};

// The map a robot builds from its key-pose bundles: each bundle's objects, placed with the
// ground-truth key pose, are associated with the landmarks by the back-end's own rule
// (backend/data_association.h: class, centre distance, model difference and box footprints
// within the class table's thresholds, one detection per landmark). As in the back-end, a box
// read two ways counts as the reading its landmark agrees with once kWholeViewsToChooseReading
// whole views fixed that landmark. An associated landmark takes the newer model, centred on the
// per-axis median of all its detections' centres (the back-end fits a landmark to all its
// observations under a robust loss: one late, wrong view moves it little), and, as in the
// back-end, the class with the most confidence-weighted votes; an unassociated object becomes
// a new landmark. A box read two ways first takes the reading its map neighbours seen whole agree
// with, as in the back-end. No evaluator-side merging.
void addToMap(const KeyPoseBundle& bundle, const Pose& T_world_body, const ClassTable& classes, double vote_radius,
              std::vector<Object>& map, std::vector<LandmarkEvidence>& evidence) {
  std::vector<backend::Detection> detections;
  for (const auto& o : bundle.objects) {
    detections.push_back({transformObject(T_world_body, o)});
    // As the back-end (Optimizer::settleReading): a box read two ways takes the reading that the
    // landmarks of its class within vote_radius, each fixed by whole views, agree with more.
    Object& d = detections.back().object;
    if (vote_radius <= 0 || !d.other_reading || !std::holds_alternative<Cuboid>(d.model)) continue;
    std::vector<double> headings;
    for (std::size_t i = 0; i < map.size(); ++i)
      if (evidence[i].whole_views >= kWholeViewsToChooseReading && map[i].class_id == d.class_id &&
          std::holds_alternative<Cuboid>(map[i].model) &&
          (map[i].position() - d.position()).head<2>().norm() <= vote_radius)
        headings.push_back(headingOf(std::get<Cuboid>(map[i].model)));
    if (otherReadingAgreesMore(d, headings)) d = otherReadingOf(d);
  }
  std::vector<backend::LandmarkCandidate> candidates;
  for (std::size_t i = 0; i < map.size(); ++i)
    if ((map[i].position() - T_world_body.translation()).head<2>().norm() < 100.0)
      candidates.push_back({static_cast<int>(i), &map[i]});
  const std::vector<int> assoc = backend::associateDetections(detections, candidates, classes);
  for (std::size_t k = 0; k < detections.size(); ++k) {
    const std::size_t i = assoc[k] >= 0 ? static_cast<std::size_t>(assoc[k]) : map.size();
    // A box read two ways counts as the reading its landmark agrees with, as in the back-end.
    const Object o = i < map.size() && evidence[i].whole_views >= kWholeViewsToChooseReading
                         ? nearestReading(detections[k].object, map[i])
                         : detections[k].object;
    if (i == map.size()) map.emplace_back(), evidence.emplace_back();
    LandmarkEvidence& e = evidence[i];
    e.whole_views += !detections[k].object.other_reading;
    e.centres.push_back(o.position());
    Pose to_median = Pose::Identity();
    for (int a = 0; a < 3; ++a) {
      std::vector<double> v;
      for (const auto& c : e.centres) v.push_back(c[a]);
      std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
      to_median.translation()[a] = v[v.size() / 2] - o.position()[a];
    }
    map[i] = transformObject(to_median, o);
    e.votes[o.class_id] += std::clamp(o.confidence, 1e-3, 1.0);
    double most = -1;  // as the back-end: ties go to the lower class id
    for (const auto& [c, v] : e.votes)
      if (v > most) most = v, map[i].class_id = c;
  }
}

// Horizontal centre distances between estimates (rows) and real objects (columns).
Eigen::MatrixXd horizontalDistances(const std::vector<const Object*>& E, const std::vector<const Object*>& G) {
  Eigen::MatrixXd cost(E.size(), G.size());
  for (std::size_t i = 0; i < E.size(); ++i)
    for (std::size_t j = 0; j < G.size(); ++j) cost(i, j) = (E[i]->position() - G[j]->position()).head<2>().norm();
  return cost;
}

struct Runner {
  std::string mode;
  std::unique_ptr<frontend::LidarSegmenter> lidar;
  std::shared_ptr<const frontend::PointLabeler> labeler;  // learned mode: labels the points for `lidar`
  eval::LabelIou label_iou;                           // learned mode: its labels against the truth
  std::unique_ptr<frontend::KeyPoseBundler> bundler;
  std::vector<Object> landmarks;  // world frame: the map the back-end's association builds
  std::vector<LandmarkEvidence> evidence;  // per landmark
  ModeResult result;
  std::unique_ptr<SegmentDiagnosis> diagnosis;  // --diagnose, LiDAR modes
  std::map<std::int64_t, std::pair<int, int>> moving_tracks;  // --diagnose: track -> (class, hits) of tracks taken as moving
};
}  // namespace

WorldEvalResult evaluateWorld(const WorldEvalSpec& spec, const ClassTable& classes,
                              const frontend::FrontendConfig& cfg) {
  simulator::ScenarioSpec ss;
  ss.world = spec.world;
  ss.robots = 1;
  ss.seed = spec.seed;
  ss.aerial = spec.aerial;
  ss.distance = spec.distance;
  ss.rate = spec.rate;
  ss.data_dir = spec.data_dir;
  const simulator::Scenario sc = simulator::buildScenario(ss);
  const simulator::RobotRun& robot = sc.robots.at(0);
  const simulator::LidarModel lidar = simulator::lidarModel("os1-64");
  const simulator::CameraModel camera = simulator::cameraModel("d455");

  std::vector<Runner> runners;
  for (const auto& mode : spec.modes) {
    Runner r;
    r.mode = r.result.mode = mode;
    if (mode == "learned") r.labeler = frontend::RangeNetLabeler::fromParams(cfg.learned);
    if (mode == "emulated" || mode == "oracle" || mode == "learned")
      r.lidar = std::make_unique<frontend::LabelledSegmenter>(classes, cfg.labelled);
    else if (mode == "geometric") r.lidar = std::make_unique<frontend::GeometricSegmenter>(classes, cfg.geometric);
    else if (mode != "rgbd" && mode != "rgbd.oracle") throw std::invalid_argument("unknown mode '" + mode + "'");
    r.bundler =
        std::make_unique<frontend::KeyPoseBundler>(frontend::Tracker(classes, cfg.tracker, cfg.fit), cfg.keypose);
    runners.push_back(std::move(r));
  }
  bool any_moving = false;
  for (const auto& o : sc.world.objects) any_moving |= o.moving();
  bool need_lidar = false, need_rgbd = false, need_emulated = false;
  for (const auto& r : runners) (isRgbd(r.mode) ? need_rgbd : need_lidar) = true, need_emulated |= r.mode == "emulated";
  const uint64_t emulator_seed = spec.emulator.seed ^ (spec.seed * 0x9e3779b97f4a7c15ULL);
  IouCounts iou_counts;

  std::map<int, int> object_class;  // static objects, for --diagnose
  for (const auto& g : sc.world.objects)
    if (!g.moving()) object_class[static_cast<int>(g.object.id)] = g.object.class_id;
  if (spec.diagnose)
    for (auto& r : runners) {
      if (isRgbd(r.mode)) continue;
      std::map<int, int> scored_class;  // as the mode is scored: the label-free mode's furniture as "other"
      for (const auto& [id, c] : object_class) {
        const ClassInfo* info = classes.find(c);
        const std::optional<int> grp = info ? scoreGroup(r.mode, *info, cfg) : std::nullopt;
        scored_class[id] = grp.value_or(c);
      }
      r.diagnosis = std::make_unique<SegmentDiagnosis>(scored_class, spec.min_points, spec.max_range);
    }
  std::map<int, int> seen_lidar, seen_rgbd;
  struct RgbdTrace {
    int seen = 0, detectable = 0, detected = 0, confident = 0;  // detectable: at least the emulator's min_area_px
    double min_range = 1e9;
    int instance = 0, instance_class = 0, max_hits = 0, reported = 0, reported_other = 0;  // rgbd mode's pipeline
    bool moving = false, other_class_track = false;
  };
  std::map<int, RgbdTrace> rgbd_trace;  // --verbose: object id -> frames
  std::map<std::int64_t, int> max_points;  // object id -> frames with >= min_points
  std::unique_ptr<simulator::RayCaster> caster;
  const std::size_t n = robot.ground_truth.size();
  for (std::size_t k = 0; k < n; ++k) {
    const double t = robot.ground_truth.times[k];
    if (!caster || any_moving) caster = std::make_unique<simulator::RayCaster>(sc.world, t);
    const Pose& T_world_body = robot.ground_truth.poses[k];
    std::mt19937_64 rng = simulator::frameRng(spec.seed, 0, static_cast<int>(k));
    io::LabelledScan scan, unlabelled, emulated;
    frontend::RgbdFrame frame, emulated_frame;
    std::map<int, int> count;
    if (need_lidar) {
      scan = simulator::simulateLidarScan(*caster, T_world_body, lidar, rng);
      unlabelled.xyz = scan.xyz;
      unlabelled.intensity = scan.intensity;
      count.clear();
      for (std::size_t i = 0; i < scan.size(); ++i)
        if (scan.xyz[i].head<2>().norm() <= spec.max_range) ++count[scan.instance[i]];
      for (const auto& [id, c] : count) {
        if (id != 0 && c >= spec.min_points) ++seen_lidar[id];
        max_points[id] = std::max(max_points[id], c);
      }
      if (need_emulated) {
        emulated = emulator::emulateLidarLabels(scan, spec.emulator.lidar,
                                                emulator::detectionSeed(emulator_seed, 0, static_cast<int>(k)));
        countIou(scan, emulated, iou_counts);
      }
    }
    if (need_rgbd) {
      const simulator::RgbdImage img = simulator::renderRgbd(*caster, T_world_body, camera, rng);
      frame = mapped_robot::rgbdFrameOf(img, camera);
      emulated_frame = emulatedFrame(img, camera, spec.emulator.rgbd,
                                     emulator::detectionSeed(emulator_seed, 0, static_cast<int>(k)));
      // Seen: at least min_points pixels of the object with a depth reading (beyond the
      // camera's depth range an object is in the picture but not measurable).
      std::vector<int> pix(img.instance_object.size() + 1, 0);
      for (std::size_t i = 0; i < frame.mask.size(); ++i)
        if (const auto id = frame.mask[i]; id > 0 && id < pix.size() && frame.depth[i] > 0) ++pix[id];
      for (std::size_t i = 0; i < img.instance_object.size(); ++i)
        if (img.instance_object[i] > 0 && pix[i + 1] >= spec.min_points) ++seen_rgbd[img.instance_object[i]];
      // --verbose: per seen object, whether the emulated detector output a mask over most of it
      // (any class), with what confidence, and the object's distance.
      if (spec.verbose) {
        std::map<std::pair<int, int>, int> overlap;  // (truth id, emulated id) -> pixels
        for (std::size_t i = 0; i < frame.mask.size(); ++i)
          if (frame.mask[i] > 0 && emulated_frame.mask[i] > 0) ++overlap[{frame.mask[i], emulated_frame.mask[i]}];
        for (std::size_t i = 0; i < img.instance_object.size(); ++i) {
          if (img.instance_object[i] <= 0 || pix[i + 1] < spec.min_points) continue;
          RgbdTrace& tr = rgbd_trace[img.instance_object[i]];
          ++tr.seen;
          tr.detectable += pix[i + 1] >= spec.emulator.rgbd.min_area_px;
          const double range = (sc.world.objects.at(img.instance_object[i] - 1).object.position() - T_world_body.translation()).head<2>().norm();
          tr.min_range = std::min(tr.min_range, range);
          float best = -1;
          for (const auto& [ids, n] : overlap)
            if (ids.first == static_cast<int>(i + 1) && 2 * n >= pix[i + 1])
              best = std::max(best, emulated_frame.instance_confidence.at(ids.second - 1));
          if (best >= 0) ++tr.detected, tr.confident += best >= cfg.rgbd.min_confidence;
        }
      }
    }
    for (auto& r : runners) {
      frontend::InputIssues issues;
      const auto t0 = std::chrono::steady_clock::now();
      frontend::FrameInstances fi;
      fi.utime = static_cast<std::int64_t>(t * 1e6);
      fi.odom_pose = robot.odometry[k];
      if (r.mode == "rgbd") fi.instances = frontend::segmentRgbd(emulated_frame, classes, cfg.rgbd, issues);
      else if (r.mode == "rgbd.oracle") fi.instances = frontend::segmentRgbd(frame, classes, cfg.rgbd, issues);
      else if (r.labeler) {
        io::LabelledScan labelled = unlabelled;
        r.labeler->label(labelled);
        r.label_iou.add(scan.semantic, labelled.semantic);
        fi.instances = r.lidar->segment(labelled, issues);
      } else fi.instances = r.lidar->segment(r.mode == "oracle" ? scan : r.mode == "emulated" ? emulated : unlabelled, issues);
      if (r.diagnosis) r.diagnosis->addFrame(scan, fi.instances);
      const auto bundle = r.bundler->process(fi, issues);
      if (r.diagnosis)
        for (const auto& [id, t] : r.bundler->tracker().tracks())
          if (t.moving) r.moving_tracks[id] = {t.class_id, t.hits};
      if (spec.verbose && r.mode == "rgbd") {  // the pipeline's view of every seen object, this frame
        const Pose T_world_odom = T_world_body * robot.odometry[k].inverse();
        for (auto& [id, tr] : rgbd_trace) {
          const Object& g = sc.world.objects.at(id - 1).object;
          auto near = [&](const Eigen::Vector3d& p) { return (p - g.position()).head<2>().norm() < 0.5; };
          bool inst = false, inst_class = false;
          for (const auto& in : fi.instances)
            if (!in.points.empty() && near(T_world_body * frontend::centroidOf(in.points)))
              inst = true, inst_class |= in.class_id == g.class_id;
          tr.instance += inst, tr.instance_class += inst_class;
          for (const auto& [tid, t] : r.bundler->tracker().tracks())
            if (near(T_world_odom * t.last_centroid)) {
              tr.max_hits = std::max(tr.max_hits, t.hits);
              tr.moving |= t.moving;
              if (t.class_id != g.class_id) tr.other_class_track = true;
            }
          if (bundle)
            for (const auto& o : bundle->objects)
              if (near(T_world_body * o.position())) (o.class_id == g.class_id ? tr.reported : tr.reported_other)++;
        }
      }
      r.result.frame_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      r.result.issues += issues.total();
      if (bundle) {
        addToMap(*bundle, T_world_body, classes, spec.reading_vote_radius, r.landmarks, r.evidence);
        for (const Object& o : bundle->objects) {
          const Eigen::Vector3d p = T_world_body * o.position();
          const Object* best = nullptr;
          double best_d = 2.0;
          for (const auto& g : sc.world.objects)
            if (g.object.class_id == o.class_id && (g.object.position() - p).head<2>().norm() < best_d)
              best_d = (g.object.position() - p).head<2>().norm(), best = &g.object;
          const ClassInfo* info = classes.find(o.class_id);
          if (!best || !info) continue;
          const Eigen::Vector2d ray = (p - T_world_body.translation()).head<2>().normalized();
          r.result.along_ray[info->name].push_back((p - best->position()).head<2>().dot(ray));
          r.result.along_ray_range[info->name].push_back(o.position().head<2>().norm());
          r.result.centre_error[info->name].push_back(best_d);
        }
      }
    }
  }

  WorldEvalResult out;
  out.world = spec.world;
  out.frames = static_cast<int>(n);
  for (auto& r : runners) {
    if (r.diagnosis) {
      std::map<int, std::string> names;
      for (int id : classes.ids()) names[id] = classes.at(id).name;
      r.diagnosis->print(r.mode, names);
      std::map<int, std::pair<int, int>> moving;  // class -> tracks, hits
      for (const auto& [id, ch] : r.moving_tracks) ++moving[ch.first].first, moving[ch.first].second += ch.second;
      for (const auto& [c, th] : moving)
        std::printf("  diagnose %s: %d %s tracks taken as moving (%d observations)\n", r.mode.c_str(), th.first,
                    names[c].c_str(), th.second);
    }
    const auto& seen = isRgbd(r.mode) ? seen_rgbd : seen_lidar;
    std::map<int, std::vector<const Object*>> gt, est, unscored;  // by evaluation group
    for (const auto& g : sc.world.objects) {
      const ClassInfo* c = classes.find(g.object.class_id);
      const std::optional<int> grp = c ? scoreGroup(r.mode, *c, cfg) : std::nullopt;
      if (!grp || g.moving()) continue;
      const auto it = seen.find(static_cast<int>(g.object.id));
      const bool visible = it != seen.end() && it->second >= spec.min_frames;
      (visible ? gt : unscored)[*grp].push_back(&g.object);
      if (visible && *grp != c->id) ++r.result.scored_as[c->name + " as " + classes.at(*grp).name];
    }
    // The map: every landmark, none merged here. A landmark nearer to a real object below the
    // visibility criterion (too far, too few returns) than to any scored one, and within the
    // match distance of it, is neither credited nor penalised (counted as ignored).
    std::vector<Object> estimates;
    std::vector<int> detections;  // per estimate: the key-pose detections behind its landmark
    for (std::size_t l = 0; l < r.landmarks.size(); ++l) {
      const Object& o = r.landmarks[l];
      const ClassInfo* c = classes.find(o.class_id);
      if (!c || !producible(r.mode, *c, cfg)) continue;
      const int grp = o.class_id;
      auto nearest = [&](const std::vector<const Object*>& v) {
        double d = 1e18;
        for (const Object* g : v) d = std::min(d, (g->position() - o.position()).head<2>().norm());
        return d;
      };
      const double d_out = nearest(unscored[grp]);
      if (d_out <= spec.match_distance && d_out < nearest(gt[grp])) {
        ++r.result.ignored;
        continue;
      }
      estimates.push_back(o);
      detections.push_back(static_cast<int>(r.evidence[l].centres.size()));
    }
    for (const auto& o : estimates) est[o.class_id].push_back(&o);
    ModeResult& m = r.result;
    // The landmarks the back-end would publish, scored alone (no verbose listing).
    {
      std::map<int, std::vector<const Object*>> confirmed;
      for (std::size_t i = 0; i < estimates.size(); ++i)
        if (detections[i] >= spec.confirm_observations) confirmed[estimates[i].class_id].push_back(&estimates[i]);
      for (const auto& [g, E] : confirmed) {
        m.confirmed_estimated += static_cast<int>(E.size());
        const auto it = gt.find(g);
        if (it == gt.end() || it->second.empty()) continue;
        const auto& G = it->second;
        for (int a : assignment::solveGatedAssignment(horizontalDistances(E, G), spec.match_distance))
          m.confirmed_matched += a >= 0;
      }
    }
    // --verbose: the real object nearest to an estimate (any class), its distance in `d`.
    auto nearestTruth = [&](const Object& o, double& d) {
      const io::GroundTruthObject* near = nullptr;
      for (const auto& g : sc.world.objects) {
        const double dg = (g.object.position() - o.position()).head<2>().norm();
        if (dg < d) d = dg, near = &g;
      }
      return near;
    };
    std::set<int> groups;
    for (const auto& [g, v] : gt) groups.insert(g);
    for (const auto& [g, v] : est) groups.insert(g);
    for (int g : groups) {
      const auto& G = gt[g];
      const auto& E = est[g];
      const ClassInfo& info = classes.at(g);
      int matched = 0;
      if (!G.empty() && !E.empty()) {
        const Eigen::MatrixXd cost = horizontalDistances(E, G);
        const auto assign = assignment::solveGatedAssignment(cost, spec.match_distance);
        std::vector<char> hit(G.size(), 0);
        for (int a : assign)
          if (a >= 0) ++matched, hit[a] = 1;
        for (std::size_t i = 0; i < E.size(); ++i) {
          if (assign[i] >= 0) continue;
          bool dup = false;
          for (std::size_t j = 0; j < G.size(); ++j) dup |= hit[j] && cost(i, j) <= info.association_distance;
          ++(dup ? m.duplicates : m.false_objects);
        }
        if (spec.verbose)
          for (std::size_t i = 0; i < E.size(); ++i) {
            if (assign[i] >= 0) continue;
            double d = 1e9;
            const io::GroundTruthObject* near = nearestTruth(*E[i], d);
            const auto it = near ? seen.find(static_cast<int>(near->object.id)) : seen.end();
            std::printf("  extra %s %s at (%.1f, %.1f): nearest object %ld (class %d%s, seen in %d frames) at %.2f m\n",
                        r.mode.c_str(), info.name.c_str(), E[i]->position().x(), E[i]->position().y(),
                        near ? static_cast<long>(near->object.id) : -1L, near ? near->object.class_id : -1,
                        near && near->moving() ? ", moving" : "", it == seen.end() ? 0 : it->second, d);
            // Cuboids: this box and the estimates near the same object, against the true box.
            auto describe = [](const Object& o) {
              char buf[160];
              if (const auto* b = std::get_if<Cuboid>(&o.model))
                std::snprintf(buf, sizeof buf, "(%.1f, %.1f) yaw %.0f deg dims %.1f x %.1f, %d observations", o.position().x(),
                              o.position().y(), yawOf(b->pose.linear()) * 180 / M_PI, b->dims.x(), b->dims.y(), o.num_observations);
              else if (const auto* c = std::get_if<Cylinder>(&o.model))
                std::snprintf(buf, sizeof buf, "(%.2f, %.2f) radius %.2f, z %.1f to %.1f, %d observations", o.position().x(),
                              o.position().y(), c->radius, c->root.z(), c->root.z() + c->length, o.num_observations);
              else
                return std::string();
              return std::string(buf);
            };
            if (near && !std::holds_alternative<Ellipsoid>(E[i]->model)) {
              std::printf("    this estimate %s; truth %s\n", describe(*E[i]).c_str(), describe(near->object).c_str());
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
            const ClassInfo* truth_class = classes.find(G[j]->class_id);
            std::printf("  missed %s %s id %ld (a %s) at (%.1f, %.1f): seen in %d frames, max %d points, nearest estimate %.2f m\n",
                        r.mode.c_str(), info.name.c_str(), static_cast<long>(G[j]->id),
                        truth_class ? truth_class->name.c_str() : "?", G[j]->position().x(), G[j]->position().y(),
                        seen.at(static_cast<int>(G[j]->id)), max_points[G[j]->id], nearest);
            for (const auto* e : E)  // the estimates near it (matched to a neighbour, or too far off)
              if ((e->position() - G[j]->position()).head<2>().norm() < 4.0) {
                const auto* b = std::get_if<Cuboid>(&e->model);
                const auto* tb = std::get_if<Cuboid>(&G[j]->model);
                if (b && tb)
                  std::printf("    near estimate (%.1f, %.1f) yaw %.0f dims %.1f x %.1f, %d obs; truth yaw %.0f dims %.1f x %.1f\n",
                              e->position().x(), e->position().y(), yawOf(b->pose.linear()) * 180 / M_PI, b->dims.x(),
                              b->dims.y(), e->num_observations, yawOf(tb->pose.linear()) * 180 / M_PI, tb->dims.x(), tb->dims.y());
              }
            if (isRgbd(r.mode) && rgbd_trace.count(static_cast<int>(G[j]->id))) {
              const RgbdTrace& tr = rgbd_trace.at(static_cast<int>(G[j]->id));
              std::printf("    emulated detector: a mask over it in %d of %d frames (%d with >= %d pixels), %d of them with confidence >= %.2f; "
                          "nearest %.1f m; pipeline: instances near it in %d frames (%d of its class), tracks near it up to %d hits%s%s, "
                          "reported in %d key poses (%d as another class)\n", tr.detected, tr.seen, tr.detectable,
                          spec.emulator.rgbd.min_area_px, tr.confident,
                          cfg.rgbd.min_confidence, tr.min_range, tr.instance, tr.instance_class, tr.max_hits,
                          tr.moving ? ", one moving" : "", tr.other_class_track ? ", one of another class" : "", tr.reported,
                          tr.reported_other);
            }
          }
      } else {
        m.false_objects += static_cast<int>(E.size());
      }
      if (spec.verbose && (G.empty() || E.empty())) {
        for (const auto* g : G)
          std::printf("  missed %s %s id %ld: no estimate of the class\n", r.mode.c_str(), info.name.c_str(), static_cast<long>(g->id));
        for (const auto* e : E) {
          const auto* b = std::get_if<Cuboid>(&e->model);
          std::printf("  extra %s %s at (%.1f, %.1f): no ground truth of the class", r.mode.c_str(), info.name.c_str(),
                      e->position().x(), e->position().y());
          double d = 1e9;
          if (const io::GroundTruthObject* near = nearestTruth(*e, d))
            std::printf("; nearest object of any class: class %d at %.2f m (height %.1f, its %.1f)", near->object.class_id, d,
                        e->position().z(), near->object.position().z());
          if (const auto* el = std::get_if<Ellipsoid>(&e->model))
            std::printf("; ellipsoid radius %.2f height %.2f, %d observations", el->radius, el->height, e->num_observations);
          if (const auto* cy = std::get_if<Cylinder>(&e->model))
            std::printf("; cylinder radius %.2f, %d observations", cy->radius, e->num_observations);
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
    for (const std::string& g : r.labeler ? r.label_iou.groups() : std::vector<std::string>{})
      if (const auto v = r.label_iou.iou(g)) m.iou[g] = *v;
    if (r.mode == "emulated")
      for (const auto& [c, n] : iou_counts)
        if (const ClassInfo* info = classes.find(c); info && n[0] + n[2] > 0)  // classes the world holds
          m.iou[info->name] = double(n[0]) / double(n[0] + n[1] + n[2]);
    m.precision = m.estimated ? double(m.matched) / m.estimated : 0.0;
    m.recall = m.ground_truth ? double(m.matched) / m.ground_truth : 0.0;
    m.f1 = m.precision + m.recall > 0 ? 2 * m.precision * m.recall / (m.precision + m.recall) : 0.0;
    out.modes.push_back(std::move(m));
  }
  return out;
}

}  // namespace slide
