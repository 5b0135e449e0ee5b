// slide-match: place recognition between two object-map text files; prints one JSON object
// with the transform mapping MAP_B's frame into MAP_A's, or found=false and the reason.
#include <cmath>
#include <cstdio>
#include <spdlog/spdlog.h>

#include "app/app.h"
#include "io/object_map_text.h"
#include "place/place_config.h"

namespace {
std::string jsonEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
      continue;
    }
    out += c;
  }
  return out;
}

void printJson(const std::string& method, const slide::place::PlaceResult& r) {
  const Eigen::Vector4d v = slide::xyzYawOf(r.T_a_b);
  std::printf("{\"found\": %s, \"method\": \"%s\"", r.found ? "true" : "false", method.c_str());
  if (r.found)
    std::printf(", \"x\": %.6f, \"y\": %.6f, \"z\": %.6f, \"yaw_deg\": %.6f", v[0], v[1], v[2], v[3] * 180.0 / M_PI);
  std::printf(", \"inliers\": %zu, \"residual_rms\": %.6f, \"chance_inliers\": %.3f, \"score\": %.1f", r.inliers.size(),
              r.residual_rms, r.chance_inliers, r.score);
  if (method == "slidegraph") std::printf(", \"associations\": %zu", r.associations);
  if (r.by_shape) std::printf(", \"by_shape\": true");
  if (r.found && r.by_tile_votes) std::printf(", \"by_tile_votes\": true");
  std::printf(", \"ms\": %.3f, \"budget_exhausted\": %s", r.ms, r.budget_exhausted ? "true" : "false");
  if (!r.found) std::printf(", \"reason\": \"%s\"", jsonEscape(r.reason).c_str());
  std::printf("}\n");
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Place recognition between two object maps (text: one object per line, 'label x y z [sx sy sz]').\n"
               "Prints one JSON object: found, x, y, z, yaw_deg (mapping MAP_B's frame into MAP_A's), inliers,\n"
               "residual_rms, ms, and reason when no transform is found.",
               "slide-match"};
  slide::app::CommonOptions common;
  slide::app::addCommonOptions(app, common);
  std::string method = "slidegraph", map_a, map_b, classes_path, config_path;
  double budget_ms = -1;
  app.add_option("--method", method, "slidegraph or slidematch")
      ->check(CLI::IsMember({"slidegraph", "slidematch"}))
      ->capture_default_str();
  app.add_option("--classes", classes_path, "Class table (default: config/classes.yaml)");
  app.add_option("--config", config_path, "Place-recognition parameters (default: config/place.yaml)");
  app.add_option("--budget-ms", budget_ms, "Time budget of either method in ms (overrides the config)");
  app.add_option("MAP_A", map_a, "Reference map")->required();
  app.add_option("MAP_B", map_b, "Map whose frame is found in MAP_A's")->required();
  return slide::app::runApp(app, common, argc, argv, [&]() {
    const slide::ClassTable classes =
        classes_path.empty() ? slide::ClassTable::loadDefault() : slide::ClassTable::load(classes_path);
    slide::place::PlaceConfig config =
        config_path.empty() ? slide::place::loadDefaultPlaceConfig() : slide::place::loadPlaceConfig(config_path);
    if (budget_ms >= 0) config.slidematch.budget_ms = config.slidegraph.budget_ms = budget_ms;
    std::vector<slide::place::Landmark> lms[2];
    const std::string paths[2] = {map_a, map_b};
    for (int k = 0; k < 2; ++k) {
      try {
        const slide::io::ObjectMapText text =
            slide::io::readObjectMapText(paths[k], classes, slide::io::MissingSize::Zero);
        for (const std::string& w : text.warnings) spdlog::warn("{}", w);
        lms[k] = slide::place::landmarksOf(text.map);
      } catch (const std::exception& e) {
        slide::place::PlaceResult r;
        r.reason = e.what();
        printJson(method, r);
        spdlog::error("{}", e.what());
        return 1;
      }
    }
    const slide::place::PlaceResult r =
        slide::place::recognizePlace(slide::place::parsePlaceMethod(method), lms[0], lms[1], config);
    printJson(method, r);
    return 0;
  });
}
