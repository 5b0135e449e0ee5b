#include "simulator/semantic_labels.h"

namespace slide::simulator::label {

int classIdOfLabel(uint16_t semantic) {
  switch (semantic) {
    case kCar: return 10;
    case kTrunk: return 71;
    case kPole:
    case kTrafficSign: return 80;
    case kChair: return 1;
    case kTable: return 2;
    case kMonitor: return 3;
    default: return 0;
  }
}

uint16_t labelOfClassId(int class_id) {
  switch (class_id) {
    case 10: return kCar;
    case 71: return kTrunk;
    case 80: return kPole;
    case 1: return kChair;
    case 2: return kTable;
    case 3: return kMonitor;
    default: return kOtherObject;
  }
}

}  // namespace slide::simulator::label
