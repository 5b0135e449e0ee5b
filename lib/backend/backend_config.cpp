#include "backend/backend_config.h"

#include "config/config.h"

namespace slide::backend {

BackendConfig loadBackendConfig(const std::string& path) {
  const ConfigNode root = ConfigNode::load(path);
  BackendConfig c;
  if (root.has("odometry")) {
    const ConfigNode n = root.child("odometry");
    n.read("use_message_sigma", c.use_message_sigma);
    n.read("translation_per_m", c.odom_translation_per_m);
    n.read("rotation_per_m", c.odom_rotation_per_m);
    n.read("translation_floor", c.odom_translation_floor);
    n.read("rotation_floor", c.odom_rotation_floor);
    n.read("max_step_m", c.max_step_m);
    n.read("max_step_rad", c.max_step_rad);
    n.read("scale_sigma", c.odom_scale_sigma);
    if (!(c.odom_scale_sigma >= 0 && c.odom_scale_sigma < 0.5)) n.fail("scale_sigma", "must be in [0, 0.5)");
    for (const char* k : {"translation_floor", "rotation_floor", "max_step_m", "max_step_rad"})
      if (n.has(k)) n.requirePositive(k, n.get<double>(k));
  }
  if (root.has("priors")) {
    const ConfigNode n = root.child("priors");
    n.read("first_translation_sigma", c.prior_translation_sigma);
    n.read("first_rotation_sigma", c.prior_rotation_sigma);
    n.read("peer_translation_sigma", c.peer_translation_sigma);
    n.read("peer_vertical_sigma", c.peer_vertical_sigma);
    n.read("peer_rotation_sigma", c.peer_rotation_sigma);
    n.read("loop_translation_sigma", c.loop_translation_sigma);
    n.read("loop_rotation_sigma", c.loop_rotation_sigma);
    n.read("gravity_sigma", c.gravity_sigma);
    n.rejectUnknownKeys();  // before the checks below, which read every key
    for (const auto& k : n.keys()) n.requirePositive(k, n.get<double>(k));
  }
  if (root.has("objects")) {
    const ConfigNode n = root.child("objects");
    n.read("range_sigma", c.range_sigma);
    n.read("bearing_sigma", c.bearing_sigma);
    n.read("vertical_sigma", c.vertical_sigma);
    n.read("position_sigma_floor", c.position_sigma_floor);
    n.read("ellipsoid_partial_view", c.ellipsoid_partial_view);
    n.read("cuboid_rotation_sigma", c.cuboid_rotation_sigma);
    n.read("cuboid_dims_sigma", c.cuboid_dims_sigma);
    n.read("cylinder_along_axis_sigma", c.cylinder_along_axis_sigma);
    n.read("cylinder_axis_sigma", c.cylinder_axis_sigma);
    n.read("cylinder_radius_sigma", c.cylinder_radius_sigma);
    n.read("ellipsoid_size_ema", c.ellipsoid_size_ema);
    n.read("robust_loss_scale", c.robust_loss_scale);
    n.read("max_object_range_m", c.max_object_range_m);
    n.rejectUnknownKeys();  // before the checks below, which read every key
    for (const auto& k : n.keys()) n.requirePositive(k, n.get<double>(k));
    if (c.ellipsoid_size_ema > 1) n.fail("ellipsoid_size_ema", "must be in (0, 1]");
  }
  if (root.has("gates")) {
    const ConfigNode n = root.child("gates");
    n.read("max_robot_offset_m", c.max_robot_offset_m);
    n.rejectUnknownKeys();  // before the checks below, which read every key
    for (const auto& k : n.keys()) n.requirePositive(k, n.get<double>(k));
  }
  if (root.has("association")) {
    const ConfigNode n = root.child("association");
    n.read("min_observations", c.min_observations);
    n.read("association_sigmas", c.association_sigmas);
    n.read("association_gate", c.association_gate);
    if (c.association_gate < 0) n.fail("association_gate", "must not be negative (0 turns it off)");
    n.read("outlier_sigmas", c.outlier_sigmas);
    n.read("merge_within_shape", c.merge_within_shape);
    n.read("merge_shared_fraction", c.merge_shared_fraction);
    n.read("revisit_sigmas", c.revisit_sigmas);
    n.read("reading_vote_radius", c.reading_vote_radius);
    if (!(c.reading_vote_radius >= 0)) n.fail("reading_vote_radius", "must not be negative (0 turns it off)");
    if (!(c.merge_shared_fraction >= 0 && c.merge_shared_fraction < 1))
      n.fail("merge_shared_fraction", "must lie in [0, 1)");
    if (c.association_sigmas < 0) n.fail("association_sigmas", "must not be negative");
    if (!(c.revisit_sigmas >= 0)) n.fail("revisit_sigmas", "must not be negative");
    if (c.min_observations < 1) n.fail("min_observations", "must be at least 1");
  }
  if (root.has("peers")) {
    const ConfigNode n = root.child("peers");
    n.read("max_peers", c.max_peers);
    n.read("max_held_bundles", c.max_held_bundles);
    if (c.max_peers < 0) n.fail("max_peers", "must not be negative");
    if (c.max_held_bundles < 1) n.fail("max_held_bundles", "must be at least 1");
  }
  if (root.has("incremental")) {
    const ConfigNode n = root.child("incremental");
    n.read("window_poses", c.window_poses);
    n.read("local_iterations", c.local_iterations);
    n.read("local_function_tolerance", c.local_function_tolerance);
    n.read("settled_observations", c.settled_observations);
    n.read("full_iterations", c.full_iterations);
    n.read("loop_iterations", c.loop_iterations);
    c.spread_loops = n.get<bool>("spread_loops", c.spread_loops);
    n.read("final_iterations", c.final_iterations);
    n.read("full_every", c.full_every);
    n.read("loop_gap", c.loop_gap);
    n.read("min_full_gap", c.min_full_gap);
    n.read("full_function_tolerance", c.full_function_tolerance);
    n.read("final_function_tolerance", c.final_function_tolerance);
    n.read("full_trust_region_radius", c.full_trust_region_radius);
    n.read("num_threads", c.num_threads);
    n.rejectUnknownKeys();  // before the checks below, which read every key
    for (const auto& k : n.keys())
      if (k != "spread_loops" && !(n.get<double>(k) > 0)) n.fail(k, "must be positive");
  }
  if (root.has("soundness")) {
    const ConfigNode n = root.child("soundness");
    n.read("envelope_sigmas", c.envelope.gate_sigmas);
    n.read("envelope_floor_m", c.envelope.floor_m);
    n.read("envelope_floor_deg", c.envelope.floor_deg);
    c.guard_estimate = n.get<bool>("guard_estimate", c.guard_estimate);
    n.read("remerge_translation_m", c.remerge_translation_m);
    n.read("remerge_yaw_deg", c.remerge_yaw_deg);
    n.read("refine_until_shared", c.refine_until_shared);
    n.rejectUnknownKeys();  // before the checks below, which read every key
    for (const auto& k : n.keys())
      if (k != "guard_estimate" && !(n.get<double>(k) > 0)) n.fail(k, "must be positive");
  }
  root.rejectUnknownKeys();
  return c;
}

}  // namespace slide::backend
