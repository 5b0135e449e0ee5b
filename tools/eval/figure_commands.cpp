// slide-eval transform, bandwidth and timing.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>

#include "commands.h"
#include "eval/bandwidth.h"
#include "eval/rpe.h"
#include "eval/stage_timing.h"
#include "eval/trajectory_file.h"
#include "eval/transform_error.h"
#include "io/numbers.h"

namespace slide {

namespace {
// A transform as 4 numbers (x y z yaw_deg), 7 (x y z qx qy qz qw) or 12 (3x4 row-major),
// separated by commas or spaces, given inline or as the content of a file.
Pose parseTransform(const std::string& arg, const char* what) {
  std::string text = arg;
  if (std::ifstream f(arg); f) {
    std::ostringstream s;
    s << f.rdbuf();
    text = s.str();
  }
  for (char& c : text)
    if (c == ',') c = ' ';
  std::vector<double> v;
  try {
    v = io::parseNumberList(text);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(what) + ": " + e.what());
  }
  if (v.size() == 4) return poseFromXyzYaw(v[0], v[1], v[2], v[3] * M_PI / 180);
  if (v.size() == 7) return poseFromPositionQuaternion({v[0], v[1], v[2]}, Eigen::Quaterniond(v[6], v[3], v[4], v[5]));
  if (v.size() == 12 || v.size() == 16) {
    Pose T = Pose::Identity();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) T.matrix()(r, c) = v[r * 4 + c];
    const Eigen::Matrix3d R = T.linear();
    if (!(R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-4) || R.determinant() < 0)
      throw std::invalid_argument(std::string(what) + ": the 3x3 part is not a rotation");
    return T;
  }
  throw std::invalid_argument(std::string(what) + ": expected 4 (x y z yaw_deg), 7 (x y z qx qy qz qw) or 12 (3x4) numbers, got " +
                              std::to_string(v.size()));
}
}  // namespace

EvalCommand addTransformCommand(CLI::App* cmd) {
  auto est = std::make_shared<std::string>();
  auto truth = std::make_shared<std::string>();
  cmd->add_option("--est", *est, "Estimated transform: 'x,y,z,yaw_deg', 'x y z qx qy qz qw', 3x4 matrix, or a file")
      ->required();
  cmd->add_option("--truth", *truth, "True transform, same forms")->required();
  return [=] {
    const Pose E = parseTransform(*est, "--est"), T = parseTransform(*truth, "--truth");
    const eval::TransformError e = eval::transformError(E, T);
    std::printf("transform error: translation %.4f m, yaw %.4f deg, rotation %.4f deg\n", e.translation_m, e.yaw_deg,
                e.rotation_deg);
    report::Json j;
    j["metric"] = "transform";
    j["translation_m"] = e.translation_m;
    j["yaw_deg"] = e.yaw_deg;
    j["rotation_deg"] = e.rotation_deg;
    return j;
  };
}

EvalCommand addBandwidthCommand(CLI::App* cmd) {
  struct Args {
    double bytes = -1, metres = -1;
    std::size_t landmarks = 0;
    std::vector<std::string> trajs;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--bytes", a->bytes, "Bytes sent (or received)")->required();
  cmd->add_option("--landmarks", a->landmarks, "Landmarks in the exchanged map");
  cmd->add_option("--metres", a->metres, "Distance travelled");
  cmd->add_option("--traj", a->trajs, "Trajectories (TUM/KITTI) whose path lengths add up to the distance");
  return [=] {
    double metres = a->metres;
    if (!a->trajs.empty()) {
      metres = 0;
      for (const auto& t : a->trajs) {
        std::vector<Pose> poses;
        for (const auto& p : eval::readTrajectory(t)) poses.push_back(p.pose);
        metres += eval::pathLength(poses);
      }
    }
    const eval::BandwidthFigures f = eval::bandwidthFigures(a->bytes, a->landmarks, std::max(0.0, metres));
    std::printf("bandwidth: %.0f bytes, %.1f bytes per landmark (%zu landmarks), %.1f bytes per metre (%.1f m)\n", f.bytes,
                f.bytes_per_landmark, a->landmarks, f.bytes_per_metre, std::max(0.0, metres));
    report::Json j;
    j["metric"] = "bandwidth";
    j["bytes"] = f.bytes;
    j["landmarks"] = a->landmarks;
    j["metres"] = std::max(0.0, metres);
    j["bytes_per_landmark"] = f.bytes_per_landmark;
    j["bytes_per_metre"] = f.bytes_per_metre;
    return j;
  };
}

EvalCommand addTimingCommand(CLI::App* cmd) {
  auto files = std::make_shared<std::vector<std::string>>();
  cmd->add_option("files", *files, "Files of 'stage value' lines (or one value a line), values in ms")
      ->required()
      ->check(CLI::ExistingFile);
  return [=] {
    std::map<std::string, std::vector<double>> samples;
    for (const auto& f : *files)
      for (auto& [stage, v] : eval::readStageSamples(f))
        samples[stage].insert(samples[stage].end(), v.begin(), v.end());
    std::printf("  %-24s %8s %10s %10s %10s %10s\n", "stage", "count", "median", "p99", "mean", "max");
    report::Json stages = report::Json::array();
    for (const eval::StageTiming& t : eval::stageTimings(samples)) {
      std::printf("  %-24s %8zu %10.3f %10.3f %10.3f %10.3f\n", t.stage.c_str(), t.count, t.median, t.p99, t.mean, t.max);
      report::Json s;
      s["stage"] = t.stage;
      s["count"] = t.count;
      s["median"] = t.median;
      s["p99"] = t.p99;
      s["mean"] = t.mean;
      s["max"] = t.max;
      stages.push_back(s);
    }
    report::Json j;
    j["metric"] = "timing";
    j["stages"] = stages;
    return j;
  };
}

}  // namespace slide
