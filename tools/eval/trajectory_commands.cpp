// slide-eval ate and rpe.
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <memory>

#include "commands.h"
#include "eval/ate.h"
#include "eval/rpe.h"
#include "eval/time_association.h"
#include "eval/trajectory_file.h"
#include "eval/trajectory_warnings.h"
#include "io/io_error.h"

namespace slide {

namespace {

struct PairArgs {
  std::string est, ref, format = "auto", est_times, ref_times;
  bool kitti_lidar = false;
  double max_dt = 0.01, offset = 0.0;
};

void addPairOptions(CLI::App* cmd, PairArgs& a) {
  cmd->add_option("est", a.est, "Estimated trajectory (TUM or KITTI poses)")->required()->check(CLI::ExistingFile);
  cmd->add_option("ref", a.ref, "Reference (ground-truth) trajectory")->required()->check(CLI::ExistingFile);
  cmd->add_option("--format", a.format, "auto (by columns: 8 TUM, 12 KITTI), tum or kitti")
      ->check(CLI::IsMember({"auto", "tum", "kitti"}))
      ->capture_default_str();
  cmd->add_option("--est-times", a.est_times, "KITTI times file of the estimate (KITTI poses only; default frame index)");
  cmd->add_option("--ref-times", a.ref_times, "KITTI times file of the reference");
  cmd->add_flag("--kitti-lidar", a.kitti_lidar, "Convert KITTI camera poses to the LiDAR frame (04-10 calibration)");
  cmd->add_option("--max-dt", a.max_dt, "Largest time difference of associated poses, seconds")->capture_default_str();
  cmd->add_option("--offset", a.offset, "Added to the estimate's stamps before association, seconds")->capture_default_str();
}

eval::AssociatedPoses loadPair(const PairArgs& a, std::size_t* n_est, std::size_t* n_ref) {
  eval::TrajectoryReadOptions o;
  o.format = eval::parseTrajectoryFormat(a.format);
  o.kitti_lidar = a.kitti_lidar;
  o.kitti_times = a.est_times;
  const auto est = eval::readTrajectory(a.est, o);
  o.kitti_times = a.ref_times;
  const auto ref = eval::readTrajectory(a.ref, o);
  *n_est = est.size();
  *n_ref = ref.size();
  try {
    return eval::associatePoses(est, ref, a.max_dt, a.offset, 3);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(e.what()) +
                                "; KITTI poses are stamped by frame index unless --est-times/--ref-times are given, "
                                "and --offset shifts the estimate's stamps");
  }
}

report::Json poseJson(const Pose& T) {
  const Eigen::Quaterniond q(T.linear());
  report::Json j;
  j["x"] = T.translation().x();
  j["y"] = T.translation().y();
  j["z"] = T.translation().z();
  j["qx"] = q.x();
  j["qy"] = q.y();
  j["qz"] = q.z();
  j["qw"] = q.w();
  j["yaw_deg"] = yawOf(T.linear()) * 180 / M_PI;
  return j;
}

// Logs each warning (and prints it under the figures) and returns them as a JSON array.
report::Json warnings(std::initializer_list<std::optional<std::string>> found) {
  report::Json out = report::Json::array();
  for (const auto& w : found) {
    if (!w) continue;
    spdlog::warn("{}", *w);
    std::printf("  WARNING: %s\n", w->c_str());
    out.push_back(*w);
  }
  return out;
}

}  // namespace

report::Json statsJson(const eval::ErrorStats& s) {
  report::Json j;
  j["rmse"] = s.rmse;
  j["mean"] = s.mean;
  j["median"] = s.median;
  j["std"] = s.std;
  j["min"] = s.min;
  j["max"] = s.max;
  j["count"] = s.count;
  return j;
}

std::string statsLine(const eval::ErrorStats& s, const std::string& unit) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "rmse %.4f %s  mean %.4f  median %.4f  std %.4f  min %.4f  max %.4f  (n = %zu)", s.rmse,
                unit.c_str(), s.mean, s.median, s.std, s.min, s.max, s.count);
  return buf;
}

EvalCommand addAteCommand(CLI::App* cmd) {
  auto a = std::make_shared<PairArgs>();
  auto align = std::make_shared<std::string>("se3");
  auto save_aligned = std::make_shared<std::string>();
  auto save_errors = std::make_shared<std::string>();
  addPairOptions(cmd, *a);
  cmd->add_option("--align", *align, "Alignment of the estimate onto the reference: none, se3, sim3, yaw (x, y, z, yaw)")
      ->check(CLI::IsMember({"none", "se3", "sim3", "yaw"}))
      ->capture_default_str();
  cmd->add_option("--save-aligned", *save_aligned, "Write the aligned estimate (matched poses) as TUM");
  cmd->add_option("--save-errors", *save_errors, "Write 'time error_m' per matched pose");
  return [=] {
    std::size_t n_est = 0, n_ref = 0;
    const eval::AssociatedPoses p = loadPair(*a, &n_est, &n_ref);
    const eval::AteResult r = eval::absoluteTrajectoryError(p.est, p.ref, eval::parseAlignment(*align));
    const eval::ErrorStats s = eval::errorStats(r.errors);
    std::printf("ATE of %s against %s\n", a->est.c_str(), a->ref.c_str());
    std::printf("  poses matched: %zu (estimate %zu, reference %zu, max dt %g s)\n", p.t.size(), n_est, n_ref, a->max_dt);
    std::printf("  alignment: %s; translation (%.3f, %.3f, %.3f) m, yaw %.3f deg, scale %.5f\n", align->c_str(),
                r.alignment.T.translation().x(), r.alignment.T.translation().y(), r.alignment.T.translation().z(),
                yawOf(r.alignment.T.linear()) * 180 / M_PI, r.alignment.scale);
    std::printf("  translation error: %s\n", statsLine(s, "m").c_str());
    const report::Json warned = warnings({eval::coverageWarning(p.t.size(), n_est, n_ref),
                                  *align == "sim3" ? eval::scaleWarning(r.alignment.scale) : std::nullopt});
    if (!save_aligned->empty()) {
      std::vector<StampedPose> out;
      for (std::size_t i = 0; i < p.t.size(); ++i) {
        Pose q = p.est[i];
        q.translation() = r.alignment.scale * (r.alignment.T.linear() * q.translation()) + r.alignment.T.translation();
        q.linear() = r.alignment.T.linear() * q.linear();
        out.push_back({p.t[i], q});
      }
      io::writeTum(*save_aligned, out);
      spdlog::info("wrote {}", *save_aligned);
    }
    if (!save_errors->empty()) {
      std::ofstream e(*save_errors);
      if (!e) throw io::IoError(*save_errors, "cannot write file");
      e << "# time ate_m\n" << std::setprecision(10);
      for (std::size_t i = 0; i < p.t.size(); ++i) e << p.t[i] << ' ' << r.errors[i] << '\n';
      spdlog::info("wrote {}", *save_errors);
    }
    report::Json j;
    j["metric"] = "ate";
    j["estimate"] = a->est;
    j["reference"] = a->ref;
    j["alignment"] = *align;
    j["pairs"] = p.t.size();
    j["estimate_poses"] = n_est;
    j["reference_poses"] = n_ref;
    j["translation_m"] = statsJson(s);
    j["scale"] = r.alignment.scale;
    j["transform"] = poseJson(r.alignment.T);
    j["warnings"] = warned;
    return j;
  };
}

EvalCommand addRpeCommand(CLI::App* cmd) {
  auto a = std::make_shared<PairArgs>();
  auto delta = std::make_shared<double>(1.0);
  auto unit = std::make_shared<std::string>("frames");
  auto align = std::make_shared<std::string>("none");
  addPairOptions(cmd, *a);
  cmd->add_option("--delta", *delta, "Pair spacing, in --unit")->capture_default_str();
  cmd->add_option("--unit", *unit, "frames or m (metres travelled on the reference)")
      ->check(CLI::IsMember({"frames", "m"}))
      ->capture_default_str();
  cmd->add_option("--align", *align, "none, or sim3 to correct the estimate's scale first (rigid alignment cancels)")
      ->check(CLI::IsMember({"none", "sim3"}))
      ->capture_default_str();
  return [=] {
    std::size_t n_est = 0, n_ref = 0;
    const eval::AssociatedPoses p = loadPair(*a, &n_est, &n_ref);
    eval::RpeOptions o;
    o.delta = *delta;
    o.unit = *unit == "m" ? eval::DeltaUnit::Metres : eval::DeltaUnit::Frames;
    if (*align == "sim3")
      o.scale = eval::absoluteTrajectoryError(p.est, p.ref, eval::TrajectoryAlignment::Sim3).alignment.scale;
    const eval::RpeResult r = eval::relativePoseError(p.est, p.ref, o);
    if (r.trans_errors.empty())
      throw std::invalid_argument("rpe: no pose pair is " + std::to_string(*delta) + " " + *unit + " apart");
    std::printf("RPE of %s against %s, delta %g %s\n", a->est.c_str(), a->ref.c_str(), *delta, unit->c_str());
    std::printf("  poses matched: %zu (estimate %zu, reference %zu), pairs: %zu, scale %.5f\n", p.t.size(), n_est, n_ref,
                r.trans_errors.size(), o.scale);
    std::printf("  translation: %s\n", statsLine(r.translation, "m").c_str());
    std::printf("  rotation:    %s\n", statsLine(r.rotation_deg, "deg").c_str());
    const report::Json warned = warnings({eval::coverageWarning(p.t.size(), n_est, n_ref),
                                          *align == "sim3" ? eval::scaleWarning(o.scale) : std::nullopt});
    report::Json j;
    j["metric"] = "rpe";
    j["estimate"] = a->est;
    j["reference"] = a->ref;
    j["delta"] = *delta;
    j["delta_unit"] = *unit;
    j["scale"] = o.scale;
    j["pairs"] = r.trans_errors.size();
    j["translation_m"] = statsJson(r.translation);
    j["rotation_deg"] = statsJson(r.rotation_deg);
    j["warnings"] = warned;
    return j;
  };
}

}  // namespace slide
