#pragma once
// Realistic detections laid over a scenario (the back-end bench's realistic cases): the same true
// paths and landmarks, observed again with missed detections, short-lived false objects,
// class confusion and noise the estimator does not know. The bundles keep the scenario's
// nominal odometry sigmas and the back-end its configured measurement model, so with
// noise_scale != 1 the estimator's sigmas are wrong by that factor.
#include <cstdint>
#include <string>

#include "objects/class_table.h"
#include "graph_scenario/scenario.h"

namespace slide::graph_scenario {

struct ScenarioRealism {
  double miss_rate = 0.0;           // each detection of a true landmark is dropped with this probability
  double clutter_fraction = 0.0;    // false objects make about this fraction of all detections
  int clutter_max_views = 2;        // a false object is reported by 1..this many consecutive key poses
  double confusion_rate = 0.0;      // a detection takes another class of the same shape model
  double noise_scale = 1.0;         // applied noise (measurements and odometry) = the scenario's sigmas x this
  // Each robot's odometry reads every step's length times one factor for the whole mission,
  // 1 + this x N(0, 1) (wheels, visual odometry: the simulator's odometry has 1 %); the bundles do
  // not say so. Drawn from its own generator, so the rest of the case is the same at any value.
  double odom_scale_error = 0.0;
  // e.g. "miss 0.20, clutter 0.15, confusion 0.10, noise x2.0, odometry scale 1.0 %"
  std::string describe() const;
};

// The scenario re-observed under `realism`. ScenarioRobot::seen holds -1 for a false object's
// detection. Throws std::invalid_argument on rates outside [0, 1), a scale <= 0 or a scale error
// outside [0, 0.2).
GraphScenario withRealism(const GraphScenario& s, const ScenarioRealism& realism, const ClassTable& classes,
                          std::uint32_t seed = 17);

}  // namespace slide::graph_scenario
