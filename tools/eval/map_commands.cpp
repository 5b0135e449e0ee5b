// slide-eval objects: precision, recall, F1 per class and landmark RMSE of an object map.
#include <cstdio>
#include <memory>

#include "commands.h"
#include "io/object_map_text.h"
#include "eval/object_matching.h"
#include "eval/placed_file.h"

namespace slide {

EvalCommand addObjectsCommand(CLI::App* cmd) {
  struct Args {
    std::string est, gt, classes;
    double threshold = 1.0;
    bool planar = false, any_class = false, list = false;
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
  cmd->add_flag("--list", a->list, "List every match, false positive and missed object (also in the JSON)");
  cmd->footer(
      "Matching is one-to-one and greedy by distance: all same-class pairs within the threshold, nearest first.\n"
      "precision = matched / estimated, recall = matched / ground truth, F1 = 2PR/(P+R); RMSE over matched pairs.");
  return [=] {
    const ClassTable classes = a->classes.empty() ? ClassTable::loadDefault() : ClassTable::load(a->classes);
    const eval::PlacedFile est_file = eval::parsePlacedFile(a->est), gt_file = eval::parsePlacedFile(a->gt);
    std::vector<Object> est, gt;
    for (const Object& o : io::readObjectMapFile(est_file.path, classes, a->default_class))
      est.push_back(transformObject(est_file.placement, o));
    for (const Object& o : io::readObjectMapFile(gt_file.path, classes, a->default_class))
      gt.push_back(transformObject(gt_file.placement, o));
    eval::ObjectMatchOptions o;
    o.threshold = a->threshold;
    o.planar = a->planar;
    o.match_classes = !a->any_class;
    const eval::ObjectMappingScore s = eval::scoreObjectMap(est, gt, o);

    std::printf("object map %s against %s (threshold %g m%s%s)\n", est_file.path.c_str(), gt_file.path.c_str(),
                a->threshold, a->planar ? ", planar" : "", a->any_class ? ", any class" : "");
    std::printf("  %-12s %6s %6s %6s %9s %7s %7s %9s\n", "class", "est", "gt", "match", "precision", "recall", "F1",
                "rmse [m]");
    auto row = [](const std::string& name, const eval::ClassScore& c) {
      std::printf("  %-12s %6zu %6zu %6zu %9.3f %7.3f %7.3f %9.3f\n", name.c_str(), c.num_est, c.num_gt, c.true_positives,
                  c.precision, c.recall, c.f1, c.position_rmse);
    };
    report::Json per_class = report::Json::array();
    auto classJson = [](const std::string& name, const eval::ClassScore& c) {
      report::Json j;
      j["class"] = name;
      j["class_id"] = c.class_id;
      j["estimated"] = c.num_est;
      j["ground_truth"] = c.num_gt;
      j["matched"] = c.true_positives;
      j["precision"] = c.precision;
      j["recall"] = c.recall;
      j["f1"] = c.f1;
      j["position_rmse_m"] = c.position_rmse;
      return j;
    };
    for (const eval::ClassScore& c : s.per_class) {
      const ClassInfo* info = classes.find(c.class_id);
      const std::string name = info ? info->name : std::to_string(c.class_id);
      row(name, c);
      per_class.push_back(classJson(name, c));
    }
    row("all", s.overall);
    report::Json listing;
    if (a->list) {
      auto name = [&](int id) {
        const ClassInfo* c = classes.find(id);
        return c ? c->name : std::to_string(id);
      };
      auto objectJson = [&](const Object& o, std::size_t index) {
        report::Json j;
        j["index"] = index;
        j["id"] = static_cast<long long>(o.id);
        j["class"] = name(o.class_id);
        j["x"] = o.position().x();
        j["y"] = o.position().y();
        j["z"] = o.position().z();
        return j;
      };
      std::vector<bool> est_matched(est.size(), false), gt_matched(gt.size(), false);
      report::Json matches = report::Json::array(), fps = report::Json::array(), fns = report::Json::array();
      for (const eval::ObjectMatch& m : s.matches) {
        est_matched[m.est] = gt_matched[m.gt] = true;
        const Eigen::Vector3d p = est[m.est].position(), q = gt[m.gt].position();
        std::printf("  match  %-10s est #%zu (%.2f, %.2f, %.2f) - gt #%zu (%.2f, %.2f, %.2f): %.3f m\n",
                    name(est[m.est].class_id).c_str(), m.est, p.x(), p.y(), p.z(), m.gt, q.x(), q.y(), q.z(), m.distance);
        report::Json j;
        j["estimate"] = objectJson(est[m.est], m.est);
        j["ground_truth"] = objectJson(gt[m.gt], m.gt);
        j["distance_m"] = m.distance;
        matches.push_back(j);
      }
      for (std::size_t i = 0; i < est.size(); ++i)
        if (!est_matched[i]) {
          const Eigen::Vector3d p = est[i].position();
          std::printf("  false positive %-10s est #%zu (%.2f, %.2f, %.2f)\n", name(est[i].class_id).c_str(), i, p.x(),
                      p.y(), p.z());
          fps.push_back(objectJson(est[i], i));
        }
      for (std::size_t i = 0; i < gt.size(); ++i)
        if (!gt_matched[i]) {
          const Eigen::Vector3d p = gt[i].position();
          std::printf("  missed %-10s gt #%zu (%.2f, %.2f, %.2f)\n", name(gt[i].class_id).c_str(), i, p.x(), p.y(), p.z());
          fns.push_back(objectJson(gt[i], i));
        }
      listing["matches"] = matches;
      listing["false_positives"] = fps;
      listing["missed"] = fns;
    }
    report::Json j;
    j["metric"] = "objects";
    j["estimate"] = est_file.path;
    j["ground_truth"] = gt_file.path;
    j["threshold_m"] = a->threshold;
    j["planar"] = a->planar;
    j["match_classes"] = !a->any_class;
    j["matching"] = "one-to-one, greedy by distance";
    j["overall"] = classJson("all", s.overall);
    j["per_class"] = per_class;
    if (a->list) j["listing"] = listing;
    return j;
  };
}

}  // namespace slide
