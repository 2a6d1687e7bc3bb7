#include <deal.II/base/utilities.h>

#include <scarp/base/exceptions.h>
#include <scarp/base/parameter_tools.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <regex>

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
      const std::string   value = prm.get(entry);
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


    namespace
    {
      namespace fs = std::filesystem;

      /// Where one line of the expanded input came from.
      struct Origin
      {
        std::string  file;
        unsigned int line;
      };

      /// Append @p file to @p text with its include statements replaced by
      /// the files they name, each resolved relative to the directory of
      /// the file that includes it (deal.II resolves relative to the
      /// working directory, so a nested include from another directory
      /// would fail).
      void
      expand_includes(const fs::path           &file,
                      std::string              &text,
                      std::vector<Origin>      &origin,
                      std::vector<std::string> &stack)
      {
        const std::string name = file.lexically_normal().string();
        for (const auto &open : stack)
          if (open == name)
            throw ScarpError("The parameter file <" + name +
                             "> includes itself (include cycle through <" +
                             stack.back() + ">).");
        std::ifstream in(name);
        if (!in)
          throw ScarpError("Cannot open the parameter file <" + name + ">" +
                           (stack.empty()
                              ? std::string(".")
                              : " included from <" + stack.back() + ">."));
        stack.push_back(name);
        std::string  line;
        unsigned int number = 0;
        while (std::getline(in, line))
          {
            ++number;
            const std::string code =
              Utilities::trim(line.substr(0, line.find('#')));
            if (code.size() > 8 &&
                (code.rfind("include", 0) == 0 ||
                 code.rfind("INCLUDE", 0) == 0) &&
                std::isspace(static_cast<unsigned char>(code[7])))
              {
                const fs::path target(Utilities::trim(code.substr(8)));
                expand_includes(target.is_absolute()
                                  ? target
                                  : file.parent_path() / target,
                                text,
                                origin,
                                stack);
                continue;
              }
            text += line + "\n";
            origin.push_back({name, number});
          }
        stack.pop_back();
      }
    } // namespace


    void
    parse_file(ParameterHandler  &prm,
               const std::string &filename,
               const bool         skip_undefined)
    {
      std::string              text;
      std::vector<Origin>      origin;
      std::vector<std::string> stack;
      expand_includes(fs::absolute(filename), text, origin, stack);
      try
        {
          prm.parse_input_from_string(text, "", skip_undefined);
        }
      catch (const ExceptionBase &e)
        {
          // deal.II numbers the lines of the expanded text; name the file
          // and line the user wrote instead.
          std::string       message = e.what();
          const std::regex  where("Line <([0-9]+)> of file <[^>]*>");
          std::smatch       m;
          const std::string key = message;
          if (std::regex_search(key, m, where))
            {
              const unsigned long n = std::stoul(m[1].str());
              if (n >= 1 && n <= origin.size())
                message.replace(m.position(0),
                                m.length(0),
                                "Line <" + std::to_string(origin[n - 1].line) +
                                  "> of file <" + origin[n - 1].file + ">");
            }
          throw ScarpError("in the input: " + std::string(e.get_exc_name()) +
                           "\n" + message);
        }
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
