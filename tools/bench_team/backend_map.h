#pragma once
// The map one robot's back-end builds from its own bundles and the peers' bundles as the team
// layer delivered them (thinned, quantised), fed in arrival order with the true inter-robot
// transforms, then solved to convergence; and the distance between two such maps.
#include <map>
#include <vector>

#include "backend/backend_config.h"
#include "objects/keypose_bundle.h"

namespace slide::team::bench {

struct Arrival {
  std::vector<KeyPoseBundle> bundles;  // own bundle of this step first, then peers' delivered in it
};

// `transforms`: T_host_peer per peer robot id.
std::vector<Object> backendMap(const backend::BackendConfig& cfg, std::int32_t host,
                               const std::map<std::int32_t, Pose>& transforms, const std::vector<Arrival>& arrivals);

// Landmarks of two maps paired with the nearest landmark of the same class in the other map
// within `gate_m` (both ways): the largest paired distance and how many found no partner.
struct MapComparison {
  double max_paired_m = 0;
  std::size_t unpaired = 0;
};
MapComparison compareMaps(const std::vector<Object>& a, const std::vector<Object>& b, double gate_m);

}  // namespace slide::team::bench
