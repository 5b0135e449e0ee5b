#pragma once
// The tracker's key-pose bundle as the back-end takes it (what the tracker daemon's message
// carries from one to the other, without LCM).
#include "backend/keypose_bundle.h"
#include "frontend/keypose.h"

namespace slide {

KeyPoseBundle toBackendBundle(const KeyposeBundle& b, int robot);

}  // namespace slide
