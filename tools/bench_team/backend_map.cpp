#include "backend_map.h"

#include <limits>
#include <map>

#include "backend/optimizer.h"
#include "objects/class_table.h"

namespace slide::team::bench {
namespace {

void oneWay(const std::vector<Object>& from, const std::vector<Object>& to, double gate_m, MapComparison& out) {
  for (const Object& o : from) {
    double best = std::numeric_limits<double>::infinity();
    for (const Object& p : to)
      if (p.class_id == o.class_id) best = std::min(best, (p.position() - o.position()).norm());
    if (best <= gate_m) out.max_paired_m = std::max(out.max_paired_m, best);
    else ++out.unpaired;
  }
}

}  // namespace

std::vector<Object> backendMap(const backend::BackendConfig& cfg, std::int32_t host,
                               const std::map<std::int32_t, Pose>& transforms, const std::vector<Arrival>& arrivals) {
  backend::Optimizer opt(cfg, ClassTable::loadDefault(), host);
  for (const auto& [peer, T] : transforms) opt.addRobotTransform(peer, T);
  for (const Arrival& a : arrivals)
    for (const KeyPoseBundle& b : a.bundles) opt.addBundle(b);
  opt.fullSolve();
  return opt.landmarks();
}

MapComparison compareMaps(const std::vector<Object>& a, const std::vector<Object>& b, double gate_m) {
  MapComparison out;
  oneWay(a, b, gate_m, out);
  oneWay(b, a, gate_m, out);
  return out;
}

}  // namespace slide::team::bench
