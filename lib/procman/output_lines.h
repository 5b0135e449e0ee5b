#pragma once
// Splits the text of a PM_OUTPUT entry into lines. Deputies that run children on a pty (as
// procman's does) end lines with "\r\n", pipes with "\n": both end a line, and the '\r' is
// not part of it. A last line without an ending is kept.
#include <string>
#include <vector>

namespace slide::procman {

std::vector<std::string> outputLines(const std::string& text);

}  // namespace slide::procman
