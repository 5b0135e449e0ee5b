#include "eval/transform_error.h"
#include "scenarios.h"

#include <cmath>
#include <map>

#include "io/object_map_text.h"

namespace slide::bench_place {

namespace {
bool inBox(const place::Landmark& l, double x0, double y0, double x1, double y1) {
  return l.p.x() >= x0 && l.p.x() < x1 && l.p.y() >= y0 && l.p.y() < y1;
}

std::vector<place::Landmark> readReal(const std::string& data_dir, const std::string& set, int robot) {
  static const ClassTable classes = ClassTable::loadDefault();
  const std::string path = data_dir + "/slideslam_maps/" + set + "/robot" + std::to_string(robot) + ".txt";
  return place::landmarksOf(io::readObjectMapText(path, classes, io::MissingSize::Zero).map);
}
}  // namespace

Scenario indoorScenario(unsigned seed) {
  Scenario s{"indoor", {}, "4x2 offices of 8x8 m, A sees rooms x<28 m, B rooms x>8 m; noise 5 cm, 10% missed"};
  for (int k = 0; k < 5; ++k) {
    std::mt19937 rng(seed + k);
    const World w = indoorWorld(4, 2, rng);
    const place::PerturbParams p{0.05, 0.05, 0.1};
    PairCase c;
    c.a = observe(w, [](const place::Landmark& l) { return l.p.x() < 28; }, randomFrame({10, 8}, 10, rng), p, rng);
    c.b = observe(w, [](const place::Landmark& l) { return l.p.x() > 8; }, randomFrame({25, 8}, 10, rng), p, rng);
    s.pairs.push_back(c);
  }
  return s;
}

Scenario urbanScenario(unsigned seed) {
  Scenario s{"urban", {}, "streets on a 60 m grid over 300x300 m, A sees x,y<200, B x,y>100; noise 10 cm, 10% missed"};
  for (int k = 0; k < 5; ++k) {
    std::mt19937 rng(seed + k);
    const World w = urbanWorld(300, rng);
    const place::PerturbParams p{0.1, 0.1, 0.1};
    PairCase c;
    c.a = observe(
        w, [](const place::Landmark& l) { return inBox(l, 0, 0, 200, 200); }, randomFrame({100, 100}, 50, rng), p, rng);
    c.b = observe(
        w, [](const place::Landmark& l) { return inBox(l, 100, 100, 300, 300); }, randomFrame({200, 200}, 50, rng), p,
        rng);
    s.pairs.push_back(c);
  }
  return s;
}

Scenario forestScenario(unsigned seed, int overlapping, int disjoint) {
  Scenario s{"forest", {},
             "Poisson trunks 0.09/m^2 over 400x200 m; A a 100x100 m plot (~800 trunks), B a 60x60 m plot (~290) "
             "overlapping 40-80% of B, or in the other half of the forest (disjoint); noise 10 cm, 10% missed"};
  std::mt19937 rng(seed);
  const World w = forestWorld(400, 200, 0.09, rng);
  std::uniform_real_distribution<double> u(0, 1);
  const place::PerturbParams p{0.1, 0.03, 0.1};
  for (int k = 0; k < overlapping + disjoint; ++k) {
    const bool overlap = k < overlapping;
    const double ax = u(rng) * 90, ay = u(rng) * 90;
    const double bx = overlap ? ax + 20 + 40 * u(rng) : 200 + u(rng) * 130;
    const double by = overlap ? ay + (u(rng) - 0.5) * 40 : u(rng) * 130;
    PairCase c;
    c.overlapping = overlap;
    c.a = observe(w, [&](const place::Landmark& l) { return inBox(l, ax, ay, ax + 100, ay + 100); },
                  randomFrame({ax + 50, ay + 50}, 30, rng), p, rng);
    c.b = observe(w, [&](const place::Landmark& l) { return inBox(l, bx, by, bx + 60, by + 60); },
                  randomFrame({bx + 30, by + 30}, 20, rng), p, rng);
    s.pairs.push_back(c);
  }
  return s;
}

Scenario kittiScenario(const std::string& data_dir, const std::string& seq, unsigned seed) {
  const std::vector<std::pair<int, int>> splits =
      seq == "05" ? std::vector<std::pair<int, int>>{{0, 1000}, {700, 2000}, {1600, 2760}}
                  : std::vector<std::pair<int, int>>{{0, 600}, {400, 1000}, {500, 1100}};
  Scenario s{"kitti" + seq, {},
             "robots driving KITTI " + seq + " splits observing the real poles within 25 m, maps in each robot's start "
             "frame; noise 5 cm, 10% missed; pairs sharing >= 10 poles, 3 noise draws"};
  const KittiSequence kitti = loadKitti(data_dir, seq);
  for (unsigned draw = 0; draw < 3; ++draw) {
    std::mt19937 rng(seed + draw);
    std::vector<RobotMap> robots;
    for (const auto& [first, last] : splits) robots.push_back(kittiRobot(kitti, first, last, 25.0, {0.05, 0.0, 0.1}, rng));
    for (std::size_t i = 0; i < robots.size(); ++i)
      for (std::size_t j = i + 1; j < robots.size(); ++j)
        if (sharedLandmarks(robots[i], robots[j]) >= 10) s.pairs.push_back({robots[i], robots[j], true});
  }
  return s;
}

Scenario realScenario(const std::string& data_dir, const std::string& set, unsigned seed) {
  Scenario s{set + "_real", {},
             "real SlideSLAM " + set + " maps (3 robots), each against 5 copies moved by random transforms; noise "
             "5 cm, 10% dropped"};
  std::mt19937 rng(seed);
  for (int robot = 0; robot < 3; ++robot) {
    const std::vector<place::Landmark> lms = readReal(data_dir, set, robot);
    for (int k = 0; k < 5; ++k) {
      PairCase c;
      c.a = {lms, Pose::Identity()};
      c.b.T_w_r = randomFrame({0, 0}, 30, rng);
      c.b.lms = place::perturbedCopy(lms, c.b.T_w_r, {0.05, 0.0, 0.1}, rng);
      s.pairs.push_back(c);
    }
  }
  return s;
}

MethodFigures runScenario(const Scenario& s, place::PlaceMethod method, const place::PlaceConfig& config, int repeats) {
  MethodFigures f;
  for (const PairCase& c : s.pairs) {
    place::PlaceResult first;
    for (int r = 0; r < repeats; ++r) {
      place::PlaceResult res = place::recognizePlace(method, c.a.lms, c.b.lms, config);
      f.ms.push_back(res.ms);
      f.cpu_ms.push_back(res.cpu_ms);
      std::map<std::string, double> per_run;  // stages repeated within a run are summed
      for (const auto& [name, ms] : res.stage_cpu_ms) per_run[name] += ms;
      for (const auto& [name, ms] : per_run) f.stage_cpu_ms[name].push_back(ms);
      if (r == 0) first = std::move(res);
    }
    f.peak_bytes = std::max(f.peak_bytes, first.clipper_peak_bytes);
    f.max_associations = std::max(f.max_associations, first.associations);
    if (!c.overlapping) {
      ++f.disjoint;
      f.false_positives += first.found;
      continue;
    }
    ++f.overlapping;
    if (!first.found) {
      ++f.missed;
      continue;
    }
    const eval::TransformError e = eval::transformError(first.T_a_b, truthBetween(c.a, c.b));
    if (e.translation_m < 1.0 && e.yaw_deg < 2.0) {
      ++f.correct;
      f.trans_err.push_back(e.translation_m);
      f.yaw_err.push_back(e.yaw_deg);
    } else {
      ++f.wrong;
    }
  }
  return f;
}

ClipperStress clipperStress(const PairCase& c, int outliers_per_landmark, const place::ClipperParams& params,
                            unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::uint32_t> pick(0, static_cast<std::uint32_t>(c.a.lms.size() - 1));
  std::map<std::size_t, std::uint32_t> a_of_id;
  for (std::uint32_t i = 0; i < c.a.lms.size(); ++i) a_of_id[c.a.lms[i].index] = i;
  std::vector<place::Association> assoc;
  ClipperStress s;
  for (std::uint32_t j = 0; j < c.b.lms.size(); ++j) {
    const auto it = a_of_id.find(c.b.lms[j].index);
    if (it != a_of_id.end()) {
      assoc.push_back({it->second, j});
      ++s.true_associations;
    }
    for (int k = 0; k < outliers_per_landmark; ++k) {
      const std::uint32_t i = pick(rng);
      if (it == a_of_id.end() || i != it->second) assoc.push_back({i, j});
    }
  }
  std::vector<Eigen::Vector3d> pa, pb;
  for (const place::Landmark& l : c.a.lms) pa.push_back(l.p);
  for (const place::Landmark& l : c.b.lms) pb.push_back(l.p);
  const double t0 = clock::threadCpuMs();
  const place::ClipperResult r = place::clipper(pa, pb, assoc, params);
  s.ms = clock::threadCpuMs() - t0;
  s.associations = assoc.size();
  s.selected = r.selected.size();
  for (std::size_t k : r.selected) s.selected_true += c.a.lms[assoc[k].a].index == c.b.lms[assoc[k].b].index;
  s.edges = r.edges;
  s.peak_bytes = r.peak_bytes;
  return s;
}

AliasFigures aliasedRooms(unsigned seed, place::PlaceMethod method, const place::PlaceConfig& config,
                          const place::ConsensusParams& consensus, int attempts) {
  std::mt19937 rng(seed);
  World room = indoorWorld(1, 1, rng);
  World w = room;
  for (place::Landmark l : room) {  // the twin room, 10 m further along x
    l.p.x() += 10.0;
    l.index = w.size();
    w.push_back(l);
  }
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < 4; ++k) {  // what tells the rooms apart: a few objects only in the second
    place::Landmark l;
    l.class_id = 0;
    l.p = {11.0 + 6.0 * u(rng), 1.0 + 6.0 * u(rng), 0.5};
    l.size = {0.6, 0.6, 1.0};
    l.index = w.size();
    w.push_back(l);
  }
  const RobotMap a = observe(
      w, [](const place::Landmark&) { return true; }, randomFrame({9, 4}, 3, rng), {0.03, 0.03, 0.0}, rng);
  const Pose T_w_b = randomFrame({14, 4}, 3, rng);
  const Pose truth = a.T_w_r.inverse() * T_w_b;
  place::ConsensusFilter filter(consensus);
  AliasFigures f;
  for (int k = 0; k < attempts; ++k) {
    const RobotMap b = observe(
        w, [](const place::Landmark& l) { return l.p.x() > 9.0; }, T_w_b, {0.05, 0.05, 0.3}, rng);
    const place::PlaceResult r = place::recognizePlace(method, a.lms, b.lms, config);
    ++f.attempts;
    if (!r.found) continue;
    ++f.raw_found;
    const auto wrong = [&](const Pose& T) {
      const eval::TransformError e = eval::transformError(T, truth);
      return e.translation_m > 1.0 || e.yaw_deg > 2.0;
    };
    f.raw_wrong += wrong(r.T_a_b);
    const place::ConsensusFilter::Update up = filter.add(r.T_a_b, static_cast<double>(r.inliers.size()));
    if (up.outcome == place::ConsensusFilter::Outcome::Pending) continue;
    ++f.published;
    f.published_wrong += wrong(up.T);
  }
  return f;
}

Cycle realCycle(const std::string& data_dir, const std::string& set, place::PlaceMethod method,
                const place::PlaceConfig& config) {
  std::vector<place::Landmark> maps[3];
  for (int i = 0; i < 3; ++i) maps[i] = readReal(data_dir, set, i);
  Pose T[3];
  const int links[3][2] = {{0, 1}, {1, 2}, {2, 0}};
  Cycle c;
  for (int k = 0; k < 3; ++k) {
    // Either direction will do (the acceptance test is not symmetric): T_b_a inverted.
    const place::PlaceResult r = place::recognizePlace(method, maps[links[k][0]], maps[links[k][1]], config);
    const place::PlaceResult back =
        r.found ? r : place::recognizePlace(method, maps[links[k][1]], maps[links[k][0]], config);
    if (!r.found && !back.found) {
      c.why = "robot" + std::to_string(links[k][0]) + "-robot" + std::to_string(links[k][1]) + ": " + r.reason;
      return c;
    }
    T[k] = r.found ? r.T_a_b : back.T_a_b.inverse();
  }
  const Pose loop = T[0] * T[1] * T[2];
  c.ok = true;
  c.trans_m = loop.translation().norm();
  c.yaw_deg = std::abs(yawOf(loop.linear())) * 180.0 / M_PI;
  return c;
}

}  // namespace slide::bench_place
