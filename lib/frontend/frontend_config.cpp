#include "frontend/frontend_config.h"

#include <filesystem>
#include <limits>
#include <map>
#include <string>

#include "config/config.h"

namespace slide::frontend {

namespace {
// A path in the config, relative to the config file's folder unless absolute.
std::string pathNextTo(const ConfigNode& n, const std::string& key, const std::string& config_path) {
  const std::filesystem::path p = n.get<std::string>(key);
  return p.is_absolute() ? p.string() : (std::filesystem::path(config_path).parent_path() / p).string();
}

// Reads key into `v` when present; checks lo <= v <= hi (the bounds keep every loop over
// the value within the physical or algorithmic range it is meant for).
template <typename T>
void opt(const ConfigNode& n, const std::string& key, T& v, T lo = std::numeric_limits<T>::lowest(),
         T hi = std::numeric_limits<T>::max()) {
  if (!n.has(key)) return;
  v = n.get<T>(key);
  if (!(v >= lo)) n.fail(key, "must be at least " + std::to_string(lo));
  if (!(v <= hi)) n.fail(key, "must be at most " + std::to_string(hi));
}

void sixVector(const ConfigNode& n, const std::string& key, std::array<double, 6>& v) {
  if (!n.has(key)) return;
  const auto list = n.getList<double>(key, 6);
  for (int i = 0; i < 6; ++i) {
    if (list[i] < 0) n.fail(key, "values must be non-negative");
    v[i] = list[i];
  }
}

// A map of class name: value, each at least `min` (the class names are checked against the
// class table where it is known: the segmenter and the tracker).
std::map<std::string, double> loadByClass(const ConfigNode& parent, const std::string& key, double min) {
  std::map<std::string, double> out;
  if (!parent.has(key)) return out;
  const ConfigNode m = parent.child(key);
  if (m.size() > 0) parent.fail(key, "expected a map of class name: value, got a list");
  for (const std::string& name : m.keys()) {
    double v = 0;
    opt(m, name, v, min);
    out[name] = v;
  }
  return out;
}

void loadCluster(const ConfigNode& n, GridClusterParams& c) {
  opt(n, "cell", c.cell, 1e-3);
  opt(n, "min_points", c.min_points, 1);
}

void loadNotch(const ConfigNode& c, NotchSplitParams& p) {
  opt(c, "bin_deg", p.bin_deg, 0.01, 10.0);
  opt(c, "depth", p.depth, 0.0);
  opt(c, "min_side", p.min_side, 0.0);
  opt(c, "band_low", p.band_low, 0.0);
  opt(c, "band_high", p.band_high, p.band_low);
}

void loadFreeSpace(const ConfigNode& c, FreeSpaceParams& p) {
  opt(c, "cell", p.cell, 0.0);
  opt(c, "band_low", p.band_low, 0.0);
  opt(c, "band_high", p.band_high, p.band_low);
  opt(c, "margin", p.margin, 0.0);
  opt(c, "azimuth_step_deg", p.azimuth_step_deg, 0.05, 10.0);
}

void loadGeometric(const ConfigNode& n, GeometricSegmenterParams& g) {
  opt(n, "max_range", g.max_range, 1.0, 1000.0);
  opt(n, "emit_other", g.emit_other);
  opt(n, "other_max_roughness", g.other_max_roughness, 0.0);
  opt(n, "roughness_floor_factor", g.roughness_floor_factor, 0.0);
  opt(n, "roughness_cap_min", g.roughness_cap_min, 0.0);
  opt(n, "other_max_bottom", g.other_max_bottom, 0.0);
  opt(n, "other_max_occluded", g.other_max_occluded, 0.0, 1.0);
  opt(n, "other_max_continued", g.other_max_continued, 0.0, 1.0);
  opt(n, "other_face_max_width", g.other_face_max_width, 0.0, 10.0);
  opt(n, "other_split_length", g.other_split_length, 0.0, 100.0);
  opt(n, "other_split_min_points", g.other_split_min_points, 1, 1000000);
  opt(n, "other_not_column", g.other_not_column);
  opt(n, "other_max_slenderness", g.other_max_slenderness, 0.0, 100.0);
  opt(n, "other_max_height", g.other_max_height, 0.0, 10.0);
  opt(n, "other_confidence", g.other_confidence, 1e-3, 1.0);
  if (n.has("occlusion")) {
    const ConfigNode c = n.child("occlusion");
    opt(c, "window_deg", g.occlusion.window_deg, 0.0, 10.0);
    opt(c, "beam_tolerance_deg", g.occlusion.beam_tolerance_deg, 0.0, 5.0);
    opt(c, "min_gap", g.occlusion.min_gap, 0.0);
  }
  if (n.has("view_cut")) {
    const ConfigNode c = n.child("view_cut");
    opt(c, "tolerance_deg", g.view_cut.tolerance_deg, 0.0, 5.0);
    opt(c, "min_share", g.view_cut.min_share, 0.0, 1.0);
    opt(c, "range_tolerance", g.view_cut.range_tolerance, 0.0, 5.0);
    opt(c, "max_origin_height", g.view_cut.max_origin_height, 0.0, 2.0);
    opt(c, "max_beside_share", g.view_cut.max_beside_share, 0.0, 1.0);
    opt(c, "beside_range", g.view_cut.beside_range, 0.0, 5.0);
  }
  if (n.has("ground")) {
    const ConfigNode c = n.child("ground");
    opt(c, "cell", g.ground.cell, 0.05);
    opt(c, "window", g.ground.window, 0);
    opt(c, "threshold", g.ground.threshold, 0.0);
    opt(c, "min_cell_points", g.ground.min_cell_points, 1);
    opt(c, "max_step", g.ground.max_step, 0.0);
    opt(c, "max_rise", g.ground.max_rise, 0.0);
    opt(c, "under_tolerance", g.ground.under_tolerance, 0.0);
  }
  if (n.has("column")) {
    const ConfigNode c = n.child("column");
    auto& p = g.column;
    opt(c, "slice_low", p.slice_low, 0.0);
    opt(c, "slice_high", p.slice_high, p.slice_low + 0.1);
    opt(c, "slice_height", p.slice_height, 0.05);
    opt(c, "cell", p.cell, 0.02);
    opt(c, "min_blob_points", p.min_blob_points, 1);
    opt(c, "max_diameter", p.max_diameter, 0.05);
    opt(c, "stack_distance", p.stack_distance, 0.01);
    opt(c, "min_slices", p.min_slices, 1);
    opt(c, "min_span", p.min_span, 0.0);
    opt(c, "min_multi_point_slices", p.min_multi_point_slices, 0);
    opt(c, "max_lean_deg", p.max_lean_deg, 0.0);
    opt(c, "arc_min_extent", p.arc_min_extent, 0.0);
    opt(c, "arc_min_points", p.arc_min_points, 3);
    opt(c, "arc_inlier_distance", p.arc_inlier_distance, 1e-3);
    opt(c, "arc_min_inliers", p.arc_min_inliers, 0.0);
    opt(c, "arc_max_radius_ratio", p.arc_max_radius_ratio, 0.1);
    opt(c, "min_arc_fraction", p.min_arc_fraction, 0.0);
    opt(c, "min_top", p.min_top, 0.0);
    opt(c, "ceiling_margin", p.ceiling_margin, 0.0);
    opt(c, "max_height", p.max_height, 0.5);
    opt(c, "margin", p.margin, 0.0);
    opt(c, "min_points", p.min_points, 1);
    opt(c, "trunk_min_radius", p.trunk_min_radius, 0.0);
    opt(c, "isolation_gap", p.isolation_gap, 0.0);
    opt(c, "isolation_ring", p.isolation_ring, p.isolation_gap);
    opt(c, "max_ring_fraction", p.max_ring_fraction, 0.0);
    opt(c, "single_point_ring", p.single_point_ring, 0.0);
    opt(c, "canopy_radius", p.canopy_radius, 0.0);
    opt(c, "canopy_min_fraction", p.canopy_min_fraction, 0.0);
    opt(c, "ceiling_max_spread", p.ceiling_max_spread, 0.0);
    opt(c, "ceiling_min_points", p.ceiling_min_points, 1);
    opt(c, "ceiling_full_range", p.ceiling_full_range, 0.0);
    opt(c, "ceiling_min_points_far", p.ceiling_min_points_far, 1);
    opt(c, "ceiling_min_above", p.ceiling_min_above, 0);
    opt(c, "end_margin", p.end_margin, 0.0);
    opt(c, "unsure_confidence", p.unsure_confidence, 0.0, 1.0);
    if (c.has("wall")) {
      const ConfigNode w = c.child("wall");
      auto& q = p.wall;
      opt(w, "window_deg", q.window_deg, 0.0, 10.0);
      opt(w, "window_length", q.window_length, 0.0);
      opt(w, "beam_tolerance_deg", q.beam_tolerance_deg, 0.0, 5.0);
      opt(w, "max_step", q.max_step, 0.0);
      opt(w, "line_tolerance", q.line_tolerance, 0.0);
      opt(w, "max_step_ratio", q.max_step_ratio, 1.0);
      opt(w, "corner_run", q.corner_run, 0.0);
      opt(w, "max_run_returns", q.max_run_returns, 2, 100);
      opt(w, "min_fraction", q.min_fraction, 0.0, 1.0);
    }
  }
  if (n.has("car")) {
    const ConfigNode c = n.child("car");
    auto& p = g.car;
    opt(c, "height_cap", p.height_cap, 0.5);
    opt(c, "cell", p.cell, 0.02);
    opt(c, "min_points", p.min_points, 1);
    opt(c, "min_top", p.min_top, 0.0);
    opt(c, "max_top", p.max_top, p.min_top);
    opt(c, "max_bottom", p.max_bottom, 0.0);
    opt(c, "max_range", p.max_range, 0.0);
    opt(c, "min_length", p.min_length, 0.0);
    opt(c, "max_length", p.max_length, p.min_length);
    opt(c, "max_width", p.max_width, 0.0);
    opt(c, "min_split_cell", p.min_split_cell, 0.02);
    opt(c, "max_split_length", p.max_split_length, 0.0);
    opt(c, "gap_cell", p.gap_cell, 0.0);
    opt(c, "gap_angle_deg", p.gap_angle_deg, 0.0);
    opt(c, "gap_min_points", p.gap_min_points, 1);
    if (c.has("notch")) loadNotch(c.child("notch"), p.notch);
    opt(c, "max_roughness", p.max_roughness, 0.0);
    opt(c, "max_edge_spread", p.max_edge_spread, 0.0);
    opt(c, "max_covered", p.max_covered, 0.0, 1.0);
    opt(c, "cover_height", p.cover_height, 0.0);
    opt(c, "max_hidden_bottom", p.max_hidden_bottom, 0.0, 1.0);
    opt(c, "hidden_below", p.hidden_below, 0.0);
    opt(c, "hidden_margin", p.hidden_margin, 0.0);
    opt(c, "max_ground_rise", p.max_ground_rise, 0.0);
    opt(c, "min_points_far", p.min_points_far, 1);
    opt(c, "near_range", p.near_range, 0.0);
    opt(c, "seen_ground_search", p.seen_ground_search, 0.0);
    opt(c, "seen_ground_rise", p.seen_ground_rise, 0.0);
    opt(c, "seen_ground_slope", p.seen_ground_slope, 0.0);
  }
  if (n.has("free_space")) loadFreeSpace(n.child("free_space"), g.free_space);
  if (n.has("other_cluster")) loadCluster(n.child("other_cluster"), g.other_cluster);
}

void loadFit(const ConfigNode& n, FitParams& f) {
  if (n.has("cylinder")) {
    const ConfigNode c = n.child("cylinder");
    auto& p = f.cylinder;
    opt(c, "slice_height", p.slice_height, 0.02);
    opt(c, "min_slice_points", p.min_slice_points, 3);
    opt(c, "max_height", p.max_height, 0.1);
    opt(c, "breast_height", p.breast_height, 0.0);
    opt(c, "breast_window", p.breast_window, 0.0);
    opt(c, "min_inlier_ratio", p.min_inlier_ratio, 0.0);
    opt(c, "max_lean_deg", p.max_lean_deg, 0.0);
    opt(c, "min_axis_span", p.min_axis_span, 0.0);
    opt(c, "min_points", p.min_points, 3);
    opt(c, "ransac_iterations", p.ransac.iterations, 1, 100000);
    opt(c, "inlier_distance", p.ransac.inlier_distance, 1e-4);
    opt(c, "min_radius", p.ransac.min_radius, 1e-3);
    opt(c, "max_radius", p.ransac.max_radius, p.ransac.min_radius);
  }
  if (n.has("cuboid")) {
    const ConfigNode c = n.child("cuboid");
    auto& p = f.cuboid;
    opt(c, "low_percentile", p.low_percentile, 0.0);
    opt(c, "high_percentile", p.high_percentile, p.low_percentile);
    opt(c, "face_band", p.face_band, 0.0, 1.0);
    opt(c, "face_min_span", p.face_min_span, 0.0, 100.0);
    opt(c, "footprint_cell", p.footprint_cell, 1e-3);
    opt(c, "yaw_step_deg", p.yaw_step_deg, 0.0, 45.0);
    if (p.yaw_step_deg > 0 && p.yaw_step_deg < 0.1) c.fail("yaw_step_deg", "must be 0 (off) or at least 0.1");
    opt(c, "min_visible_fraction", p.min_visible_fraction, 0.0);
    opt(c, "size_tolerance", p.size_tolerance, 1.0);
    opt(c, "complete_fraction", p.complete_fraction, 0.0, 1.0);
    opt(c, "free_cells_to_move", p.free_cells_to_move, 0);
    opt(c, "free_step", p.free_step, 0.01);
    opt(c, "free_cells_to_swap", p.free_cells_to_swap, 0);
    opt(c, "min_points", p.min_points, 3);
  }
  if (n.has("ellipsoid")) {
    const ConfigNode c = n.child("ellipsoid");
    auto& p = f.ellipsoid;
    opt(c, "radius_percentile", p.radius_percentile, 0.0);
    opt(c, "low_percentile", p.low_percentile, 0.0);
    opt(c, "high_percentile", p.high_percentile, p.low_percentile);
    opt(c, "min_points", p.min_points, 1);
    opt(c, "slice_height", p.slice_height, 0.01);
    opt(c, "min_slice_points", p.min_slice_points, 3);
    opt(c, "slice_percentile", p.slice_percentile, 0.0, 0.49);
    opt(c, "widest_fraction", p.widest_fraction, 0.0, 1.0);
    opt(c, "max_sin_half_angle", p.max_sin_half_angle, 0.1, 0.99);
  }
}
}  // namespace

FrontendConfig loadFrontendConfig(const std::string& path) {
  const ConfigNode root = ConfigNode::load(path);
  FrontendConfig cfg;
  if (root.has("segmenter")) {
    const ConfigNode s = root.child("segmenter");
    if (s.has("lidar_mode")) {
      cfg.lidar_mode = s.get<std::string>("lidar_mode");
      if (cfg.lidar_mode != "auto" && cfg.lidar_mode != "labelled" && cfg.lidar_mode != "geometric" &&
          cfg.lidar_mode != "learned")
        s.fail("lidar_mode", "expected one of auto, labelled, geometric, learned, got '" + cfg.lidar_mode + "'");
    }
    if (s.has("learned")) {
      const ConfigNode c = s.child("learned");
      auto& p = cfg.learned;
      if (c.has("model")) p.model = pathNextTo(c, "model", path);
      opt(c, "min_confidence", p.min_confidence, 0.0, 1.0);
      auto optional = [&](const char* key, auto& v, double lo, double hi) {
        if (!c.has(key)) return;
        typename std::decay_t<decltype(v)>::value_type x{};
        opt(c, key, x, decltype(x)(lo), decltype(x)(hi));
        v = x;
      };
      optional("height", p.height, 1, 4096);
      optional("width", p.width, 1, 65536);
      optional("fov_up_deg", p.fov_up_deg, -90, 90);
      optional("fov_down_deg", p.fov_down_deg, -90, 90);
    }
    if (s.has("labelled")) {
      const ConfigNode c = s.child("labelled");
      opt(c, "min_points", cfg.labelled.min_points, 1);
      opt(c, "max_range", cfg.labelled.max_range, 1.0);
      opt(c, "merge_cylinders", cfg.labelled.merge_cylinders);
      opt(c, "min_height_fraction", cfg.labelled.min_height_fraction, 0.0);
      opt(c, "vote_cell", cfg.labelled.vote_cell, 0.0);
      if (c.has("cluster")) loadCluster(c.child("cluster"), cfg.labelled.cluster);
      if (c.has("gap_cluster")) loadCluster(c.child("gap_cluster"), cfg.labelled.gap_cluster);
      opt(c, "min_split_cell", cfg.labelled.min_split_cell, 1e-3);
      opt(c, "cuboid_ground_strip", cfg.labelled.cuboid_ground_strip, 0.0);
      opt(c, "ground_cell", cfg.labelled.ground_cell, 0.05);
      if (c.has("ground_labels")) cfg.labelled.ground_labels = c.getList<int>("ground_labels");
      if (c.has("notch")) loadNotch(c.child("notch"), cfg.labelled.notch);
      if (c.has("free_space")) loadFreeSpace(c.child("free_space"), cfg.labelled.free_space);
      if (c.has("cluster_cell_by_class")) cfg.labelled.cluster_cell_by_class = loadByClass(c, "cluster_cell_by_class", 1e-3);
      if (c.has("ellipsoid_join")) {
        const ConfigNode j = c.child("ellipsoid_join");
        auto& o = cfg.labelled.ellipsoid_join;
        opt(j, "max_gap", o.max_gap, 0.0, 10.0);
        opt(j, "min_nearer", o.min_nearer, 0.0);
        opt(j, "min_returns", o.min_returns, 1);
        opt(j, "min_share", o.min_share, 0.0, 1.0);
        opt(j, "stacked_overlap", o.stacked_overlap, 0.0, 1.0);
      }
      opt(c, "other_confidence", cfg.labelled.other_confidence, 1e-3, 1.0);
      if (c.has("catch_all_debris")) {
        const ConfigNode j = c.child("catch_all_debris");
        opt(j, "radius", cfg.labelled.catch_all_debris.radius, 0.0, 10.0);
        opt(j, "max_share", cfg.labelled.catch_all_debris.max_share, 0.0, 1.0);
      }
    }
    if (s.has("geometric")) loadGeometric(s.child("geometric"), cfg.geometric);
    if (s.has("rgbd")) {
      const ConfigNode c = s.child("rgbd");
      auto& p = cfg.rgbd;
      opt(c, "min_confidence", p.min_confidence, 0.0);
      opt(c, "band_fraction", p.band_fraction, 0.0);
      if (p.band_fraction > 1.0) c.fail("band_fraction", "must be at most 1");
      opt(c, "band_margin", p.band_margin, 0.0);
      opt(c, "min_depth", p.min_depth, 0.0);
      opt(c, "max_depth", p.max_depth, p.min_depth);
      opt(c, "median_radius", p.median_radius, 0);
      opt(c, "stride", p.stride, 1);
      opt(c, "erode_px", p.erode_px, 0);
      opt(c, "restore_edges", p.restore_edges);
      opt(c, "min_points", p.min_points, 1);
      if (c.has("detector")) cfg.rgbd_detector = c.get<std::string>("detector").empty() ? "" : pathNextTo(c, "detector", path);
    }
  }
  if (root.has("fit")) loadFit(root.child("fit"), cfg.fit);
  if (root.has("tracker")) {
    const ConfigNode c = root.child("tracker");
    auto& p = cfg.tracker;
    opt(c, "gate_scale", p.gate_scale, 1e-3);
    opt(c, "min_age", p.min_age, 1);
    opt(c, "max_missed", p.max_missed, 0);
    opt(c, "report_max_missed", p.report_max_missed, 0);
    opt(c, "report_max_range", p.report_max_range, 0.0);
    if (c.has("report_max_range_by_class")) p.report_max_range_by_class = loadByClass(c, "report_max_range_by_class", 0.0);
    opt(c, "max_observations", p.max_observations, 1);
    opt(c, "max_points_per_observation", p.max_points_per_observation, 10);
    opt(c, "moving_tolerance", p.moving_tolerance, 1.0);
    opt(c, "moving_vacated_share", p.moving_vacated_share, 0.0, 1.0);
    opt(c, "moving_vacated_min_points", p.moving_vacated_min_points, 1);
    opt(c, "moving_vacated_depth", p.moving_vacated_depth, 0.0, 2.0);
    opt(c, "moving_shift", p.moving_shift, 0.0);
    opt(c, "moving_shift_interval", p.moving_shift_interval, 0.0, 10.0);
    opt(c, "moving_shift_max_interval", p.moving_shift_max_interval, 0.0, 60.0);
    opt(c, "moving_shift_reach", p.moving_shift_reach, 0.0, 50.0);
    opt(c, "moving_predict", p.moving_predict);
    opt(c, "moving_shift_similarity", p.moving_shift_similarity, 1.0);
    opt(c, "moving_shift_quantile", p.moving_shift_quantile, 0.0, 0.5);
    opt(c, "moving_shift_min_points", p.moving_shift_min_points, 1);
    opt(c, "split_distance", p.split_distance, 0.0, 5.0);
    opt(c, "split_min_points", p.split_min_points, 1);
    opt(c, "split_min_gap", p.split_min_gap, 0.0, 5.0);
    opt(c, "join_share", p.join_share, 0.0, 1.0);
    opt(c, "merge_same_shape", p.merge_same_shape);
    opt(c, "column_merge_distance", p.column_merge_distance, 0.0);
    opt(c, "catch_all_merge_distance", p.catch_all_merge_distance, 0.0);
    opt(c, "drop_oversized", p.drop_oversized);
    opt(c, "box_merge_width", p.box_merge_width, 0.0);
    opt(c, "box_merge_growth", p.box_merge_growth, 0.0);
    opt(c, "box_merge_view_quantile", p.box_merge_view_quantile, 0.0, 1.0);
    opt(c, "parallel_radius", p.parallel_radius, 0.0);
    opt(c, "parallel_fallback_radius", p.parallel_fallback_radius, 0.0);
    opt(c, "box_overlap", p.box_overlap, 0.0, 1.0);
    opt(c, "box_same_centre", p.box_same_centre, 0.0);
    opt(c, "ellipsoid_view_growth", p.ellipsoid_view_growth, 0.0);
    opt(c, "box_across", p.box_across, 0.0, 1.0);
    opt(c, "ellipsoid_same_place", p.ellipsoid_same_place, 0.0);
  }
  if (root.has("keypose")) {
    const ConfigNode c = root.child("keypose");
    opt(c, "distance", cfg.keypose.distance, 0.0);
    opt(c, "yaw_deg", cfg.keypose.yaw_deg, 0.0);
    sixVector(c, "sigma_min", cfg.keypose.sigma_min);
    sixVector(c, "sigma_per_m", cfg.keypose.sigma_per_m);
  }
  root.rejectUnknownKeys();
  return cfg;
}

FrontendConfig loadDefaultFrontendConfig() { return loadFrontendConfig(std::string(SLIDE_SOURCE_DIR) + "/config/frontend.yaml"); }

}  // namespace slide::frontend
