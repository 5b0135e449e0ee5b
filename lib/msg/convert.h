#pragma once
// Conversions between core types and LCM messages. Daemons use this area; the algorithm
// areas of lib/ never include LCM headers.
#include <string>
#include <vector>

#include "objects/keypose_bundle.h"
#include "objects/object.h"
#include "slide/keypose_bundle_t.hpp"
#include "slide/object_t.hpp"
#include "slide/pose3_t.hpp"

namespace slide::msg {

pose3_t toLcm(const Pose& T);
Pose fromLcm(const pose3_t& m);
// True when every number of `m` is finite and its quaternion is not near zero (|q|^2 > 0.25),
// so that fromLcm gives a rotation; a received pose failing it is garbage.
bool usablePose(const pose3_t& m);

object_t toLcm(const Object& o);
// Throws std::invalid_argument (naming the object id) unless exactly one model is present.
Object fromLcm(const object_t& m);

// The one conversion of a key-pose bundle (the tracker's KEYPOSE_BUNDLE, peer sync's PEER_BUNDLE).
// Sigmas travel as float; `first` and `gap` (team layer only) do not travel.
keypose_bundle_t toLcm(const KeyPoseBundle& b);
// Objects that are not exactly one model are left out, each described in *dropped (when given).
// Checks nothing else: the optimizer checks what it adds, peer sync what it shares.
KeyPoseBundle fromLcm(const keypose_bundle_t& m, std::vector<std::string>* dropped);

}  // namespace slide::msg
