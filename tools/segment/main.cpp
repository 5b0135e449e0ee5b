// slide-segment: one LiDAR scan through the segmenter and the shape fits. Prints the objects
// found as JSON, optionally draws them over the points (top view) and, with SemanticKITTI
// labels, scores them against the labelled objects.
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "app/app.h"
#include "eval/labelled_scan_score.h"
#include "frontend/frontend_config.h"
#include "frontend/geometric_segmenter.h"
#include "frontend/labelled_segmenter.h"
#include "frontend/range_net_labeler.h"
#include "frontend/xyz_cloud.h"
#include "io/io_error.h"
#include "io/kitti_scan.h"
#include "io/pcd_file.h"
#include "plot/map_plot.h"

using namespace slide;

namespace {
bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// KITTI .bin, PCD, or text "x y z [intensity]" by the file's extension.
io::LabelledScan readScan(const std::string& path) {
  const std::string l = lower(path);
  if (endsWith(l, ".bin")) return io::readVelodyneBin(path);
  if (endsWith(l, ".pcd")) return io::readPcdFile(path);
  io::LabelledScan scan;
  scan.xyz = frontend::readXyzCloud(path);
  scan.intensity.assign(scan.xyz.size(), 0.0f);
  return scan;
}

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\', out += c;
    else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else out += c;
  }
  return out + "\"";
}

std::string vec(const Eigen::Vector3d& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "[%.3f, %.3f, %.3f]", v.x(), v.y(), v.z());
  return buf;
}

struct Found {
  Object object;
  int points = 0;
};

std::string toJson(const std::string& scan_path, const std::string& mode, std::size_t num_points, double ms,
                   const std::vector<Found>& found, int unfitted, const ClassTable& classes,
                   const eval::ScanScore* score, const std::vector<frontend::ColumnRejection>& rejected) {
  std::ostringstream o;
  o << "{\n  \"scan\": " << jsonString(scan_path) << ",\n  \"mode\": " << jsonString(mode)
    << ",\n  \"points\": " << num_points << ",\n  \"segment_fit_ms\": " << ms << ",\n  \"unfitted_instances\": " << unfitted
    << ",\n  \"objects\": [";
  for (std::size_t k = 0; k < found.size(); ++k) {
    const Object& ob = found[k].object;
    o << (k ? ",\n" : "\n") << "    {\"class\": " << jsonString(classes.at(ob.class_id).name) << ", \"class_id\": " << ob.class_id
      << ", \"shape\": " << jsonString(shapeName(ob.shape())) << ", \"position\": " << vec(ob.position())
      << ", \"size\": " << vec(ob.extent());
    if (const auto* c = std::get_if<Cuboid>(&ob.model)) o << ", \"yaw_deg\": " << yawOf(c->pose.linear()) * 180.0 / M_PI;
    if (const auto* c = std::get_if<Cylinder>(&ob.model)) o << ", \"radius\": " << c->radius;
    o << ", \"points\": " << found[k].points;
    if (score) o << ", \"verdict\": " << jsonString(eval::verdictName(score->verdicts[k]));
    o << "}";
  }
  o << (found.empty() ? "]" : "\n  ]");
  if (score) {
    auto tally = [&](const char* name, const eval::ShapeTally& t) {
      o << "    " << jsonString(name) << ": {\"targets\": " << t.targets << ", \"found\": " << t.found
        << ", \"estimates\": " << t.estimates << ", \"duplicates\": " << t.duplicates << ", \"small\": " << t.small
        << ", \"false\": " << t.false_estimates << "}";
    };
    o << ",\n  \"score\": {\n";
    tally("cars", score->cars);
    o << ",\n";
    tally("trunks_poles", score->columns);
    o << ",\n";
    tally("others", score->others);
    o << ",\n    \"targets\": [";
    for (std::size_t t = 0; t < score->targets.size(); ++t) {
      const auto& g = score->targets[t];
      o << (t ? ",\n" : "\n") << "      {\"class\": " << jsonString(classes.at(g.class_id).name) << ", \"instance\": " << g.instance
        << ", \"points\": " << g.points << ", \"centroid\": " << vec(g.centroid) << ", \"found\": " << (g.estimate >= 0 ? "true" : "false");
      if (g.estimate >= 0) o << ", \"object\": " << g.estimate << ", \"distance\": " << g.distance;
      o << "}";
    }
    o << (score->targets.empty() ? "]" : "\n    ]") << "\n  }";
  }
  if (!rejected.empty()) {
    o << ",\n  \"rejected_columns\": [";
    for (std::size_t k = 0; k < rejected.size(); ++k)
      o << (k ? ",\n" : "\n") << "    {\"x\": " << rejected[k].centre.x() << ", \"y\": " << rejected[k].centre.y()
        << ", \"reason\": " << jsonString(rejected[k].reason) << "}";
    o << "\n  ]";
  }
  o << "\n}\n";
  return o.str();
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "One LiDAR scan (KITTI .bin, .pcd, or text 'x y z [intensity]' per line) through the segmenter and the shape "
      "fits: prints the objects found (class, position, size) as JSON; --plot draws them over the points (top "
      "view); --labels (SemanticKITTI .label) scores them against the labelled cars (>= 200 points), "
      "trunk/pole point groups and groups of other things (bicycles, people, other objects; >= 30 points each). Exit code 1 for an unreadable file (the message names it)."};
  app::CommonOptions common;
  common.log_level = "warn";
  app::addCommonOptions(app, common);
  std::string scan_path, labels_path, mode = "geometric", plot_path, json_path, config_file, classes_file;
  bool explain = false;
  std::vector<double> sensor_fov;
  app.add_option("scan", scan_path, "Scan file: .bin (KITTI float32 x y z i), .pcd, or text")->required();
  app.add_option("--labels", labels_path, "SemanticKITTI .label file of the scan: score the objects against it");
  app.add_option("--mode", mode,
                 "geometric (label-free), learned (the range-image model of the config's segmenter.learned labels the "
                 "points) or labelled (segments the labels; needs --labels)")
      ->check(CLI::IsMember({"geometric", "learned", "labelled"}))
      ->capture_default_str();
  app.add_option("--sensor-fov", sensor_fov,
                 "Learned mode: the scan's vertical field of view UP DOWN in degrees, overriding the config "
                 "(KITTI's HDL-64E: 3 -25; Ouster OS1-64: 16.6 -16.6)")
      ->expected(2);
  app.add_option("--plot", plot_path, "Draw the points and objects, top view (.png or .svg)");
  app.add_option("--json", json_path, "Also write the JSON to this file");
  app.add_option("--config", config_file, "Front-end YAML (default: config/frontend.yaml)");
  app.add_option("--classes", classes_file, "Class table YAML (default: config/classes.yaml)");
  app.add_flag("--explain", explain, "Geometric mode: also list the column candidates turned down and why");
  return app::runApp(app, common, argc, argv, [&]() {
    const ClassTable classes = classes_file.empty() ? ClassTable::loadDefault() : ClassTable::load(classes_file);
    const frontend::FrontendConfig cfg =
        config_file.empty() ? frontend::loadDefaultFrontendConfig() : frontend::loadFrontendConfig(config_file);
    io::LabelledScan scan = readScan(scan_path);
    if (scan.size() == 0) throw io::IoError(scan_path, "no points");
    if (!labels_path.empty()) {
      io::readLabels(labels_path, scan);
    } else if (mode == "labelled") {
      throw std::invalid_argument("--mode labelled needs --labels");
    }
    io::LabelledScan input = scan;
    if (mode != "labelled") input.semantic.clear(), input.instance.clear();  // the segmenter never sees labels
    frontend::LearnedLidarParams learned_params = cfg.learned;
    if (!sensor_fov.empty()) learned_params.fov_up_deg = sensor_fov[0], learned_params.fov_down_deg = sensor_fov[1];
    const std::optional<frontend::LearnedLidarSegmenter> learned =
        mode == "learned" ? std::optional<frontend::LearnedLidarSegmenter>(
                                std::in_place, frontend::RangeNetLabeler::fromParams(learned_params),
                                std::make_shared<frontend::LabelledSegmenter>(classes, cfg.labelled))
                          : std::nullopt;

    frontend::InputIssues issues;
    std::vector<frontend::ColumnRejection> rejected;
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<frontend::Instance> instances;
    if (mode == "geometric") {
      instances =
          frontend::GeometricSegmenter(classes, cfg.geometric).segment(input, issues, explain ? &rejected : nullptr);
    } else if (learned) {
      instances = learned->segment(input, issues);
    } else {
      instances = frontend::LabelledSegmenter(classes, cfg.labelled).segment(input, issues);
    }
    std::vector<Found> found;
    int unfitted = 0;
    for (const auto& inst : instances) {
      if (auto o = frontend::fitObject(inst.points, inst.class_id, classes, cfg.fit, Eigen::Vector3d::Zero(), nullptr,
                                       nullptr, &inst.free_space)) {
        o->id = inst.id;
        found.push_back({*o, static_cast<int>(inst.points.size())});
      } else {
        ++unfitted;
      }
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    for (const auto& [what, n] : issues.counts()) spdlog::warn("{}: {} x {}", scan_path, n, what);

    std::optional<eval::ScanScore> score;
    if (scan.hasLabels()) {
      std::vector<Object> objects;
      for (const auto& f : found) objects.push_back(f.object);
      score = eval::scoreScanAgainstLabels(scan, objects, classes);
    }
    const std::string json = toJson(scan_path, mode, scan.size(), ms, found, unfitted, classes, score ? &*score : nullptr, rejected);
    std::fputs(json.c_str(), stdout);
    if (!json_path.empty()) {
      std::ofstream out(json_path);
      if (!(out << json)) throw io::IoError(json_path, "cannot write");
    }
    if (!plot_path.empty()) {
      plot::MapPlotOptions opts;
      opts.title = scan_path;
      char sub[200];
      std::snprintf(sub, sizeof sub, "%s mode: %zu objects from %zu points", mode.c_str(), found.size(), scan.size());
      opts.subtitle = sub;
      if (score) {
        std::snprintf(sub, sizeof sub, "; cars %d/%d, trunks/poles %d/%d, other things %d/%d found; false: %d cuboids, %d cylinders, %d ellipsoids",
                      score->cars.found, score->cars.targets, score->columns.found, score->columns.targets, score->others.found,
                      score->others.targets, score->cars.false_estimates, score->columns.false_estimates, score->others.false_estimates);
        opts.subtitle += sub;
        for (const auto& t : score->targets) {
          if (t.estimate >= 0) opts.overlay.matches.emplace_back(found[t.estimate].object.position(), t.centroid);
          else opts.overlay.missed.push_back(t.centroid);
        }
        for (std::size_t k = 0; k < found.size(); ++k)
          if (score->verdicts[k] == eval::EstimateVerdict::False)
            opts.overlay.false_positives.push_back(found[k].object.position());
      }
      const double r2 = cfg.geometric.max_range * cfg.geometric.max_range;
      for (const auto& p : scan.xyz)
        if (p.allFinite() && double(p.x()) * p.x() + double(p.y()) * p.y() <= r2) opts.points.push_back(p.cast<double>());
      plot::PlotMap m{mode + " objects", {}, 0, false};
      for (const auto& f : found) m.objects.push_back(f.object);
      plot::plotMap({m}, {}, classes, opts).write(plot_path);
      spdlog::info("wrote {}", plot_path);
    }
    return 0;
  });
}
