#include "place/loop_closer_config.h"

#include "config/config.h"

namespace slide {

namespace {
template <typename T>
void read(const ConfigNode& n, const std::string& key, T& value) {
  value = n.get<T>(key, value);
}
void nonNegative(const ConfigNode& n, const std::string& key, double v) {
  if (!(v >= 0)) n.fail(key, "must not be negative");
}
}  // namespace

LoopCloserParams loadLoopCloserParams(const std::string& path) {
  const ConfigNode root = ConfigNode::load(path);
  LoopCloserParams p;
  read(root, "robot", p.robot);
  if (root.has("method")) {
    try {
      p.method = parsePlaceMethod(root.get<std::string>("method"));
    } catch (const std::invalid_argument& e) {
      root.fail("method", e.what());
    }
  }
  if (root.has("place_config")) {
    std::string place = root.get<std::string>("place_config");
    if (!place.empty() && place[0] != '/') {  // relative to this file's folder
      const auto slash = path.find_last_of('/');
      if (slash != std::string::npos) place = path.substr(0, slash + 1) + place;
    }
    p.place = loadPlaceConfig(place);
  } else {
    p.place = loadDefaultPlaceConfig();
  }
  if (root.has("inter_robot")) {
    const ConfigNode n = root.child("inter_robot");
    read(n, "period_s", p.inter_period_s);
    read(n, "stagger_s", p.stagger_s);
    nonNegative(n, "period_s", p.inter_period_s);
    nonNegative(n, "stagger_s", p.stagger_s);
  }
  if (root.has("intra_robot")) {
    const ConfigNode n = root.child("intra_robot");
    read(n, "period_s", p.intra_period_s);
    read(n, "trigger_radius_m", p.intra_trigger_radius_m);
    read(n, "min_keypose_gap", p.intra_min_keypose_gap);
    read(n, "local_radius_m", p.intra_local_radius_m);
    nonNegative(n, "period_s", p.intra_period_s);
    nonNegative(n, "trigger_radius_m", p.intra_trigger_radius_m);
    nonNegative(n, "local_radius_m", p.intra_local_radius_m);
    if (p.intra_min_keypose_gap < 1) n.fail("min_keypose_gap", "must be at least 1");
  }
  if (root.has("min_objects")) {
    const long v = root.get<long>("min_objects");
    if (v < 3) root.fail("min_objects", "must be at least 3");
    p.min_objects = static_cast<std::size_t>(v);
  }
  if (root.has("consensus")) {
    const ConfigNode n = root.child("consensus");
    read(n, "trans_tol", p.consensus.trans_tol);
    read(n, "yaw_tol_deg", p.consensus.yaw_tol_deg);
    read(n, "initial_confirmations", p.consensus.initial_confirmations);
    read(n, "change_confirmations", p.consensus.change_confirmations);
    read(n, "window", p.consensus.window);
    if (p.consensus.window < 1) n.fail("window", "must be at least 1");
  }
  return p;
}

}  // namespace slide
