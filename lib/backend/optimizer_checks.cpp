// Input validation of the optimizer: which bundles and objects are rejected, and why.
#include <cmath>

#include "backend/optimizer.h"

namespace slide::backend {

namespace {
bool finite(const Pose& T) { return T.matrix().allFinite(); }
double rotationAngle(const Pose& T) { return Eigen::AngleAxisd(T.linear()).angle(); }
}  // namespace

UpdateResult Optimizer::reject(UpdateResult r, const std::string& reason) {
  r.accepted = false;
  r.reason = reason;
  ++rejected_;
  ++rejections_[reason.substr(0, reason.find(':'))];
  return r;
}

std::string Optimizer::checkBundle(const KeyPoseBundle& b, const Robot& robot) const {
  const std::string who = "robot " + std::to_string(b.robot) + " key pose " + std::to_string(b.seq);
  if (!finite(b.odom_pose) || !finite(b.relative_odom) || !b.odom_sigma.allFinite())
    return "non-finite value: " + who + " has NaN or infinite odometry";
  if ((b.odom_sigma.array() < 0).any()) return "negative sigma: " + who + " has a negative odom_sigma";
  const double step = b.relative_odom.translation().norm(), turn = rotationAngle(b.relative_odom);
  if (step > cfg_.max_step_m || turn > cfg_.max_step_rad)
    return "odometry jump: " + who + " moves " + std::to_string(step) + " m / " + std::to_string(turn) +
           " rad in one step (limits " + std::to_string(cfg_.max_step_m) + " m, " + std::to_string(cfg_.max_step_rad) +
           " rad)";
  if (robot.held.count(b.seq)) return "duplicate key pose: " + who + " is already held";
  if (!robot.keyposes.empty()) {
    const KeyPose& last = keyposes_[robot.keyposes.back()];
    if (b.seq == last.seq || (b.seq < last.seq && findKeyPose(b.robot, b.seq)))
      return "duplicate key pose: " + who + " is already in the graph";
    if (b.seq < last.seq)
      return "sequence out of order: " + who + " arrives after key pose " + std::to_string(last.seq);
    if (b.utime < last.utime)
      return "timestamp out of order: " + who + " has utime " + std::to_string(b.utime) + " before key pose " +
             std::to_string(last.seq) + "'s " + std::to_string(last.utime);
    if (b.seq != last.seq + 1) {
      const Pose bridge = last.odom_pose.inverse() * b.odom_pose;
      if (bridge.translation().norm() > cfg_.max_step_m * (b.seq - last.seq) ||
          rotationAngle(bridge) > cfg_.max_step_rad * (b.seq - last.seq))
        return "odometry jump: " + who + " is too far from key pose " + std::to_string(last.seq) + " to bridge the gap";
    }
  }
  return {};
}

std::vector<Object> Optimizer::usableObjects(const KeyPoseBundle& b, UpdateResult& r) const {
  std::vector<Object> out;
  r.landmark_ids.assign(b.objects.size(), -1);
  for (std::size_t i = 0; i < b.objects.size(); ++i) {
    const Object& o = b.objects[i];
    const std::string who =
        "robot " + std::to_string(b.robot) + " key pose " + std::to_string(b.seq) + " object " + std::to_string(i);
    const ClassInfo* info = classes_.find(o.class_id);
    if (!o.isFinite()) {
      r.warnings.push_back("non-finite value: " + who + " dropped (NaN or infinite model)");
    } else if (!info) {
      r.warnings.push_back("unknown class: " + who + " has class " + std::to_string(o.class_id) + ", dropped");
    } else if (info->shape != o.shape()) {
      r.warnings.push_back("wrong shape: " + who + " is a " + shapeName(o.shape()) + " but class " + info->name +
                           " is a " + shapeName(info->shape) + ", dropped");
    } else if (const auto* c = std::get_if<Cylinder>(&o.model); c && (c->axis.norm() < 1e-6 || c->radius < 0)) {
      r.warnings.push_back("degenerate model: " + who + " cylinder has no axis or a negative radius, dropped");
    } else if (!(o.position().norm() <= cfg_.max_object_range_m)) {
      r.warnings.push_back("out of range: " + who + " is " + std::to_string(o.position().norm()) +
                           " m from its key pose (objects.max_object_range_m " + std::to_string(cfg_.max_object_range_m) +
                           "), dropped");
    } else if (o.position().norm() < 1e-3) {
      r.warnings.push_back("degenerate model: " + who + " sits at the sensor origin, dropped");
    } else {
      out.push_back(o);
      out.back().id = static_cast<std::int64_t>(i);  // remember the input index
      // The other reading of a box is the same box read the other way: of the class's size and
      // beside it, never elsewhere.
      const auto* box = std::get_if<Cuboid>(&o.model);
      const auto readsTheBox = [&](const Cuboid& other) {
        const Eigen::Vector3d& d = other.dims;
        return box && (d.array() > 0).all() && d.head<2>().maxCoeff() <= 2 * info->size_max.head<2>().maxCoeff() &&
               d.z() <= 2 * info->size_max.z() &&
               (other.pose.translation() - box->pose.translation()).norm() <=
                   std::max(box->dims.head<2>().maxCoeff(), d.head<2>().maxCoeff());
      };
      if (o.other_reading && !readsTheBox(*o.other_reading)) {
        r.warnings.push_back("inconsistent readings: " + who + " has a second box that is no reading of its own, " +
                             "second box dropped");
        out.back().other_reading.reset();
      }
    }
  }
  return out;
}

}  // namespace slide::backend
