#pragma once
// Object mapping quality of segmenter + tracker on a simulated world: one robot drives the
// world (lib/simulator, in memory), every frame is segmented and tracked, the latest fitted model
// of every track (placed in the world with the ground-truth key pose) forms the map, which is
// matched per class (Hungarian, centres within match_distance horizontally: 1 m, as the demo
// report scores its maps) against the ground-truth objects
// the robot saw well enough: at least min_points LiDAR returns (RGBD: mask pixels) within
// max_range metres in at least min_frames frames -- a criterion of the sensor's view, fixed
// here, not the segmenter's own thresholds. Every track counts: estimates of one object by
// several tracks are not merged (the unmatched ones are reported as duplicates).
//
// Modes: geometric (no labels), emulated (the detection emulator's labels, no instance ids,
// into the labelled segmenter), oracle (the simulator's ground-truth labels: an upper bound),
// rgbd (emulated instance masks), rgbd.oracle (ground-truth masks: an upper bound), learned
// (the range-image model of cfg.learned labels the points, the labelled segmenter clusters
// them; no ground truth on its path, which scores its point IoU only). The label-free mode names
// no furniture: real chairs, tables and monitors count as "other" for it (its catch-all
// ellipsoids); every other mode is scored on the classes it names.
#include <map>
#include <string>
#include <vector>

#include "frontend/frontend_config.h"
#include "objects/class_table.h"
#include "emulator/detection_emulator.h"

namespace slide {

struct WorldEvalSpec {
  std::string world = "forest";
  double distance = 60.0;    // metres driven
  double rate = 3.0;         // frames per second
  std::uint64_t seed = 1;
  bool aerial = false;       // the robot flies at the world's aerial altitude
  std::string data_dir;
  std::vector<std::string> modes{"emulated", "oracle", "geometric"};  // see above
  emulator::DetectionEmulatorConfig emulator;  // for the emulated modes (seed mixed with `seed`)
  int min_points = 30;       // a ground-truth object counts as seen with this many returns ...
  double max_range = 40.0;   // ... within this horizontal range (metres) ...
  int min_frames = 3;        // ... in this many frames
  double match_distance = 1.0;  // an estimate matches a real object within this horizontal distance (m)
  // The back-end publishes a landmark once this many key-pose detections back it
  // (backend.yaml min_observations): the map is also scored with those landmarks alone.
  int confirm_observations = 3;
  double reading_vote_radius = 30.0;  // backend.yaml: a box read two ways takes the reading its map neighbours agree with
  bool verbose = false;      // print every missed ground-truth object
  bool diagnose = false;     // print per-frame segmentation outcomes per class (segment_diagnosis.h)
};

struct ModeResult {
  std::string mode;
  int estimated = 0, ground_truth = 0, matched = 0;
  int duplicates = 0;        // unmatched estimates within the class's association distance of a matched object
  int false_objects = 0;     // other unmatched estimates
  int ignored = 0;           // estimates of real objects below the visibility criterion (not scored)
  // The same map with only the landmarks the back-end would publish (WorldEvalSpec::confirm_observations).
  int confirmed_estimated = 0, confirmed_matched = 0;
  std::map<std::string, double> iou;  // emulated and learned modes: per-class point IoU of their labels
  double precision = 0, recall = 0, f1 = 0;
  std::map<std::string, std::array<int, 3>> per_class;  // name -> (estimated, gt, matched)
  std::map<std::string, int> scored_as;  // "chair as other": real objects of a class the mode cannot name, scored as another
  std::vector<double> frame_ms;                         // segmentation + tracking per frame
  // Every key-pose object placed by the ground-truth key pose against the nearest real object
  // of its class within 2 m (scored with ground truth, evaluation only): its offset along the
  // horizontal line of sight from the key pose (negative: short of the real centre), per class.
  std::map<std::string, std::vector<double>> along_ray;
  std::map<std::string, std::vector<double>> along_ray_range;  // each along_ray entry's range from the key pose
  // The same observations' horizontal distance to that real object (metres), per class.
  std::map<std::string, std::vector<double>> centre_error;
  long issues = 0;
};

struct WorldEvalResult {
  std::string world;
  int frames = 0;
  std::vector<ModeResult> modes;
};

WorldEvalResult evaluateWorld(const WorldEvalSpec& spec, const ClassTable& classes,
                              const frontend::FrontendConfig& cfg);

}  // namespace slide
