#include "eval/label_iou.h"

#include <stdexcept>

namespace slide::eval {

LabelIou::LabelIou()
    : LabelIou({{"car", {10, 252}},
                {"trunk", {71}},
                {"pole", {80, 81}},
                {"vegetation", {70}},
                {"ground", {40, 44, 48, 49, 60, 72}}}) {}

LabelIou::LabelIou(std::map<std::string, std::vector<uint16_t>> groups) : groups_(std::move(groups)) {
  for (const auto& [name, labels] : groups_) {
    counts_[name] = {0, 0, 0};
    for (uint16_t l : labels)
      if (!group_of_label_.emplace(l, name).second) throw std::invalid_argument("label " + std::to_string(l) + " in two groups");
  }
}

void LabelIou::add(const std::vector<uint16_t>& truth, const std::vector<uint16_t>& predicted) {
  if (truth.size() != predicted.size())
    throw std::invalid_argument("IoU: " + std::to_string(truth.size()) + " true labels, " + std::to_string(predicted.size()) +
                                " predicted");
  auto group = [&](uint16_t l) -> std::array<long, 3>* {
    const auto it = group_of_label_.find(l);
    return it == group_of_label_.end() ? nullptr : &counts_[it->second];
  };
  for (std::size_t i = 0; i < truth.size(); ++i) {
    auto* t = group(truth[i]);
    auto* p = group(predicted[i]);
    if (t && t == p) {
      ++(*t)[0];
      continue;
    }
    if (p) ++(*p)[1];
    if (t) ++(*t)[2];
  }
}

std::optional<double> LabelIou::iou(const std::string& group) const {
  const auto& c = counts_.at(group);
  const long d = c[0] + c[1] + c[2];
  if (d == 0) return std::nullopt;
  return double(c[0]) / double(d);
}

std::vector<std::string> LabelIou::groups() const {
  std::vector<std::string> out;
  for (const auto& [name, labels] : groups_) out.push_back(name);
  return out;
}

}  // namespace slide::eval
