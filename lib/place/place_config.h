#pragma once
// Place-recognition parameters (config/place.yaml), and one entry point for either method.
#include <string>

#include "place/slidegraph.h"
#include "place/slidematch.h"

namespace slide::place {

struct PlaceConfig {
  SlideGraphParams slidegraph;
  SlideMatchParams slidematch;
  // Two maps whose classes overlap less than this (sharedClassShare: e.g. a label-free LiDAR's
  // "other" furniture against an RGBD detector's chairs and tables) are matched by shape family.
  double min_shared_class_share = 0.5;
  // SlideGraph's answer between maps of at most this many landmarks each must also stand against
  // the alignments SlideMatch's exhaustive search verifies (the ambiguity test of verify.h with
  // SlideMatch's candidates as rivals); 0 turns the check off. CLIPPER's few densest sets can
  // miss the true alignment of a periodic scene: a block grid's half-turn alias matched 13
  // landmarks of two urban robots' maps, the true alignment (the simulator's start poses) 12, and
  // only the alias was verified (tests/data/recorded/urban_half_turn_alias).
  std::size_t rival_search_max_landmarks = 400;
  // An ambiguous result (verify.h, the rival test) is checked again with the maps' roles
  // swapped; its stronger alignment stands when that check finds the same one unambiguously.
  bool ambiguous_recheck_swapped = true;
  // SlideGraph that finds no transform (neither ambiguous nor out of time) between maps of at
  // most this many landmarks each tries SlideMatch's tile votes alone (neighbourhood agreement,
  // slidematch.h) with what is left of its budget: at 0.25 m noise, a fifth of either map
  // missed or spurious, Delaunay triangles of two maps rarely coincide ("best hypothesis has 0-4
  // inliers") while verification at the truth accepts. 0 turns it off. Above the limit SlideGraph
  // stays alone (its time targets on maps of thousands of objects).
  std::size_t tile_fallback_max_landmarks = 1000;
};

// Every key is optional (defaults of the structs above); a wrong type or value throws
// ConfigError naming the file and key. The shared `verify` section applies to both methods.
PlaceConfig loadPlaceConfig(const std::string& path);
// config/place.yaml of the source tree.
PlaceConfig loadDefaultPlaceConfig();

// "slidegraph" or "slidematch"; throws std::invalid_argument otherwise.
PlaceMethod parsePlaceMethod(const std::string& name);

// Matches with the configured method (SlideGraph's answer checked against SlideMatch's rivals on
// small maps, see rival_search_max_landmarks; its misses tried with the tile votes, see
// tile_fallback_max_landmarks); when the maps' classes barely overlap, by shape family
// and with SlideMatch whatever the method (the result says so through `by_shape`): with classes
// collapsed to three families SlideGraph's class-triple descriptors no longer tell places apart
// (an indoor LiDAR robot's "other" furniture against an RGBD robot's chairs and tables: no
// transform from SlideGraph, SlideMatch within 0.2 m / 0.2 deg of the truth).
PlaceResult recognizePlace(PlaceMethod method, const std::vector<Landmark>& a, const std::vector<Landmark>& b,
                           const PlaceConfig& config);

}  // namespace slide::place
