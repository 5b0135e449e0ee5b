#include "procman/output_lines.h"

namespace slide::procman {

std::vector<std::string> outputLines(const std::string& text) {
  std::vector<std::string> lines;
  for (std::size_t b = 0; b < text.size();) {
    std::size_t e = text.find('\n', b);
    const std::size_t next = e == std::string::npos ? text.size() : e + 1;
    if (e == std::string::npos) e = text.size();
    if (e > b && text[e - 1] == '\r') --e;
    lines.push_back(text.substr(b, e - b));
    b = next;
  }
  return lines;
}

}  // namespace slide::procman
