#include <deal.II/base/utilities.h>

#include <scarp/base/exceptions.h>
#include <scarp/base/parameter_tools.h>

#include <filesystem>

namespace scarp
{
  namespace ParameterTools
  {
    std::unique_ptr<Patterns::PatternBase>
    double_list(const unsigned int n)
    {
      return std::make_unique<Patterns::List>(Patterns::Double(), n, n, ",");
    }


    std::vector<double>
    get_doubles(const ParameterHandler &prm,
                const std::string      &entry,
                const unsigned int      n)
    {
      const std::string value = prm.get(entry);
      std::vector<double> numbers;
      try
        {
          numbers = Utilities::string_to_double(
            Utilities::split_string_list(value, ','));
        }
      catch (...)
        {
          throw ScarpError("Entry <" + entry + "> = <" + value +
                           "> is not a comma-separated list of numbers.");
        }
      if (numbers.size() != n)
        throw ScarpError("Entry <" + entry + "> = <" + value + "> must have " +
                         std::to_string(n) + " comma-separated numbers, not " +
                         std::to_string(numbers.size()) + ".");
      return numbers;
    }


    template <int dim>
    Point<dim>
    get_point(const ParameterHandler &prm, const std::string &entry)
    {
      const auto x = get_doubles(prm, entry, dim);
      Point<dim> p;
      for (unsigned int d = 0; d < dim; ++d)
        p[d] = x[d];
      return p;
    }


    template <int dim>
    Tensor<1, dim>
    get_vector(const ParameterHandler &prm, const std::string &entry)
    {
      return get_point<dim>(prm, entry);
    }


    void
    parse_file(ParameterHandler  &prm,
               const std::string &filename,
               const bool         skip_undefined)
    {
      namespace fs                = std::filesystem;
      const fs::path absolute     = fs::absolute(filename);
      const fs::path working_dir  = fs::current_path();
      fs::current_path(absolute.parent_path());
      try
        {
          prm.parse_input(absolute.string(), "", skip_undefined);
        }
      catch (...)
        {
          fs::current_path(working_dir);
          throw;
        }
      fs::current_path(working_dir);
    }


    std::vector<std::string>
    get_names(const ParameterHandler &prm, const std::string &entry)
    {
      std::vector<std::string> names;
      for (const auto &name : Utilities::split_string_list(prm.get(entry), ','))
        if (!name.empty())
          names.push_back(name);
      return names;
    }

    template Point<2>
    get_point<2>(const ParameterHandler &, const std::string &);
    template Point<3>
    get_point<3>(const ParameterHandler &, const std::string &);
    template Tensor<1, 2>
    get_vector<2>(const ParameterHandler &, const std::string &);
    template Tensor<1, 3>
    get_vector<3>(const ParameterHandler &, const std::string &);
  } // namespace ParameterTools
} // namespace scarp
