#pragma once
// How far apart two objects of the map are, in position, footprint and model (the back-end's
// data association weighs them against the class table's thresholds).
// Vocabulary: in namespace slide itself, not slide::objects, as every area uses it (README).
#include <vector>

#include "objects/object.h"

namespace slide {

// Position distance: between centres; for two cylinders, the mean distance of each centre
// to the other's axis line (views of one trunk cover different heights).
double associationDistance(const Object& a, const Object& b);

// True when the horizontal footprints of two boxes, each grown by `margin` on every side,
// overlap (separating axes). Two cars parked side by side are closer than a partial view of one
// may be from its whole (3 m) but their footprints stay apart. A box standing on its end has
// no footprint to test: true.
bool footprintsOverlap(const Cuboid& a, const Cuboid& b, double margin = 0.0);

// The detection as the reading of its box (Object::other_reading) nearer `landmark`: least
// centre distance plus model difference. The detection itself when it has one reading.
Object nearestReading(const Object& detection, const Object& landmark);
// The detection read its other way: Object::other_reading its box, its box the other reading.
// The detection itself when it has one reading.
Object otherReadingOf(const Object& detection);
// A landmark chooses between a detection's readings once this many detections read one way
// only (whole views) fixed it; before, the detection keeps the front-end's reading (a landmark
// begun from one partial view would keep choosing its own reading).
constexpr int kWholeViewsToChooseReading = 2;

// Whether the other reading of a box read two ways (Object::other_reading) agrees more with
// the headings of boxes seen whole around it (parked cars stand parallel to their neighbours):
// the sum over them of cos(2 x heading difference), +1 parallel and -1 across, is larger for it.
// False for a detection with one reading or no headings.
bool otherReadingAgreesMore(const Object& detection, const std::vector<double>& whole_headings);
// The same for a box `first` whose other reading is `second`.
bool otherReadingAgreesMore(const Cuboid& first, const Cuboid& second, const std::vector<double>& whole_headings);
// The horizontal heading (rad) of a box's length axis.
double headingOf(const Cuboid& box);

// Model difference in metres: cuboids, norm of the extent difference (length and width may
// swap); cylinders, radius difference; ellipsoids, norm of (radius, height) difference.
// Infinite for different shapes.
double modelDifference(const Object& a, const Object& b);

}  // namespace slide
