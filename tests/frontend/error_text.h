#pragma once
// The message of what `f` throws ("(nothing thrown)" when it returns): for tests that check
// an error names the file and what was expected.
#include <exception>
#include <functional>
#include <string>

namespace slide::test {

inline std::string errorText(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

}  // namespace slide::test
