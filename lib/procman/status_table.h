#pragma once
// The sheriff's status table as text: one row per configured command.
#include <string>

#include "procman/sheriff_model.h"

namespace slide::procman {

std::string formatStatusTable(const SheriffModel& model);

}  // namespace slide::procman
