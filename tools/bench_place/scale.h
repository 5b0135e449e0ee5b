#pragma once
// The place benchmark at scale (issue 21; suite place_scale, not part of `./slide bench place`):
// realistic bent maps (sim/drifted_object_map.h, the realistic cases' error conditions) of about
// 1,000, 10,000 and 30,000 objects, made by robots driving long routes through a large Poisson
// forest (forest_scale). Each overlapping pair shares one 200 m stretch of route (20 % of a
// 10 km route would be a stretch the two maps bend against each other by tens of degrees);
// disjoint pairs drive opposite halves of the world. Recall, wrong transforms, false positives,
// thread CPU time (median, max) and peak memory per query, per method.
#include <string>
#include <vector>

#include "bench/report.h"
#include "place/place_config.h"

namespace slide::bench_place {

void runScale(bench::BenchReport& rep, const place::PlaceConfig& config, unsigned seed, const std::vector<int>& sizes,
              const std::vector<std::string>& conditions);

}  // namespace slide::bench_place
