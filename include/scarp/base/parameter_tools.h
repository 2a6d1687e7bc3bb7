#ifndef scarp_base_parameter_tools_h
#define scarp_base_parameter_tools_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace scarp
{
  using namespace dealii;

  /**
   * @brief Small helpers to read structured values (points, lists) out of a
   * ParameterHandler with messages that name the entry.
   */
  namespace ParameterTools
  {
    /// A pattern for a comma-separated list of @p n doubles.
    std::unique_ptr<Patterns::PatternBase>
    double_list(const unsigned int n);

    /// Read @p entry as a list of exactly @p n doubles.
    std::vector<double>
    get_doubles(const ParameterHandler &prm,
                const std::string      &entry,
                const unsigned int      n);

    /// Read @p entry as a point of dimension dim.
    template <int dim>
    Point<dim>
    get_point(const ParameterHandler &prm, const std::string &entry);

    /// Read @p entry as a vector (Tensor<1,dim>).
    template <int dim>
    Tensor<1, dim>
    get_vector(const ParameterHandler &prm, const std::string &entry);

    /// Parse @p filename into @p prm with `include` lines resolved relative
    /// to the directory of the including file, at any depth (deal.II
    /// resolves them relative to the working directory). An error is a
    /// ScarpError of one line in the words of the scene file, never deal.II's
    /// exception text: "FILE:LINE: invalid value <VALUE> for
    /// <Subsection/Entry>; accepted: WHAT.", "FILE:LINE: unknown entry
    /// <...>.", "FILE:LINE: unknown subsection <...>.", "FILE:LINE:
    /// subsection <...> is not closed: an 'end' line is missing.", "FILE:
    /// cannot read the file (REASON)."; FILE is the file the user wrote the
    /// line in (an included one, named relative to the scene file's
    /// directory as given). An include cycle is an error.
    void
    parse_file(ParameterHandler  &prm,
               const std::string &filename,
               const bool         skip_undefined = false);

    /// Split a comma-separated list of names, trimming blanks; no empties.
    std::vector<std::string>
    get_names(const ParameterHandler &prm, const std::string &entry);
  } // namespace ParameterTools
} // namespace scarp

#endif
