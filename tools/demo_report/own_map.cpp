#include "own_map.h"

#include <stdexcept>

#include "app/channels.h"
#include "optimizer_node.h"
#include "slide/loop_closure_t.hpp"

namespace slide {

std::vector<Object> ownOnlyMap(const std::string& journal, int robot, const backend::BackendConfig& config,
                               const ClassTable& classes) {
  OptimizerNode node(config, classes, robot, {}, {});
  for (const OptimizerNode::JournalInput& in : OptimizerNode::readJournal(journal)) {
    const int size = static_cast<int>(in.bytes.size());
    if (in.channel == app::channels::kLoopClosure) {
      loop_closure_t m;
      if (m.decode(in.bytes.data(), 0, size) != size) throw std::runtime_error(journal + ": undecodable loop closure");
      if (m.robot_a != robot || m.robot_b != robot) continue;
    } else if (in.channel != app::channels::kKeyPoseBundle) {
      continue;  // peers' bundles
    }
    node.handle(in.channel, in.bytes.data(), size);
  }
  node.optimizer().fullSolve();
  return node.optimizer().landmarks();
}

}  // namespace slide
