#include "backend/backend_config.h"

#include "config/config.h"

namespace slide {

namespace {
template <typename T>
void read(const ConfigNode& n, const std::string& key, T& value) {
  value = n.get<T>(key, value);
}
void positive(const ConfigNode& n, const std::string& key, double v) {
  if (!(v > 0)) n.fail(key, "must be positive");
}
}  // namespace

BackendConfig loadBackendConfig(const std::string& path) {
  const ConfigNode root = ConfigNode::load(path);
  BackendConfig c;
  if (root.has("odometry")) {
    const ConfigNode n = root.child("odometry");
    read(n, "use_message_sigma", c.use_message_sigma);
    read(n, "translation_per_m", c.odom_translation_per_m);
    read(n, "rotation_per_m", c.odom_rotation_per_m);
    read(n, "translation_floor", c.odom_translation_floor);
    read(n, "rotation_floor", c.odom_rotation_floor);
    read(n, "max_step_m", c.max_step_m);
    read(n, "max_step_rad", c.max_step_rad);
    for (const char* k : {"translation_floor", "rotation_floor", "max_step_m", "max_step_rad"})
      if (n.has(k)) positive(n, k, n.get<double>(k));
  }
  if (root.has("priors")) {
    const ConfigNode n = root.child("priors");
    read(n, "first_translation_sigma", c.prior_translation_sigma);
    read(n, "first_rotation_sigma", c.prior_rotation_sigma);
    read(n, "peer_translation_sigma", c.peer_translation_sigma);
    read(n, "peer_rotation_sigma", c.peer_rotation_sigma);
    read(n, "loop_translation_sigma", c.loop_translation_sigma);
    read(n, "loop_rotation_sigma", c.loop_rotation_sigma);
    for (const auto& k : n.keys()) positive(n, k, n.get<double>(k));
  }
  if (root.has("objects")) {
    const ConfigNode n = root.child("objects");
    read(n, "range_sigma", c.range_sigma);
    read(n, "bearing_sigma", c.bearing_sigma);
    read(n, "vertical_sigma", c.vertical_sigma);
    read(n, "position_sigma_floor", c.position_sigma_floor);
    read(n, "cuboid_rotation_sigma", c.cuboid_rotation_sigma);
    read(n, "cuboid_dims_sigma", c.cuboid_dims_sigma);
    read(n, "cylinder_along_axis_sigma", c.cylinder_along_axis_sigma);
    read(n, "cylinder_axis_sigma", c.cylinder_axis_sigma);
    read(n, "cylinder_radius_sigma", c.cylinder_radius_sigma);
    read(n, "ellipsoid_size_ema", c.ellipsoid_size_ema);
    read(n, "robust_loss_scale", c.robust_loss_scale);
    for (const auto& k : n.keys()) positive(n, k, n.get<double>(k));
    if (c.ellipsoid_size_ema > 1) n.fail("ellipsoid_size_ema", "must be in (0, 1]");
  }
  if (root.has("association")) {
    const ConfigNode n = root.child("association");
    read(n, "min_observations", c.min_observations);
    read(n, "association_sigmas", c.association_sigmas);
    read(n, "association_gate", c.association_gate);
    if (c.association_gate < 0) n.fail("association_gate", "must not be negative (0 turns it off)");
    read(n, "outlier_sigmas", c.outlier_sigmas);
    if (c.association_sigmas < 0) n.fail("association_sigmas", "must not be negative");
    if (c.min_observations < 1) n.fail("min_observations", "must be at least 1");
  }
  if (root.has("incremental")) {
    const ConfigNode n = root.child("incremental");
    read(n, "window_poses", c.window_poses);
    read(n, "local_iterations", c.local_iterations);
    read(n, "settled_observations", c.settled_observations);
    read(n, "full_iterations", c.full_iterations);
    read(n, "loop_iterations", c.loop_iterations);
    read(n, "final_iterations", c.final_iterations);
    read(n, "full_every", c.full_every);
    read(n, "loop_gap", c.loop_gap);
    read(n, "min_full_gap", c.min_full_gap);
    read(n, "full_function_tolerance", c.full_function_tolerance);
    read(n, "final_function_tolerance", c.final_function_tolerance);
    read(n, "num_threads", c.num_threads);
    for (const auto& k : n.keys())
      if (!(n.get<double>(k) > 0)) n.fail(k, "must be positive");
  }
  return c;
}

}  // namespace slide
