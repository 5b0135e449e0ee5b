#pragma once
// Per-point class labels written by the simulator, in the SemanticKITTI convention
// (labels/*.label: lower 16 bits class, upper 16 bits instance; instance = object index + 1,
// 0 for points that belong to no ground-truth object).
// SemanticKITTI has no indoor furniture classes; the simulator uses the otherwise unused ids
// 100-102 for them (chair, table, monitor) so a segmenter can still tell them apart.
#include <cstdint>

namespace slide::simulator::label {

constexpr uint16_t kUnlabeled = 0;
constexpr uint16_t kCar = 10;
constexpr uint16_t kRoad = 40;
constexpr uint16_t kParking = 44;
constexpr uint16_t kSidewalk = 48;
constexpr uint16_t kOtherGround = 49;
constexpr uint16_t kBuilding = 50;
constexpr uint16_t kFence = 51;
constexpr uint16_t kOtherStructure = 52;
constexpr uint16_t kVegetation = 70;
constexpr uint16_t kTrunk = 71;
constexpr uint16_t kTerrain = 72;
constexpr uint16_t kPole = 80;
constexpr uint16_t kTrafficSign = 81;
constexpr uint16_t kOtherObject = 99;
// Simulator extensions (not in SemanticKITTI).
constexpr uint16_t kChair = 100;
constexpr uint16_t kTable = 101;
constexpr uint16_t kMonitor = 102;

// Class id of config/classes.yaml that a simulator label means (0 "other" for anything else).
int classIdOfLabel(uint16_t semantic);
// SemanticKITTI-style label the simulator writes for points of an object of class `class_id`.
uint16_t labelOfClassId(int class_id);

}  // namespace slide::simulator::label
