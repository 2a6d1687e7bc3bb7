#ifndef scarp_tests_scenes_check_h
#define scarp_tests_scenes_check_h

// Minimal checks for the scenes tests: report every failure, exit non-zero
// at the end (see finish()).

#include <cmath>
#include <exception>
#include <iostream>
#include <string>

namespace scenes_test
{
  inline unsigned int n_failures = 0;

  inline int
  finish()
  {
    if (n_failures > 0)
      std::cout << n_failures << " check(s) FAILED" << std::endl;
    else
      std::cout << "OK" << std::endl;
    return n_failures > 0 ? 1 : 0;
  }

  /// @p text with every run of blanks and line breaks turned into one
  /// blank: deal.II wraps the text of an ExcMessage at about 80 columns.
  inline std::string
  collapse_blanks(const std::string &text)
  {
    std::string result;
    for (const char c : text)
      {
        const bool blank = (c == ' ' || c == '\n' || c == '\t');
        if (!blank)
          result += c;
        else if (!result.empty() && result.back() != ' ')
          result += ' ';
      }
    return result;
  }

  /// The message of the exception that @p f throws (blanks collapsed), ""
  /// if it does not throw.
  template <typename F>
  std::string
  message_of(const F &f)
  {
    try
      {
        f();
      }
    catch (const std::exception &e)
      {
        return collapse_blanks(e.what());
      }
    return "";
  }
} // namespace scenes_test

#define CHECK(condition)                                           \
  do                                                               \
    {                                                              \
      if (!(condition))                                            \
        {                                                          \
          std::cout << __FILE__ << ":" << __LINE__                 \
                    << ": CHECK failed: " #condition << std::endl; \
          ++scenes_test::n_failures;                               \
        }                                                          \
    }                                                              \
  while (false)

#define CHECK_CLOSE(a, b, tolerance)                                         \
  do                                                                         \
    {                                                                        \
      const double _a = (a), _b = (b);                                       \
      if (!(std::abs(_a - _b) <= (tolerance)))                               \
        {                                                                    \
          std::cout << __FILE__ << ":" << __LINE__                           \
                    << ": CHECK_CLOSE failed: " << #a << " = " << _a << ", " \
                    << #b << " = " << _b << ", tolerance " << (tolerance)    \
                    << std::endl;                                            \
          ++scenes_test::n_failures;                                         \
        }                                                                    \
    }                                                                        \
  while (false)

// Checks that @p statement throws and that the message contains @p text.
#define CHECK_THROWS_WITH(statement, text)                                     \
  do                                                                           \
    {                                                                          \
      const std::string _m = scenes_test::message_of([&]() { statement; });    \
      if (_m.find(text) == std::string::npos)                                  \
        {                                                                      \
          std::cout << __FILE__ << ":" << __LINE__ << ": expected " #statement \
                    << " to throw a message with '" << (text) << "', got '"    \
                    << _m << "'" << std::endl;                                 \
          ++scenes_test::n_failures;                                           \
        }                                                                      \
    }                                                                          \
  while (false)

#endif
