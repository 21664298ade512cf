// SPDX-License-Identifier: BSD-3-Clause
// Small helpers shared by the C++ tests: numeric checks that count failures,
// so one run reports every broken assertion, and the exit code fails ctest.
#ifndef DSTestHelpers_h
#define DSTestHelpers_h

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

namespace dstest
{
inline int& Failures()
{
  static int failures = 0;
  return failures;
}

inline void Check(bool ok, const std::string& what, const char* file, int line)
{
  if (!ok)
  {
    ++Failures();
    std::cerr << file << ":" << line << ": FAILED: " << what << std::endl;
  }
}

inline int Result(const char* name)
{
  if (Failures() != 0)
  {
    std::cerr << name << ": " << Failures() << " check(s) failed" << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << name << ": all checks passed" << std::endl;
  return EXIT_SUCCESS;
}
} // namespace dstest

/// DS_CHECK(cond, message): counts a failure when cond is false.
#define DS_CHECK(cond, msg)                                                                        \
  ::dstest::Check(static_cast<bool>(cond), std::string(#cond) + " -- " + (msg), __FILE__, __LINE__)
/// DS_CHECK_LE(value, limit, what): value <= limit, printing both.
#define DS_CHECK_LE(v, lim, what)                                                                  \
  do                                                                                               \
  {                                                                                                \
    const double ds_v_ = (v), ds_l_ = (lim);                                                       \
    std::cout << "  " << (what) << " = " << ds_v_ << " (limit <= " << ds_l_ << ")" << std::endl;   \
    ::dstest::Check(ds_v_ <= ds_l_,                                                                \
      std::string(what) + " = " + std::to_string(ds_v_) + " > " + std::to_string(ds_l_), __FILE__, \
      __LINE__);                                                                                   \
  } while (0)
/// DS_CHECK_GE(value, limit, what): value >= limit, printing both.
#define DS_CHECK_GE(v, lim, what)                                                                  \
  do                                                                                               \
  {                                                                                                \
    const double ds_v_ = (v), ds_l_ = (lim);                                                       \
    std::cout << "  " << (what) << " = " << ds_v_ << " (limit >= " << ds_l_ << ")" << std::endl;   \
    ::dstest::Check(ds_v_ >= ds_l_,                                                                \
      std::string(what) + " = " + std::to_string(ds_v_) + " < " + std::to_string(ds_l_), __FILE__, \
      __LINE__);                                                                                   \
  } while (0)

#endif
