#include "simmap/bundle_convert.h"

namespace slide {

KeyPoseBundle toBackendBundle(const KeyposeBundle& b, int robot) {
  KeyPoseBundle out;
  out.robot = robot;
  out.seq = b.seq;
  out.utime = b.utime;
  out.odom_pose = b.odom_pose;
  out.relative_odom = b.relative_odom;
  for (int i = 0; i < 6; ++i) out.odom_sigma[i] = b.odom_sigma[i];
  out.objects = b.objects;
  return out;
}

}  // namespace slide
