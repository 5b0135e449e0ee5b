#pragma once
// Numbers in text files and command-line values: one token is one number (strtod syntax, the
// whole token; "nan" and "inf" are numbers, callers that need finite values check).
#include <optional>
#include <string>
#include <vector>

namespace slide::io {

// nullopt unless the whole token is a number.
std::optional<double> parseNumber(const std::string& token);

// The numbers of `text`, separated by white space. Throws std::invalid_argument("'TOKEN' is not
// a number") at the first token that is not one; callers prefix where it stands.
std::vector<double> parseNumberList(const std::string& text);

}  // namespace slide::io
