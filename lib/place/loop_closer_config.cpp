#include "place/loop_closer_config.h"

#include "config/config.h"

namespace slide::place {

LoopCloserParams loadLoopCloserParams(const ConfigNode& root) {
  const std::string& path = root.file();
  LoopCloserParams p;
  root.read("robot", p.robot);
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
    n.read("period_s", p.inter_period_s);
    n.read("stagger_s", p.stagger_s);
    n.requireNonNegative("period_s", p.inter_period_s);
    n.requireNonNegative("stagger_s", p.stagger_s);
  }
  if (root.has("intra_robot")) {
    const ConfigNode n = root.child("intra_robot");
    n.read("period_s", p.intra_period_s);
    n.read("trigger_radius_m", p.intra_trigger_radius_m);
    n.read("min_keypose_gap", p.intra_min_keypose_gap);
    n.read("local_radius_m", p.intra_local_radius_m);
    n.read("drift_fraction", p.intra_drift_fraction);
    n.requireNonNegative("drift_fraction", p.intra_drift_fraction);
    n.requireNonNegative("period_s", p.intra_period_s);
    n.requireNonNegative("trigger_radius_m", p.intra_trigger_radius_m);
    n.requireNonNegative("local_radius_m", p.intra_local_radius_m);
    if (p.intra_min_keypose_gap < 1) n.fail("min_keypose_gap", "must be at least 1");
  }
  if (root.has("min_objects")) {
    const long v = root.get<long>("min_objects");
    if (v < 3) root.fail("min_objects", "must be at least 3");
    p.min_objects = static_cast<std::size_t>(v);
  }
  if (root.has("max_map_objects")) {
    const long v = root.get<long>("max_map_objects");
    if (v < static_cast<long>(p.min_objects)) root.fail("max_map_objects", "must be at least min_objects");
    p.max_map_objects = static_cast<std::size_t>(v);
  }
  if (root.has("consensus")) {
    const ConfigNode n = root.child("consensus");
    n.read("trans_tol", p.consensus.trans_tol);
    n.read("yaw_tol_deg", p.consensus.yaw_tol_deg);
    n.read("initial_confirmations", p.consensus.initial_confirmations);
    n.read("change_confirmations", p.consensus.change_confirmations);
    n.read("window", p.consensus.window);
    n.read("ambiguous_may_replace", p.consensus.ambiguous_may_replace);
    n.read("ambiguous_may_confirm", p.consensus.ambiguous_may_confirm);
    n.read("contest_min_offset", p.consensus.contest_min_offset);
    n.read("contest_min_yaw_deg", p.consensus.contest_min_yaw_deg);
    if (!(p.consensus.contest_min_offset >= 0)) n.fail("contest_min_offset", "must not be negative");
    if (!(p.consensus.contest_min_yaw_deg >= 0)) n.fail("contest_min_yaw_deg", "must not be negative");
    if (p.consensus.window < 1) n.fail("window", "must be at least 1");
  }
  return p;
}

}  // namespace slide::place
