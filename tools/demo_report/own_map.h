#pragma once
// A robot's map from its own observations alone: the own key-pose bundles and intra-robot loop
// closures of its optimizer journal, replayed in order through the same node without the
// peers' bundles or inter-robot transforms. What a robot knew before it merged anyone: the
// map the paper aligns to judge inter-robot transforms.
#include <string>
#include <vector>

#include "backend/backend_config.h"
#include "objects/class_table.h"
#include "objects/object.h"

namespace slide {

// Throws std::runtime_error naming the journal when it cannot be read or holds an
// undecodable loop closure.
std::vector<Object> ownOnlyMap(const std::string& journal, int robot, const backend::BackendConfig& config,
                               const ClassTable& classes);

}  // namespace slide
