#pragma once
// Tokens of the .pmd language with their positions (internal to pmd_config.cpp).
#include <string>
#include <vector>

#include "procman/pmd_config.h"

namespace slide::procman {

struct PmdToken {
  enum Type { kIdent, kString, kInteger, kOpen, kClose, kAssign, kEnd, kEof } type;
  std::string text;
  SourcePos pos;
};

// Splits text into tokens (comments start with '#'). Throws PmdError.
std::vector<PmdToken> tokenizePmd(const std::string& text, const std::string& file);

const char* describe(PmdToken::Type t);

}  // namespace slide::procman
