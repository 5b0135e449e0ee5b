#pragma once
// Object mapping quality of segmenter + tracker on a simulated world: one robot drives the
// world (lib/sim, in memory), every frame is segmented and tracked, the latest fitted model
// of every track (placed in the world with the ground-truth key pose) forms the map, which is
// matched per class (Hungarian, class association distance) against the ground-truth objects
// the robot saw well enough (at least min_points points in at least min_frames frames).
// Labelled and RGBD modes first keep one estimate per landmark (estimates of a group that
// are the same object); the geometric (label-free) mode is scored on every estimate, and
// its unmatched estimates are counted as duplicates (near a ground-truth object) or false.
#include <map>
#include <string>
#include <vector>

#include "frontend/frontend_config.h"
#include "objects/class_table.h"
#include "sim/forest_world.h"

namespace slide {

struct WorldEvalSpec {
  std::string world = "forest";
  double distance = 60.0;    // metres driven
  double rate = 3.0;         // frames per second
  std::uint64_t seed = 1;
  std::string data_dir;
  ForestParams forest;       // forest world parameters (terrain, undergrowth)
  std::vector<std::string> modes{"labelled", "geometric"};  // labelled | geometric | rgbd
  int min_points = 15;       // a ground-truth object counts as seen ...
  int min_frames = 3;        // ... in this many frames
  bool verbose = false;      // print every missed ground-truth object
};

struct ModeResult {
  std::string mode;
  int estimated = 0, ground_truth = 0, matched = 0;
  int duplicates = 0;     // unmatched estimates near a ground-truth object of their group
  int false_objects = 0;  // unmatched estimates near none
  double precision = 0, recall = 0, f1 = 0;
  std::map<std::string, std::array<int, 3>> per_class;  // name -> (estimated, gt, matched)
  std::vector<double> frame_ms;                         // segmentation + tracking per frame
  long issues = 0;
};

struct WorldEvalResult {
  std::string world;
  int frames = 0;
  std::vector<ModeResult> modes;
};

WorldEvalResult evaluateWorld(const WorldEvalSpec& spec, const ClassTable& classes, const FrontendConfig& cfg);

}  // namespace slide
