#pragma once
// How far apart two objects of the map are, in position and in model, and whether one
// observation may be the other landmark under the class table's thresholds.
// Vocabulary: in namespace slide itself, not slide::objects, as every area uses it (README).
#include "objects/class_table.h"

namespace slide {

// Position distance: between centres; for two cylinders, the mean distance of each centre
// to the other's axis line (views of one trunk cover different heights).
double associationDistance(const Object& a, const Object& b);

// Model difference in metres: cuboids, norm of the extent difference (length and width may
// swap); cylinders, radius difference; ellipsoids, norm of (radius, height) difference.
// Infinite for different shapes.
double modelDifference(const Object& a, const Object& b);

// Same class, and both distances within that class's thresholds.
bool associable(const Object& a, const Object& b, const ClassTable& classes);

}  // namespace slide
