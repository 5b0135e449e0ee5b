#include "procman/exec_args.h"

#include <cctype>
#include <stdexcept>

namespace slide::procman {
namespace {

std::vector<std::string> splitWords(const std::string& s) {
  std::vector<std::string> words;
  std::string cur;
  bool in_word = false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (c == '\'' || c == '"') {
      const std::size_t close = s.find(c, i + 1);
      if (close == std::string::npos)
        throw std::invalid_argument("unterminated " + std::string(1, c) + " quote in exec string: " + s);
      for (std::size_t j = i + 1; j < close; ++j) {
        if (c == '"' && s[j] == '\\' && j + 1 < close) ++j;
        cur += s[j];
      }
      i = close;
      in_word = true;
    } else if (c == '\\' && i + 1 < s.size()) {
      cur += s[++i];
      in_word = true;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      if (in_word) words.push_back(cur);
      cur.clear();
      in_word = false;
    } else {
      cur += c;
      in_word = true;
    }
  }
  if (in_word) words.push_back(cur);
  return words;
}

bool isAssignment(const std::string& w) {
  const std::size_t eq = w.find('=');
  if (eq == std::string::npos || eq == 0) return false;
  for (std::size_t i = 0; i < eq; ++i) {
    const char c = w[i];
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  }
  return !std::isdigit(static_cast<unsigned char>(w[0]));
}

}  // namespace

ExecArgs splitExec(const std::string& exec) {
  ExecArgs out;
  bool in_env = true;
  for (std::string& w : splitWords(exec)) {
    if (in_env && isAssignment(w)) {
      const std::size_t eq = w.find('=');
      out.env.emplace_back(w.substr(0, eq), w.substr(eq + 1));
    } else {
      in_env = false;
      out.argv.push_back(std::move(w));
    }
  }
  if (out.argv.empty()) throw std::invalid_argument("exec string names no program: '" + exec + "'");
  return out;
}

}  // namespace slide::procman
