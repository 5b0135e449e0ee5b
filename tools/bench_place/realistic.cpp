#include "realistic.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <set>
#include <unordered_map>

#include "simulator/forest_world.h"
#include "simulator/route_lattice.h"
#include "bench/stats.h"
#include "peak_memory.h"
#include "worlds.h"

namespace slide::bench_place {

namespace {
std::vector<place::Landmark> landmarksOfWorld(const simulator::World& w) {
  ObjectMap map;
  for (const io::GroundTruthObject& g : w.objects) map.add(g.object);
  std::vector<place::Landmark> out = place::landmarksOf(map);
  for (std::size_t i = 0; i < out.size(); ++i) out[i].index = i;
  return out;
}

// Offices of 8 x 8 m in a grid, each furnished from one of two template rooms (chairs missing at
// random, everything shifted a little): many rooms look alike.
std::vector<place::Landmark> repeatedRooms(int rooms_x, int rooms_y, std::mt19937& rng) {
  const World templates[2] = {indoorWorld(1, 1, rng), indoorWorld(1, 1, rng)};
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> jitter(0, 0.1);
  std::vector<place::Landmark> out;
  for (int rx = 0; rx < rooms_x; ++rx)
    for (int ry = 0; ry < rooms_y; ++ry)
      for (place::Landmark l : templates[u(rng) < 0.5 ? 0 : 1]) {
        if (l.class_id == 1 && u(rng) < 0.25) continue;
        l.p += Eigen::Vector3d(rx * 10.0 + jitter(rng), ry * 10.0 + jitter(rng), 0);
        l.index = out.size();
        out.push_back(l);
      }
  return out;
}

// A walk over the route graph of at least `length` metres through nodes `allowed` accepts:
// no U-turn unless at a dead end, the least visited neighbour first (ties at random).
std::vector<Eigen::Vector2d> walkRoute(const simulator::RouteGraph& g, double length,
                                       const std::function<bool(const Eigen::Vector2d&)>& allowed, std::mt19937& rng) {
  const std::vector<std::vector<int>> nb = g.neighbours();
  std::vector<int> ok;
  for (std::size_t v = 0; v < g.nodes.size(); ++v)
    if (allowed(g.nodes[v])) ok.push_back(static_cast<int>(v));
  if (ok.empty()) return {};
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<int> visits(g.nodes.size(), 0);
  int cur = ok[std::min(ok.size() - 1, static_cast<std::size_t>(u(rng) * ok.size()))], prev = -1;
  std::vector<Eigen::Vector2d> line{g.nodes[cur]};
  double s = 0;
  ++visits[cur];
  while (s < length) {
    std::vector<int> options;
    for (int v : nb[cur])
      if (v != prev && allowed(g.nodes[v])) options.push_back(v);
    if (options.empty() && prev >= 0) options.push_back(prev);
    if (options.empty()) break;
    int fewest = visits[options.front()];
    for (int v : options) fewest = std::min(fewest, visits[v]);
    std::vector<int> best;
    for (int v : options)
      if (visits[v] == fewest) best.push_back(v);
    const int next = best[std::min(best.size() - 1, static_cast<std::size_t>(u(rng) * best.size()))];
    s += (g.nodes[next] - g.nodes[cur]).norm();
    prev = cur;
    cur = next;
    ++visits[cur];
    line.push_back(g.nodes[cur]);
  }
  return line;
}

// The part of a polyline between arclengths s0 and s1.
std::vector<Eigen::Vector2d> subRoute(const std::vector<Eigen::Vector2d>& line, double s0, double s1) {
  std::vector<Eigen::Vector2d> out;
  double s = 0;
  for (std::size_t i = 1; i < line.size(); ++i) {
    const Eigen::Vector2d d = line[i] - line[i - 1];
    const double len = d.norm();
    if (len <= 0) continue;
    const double from = std::max(s0, s), to = std::min(s1, s + len);
    if (from < to) {
      const Eigen::Vector2d p0 = line[i - 1] + d * ((from - s) / len), p1 = line[i - 1] + d * ((to - s) / len);
      if (out.empty() || (out.back() - p0).norm() > 1e-9) out.push_back(p0);
      out.push_back(p1);
    }
    s += len;
  }
  return out;
}

struct Error {
  double trans_m = 0, yaw_deg = 0;
};
// Translation error where it matters, at the shared objects' centroid (B's frame); yaw error.
Error errorAt(const Pose& estimate, const simulator::SharedTruth& t) {
  return {(estimate * t.centroid_b - t.T_a_b * t.centroid_b).norm(),
          std::abs(wrapAngle(yawOf(estimate.linear()) - yawOf(t.T_a_b.linear()))) * 180.0 / M_PI};
}
bool withinTolerance(const Error& e) { return e.trans_m <= 1.0 && e.yaw_deg <= 2.0; }
// "X m / Y deg off", or that the maps share too few objects for a truth (any transform is wrong).
std::string offBy(const Pose& estimate, const simulator::SharedTruth& t) {
  if (!t.ok) return fmt::format("given while the maps share {} objects", t.shared);
  const Error e = errorAt(estimate, t);
  return fmt::format("{:.2f} m / {:.2f} deg off", e.trans_m, e.yaw_deg);
}

std::size_t trueObjects(const std::vector<place::Landmark>& lms) {
  return static_cast<std::size_t>(std::count_if(
      lms.begin(), lms.end(), [](const place::Landmark& l) { return l.index != simulator::kSpuriousObject; }));
}
}  // namespace

RouteWorld routeWorld(const std::string& name, unsigned seed) {
  RouteWorld w;
  w.name = name;
  const simulator::ClassConfusions outdoor{{71, {80}}, {80, {71}}, {10, {0}}, {0, {10, 80}}};
  w.confusions = outdoor;
  std::mt19937 rng(seed);
  std::mt19937_64 rng64(seed);
  if (name == "forest" || name == "longleaf" || name == "spruces" || name == "finpines") {
    simulator::ForestParams p;
    p.crowns = false;
    p.bushes = 0;
    if (name == "forest") {
      p.side = 400;
      p.num_trees = static_cast<int>(860 * (400.0 / 150) * (400.0 / 150));  // the simulator's default density
      w.route_length = 300, w.range = 15;
    } else {
      p.layout = name;
      // One plot (the side is its larger extent: spruces and finpines get a strip of a mirrored copy).
      p.side = name == "longleaf" ? 200 : (name == "spruces" ? 55 : 10);
      p.route_spacing = name == "longleaf" ? 20 : (name == "spruces" ? 8 : 2.5);
      w.route_length = name == "longleaf" ? 250 : (name == "spruces" ? 60 : 12);
      w.range = name == "longleaf" ? 12 : (name == "spruces" ? 8 : 3);
    }
    const simulator::World world = simulator::makeForestWorld(p, seed);
    w.objects = landmarksOfWorld(world);
    w.routes = world.routes;
    w.description = fmt::format("{} trunks over {:.0f} x {:.0f} m ({}), route {:.0f} m, range {:.0f} m", w.objects.size(),
                                p.side, p.side, name == "forest" ? "procedural, clustered" : "real inventory plot",
                                w.route_length, w.range);
  } else if (name == "forest_scale") {
    w.objects = forestWorld(1500, 1500, 0.1, rng);
    w.routes =
        simulator::routeLattice(Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(1500, 1500)), 25, 5, rng64);
    w.route_length = 3500, w.range = 15;
    w.description = fmt::format("{} Poisson trunks (0.1/m^2) over 1,500 x 1,500 m, range {:.0f} m", w.objects.size(), w.range);
  } else if (name == "forest_large") {
    w.objects = forestWorld(600, 600, 0.1, rng);
    w.routes =
        simulator::routeLattice(Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(600, 600)), 25, 5, rng64);
    w.route_length = 1000, w.range = 15;
    w.description = fmt::format("{} Poisson trunks (0.1/m^2) over 600 x 600 m, route {:.0f} m, range {:.0f} m",
                                w.objects.size(), w.route_length, w.range);
  } else if (name == "urban") {
    w.objects = urbanWorld(420, rng);
    w.routes =
        simulator::routeLattice(Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(420, 420)), 60, 0, rng64);
    w.route_length = 500, w.range = 25;
    w.description = fmt::format("{} cars, poles, trees, other along a 60 m street grid over 420 x 420 m, route {:.0f} m, "
                                "range {:.0f} m", w.objects.size(), w.route_length, w.range);
  } else if (name == "indoor" || name == "indoor_repeated") {
    const bool repeated = name == "indoor_repeated";
    w.objects = repeated ? repeatedRooms(8, 4, rng) : indoorWorld(6, 4, rng);
    const double wx = repeated ? 80 : 60;
    w.routes = simulator::routeLattice(Eigen::AlignedBox2d(Eigen::Vector2d(-1, -1), Eigen::Vector2d(wx - 1, 39)), 10, 0,
                                       rng64);
    w.confusions = {{1, {2}}, {2, {1}}, {3, {0}}};
    w.route_length = 80, w.range = 5;
    w.description = fmt::format("{} tables, chairs, monitors in {} 8 x 8 m offices{}, route {:.0f} m through room centres, "
                                "range {:.0f} m", w.objects.size(), repeated ? 32 : 24,
                                repeated ? " furnished from two templates" : "", w.route_length, w.range);
  } else {
    throw std::invalid_argument("unknown route world '" + name + "'");
  }
  return w;
}

namespace {
// The indices of the objects of `world` within `range` (horizontally) of the route, in world order.
std::vector<std::size_t> withinReach(const std::vector<place::Landmark>& world,
                                     const std::vector<Eigen::Vector2d>& route, double range) {
  const double cell = std::max(range, 1.0);
  auto key = [&](double x, double y) {
    return (static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(x / cell))) << 32) ^
           (static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(y / cell))) & 0xffffffffULL);
  };
  std::unordered_map<std::uint64_t, std::vector<Eigen::Vector2d>> cells;
  for (const Pose& T : simulator::posesAlong(route, 0.25 * cell)) {
    const Eigen::Vector2d p = T.translation().head<2>();
    cells[key(p.x(), p.y())].push_back(p);
  }
  std::vector<std::size_t> out;
  // Poses lie every quarter range along the routes: an object seen within `range` of the route
  // is within range + cell / 8 of a pose.
  const double reach = range + 0.125 * cell;
  for (std::size_t i = 0; i < world.size(); ++i) {
    const place::Landmark& l = world[i];
    bool near = false;
    for (int dx = -2; dx <= 2 && !near; ++dx)
      for (int dy = -2; dy <= 2 && !near; ++dy) {
        const auto it = cells.find(key(l.p.x() + dx * cell, l.p.y() + dy * cell));
        if (it == cells.end()) continue;
        for (const Eigen::Vector2d& p : it->second)
          if ((p - l.p.head<2>()).norm() <= reach) {
            near = true;
            break;
          }
      }
    if (near) out.push_back(i);
  }
  return out;
}

// mapAlongRoute over the objects within reach of the route only: the same map (objects out of
// reach are never seen and draw no random numbers), without a pass over every pose for each
// object of a large world. Landmark::index is the world index, as mapAlongRoute's own.
simulator::DriftedMap mapInReach(const RouteWorld& w, const std::vector<Eigen::Vector2d>& route,
                                 const simulator::MapErrorParams& errors, std::mt19937& rng) {
  const std::vector<std::size_t> origin = withinReach(w.objects, route, errors.range);
  std::vector<place::Landmark> objects;
  objects.reserve(origin.size());
  for (std::size_t i : origin) objects.push_back(w.objects[i]);
  simulator::DriftedMap m = simulator::mapAlongRoute(objects, route, errors, w.confusions, rng);
  for (place::Landmark& l : m.lms)
    if (l.index != simulator::kSpuriousObject) l.index = origin[l.index];
  return m;
}
}  // namespace

std::vector<MapPair> makePairs(const RouteWorld& w, const Condition& c, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<MapPair> out;
  const double L = w.route_length, f = c.overlap;
  simulator::MapErrorParams errors = c.errors;
  errors.range = w.range;
  for (int k = 0; k < c.pairs; ++k) {
    const std::vector<Eigen::Vector2d> master = walkRoute(w.routes, (2 - f) * L + 1, [](const Eigen::Vector2d&) { return true; }, rng);
    MapPair p;
    p.opposite = k % 2 == 1;
    std::vector<Eigen::Vector2d> rb = subRoute(master, (1 - f) * L, (2 - f) * L);
    if (p.opposite) std::reverse(rb.begin(), rb.end());
    p.a = mapInReach(w, subRoute(master, 0, L), errors, rng);
    p.b = mapInReach(w, rb, errors, rng);
    out.push_back(std::move(p));
  }
  std::vector<double> xs;
  for (const Eigen::Vector2d& n : w.routes.nodes) xs.push_back(n.x());
  std::nth_element(xs.begin(), xs.begin() + xs.size() / 2, xs.end());
  const double cx = xs[xs.size() / 2], margin = w.range + 1.0;
  for (int k = 0; k < c.disjoint_pairs; ++k) {
    MapPair p;
    p.overlapping = false;
    p.a = mapInReach(w, walkRoute(w.routes, L, [&](const Eigen::Vector2d& n) { return n.x() < cx - margin; }, rng), errors, rng);
    p.b = mapInReach(w, walkRoute(w.routes, L, [&](const Eigen::Vector2d& n) { return n.x() > cx + margin; }, rng), errors, rng);
    out.push_back(std::move(p));
  }
  return out;
}

std::vector<simulator::SharedTruth> sharedPlaces(const simulator::DriftedMap& a, const std::vector<place::Landmark>& b,
                                                 double gap) {
  // Shared objects in the order A passed them; a gap of more than `gap` metres along A's route
  // starts another place.
  std::vector<std::size_t> in_b;
  for (const place::Landmark& l : b)
    if (l.index != simulator::kSpuriousObject) in_b.push_back(l.index);
  std::sort(in_b.begin(), in_b.end());
  std::vector<std::pair<double, std::size_t>> along;  // (A's metres, A's landmark)
  for (std::size_t i = 0; i < a.lms.size(); ++i)
    if (a.lms[i].index != simulator::kSpuriousObject && std::binary_search(in_b.begin(), in_b.end(), a.lms[i].index))
      along.emplace_back(a.seen_at[i], i);
  std::sort(along.begin(), along.end());
  std::vector<simulator::SharedTruth> out;
  std::vector<place::Landmark> place;
  for (std::size_t k = 0; k <= along.size(); ++k) {
    if (k == along.size() || (k > 0 && along[k].first - along[k - 1].first > gap)) {
      const simulator::SharedTruth t = simulator::sharedObjectTruth(place, b);
      if (t.ok) out.push_back(t);
      place.clear();
    }
    if (k < along.size()) place.push_back(a.lms[along[k].second]);
  }
  return out;
}

namespace {
// "N shared places, nearest: X m / Y deg off of a place of M objects, fit R m rms".
std::string nearestPlaceNote(const Pose& T, const std::vector<simulator::SharedTruth>& places) {
  std::string nearest = "none";
  double best = 1e300;
  for (const simulator::SharedTruth& q : places)
    if (const double d = errorAt(T, q).trans_m; d < best)
      best = d, nearest = offBy(T, q) + fmt::format(" of a place of {} objects, fit {:.2f} m rms", q.shared, q.rms);
  return fmt::format("{} shared places, nearest: {}", places.size(), nearest);
}
}  // namespace

RealisticFigures runPairs(const std::vector<MapPair>& pairs, place::PlaceMethod method,
                          const place::PlaceConfig& config, double place_gap, bool places_count) {
  RealisticFigures f;
  for (const MapPair& p : pairs) {
    const PeakMemory memory;
    const place::PlaceResult r = place::recognizePlace(method, p.a.lms, p.b.lms, config);
    f.peak_mb.push_back(memory.extraMb());
    f.cpu_ms.push_back(r.cpu_ms);
    std::map<std::string, double> stages;  // a stage may run more than once (SlideGraph's hypotheses)
    for (const auto& [stage, ms] : r.stage_cpu_ms) stages[stage] += ms;
    for (const auto& [stage, ms] : stages) f.stage_cpu_ms[stage].push_back(ms);
    f.peak_bytes = std::max(f.peak_bytes, r.clipper_peak_bytes);
    f.objects_a.push_back(static_cast<double>(p.a.lms.size()));
    f.objects_b.push_back(static_cast<double>(p.b.lms.size()));
    if (!p.overlapping) {
      ++f.disjoint;
      if (r.found) {
        ++f.false_positives;
        f.wrong_notes.push_back(fmt::format("disjoint pair: {} inliers (chance {:.1f})", r.inliers.size(), r.chance_inliers));
      }
      continue;
    }
    ++f.overlapping;
    const simulator::SharedTruth t = simulator::sharedObjectTruth(p.a.lms, p.b.lms);
    f.shared_fraction.push_back(static_cast<double>(t.shared) / std::max<std::size_t>(1, trueObjects(p.b.lms)));
    f.truth_rms.push_back(t.rms);
    if (!r.found) {
      ++f.missed;
      f.miss_notes.push_back(fmt::format("{} shared: {}", t.shared, r.reason));
      continue;
    }
    Error e = t.ok ? errorAt(r.T_a_b, t) : Error{};
    bool correct = t.ok && withinTolerance(e);
    if (!correct && place_gap > 0 && places_count)  // right about one of the places the maps share
      for (const simulator::SharedTruth& place : sharedPlaces(p.a, p.b.lms, place_gap))
        if (withinTolerance(errorAt(r.T_a_b, place))) {
          correct = true;
          e = errorAt(r.T_a_b, place);
          break;
        }
    if (correct) {
      ++f.correct;
      f.trans_err.push_back(e.trans_m);
      f.yaw_err.push_back(e.yaw_deg);
    } else {
      ++f.wrong;
      const std::string places =
          place_gap > 0 ? "; " + nearestPlaceNote(r.T_a_b, sharedPlaces(p.a, p.b.lms, place_gap)) : "";
      f.wrong_notes.push_back(fmt::format("{} ({} inliers, chance {:.1f}, {} shared, the truth's own fit {:.2f} m rms, {}{})",
                                          offBy(r.T_a_b, t), r.inliers.size(), r.chance_inliers, t.shared, t.rms,
                                          p.opposite ? "opposite" : "same way", places));
    }
  }
  return f;
}

ConsensusFigures runConsensus(const std::vector<MapPair>& pairs, place::PlaceMethod method,
                              const place::PlaceConfig& config, const place::ConsensusParams& consensus, int checks,
                              double place_gap) {
  ConsensusFigures f;
  for (const MapPair& p : pairs) {
    place::ConsensusFilter filter(consensus);
    const double length = p.b.s.empty() ? 0 : p.b.s.back();
    int fed = 0;
    double first_correct_s = -1;
    bool published_correct = false, published_wrong = false;
    (p.overlapping ? f.pairs : f.disjoint) += 1;
    for (int k = 1; k <= checks; ++k) {
      const double s = length * k / checks;
      const std::vector<place::Landmark> b = simulator::mapUpTo(p.b, s);
      if (b.size() < 6) continue;  // the loop closer's minimum
      ++f.queries;
      const place::PlaceResult r = place::recognizePlace(method, p.a.lms, b, config);
      // As the loop closer: an ambiguous result's stronger alignment may contest a held transform
      // or confirm a pending one (ConsensusParams).
      if (!r.found && !(r.ambiguous && place::feedsAmbiguous(method, filter))) continue;
      const simulator::SharedTruth t = simulator::sharedObjectTruth(p.a.lms, b);
      const auto correct = [&](const Pose& T) { return p.overlapping && t.ok && withinTolerance(errorAt(T, t)); };
      if (r.found) {
        ++f.raw_found;
        ++fed;
        const bool raw_ok = correct(r.T_a_b);
        f.raw_wrong += !raw_ok;
        if (raw_ok && first_correct_s < 0) first_correct_s = s;
      }
      const place::ConsensusFilter::Update u = filter.add(r.T_a_b, static_cast<double>(r.inliers.size()), r.found);
      if (u.outcome == place::ConsensusFilter::Outcome::Pending) continue;
      if (correct(u.T)) {
        if (!published_correct) {
          f.detections_to_publish.push_back(fed);
          f.metres_delay.push_back(s - first_correct_s);
        }
        published_correct = true;
      } else if (!published_wrong) {
        published_wrong = true;
        // Against the places the two maps (B's as grown) share, as runPairs notes it.
        const std::string place = p.overlapping ? "; " + nearestPlaceNote(u.T, sharedPlaces(p.a, b, place_gap)) : "";
        f.wrong_notes.push_back(fmt::format("{}published, {}, after {} detections at {:.0f} m{}",
                                            p.overlapping ? "" : "disjoint pair: ", offBy(u.T, t), fed, s, place));
      }
    }
    if (p.overlapping) {
      f.published_correct += published_correct;
      f.published_wrong += published_wrong;
    } else {
      f.disjoint_published += published_wrong;
    }
  }
  return f;
}

namespace {
simulator::MapErrorParams errorsOf(double noise, double missed, double spurious, double confusion, double drift_deg) {
  simulator::MapErrorParams e;
  e.position_sigma = noise, e.missed = missed, e.spurious = spurious, e.confusion = confusion;
  e.yaw_drift_deg_per_100m = drift_deg;
  e.scale_error = 0.005;
  e.vertical_drift_per_100m = 0.3;
  return e;
}
const simulator::MapErrorParams kTarget = errorsOf(0.25, 0.2, 0.2, 0.075, 1.5);  // the recall condition
const simulator::MapErrorParams kMild = errorsOf(0.1, 0.1, 0.1, 0.05, 0.5);
const simulator::MapErrorParams kHarsh = errorsOf(0.3, 0.3, 0.25, 0.1, 2.0);

struct Case {
  std::string world;
  Condition condition;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  for (const char* w : {"forest", "longleaf", "spruces", "finpines", "urban", "indoor"}) {
    const bool fp = std::string(w) == "forest" || std::string(w) == "urban";
    out.push_back({w, {"target", kTarget, 0.2, 10, fp ? 10 : 0}});
    out.push_back({w, {"mild", kMild, 0.5, 6, 0}});
    out.push_back({w, {"harsh", kHarsh, 0.1, 6, fp ? 6 : 0}});
  }
  out.push_back({"indoor_repeated", {"target", kTarget, 0.2, 0, 10}});
  for (double f : {0.1, 0.3, 0.5}) out.push_back({"forest", {fmt::format("overlap{:.0f}", 100 * f), kTarget, f, 6, 0}});
  for (double d : {0.5, 1.0, 2.0}) {
    simulator::MapErrorParams e = kTarget;
    e.yaw_drift_deg_per_100m = d;
    out.push_back({"forest", {fmt::format("drift{:.1f}", d), e, 0.2, 6, 0}});
  }
  out.push_back({"forest_large", {"target", kTarget, 0.2, 4, 2}});
  return out;
}

std::string describe(const Condition& c) {
  const simulator::MapErrorParams& e = c.errors;
  return fmt::format("noise {:.2f} m, {:.0f}% missed, {:.0f}% spurious, {:.1f}% confused, {:.1f} deg/100 m yaw drift, "
                     "{:.1f}% scale, {:.1f} m/100 m vertical, overlap {:.0f}% of the route",
                     e.position_sigma, 100 * e.missed, 100 * e.spurious, 100 * e.confusion, e.yaw_drift_deg_per_100m,
                     100 * e.scale_error, e.vertical_drift_per_100m, 100 * c.overlap);
}

}  // namespace

simulator::MapErrorParams conditionErrors(const std::string& name) {
  if (name == "target") return kTarget;
  if (name == "mild") return kMild;
  if (name == "harsh") return kHarsh;
  throw std::invalid_argument("unknown condition '" + name + "' (expected target, mild or harsh)");
}

std::string joined(const std::vector<std::string>& notes) {
  std::string out;
  for (const std::string& n : notes) out += (out.empty() ? "" : "; ") + n;
  return out;
}

void runRealistic(bench::BenchReport& rep, const place::PlaceConfig& config, const place::ConsensusParams& consensus,
                  unsigned seed, const std::vector<std::string>& worlds, const std::string& dump) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::set<std::string> want(worlds.begin(), worlds.end());
  std::map<std::string, RouteWorld> built;
  std::map<std::string, std::vector<MapPair>> target_pairs;  // for the consensus runs
  std::string table = "| world | condition | method | maps (A x B, median) | shared | recall | wrong | FP | trans m | yaw deg | CPU ms (median / max) |\n"
                      "|---|---|---|---|---|---|---|---|---|---|---|\n";
  unsigned k = 0;
  for (const Case& c : cases()) {
    ++k;
    if (!want.empty() && !want.count(c.world)) continue;
    if (!built.count(c.world)) {
      built.emplace(c.world, routeWorld(c.world, seed));
      spdlog::info("realistic {}: {}", c.world, built.at(c.world).description);
    }
    const RouteWorld& w = built.at(c.world);
    const std::vector<MapPair> pairs = makePairs(w, c.condition, seed * 1000 + k);
    if (c.condition.name == "target") target_pairs[c.world] = pairs;
    for (std::size_t i = 0; !dump.empty() && i < pairs.size(); ++i) {
      const std::string stem = fmt::format("{}/realistic_{}_{}_{}", dump, c.world, c.condition.name, i);
      writeLandmarks(stem + "_a.txt", pairs[i].a.lms);
      writeLandmarks(stem + "_b.txt", pairs[i].b.lms);
      const auto truth = [](const simulator::SharedTruth& t) {
        const Eigen::Vector4d x = xyzYawOf(t.T_a_b);
        return fmt::format("x {:.3f} y {:.3f} z {:.3f} yaw {:.3f} deg ({} shared objects, fit {:.2f} m rms)", x[0], x[1], x[2],
                           x[3] * 180 / M_PI, t.shared, t.rms);
      };
      const simulator::SharedTruth t = simulator::sharedObjectTruth(pairs[i].a.lms, pairs[i].b.lms);
      std::string places;
      for (const simulator::SharedTruth& q : sharedPlaces(pairs[i].a, pairs[i].b.lms, 2 * w.range))
        places += "; a place: " + truth(q);
      spdlog::info("{}: {}", stem, pairs[i].overlapping && t.ok ? "truth " + truth(t) + places : "disjoint: no transform expected");
    }
    const std::string cond = c.world + "." + c.condition.name;
    spdlog::info("realistic {}: {} overlapping + {} disjoint pairs; {}", cond, c.condition.pairs, c.condition.disjoint_pairs,
                 describe(c.condition));
    for (place::PlaceMethod m : {place::PlaceMethod::SlideGraph, place::PlaceMethod::SlideMatch}) {
      const RealisticFigures f = runPairs(pairs, m, config, 2 * w.range, false);
      const std::string prefix = "realistic." + cond + "." + place::methodName(m) + ".";
      const bool headline = c.condition.name == "target" && c.world != "forest_large";
      if (f.overlapping) {
        rep.add(prefix + "recall", double(f.correct) / f.overlapping, "", false, headline ? std::optional<double>(0.9) : std::nullopt)
            .note = fmt::format("{} correct of {} overlapping pairs ({} missed, {} wrong); {}", f.correct, f.overlapping,
                                f.missed, f.wrong, describe(c.condition));
        if (f.missed) rep.add(prefix + "missed", f.missed, "", true).note = joined(f.miss_notes);
        rep.add(prefix + "wrong", f.wrong, "", true, 0.0).note =
            f.wrong ? joined(f.wrong_notes) : "found but more than 1 m (at the shared objects' centroid) or 2 deg off";
        rep.add(prefix + "trans_err_m", f.trans_err.empty() ? nan : bench::median(f.trans_err), "m").note =
            "median over the correct, at the centroid of the shared objects, against the least-squares truth";
        rep.add(prefix + "yaw_err_deg", f.yaw_err.empty() ? nan : bench::median(f.yaw_err), "deg").note =
            "median over the correct";
        rep.add(prefix + "shared_fraction", bench::median(f.shared_fraction), "", false).note =
            "median share of B's true objects that A holds too";
      }
      if (f.disjoint) {
        rep.add(prefix + "false_positives", f.false_positives, "", true, 0.0).note =
            fmt::format("transforms on {} pairs in disjoint halves of the world{}", f.disjoint,
                        f.false_positives ? ": " + joined(f.wrong_notes) : "");
      }
      const bool large_graph = c.world == "forest_large" && m == place::PlaceMethod::SlideGraph;
      rep.add(prefix + "ms", bench::median(f.cpu_ms), "ms", true,
              large_graph ? std::optional<double>(50.0) : std::nullopt)
          .note =
          fmt::format("thread CPU time, median of one query per pair ({} pairs), maps {:.0f} x {:.0f} objects (median)",
                      f.cpu_ms.size(), bench::median(f.objects_a), bench::median(f.objects_b));
      rep.add(prefix + "ms.max", *std::max_element(f.cpu_ms.begin(), f.cpu_ms.end()), "ms").note = "thread CPU time, slowest pair";
      if (m == place::PlaceMethod::SlideGraph)
        rep.add(prefix + "clipper_peak_mb", f.peak_bytes / 1e6, "MB").note =
            "largest consistency graph + solver vectors of any query (associations capped at max_associations)";
      table +=
          fmt::format("| {} | {} | {} | {:.0f} x {:.0f} | {} | {} | {} | {} | {} | {} | {:.1f} / {:.1f} |\n", c.world,
                      c.condition.name, place::methodName(m), bench::median(f.objects_a), bench::median(f.objects_b),
                      f.shared_fraction.empty() ? "-" : fmt::format("{:.2f}", bench::median(f.shared_fraction)),
                      f.overlapping ? fmt::format("{}/{}", f.correct, f.overlapping) : "-",
                      f.overlapping ? std::to_string(f.wrong) : "-",
                      f.disjoint ? fmt::format("{}/{}", f.false_positives, f.disjoint) : "-",
                      f.trans_err.empty() ? "-" : fmt::format("{:.2f}", bench::median(f.trans_err)),
                      f.yaw_err.empty() ? "-" : fmt::format("{:.2f}", bench::median(f.yaw_err)),
                      bench::median(f.cpu_ms), *std::max_element(f.cpu_ms.begin(), f.cpu_ms.end()));
    }
  }
  // Consensus over time on the target condition: B's map grows, checked 8 times along its route.
  for (auto& [world, pairs] : target_pairs) {
    if (world == "forest_large") continue;
    for (place::PlaceMethod m : {place::PlaceMethod::SlideGraph, place::PlaceMethod::SlideMatch}) {
      const ConsensusFigures f = runConsensus(pairs, m, config, consensus, 8, 2 * built.at(world).range);
      const std::string prefix = "realistic." + world + ".consensus." + place::methodName(m) + ".";
      if (f.pairs) {
        rep.add(prefix + "recall", double(f.published_correct) / f.pairs, "", false).note = fmt::format(
            "pairs with a correct published transform, of {} (B's map checked 8 times as it grows; {} queries, {} found, "
            "{} of them wrong)", f.pairs, f.queries, f.raw_found, f.raw_wrong);
        rep.add(prefix + "published_wrong", f.published_wrong, "", true, 0.0).note =
            f.published_wrong ? joined(f.wrong_notes) : "pairs where the filter published a wrong transform";
        rep.add(prefix + "detections", f.detections_to_publish.empty() ? nan : bench::median(f.detections_to_publish),
                "")
            .note = "found results fed to the filter until the first correct publication, median";
        rep.add(prefix + "delay_m", f.metres_delay.empty() ? nan : bench::median(f.metres_delay), "m").note =
            "metres B drove from its first correct raw detection to the first correct publication, median";
      }
      if (f.disjoint)
        rep.add(prefix + "false_positives", f.disjoint_published, "", true, 0.0).note =
            fmt::format("disjoint pairs with a published transform, of {}", f.disjoint);
    }
  }
  std::cout << "\nPlace recognition on realistic maps (one query per pair; wrong: > 1 m or > 2 deg from the least-squares "
               "truth over shared objects):\n" << table << std::endl;
}

}  // namespace slide::bench_place
