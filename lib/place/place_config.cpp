#include "place/place_config.h"

#include <stdexcept>

#include "config/config.h"

namespace slide {

namespace {
template <typename T>
void read(const ConfigNode& n, const std::string& key, T& value) {
  value = n.get<T>(key, value);
}

void read(const ConfigNode& n, const std::string& key, std::size_t& value) {
  const long v = n.get<long>(key, static_cast<long>(value));
  if (v < 0) n.fail(key, "must not be negative");
  value = static_cast<std::size_t>(v);
}

void positive(const ConfigNode& n, const std::string& key, double v) {
  if (!(v > 0)) n.fail(key, "must be positive");
}
}  // namespace

PlaceConfig loadPlaceConfig(const std::string& path) {
  const ConfigNode root = ConfigNode::load(path);
  PlaceConfig c;
  VerifyParams v;
  if (root.has("verify")) {
    const ConfigNode n = root.child("verify");
    read(n, "match_radius", v.match_radius);
    read(n, "size_tolerance", v.size_tolerance);
    read(n, "min_inliers", v.min_inliers);
    read(n, "min_inlier_ratio", v.min_inlier_ratio);
    read(n, "significance", v.significance);
    read(n, "robust_scale", v.robust_scale);
    read(n, "rounds", v.rounds);
    positive(n, "match_radius", v.match_radius);
    positive(n, "robust_scale", v.robust_scale);
  }
  c.slidegraph.verify = c.slidematch.verify = v;
  if (root.has("clipper")) {
    const ConfigNode n = root.child("clipper");
    read(n, "sigma", c.slidegraph.clipper.consistency.sigma);
    read(n, "epsilon", c.slidegraph.clipper.consistency.epsilon);
    read(n, "seed", c.slidegraph.clipper.seed);
    read(n, "max_outer", c.slidegraph.clipper.max_outer);
    read(n, "max_inner", c.slidegraph.clipper.max_inner);
    read(n, "tol_f", c.slidegraph.clipper.tol_f);
    positive(n, "sigma", c.slidegraph.clipper.consistency.sigma);
    positive(n, "epsilon", c.slidegraph.clipper.consistency.epsilon);
  }
  if (root.has("slidegraph")) {
    const ConfigNode n = root.child("slidegraph");
    read(n, "descriptor_radius", c.slidegraph.descriptor_radius);
    read(n, "neighbors_per_simplex", c.slidegraph.neighbors_per_simplex);
    read(n, "max_associations", c.slidegraph.max_associations);
    read(n, "use_classes", c.slidegraph.use_classes);
    read(n, "min_votes", c.slidegraph.min_votes);
    read(n, "hypotheses", c.slidegraph.hypotheses);
    read(n, "small_map", c.slidegraph.small_map);
    read(n, "retry_tolerance_scale", c.slidegraph.retry_tolerance_scale);
    read(n, "min_voted", c.slidegraph.min_voted);
    read(n, "min_landmarks", c.slidegraph.min_landmarks);
    positive(n, "descriptor_radius", c.slidegraph.descriptor_radius);
  }
  if (root.has("slidematch")) {
    const ConfigNode n = root.child("slidematch");
    read(n, "budget_ms", c.slidematch.budget_ms);
    read(n, "coarse_bin", c.slidematch.coarse_bin);
    read(n, "max_coarse_bins", c.slidematch.max_coarse_bins);
    read(n, "min_yaw_step_deg", c.slidematch.min_yaw_step_deg);
    read(n, "max_yaw_step_deg", c.slidematch.max_yaw_step_deg);
    read(n, "refine_candidates", c.slidematch.refine_candidates);
    read(n, "min_landmarks", c.slidematch.min_landmarks);
    positive(n, "coarse_bin", c.slidematch.coarse_bin);
    positive(n, "min_yaw_step_deg", c.slidematch.min_yaw_step_deg);
    if (c.slidematch.max_yaw_step_deg < c.slidematch.min_yaw_step_deg)
      n.fail("max_yaw_step_deg", "must be at least min_yaw_step_deg");
  }
  return c;
}

PlaceConfig loadDefaultPlaceConfig() { return loadPlaceConfig(std::string(SLIDE_SOURCE_DIR) + "/config/place.yaml"); }

PlaceMethod parsePlaceMethod(const std::string& name) {
  if (name == "slidegraph") return PlaceMethod::SlideGraph;
  if (name == "slidematch") return PlaceMethod::SlideMatch;
  throw std::invalid_argument("unknown place-recognition method '" + name + "' (expected slidegraph or slidematch)");
}

PlaceResult recognizePlace(PlaceMethod method, const std::vector<Landmark>& a, const std::vector<Landmark>& b,
                           const PlaceConfig& config) {
  return method == PlaceMethod::SlideGraph ? slideGraph(a, b, config.slidegraph) : slideMatch(a, b, config.slidematch);
}

}  // namespace slide
