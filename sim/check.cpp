// Failure reports of sim/check.h.

#include "sim/check.h"

#include <cstdio>
#include <cstdlib>

namespace sim::detail {

void CheckFailed(const char* expression, const char* file, int line) {
  std::fprintf(stderr, "aasim: check failed at %s:%d: %s\n", file, line, expression);
  std::abort();
}

void CheckOpFailed(const char* expression, const char* file, int line, const std::string& left,
                   const std::string& right) {
  std::fprintf(stderr, "aasim: check failed at %s:%d: %s (%s vs %s)\n", file, line, expression, left.c_str(),
               right.c_str());
  std::abort();
}

std::string CheckOperand(long long value) { return std::to_string(value); }
std::string CheckOperand(unsigned long long value) { return std::to_string(value); }

std::string CheckOperand(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.17g", value);
  return text;
}

std::string CheckOperand(std::string_view value) {
  // Appended piecewise: GCC 12 flags "\"" + string with a false -Wrestrict.
  std::string quoted = "\"";
  quoted += value;
  quoted += '"';
  return quoted;
}

std::string CheckOperand(const void* value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%p", value);
  return text;
}

}  // namespace sim::detail
