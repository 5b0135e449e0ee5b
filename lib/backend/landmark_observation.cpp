// Landmarks of the optimizer: creation, observation factors and their current models.
#include <algorithm>
#include <cmath>

#include "backend/data_association.h"
#include "backend/factors.h"
#include "backend/optimizer.h"
#include "backend/pose_block.h"
#include "objects/association.h"

namespace slide::backend {

namespace {
// Whitening of a body-frame position error for a range-bearing sensor at the origin.
Eigen::Matrix3d rangeBearingSqrtInfo(const Eigen::Vector3d& p, const BackendConfig& c) {
  const double rho = p.head<2>().norm();
  const Eigen::Vector3d radial = rho > 1e-6 ? Eigen::Vector3d(p.x() / rho, p.y() / rho, 0) : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d tangential = Eigen::Vector3d::UnitZ().cross(radial);
  Eigen::Matrix3d L;
  L.row(0) = radial.transpose() / std::max(c.position_sigma_floor, c.range_sigma);
  L.row(1) = tangential.transpose() / std::max(c.position_sigma_floor, c.bearing_sigma * rho);
  L.row(2) = Eigen::Vector3d::UnitZ().transpose() / std::max(c.position_sigma_floor, c.vertical_sigma);
  return L;
}

// The measured cuboid pose turned by a multiple of 90 degrees about its z axis (with length
// and width swapped on odd turns) to be closest to the predicted one: boxes look the same.
std::pair<Pose, Eigen::Vector3d> closestCuboidSymmetry(const Cuboid& m, const Pose& predicted) {
  std::pair<Pose, Eigen::Vector3d> best{m.pose, m.dims};
  double best_angle = 1e9;
  for (int k = 0; k < 4; ++k) {
    Pose T = m.pose;
    T.linear() = m.pose.linear() * rotZ(k * M_PI / 2);
    const double angle = Eigen::AngleAxisd(predicted.linear().transpose() * T.linear()).angle();
    if (angle < best_angle) {
      best_angle = angle;
      best.first = T;
      best.second = k % 2 ? Eigen::Vector3d(m.dims.y(), m.dims.x(), m.dims.z()) : m.dims;
    }
  }
  return best;
}

// Horizontal radius of the solid an object model stands for (a box: half its narrower side).
double bodyRadius(const Object& o) {
  if (const auto* c = std::get_if<Cuboid>(&o.model)) return 0.5 * std::min(c->dims.x(), c->dims.y());
  if (const auto* c = std::get_if<Cylinder>(&o.model)) return c->radius;
  return std::get<Ellipsoid>(o.model).radius;
}

// One ellipsoid lies whole within the other (horizontally within its radius, vertically within
// its height, each to a tolerance): a part of it seen alone, e.g. a chair's seat with the back
// hidden, whose height differs from the whole by more than the class's model difference.
bool partOfTheOther(const Object& x, const Object& y) {
  const auto* ex = std::get_if<Ellipsoid>(&x.model);
  const auto* ey = std::get_if<Ellipsoid>(&y.model);
  if (!ex || !ey) return false;
  const Ellipsoid& part = ex->height <= ey->height ? *ex : *ey;
  const Ellipsoid& whole = ex->height <= ey->height ? *ey : *ex;
  constexpr double kTolerance = 0.1;  // metres
  return (part.centroid - whole.centroid).head<2>().norm() + part.radius <= whole.radius + kTolerance &&
         part.centroid.z() - 0.5 * part.height >= whole.centroid.z() - 0.5 * whole.height - kTolerance &&
         part.centroid.z() + 0.5 * part.height <= whole.centroid.z() + 0.5 * whole.height + kTolerance;
}
}  // namespace

int Optimizer::addLandmark(const Object& w) {
  Landmark lm;
  lm.id = static_cast<std::int64_t>(landmarks_.size());
  lm.class_id = w.class_id;
  lm.shape = w.shape();
  if (const auto* c = std::get_if<Cuboid>(&w.model)) {
    lm.var = graph_.addVariable(BlockKind::Pose, toPoseBlock(c->pose).data(), true);
    lm.dims_var = graph_.addVariable(BlockKind::Vector3, c->dims.data(), false);
  } else if (const auto* c = std::get_if<Cylinder>(&w.model)) {
    const Eigen::Vector3d axis = c->axis.normalized();
    const double block[7] = {c->root.x(), c->root.y(), c->root.z(), axis.x(), axis.y(), axis.z(), c->radius};
    lm.var = graph_.addVariable(BlockKind::Cylinder, block, true);
    lm.length = c->length;
  } else {
    const auto& e = std::get<Ellipsoid>(w.model);
    lm.var = graph_.addVariable(BlockKind::Vector3, e.centroid.data(), true);
    lm.radius = e.radius;
    lm.height = e.height;
  }
  landmarks_.push_back(lm);
  const int index = static_cast<int>(landmarks_.size()) - 1;
  grid_.move(index, w.position());
  return index;
}

int Optimizer::wholeViews(const Landmark& lm) {
  int whole = 0;
  for (const Observation& s : lm.seen) whole += !s.body.other_reading;
  return whole;
}

void Optimizer::settleReading(Object& seen, const Pose& T_w_b) const {
  if (cfg_.reading_vote_radius <= 0 || !seen.other_reading || !std::holds_alternative<Cuboid>(seen.model)) return;
  const Object w = transformObject(T_w_b, seen);
  std::vector<int> near;
  grid_.near(w.position(), cfg_.reading_vote_radius, near);
  std::vector<double> headings;
  for (int i : near) {
    const Landmark& lm = landmarks_[i];
    if (!lm.alive || lm.class_id != seen.class_id || lm.shape != Shape::Cuboid) continue;
    const Object o = landmarkObject(lm);
    // The grid gives whole cells: the distance first, then the count over the landmark's views.
    if ((o.position() - w.position()).head<2>().norm() <= cfg_.reading_vote_radius &&
        wholeViews(lm) >= kWholeViewsToChooseReading)
      headings.push_back(headingOf(std::get<Cuboid>(o.model)));
  }
  if (otherReadingAgreesMore(w, headings)) seen = otherReadingOf(seen);
}

void Optimizer::addObservation(int pose_var, const Pose& T_w_b, const Object& seen, Landmark& lm) {
  const double a = cfg_.ellipsoid_size_ema;
  // A box read two ways is the reading the landmark agrees with, once boxes read one way only
  // (whole views) have fixed it; before, the front-end's choice.
  const int whole = seen.other_reading ? wholeViews(lm) : 0;
  const Object o = whole >= kWholeViewsToChooseReading
                       ? nearestReading(seen, transformObject(T_w_b.inverse(), landmarkObject(lm)))
                       : seen;
  int factor = -1;
  if (const auto* c = std::get_if<Cuboid>(&o.model)) {
    const Pose predicted = T_w_b.inverse() * fromPoseBlock(graph_.value(lm.var));
    const auto [pose, dims] = closestCuboidSymmetry(*c, predicted);
    const double range = pose.translation().norm();
    const double t_sigma = std::max({cfg_.position_sigma_floor, cfg_.range_sigma, cfg_.bearing_sigma * range});
    PoseSigma sigma;
    sigma << t_sigma, t_sigma, t_sigma, cfg_.cuboid_rotation_sigma, cfg_.cuboid_rotation_sigma, cfg_.cuboid_rotation_sigma;
    factor = graph_.addFactor(cuboidFactor(pose, dims, sigma, Eigen::Vector3d::Constant(cfg_.cuboid_dims_sigma)),
                              {pose_var, lm.var, lm.dims_var}, true);
  } else if (const auto* c = std::get_if<Cylinder>(&o.model)) {
    CylinderNoise n;
    n.position_sqrt_info = rangeBearingSqrtInfo(c->root + 0.5 * c->length * c->axis.normalized(), cfg_);
    n.along_axis_sigma = cfg_.cylinder_along_axis_sigma;
    n.axis_sigma = cfg_.cylinder_axis_sigma;
    n.radius_sigma = cfg_.cylinder_radius_sigma;
    factor = graph_.addFactor(cylinderFactor(c->root, c->axis.normalized(), c->radius, n), {pose_var, lm.var}, true);
    if (lm.observations > 0) lm.length = (1 - a) * lm.length + a * c->length;
  } else {
    const auto& e = std::get<Ellipsoid>(o.model);
    const double range_sigma =
        std::max({cfg_.position_sigma_floor, cfg_.range_sigma, cfg_.ellipsoid_partial_view * e.radius});
    factor = graph_.addFactor(ellipsoidFactor(e.centroid, range_sigma, cfg_.bearing_sigma), {pose_var, lm.var}, true);
    if (lm.observations > 0) {
      lm.radius = (1 - a) * lm.radius + a * e.radius;
      lm.height = (1 - a) * lm.height + a * e.height;
    }
  }
  ++lm.observations;
  lm.last_step = step_;
  lm.seen.push_back({factor, pose_var, o});
  voteClass(lm, o.class_id, o.confidence);
}

void Optimizer::voteClass(Landmark& lm, int class_id, double confidence) {
  lm.class_votes[class_id] += std::isfinite(confidence) ? std::clamp(confidence, 1e-3, 1.0) : 1e-3;
  double most = -1;  // ties go to the lower class id
  for (const auto& [c, v] : lm.class_votes)
    if (v > most) most = v, lm.class_id = c;
}

void Optimizer::moveObservations(Landmark& from, Landmark& to) {
  const int last_step = std::max(from.last_step, to.last_step);
  for (const Observation& obs : from.seen) {
    graph_.removeFactor(obs.factor);
    addObservation(obs.pose_var, fromPoseBlock(graph_.value(obs.pose_var)), obs.body, to);
  }
  to.last_step = last_step;
  from.seen.clear();
  from.observations = 0;
  from.alive = false;
  graph_.removeVariable(from.var);
  if (from.dims_var >= 0) graph_.removeVariable(from.dims_var);
}

int Optimizer::detachOutliers(const std::vector<double>* norms) {
  int detached = 0;
  const std::size_t count = landmarks_.size();
  for (std::size_t i = 0; i < count; ++i) {
    if (!landmarks_[i].alive || landmarks_[i].seen.size() < 2) continue;
    const Object landmark = landmarkObject(landmarks_[i]);
    auto outlier = [&](const Observation& obs) {
      if (norms && obs.factor >= static_cast<int>(norms->size())) return false;  // made after the solve's snapshot
      const double limit = cfg_.outlier_sigmas * std::sqrt(static_cast<double>(graph_.residualCount(obs.factor)));
      if ((norms ? (*norms)[obs.factor] : graph_.residualNorm(obs.factor)) > limit) return true;
      // Placed by the solved key pose, the detection must still pass the gate that admitted it
      // (under the landmark's class: a confused class was admitted by its shape).
      Object seen = transformObject(poseOf(obs.pose_var), obs.body);
      seen.class_id = landmark.class_id;
      return associationCost(nearestReading(seen, landmark), landmark, classes_, associationSlack(obs.body)) < 0;
    };
    const std::vector<Observation>& seen = landmarks_[i].seen;
    if (std::none_of(seen.begin(), seen.end(), outlier)) continue;  // the common case: nothing copied
    std::vector<Observation> keep, bad;
    for (const Observation& obs : seen) (outlier(obs) ? bad : keep).push_back(obs);
    if (bad.empty() || keep.empty()) continue;
    landmarks_[i].seen = keep;
    landmarks_[i].observations = static_cast<int>(keep.size());
    landmarks_[i].class_votes.clear();
    for (const Observation& obs : keep) voteClass(landmarks_[i], obs.body.class_id, obs.body.confidence);
    for (const Observation& obs : bad) {
      graph_.removeFactor(obs.factor);
      const Pose T_w_b = fromPoseBlock(graph_.value(obs.pose_var));
      const int index = addLandmark(transformObject(T_w_b, obs.body));
      addObservation(obs.pose_var, T_w_b, obs.body, landmarks_[index]);
      ++detached;
    }
  }
  detached_ += detached;
  return detached;
}

bool Optimizer::sameObject(const Landmark& a, const Object& oa, const Landmark& b, const Object& ob) const {
  if (a.shape != b.shape) return false;
  if (classes_.sameKind(a.class_id, b.class_id)) return associationCost(ob, oa, classes_) >= 0;
  if (!cfg_.merge_within_shape) return false;
  // Two classes: associable under each one's thresholds, i.e. the stricter's.
  Object ob_as_a = ob, oa_as_b = oa;
  ob_as_a.class_id = a.class_id;
  oa_as_b.class_id = b.class_id;
  return associationCost(ob_as_a, oa, classes_) >= 0 && associationCost(ob, oa_as_b, classes_) >= 0;
}

int Optimizer::mergeDuplicates() {
  int merged = 0;
  std::vector<int> near;
  for (std::size_t i = 0; i < landmarks_.size(); ++i) {
    if (!landmarks_[i].alive) continue;
    const Object oi = landmarkObject(landmarks_[i]);
    near.clear();
    grid_.near(oi.position(), max_association_distance_, near);
    for (int j : near) {
      Landmark& a = landmarks_[i];
      Landmark& b = landmarks_[j];
      if (j <= static_cast<int>(i) || !b.alive) continue;
      const Object ob = landmarkObject(b);
      // Only a named class's part merges into its whole: a catch-all's blob may hold several objects.
      const ClassInfo* named = a.class_id == b.class_id ? classes_.find(a.class_id) : nullptr;
      if (!sameObject(a, oi, b, ob) && !(named && !named->catch_all && partOfTheOther(oi, ob))) continue;
      // A robot that saw one long before the other may have drifted by more than their distance.
      if (revisitUnsure(a, driftBetween(a, &b), &b)) continue;
      // One object gives one detection per key pose, so two landmarks seen from one key pose are
      // two objects, unless they overlap: two solid objects of one kind do not stand inside one
      // another, and a key pose that saw both then took a neighbour's or a false object's detection
      // for one of them, or reported the object in two pieces (a table and a blob of it) - a few of
      // their key poses, up to merge_shared_fraction of the fewer one's. Two classes of one shape
      // seen together are two objects (a chair under a table).
      const std::size_t shared = static_cast<std::size_t>(std::count_if(b.seen.begin(), b.seen.end(), [&](const Observation& y) {
        return std::any_of(a.seen.begin(), a.seen.end(), [&](const Observation& x) { return x.pose_var == y.pose_var; });
      }));
      if (shared > 0) {
        if (!classes_.sameKind(a.class_id, b.class_id) ||
            associationDistance(ob, oi) >= std::max(bodyRadius(oi), bodyRadius(ob)) ||
            shared > cfg_.merge_shared_fraction * std::min(a.seen.size(), b.seen.size()))
          continue;
      }
      // The older landmark (lower index) keeps its id and takes every observation (one that does
      // not fit is detached after the next solve); the class is voted again over both.
      const std::map<int, Span> span_a = spansOf(a);
      for (const auto& [robot, y] : spansOf(b))
        if (const auto it = span_a.find(robot); it != span_a.end()) tie(robot, it->second, y, a);
      moveObservations(b, a);
      ++merged;
    }
  }
  merges_ += merged;
  return merged;
}

Object Optimizer::landmarkObject(const Landmark& lm, const FactorGraph::Values* values) const {
  const double* v = values ? (*values)[lm.var].data() : graph_.value(lm.var);
  Object o;
  o.id = lm.id;
  o.class_id = lm.class_id;
  o.num_observations = lm.observations;
  switch (lm.shape) {
    case Shape::Cuboid: {
      const double* d = values ? (*values)[lm.dims_var].data() : graph_.value(lm.dims_var);
      o.model = Cuboid{fromPoseBlock(v), Eigen::Vector3d(d[0], d[1], d[2])};
      break;
    }
    case Shape::Cylinder:
      o.model = Cylinder{{v[0], v[1], v[2]}, Eigen::Vector3d(v[3], v[4], v[5]).normalized(), v[6], lm.length};
      break;
    case Shape::Ellipsoid:
      o.model = Ellipsoid{{v[0], v[1], v[2]}, lm.radius, lm.height};
      break;
  }
  return o;
}

}  // namespace slide::backend
