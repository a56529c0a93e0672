#pragma once
// Internal invariants, in pbrt-v4's two tiers (src/pbrt/util/check.h): AASIM_CHECK* is always
// on; AASIM_DCHECK* only in debug builds (no NDEBUG) and sanitizer or fuzz builds (AASIM_DCHECKS,
// set by cmake/AasimCompilerOptions.cmake), for checks too costly for a release hot path. A
// failed check prints the expression, both operands and the location to stderr and aborts: it
// is a bug in aasim. Input errors throw instead (std::invalid_argument with the input named), and
// a kernel that breaks a rule of the machine gets a sim::KernelError naming its dispatch.
//
//   AASIM_CHECK(pointer != nullptr);
//   AASIM_CHECK_LT(slot, traffic.size());   // "check failed: slot < traffic.size() (7 vs 3)"

#include <string>
#include <string_view>
#include <type_traits>

namespace sim::detail {

[[noreturn]] void CheckFailed(const char* expression, const char* file, int line);
[[noreturn]] void CheckOpFailed(const char* expression, const char* file, int line, const std::string& left,
                                const std::string& right);

std::string CheckOperand(long long value);
std::string CheckOperand(unsigned long long value);
std::string CheckOperand(double value);
std::string CheckOperand(std::string_view value);
std::string CheckOperand(const void* value);

// Operands are printed by kind, so this header needs no <sstream>.
template <typename T>
std::string FormatCheckOperand(const T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    return value ? "true" : "false";
  } else if constexpr (std::is_enum_v<T>) {
    return FormatCheckOperand(static_cast<std::underlying_type_t<T>>(value));
  } else if constexpr (std::is_integral_v<T> && std::is_signed_v<T>) {
    return CheckOperand(static_cast<long long>(value));
  } else if constexpr (std::is_integral_v<T>) {
    return CheckOperand(static_cast<unsigned long long>(value));
  } else if constexpr (std::is_floating_point_v<T>) {
    return CheckOperand(static_cast<double>(value));
  } else if constexpr (std::is_convertible_v<const T&, std::string_view>) {
    return CheckOperand(std::string_view(value));
  } else if constexpr (std::is_pointer_v<T> || std::is_null_pointer_v<T>) {
    return CheckOperand(static_cast<const void*>(value));
  } else {
    return "(not printable)";
  }
}

}  // namespace sim::detail

#define AASIM_CHECK(condition) \
  ((condition) ? static_cast<void>(0) : ::sim::detail::CheckFailed(#condition, __FILE__, __LINE__))

// Each operand is evaluated once.
#define AASIM_CHECK_OP(left, op, right)                                                                     \
  do {                                                                                                      \
    const auto& aasim_check_left = (left);                                                                  \
    const auto& aasim_check_right = (right);                                                                \
    if (!(aasim_check_left op aasim_check_right)) [[unlikely]] {                                            \
      ::sim::detail::CheckOpFailed(#left " " #op " " #right, __FILE__, __LINE__,                            \
                                   ::sim::detail::FormatCheckOperand(aasim_check_left),                     \
                                   ::sim::detail::FormatCheckOperand(aasim_check_right));                   \
    }                                                                                                       \
  } while (false)

#define AASIM_CHECK_EQ(left, right) AASIM_CHECK_OP(left, ==, right)
#define AASIM_CHECK_NE(left, right) AASIM_CHECK_OP(left, !=, right)
#define AASIM_CHECK_LT(left, right) AASIM_CHECK_OP(left, <, right)
#define AASIM_CHECK_LE(left, right) AASIM_CHECK_OP(left, <=, right)
#define AASIM_CHECK_GT(left, right) AASIM_CHECK_OP(left, >, right)
#define AASIM_CHECK_GE(left, right) AASIM_CHECK_OP(left, >=, right)

#if !defined(NDEBUG) || defined(AASIM_DCHECKS)
#define AASIM_DCHECKS_ACTIVE 1
#define AASIM_DCHECK(condition) AASIM_CHECK(condition)
#define AASIM_DCHECK_EQ(left, right) AASIM_CHECK_EQ(left, right)
#define AASIM_DCHECK_NE(left, right) AASIM_CHECK_NE(left, right)
#define AASIM_DCHECK_LT(left, right) AASIM_CHECK_LT(left, right)
#define AASIM_DCHECK_LE(left, right) AASIM_CHECK_LE(left, right)
#define AASIM_DCHECK_GT(left, right) AASIM_CHECK_GT(left, right)
#define AASIM_DCHECK_GE(left, right) AASIM_CHECK_GE(left, right)
#else
#define AASIM_DCHECKS_ACTIVE 0
// Not evaluated, but still compiled, so a DCHECK cannot rot in release builds.
#define AASIM_DCHECK(condition) static_cast<void>(sizeof(static_cast<bool>(condition)))
#define AASIM_DCHECK_OP_UNEVALUATED(left, op, right) static_cast<void>(sizeof((left)op(right)))
#define AASIM_DCHECK_EQ(left, right) AASIM_DCHECK_OP_UNEVALUATED(left, ==, right)
#define AASIM_DCHECK_NE(left, right) AASIM_DCHECK_OP_UNEVALUATED(left, !=, right)
#define AASIM_DCHECK_LT(left, right) AASIM_DCHECK_OP_UNEVALUATED(left, <, right)
#define AASIM_DCHECK_LE(left, right) AASIM_DCHECK_OP_UNEVALUATED(left, <=, right)
#define AASIM_DCHECK_GT(left, right) AASIM_DCHECK_OP_UNEVALUATED(left, >, right)
#define AASIM_DCHECK_GE(left, right) AASIM_DCHECK_OP_UNEVALUATED(left, >=, right)
#endif
