#pragma once
#include <stdexcept>
#include <string>

namespace slide::io {

// A dataset file that is missing, truncated or unparsable; the message names the file.
class IoError : public std::runtime_error {
 public:
  IoError(const std::string& path, const std::string& problem) : std::runtime_error(path + ": " + problem) {}
};

}  // namespace slide::io
