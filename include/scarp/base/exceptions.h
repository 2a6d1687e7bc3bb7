#ifndef scarp_base_exceptions_h
#define scarp_base_exceptions_h

#include <stdexcept>
#include <string>

namespace scarp
{
  /**
   * @brief The error a run stops with: bad input, an unstable step, a body
   * outside the mesh. Its message names the cause; main() prints it and
   * exits with a non-zero status.
   *
   * Thrown collectively (every MPI rank throws the same message), so that no
   * rank is left waiting in a collective call.
   */
  class ScarpError : public std::runtime_error
  {
  public:
    explicit ScarpError(const std::string &message)
      : std::runtime_error(message)
    {}
  };
} // namespace scarp

#endif
