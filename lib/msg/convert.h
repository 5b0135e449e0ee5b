#pragma once
// Conversions between core types and LCM messages. Daemons use this area; the algorithm
// areas of lib/ never include LCM headers.
#include <string>

#include "objects/object.h"
#include "slide/object_t.hpp"
#include "slide/pose3_t.hpp"

namespace slide {

pose3_t toMsg(const Pose& T);
Pose fromMsg(const pose3_t& m);
// True when every number of `m` is finite and its quaternion is not near zero (|q|^2 > 0.25),
// so that fromMsg gives a rotation; a received pose failing it is garbage.
bool usablePose(const pose3_t& m);

object_t toMsg(const Object& o);
// Throws std::invalid_argument (naming the object id) unless exactly one model is present.
Object fromMsg(const object_t& m);

}  // namespace slide
