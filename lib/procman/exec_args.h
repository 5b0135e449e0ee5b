#pragma once
// Splits a procman exec string into leading NAME=value environment assignments and argv,
// honouring single quotes, double quotes and backslash escapes like a POSIX shell (no
// expansion). Throws std::invalid_argument for an unterminated quote or an empty command.
#include <string>
#include <utility>
#include <vector>

namespace slide::procman {

struct ExecArgs {
  std::vector<std::pair<std::string, std::string>> env;
  std::vector<std::string> argv;
};

ExecArgs splitExec(const std::string& exec);

}  // namespace slide::procman
