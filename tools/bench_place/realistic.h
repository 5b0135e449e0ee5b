#pragma once
// The place benchmark on realistic maps (issue 20): each robot's map made by driving a route
// through a world with drifting odometry, position noise, missed, spurious and class-confused
// objects (sim/drifted_object_map.h). Pairs overlap along a shared stretch of route, driven the
// same way or the opposite way, or lie in disjoint parts of the world (false-positive checks).
// Truth is the least-squares transform over the objects both maps hold.
#include <map>
#include <string>
#include <vector>

#include "bench/report.h"
#include "place/consensus_filter.h"
#include "place/place_config.h"
#include "simulator/drifted_object_map.h"
#include "simulator/world.h"

namespace slide::bench_place {

// A world of objects with the routes robots drive through it.
struct RouteWorld {
  std::string name;
  std::vector<place::Landmark> objects;  // index = position
  simulator::RouteGraph routes;
  simulator::ClassConfusions confusions;
  double range = 15;         // sensor range of its robots, metres
  double route_length = 300; // metres each robot drives
  std::string description;
};

// forest (procedural, 150 x 150 m at the simulator's default density, tiled up to `side`),
// forest_large (0.1 trunks/m^2 over 600 x 600 m: ~3,000-object maps), longleaf, spruces,
// finpines (the real inventories), urban (60 m street grid), indoor (offices), indoor_repeated
// (rooms furnished from two templates).
// forest_scale: 0.1 trunks/m^2 (Poisson) over 1,500 x 1,500 m, a 25 m route lattice, 15 m range:
// room for routes of 10 km and more (the scale cases set the route length).
RouteWorld routeWorld(const std::string& name, unsigned seed);

// The error parameters of a named condition: "target" (the recall condition: 0.25 m
// noise, 20 % missed, 20 % spurious, 7.5 % confused, 1.5 deg/100 m), "mild", "harsh".
simulator::MapErrorParams conditionErrors(const std::string& name);

// A condition: error parameters, overlap (share of B's route along A's), pairs and how many of
// them are disjoint (routes in opposite halves of the world).
struct Condition {
  std::string name;
  simulator::MapErrorParams errors;
  double overlap = 0.2;
  int pairs = 6;           // overlapping pairs; odd ones drive the shared stretch the opposite way
  int disjoint_pairs = 0;  // pairs in disjoint halves: any transform is a false positive
};

struct MapPair {
  simulator::DriftedMap a, b;
  bool overlapping = true;
  bool opposite = false;
};
std::vector<MapPair> makePairs(const RouteWorld& w, const Condition& c, unsigned seed);

// Scoring: a transform is correct within 1 m (at the centroid of the shared objects, in B's
// frame) and 2 degrees of the truth; otherwise wrong; any transform on a disjoint pair is a false
// positive.
struct RealisticFigures {
  int overlapping = 0, correct = 0, wrong = 0, missed = 0, disjoint = 0, false_positives = 0;
  std::vector<double> trans_err, yaw_err, cpu_ms;  // errors of correct results; CPU of every query
  std::vector<double> peak_mb;                     // every query: peak resident memory above the start
  std::map<std::string, std::vector<double>> stage_cpu_ms;  // per stage, every query that ran it
  std::vector<double> objects_a, objects_b, shared_fraction, truth_rms;
  std::size_t peak_bytes = 0;  // SlideGraph: largest consistency graph of any query
  std::vector<std::string> wrong_notes;  // what each wrong / false-positive transform was
  std::vector<std::string> miss_notes;   // why each overlapping pair gave no transform
};
// place_gap > 0: the places the maps share (runs of shared objects no more than place_gap metres
// apart along A's route, each with its own least-squares truth) are named in the notes of wrong
// transforms, and with places_count a transform right (same tolerance) about one of them is
// correct. Long routes cross each other: the whole shared set then spans places the two maps
// bend differently, and no rigid transform fits all of them.
RealisticFigures runPairs(const std::vector<MapPair>& pairs, place::PlaceMethod method,
                          const place::PlaceConfig& config, double place_gap = 0, bool places_count = true);
// The places two maps share (see runPairs), each with its least-squares truth (places with fewer
// than 3 shared objects left out).
std::vector<simulator::SharedTruth> sharedPlaces(const simulator::DriftedMap& a, const std::vector<place::Landmark>& b,
                                                 double gap);

// The loop closer's way: B's map grows along its route; it is checked `checks` times (evenly
// along the route) against A's whole map and every found transform goes through the consensus
// filter. Delay: found results fed in until the first correct publication, and metres B drove
// from its first correct raw detection to that publication.
struct ConsensusFigures {
  int pairs = 0, disjoint = 0, queries = 0, raw_found = 0, raw_wrong = 0;
  int published_correct = 0, published_wrong = 0, disjoint_published = 0;
  std::vector<double> detections_to_publish, metres_delay;
  std::vector<std::string> wrong_notes;
};
// place_gap: the places of a wrong publication's note (see runPairs).
ConsensusFigures runConsensus(const std::vector<MapPair>& pairs, place::PlaceMethod method,
                              const place::PlaceConfig& config, const place::ConsensusParams& consensus, int checks,
                              double place_gap);

}  // namespace slide::bench_place

namespace slide::bench_place {

// The suite's cases (world and condition), and running them: figures per case and method into
// `rep` (names realistic.<world>.<condition>.<method>.*) and a summary table on stdout. `worlds`
// empty runs every world. Consensus: the loop closer's filter over growing maps (target condition).
// `dump` (a folder, or empty): every pair's maps as realistic_<world>_<condition>_<k>_{a,b}.txt,
// the least-squares truth logged.
void runRealistic(bench::BenchReport& rep, const place::PlaceConfig& config, const place::ConsensusParams& consensus,
                  unsigned seed, const std::vector<std::string>& worlds, const std::string& dump = "");

// Joined with "; " (notes of several pairs in one figure).
std::string joined(const std::vector<std::string>& notes);

}  // namespace slide::bench_place
