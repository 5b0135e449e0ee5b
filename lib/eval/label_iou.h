#pragma once
// Per-class point IoU of predicted SemanticKITTI labels against ground-truth labels, over
// named groups of labels (e.g. ground = road, parking, sidewalk, other-ground, lane marking,
// terrain). IoU = tp / (tp + fp + fn) per group; labels in no group count for none.
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace slide::eval {

class LabelIou {
 public:
  // Groups car {10, 252}, trunk {71}, pole {80, 81}, vegetation {70}, ground {40, 44, 48,
  // 49, 60, 72}: the classes the learned front-end is measured on.
  LabelIou();
  explicit LabelIou(std::map<std::string, std::vector<uint16_t>> groups);
  // Counts one scan; throws std::invalid_argument when the sizes differ.
  void add(const std::vector<uint16_t>& truth, const std::vector<uint16_t>& predicted);
  // tp / (tp + fp + fn); nullopt for a group that neither truth nor prediction holds.
  std::optional<double> iou(const std::string& group) const;
  std::vector<std::string> groups() const;
  const std::array<long, 3>& counts(const std::string& group) const { return counts_.at(group); }  // tp, fp, fn

 private:
  std::map<std::string, std::vector<uint16_t>> groups_;
  std::map<uint16_t, std::string> group_of_label_;
  std::map<std::string, std::array<long, 3>> counts_;
};

}  // namespace slide::eval
