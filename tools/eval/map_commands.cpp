// slide-eval objects: precision, recall, F1 per class and landmark RMSE of an object map.
#include <cstdio>
#include <memory>

#include "commands.h"
#include "eval/object_map_file.h"
#include "eval/object_matching.h"
#include "eval/placed_file.h"

namespace slide {

EvalCommand addObjectsCommand(CLI::App* cmd) {
  struct Args {
    std::string est, gt, classes;
    double threshold = 1.0;
    bool planar = false, any_class = false;
    int default_class = -1;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("est", a->est, "Estimated object map (text 'label x y z ...' or CSV); FILE@x,y,z,yaw_deg places it")
      ->required();
  cmd->add_option("gt", a->gt, "Ground-truth object map, same formats")->required();
  cmd->add_option("--threshold", a->threshold, "Largest centre distance of a match, metres")->capture_default_str();
  cmd->add_flag("--planar", a->planar, "Measure distances in x-y only");
  cmd->add_flag("--any-class", a->any_class, "Let objects of different classes match");
  cmd->add_option("--class", a->default_class, "Class id for CSV maps without a class column (e.g. 80 for pole lists)");
  cmd->add_option("--classes", a->classes, "Class table (default config/classes.yaml)");
  cmd->footer(
      "Matching is one-to-one and greedy by distance: all same-class pairs within the threshold, nearest first.\n"
      "precision = matched / estimated, recall = matched / ground truth, F1 = 2PR/(P+R); RMSE over matched pairs.");
  return [=] {
    const ClassTable classes = a->classes.empty() ? ClassTable::loadDefault() : ClassTable::load(a->classes);
    const PlacedFile est_file = parsePlacedFile(a->est), gt_file = parsePlacedFile(a->gt);
    std::vector<Object> est, gt;
    for (const Object& o : readObjectMapFile(est_file.path, classes, a->default_class))
      est.push_back(transformObject(est_file.placement, o));
    for (const Object& o : readObjectMapFile(gt_file.path, classes, a->default_class))
      gt.push_back(transformObject(gt_file.placement, o));
    ObjectMatchOptions o;
    o.threshold = a->threshold;
    o.planar = a->planar;
    o.match_classes = !a->any_class;
    const ObjectMappingScore s = scoreObjectMap(est, gt, o);

    std::printf("object map %s against %s (threshold %g m%s%s)\n", est_file.path.c_str(), gt_file.path.c_str(),
                a->threshold, a->planar ? ", planar" : "", a->any_class ? ", any class" : "");
    std::printf("  %-12s %6s %6s %6s %9s %7s %7s %9s\n", "class", "est", "gt", "match", "precision", "recall", "F1",
                "rmse [m]");
    auto row = [](const std::string& name, const ClassScore& c) {
      std::printf("  %-12s %6zu %6zu %6zu %9.3f %7.3f %7.3f %9.3f\n", name.c_str(), c.num_est, c.num_gt, c.true_positives,
                  c.precision, c.recall, c.f1, c.position_rmse);
    };
    Json per_class = Json::array();
    auto classJson = [](const std::string& name, const ClassScore& c) {
      Json j;
      j.set("class", name);
      j.set("class_id", c.class_id);
      j.set("estimated", c.num_est);
      j.set("ground_truth", c.num_gt);
      j.set("matched", c.true_positives);
      j.set("precision", c.precision);
      j.set("recall", c.recall);
      j.set("f1", c.f1);
      j.set("position_rmse_m", c.position_rmse);
      return j;
    };
    for (const ClassScore& c : s.per_class) {
      const ClassInfo* info = classes.find(c.class_id);
      const std::string name = info ? info->name : std::to_string(c.class_id);
      row(name, c);
      per_class.push(classJson(name, c));
    }
    row("all", s.overall);
    Json j;
    j.set("metric", "objects");
    j.set("estimate", est_file.path);
    j.set("ground_truth", gt_file.path);
    j.set("threshold_m", a->threshold);
    j.set("planar", a->planar);
    j.set("match_classes", !a->any_class);
    j.set("matching", "one-to-one, greedy by distance");
    j.set("overall", classJson("all", s.overall));
    j.set("per_class", per_class);
    return j;
  };
}

}  // namespace slide
