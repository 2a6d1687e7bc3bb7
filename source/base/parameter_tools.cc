#include <deal.II/base/utilities.h>

#include <scarp/base/exceptions.h>
#include <scarp/base/parameter_tools.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

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

      /// Where one line of the expanded input came from, as the user wrote
      /// it: the file name relative to the working directory when it was
      /// given so, and the line number in that file.
      struct Origin
      {
        std::string  file;
        unsigned int line;
      };

      /// The input with its includes expanded, line by line.
      struct ExpandedInput
      {
        std::string              text;
        std::vector<std::string> lines;
        std::vector<Origin>      origin;
      };

      std::string
      where(const Origin &origin)
      {
        return origin.file + ":" + std::to_string(origin.line) + ": ";
      }

      /// Why @p file cannot be read, in words (the stream says nothing).
      std::string
      why_unreadable(const fs::path &file)
      {
        std::error_code error;
        const auto      status = fs::status(file, error);
        if (!fs::exists(status))
          return "no such file";
        if (fs::is_directory(status))
          return "it is a directory";
        return "permission denied or not a regular file";
      }

      /// Append the file @p shown (its name as messages show it) to @p input
      /// with its include statements replaced by the files they name, each
      /// resolved relative to the directory of the file that includes it
      /// (deal.II resolves relative to the working directory, so a nested
      /// include from another directory would fail). @p included_at: the
      /// include line, none for the scene file itself. @p stack holds the
      /// canonical names of the files being read, to find cycles.
      void
      expand_includes(const fs::path           &shown,
                      const Origin             *included_at,
                      ExpandedInput            &input,
                      std::vector<std::string> &stack)
      {
        std::error_code   error;
        const std::string name = fs::weakly_canonical(shown, error).string();
        const std::string prefix =
          included_at ? where(*included_at) : shown.string() + ": ";
        for (const auto &open : stack)
          if (open == name)
            throw ScarpError(prefix + "the file <" + shown.string() +
                             "> includes itself (an include cycle).");
        std::ifstream in(shown);
        // An ifstream opens a directory without complaint and reads nothing:
        // the run would go on with every default.
        std::string line;
        if (!in || fs::is_directory(shown, error))
          throw ScarpError(
            prefix +
            (included_at
               ? "cannot read the included file <" + shown.string() + "> (" +
                   why_unreadable(shown) + ")."
               : "cannot read the file (" + why_unreadable(shown) + ")."));
        stack.push_back(name);
        unsigned int number = 0;
        while (std::getline(in, line))
          {
            ++number;
            const Origin      origin{shown.string(), number};
            const std::string code =
              Utilities::trim(line.substr(0, line.find('#')));
            if (code.size() > 8 &&
                (code.rfind("include", 0) == 0 ||
                 code.rfind("INCLUDE", 0) == 0) &&
                std::isspace(static_cast<unsigned char>(code[7])))
              {
                const fs::path target(Utilities::trim(code.substr(8)));
                expand_includes(
                  target.is_absolute()
                    ? target
                    : (shown.parent_path() / target).lexically_normal(),
                  &origin,
                  input,
                  stack);
                continue;
              }
            input.text += line + "\n";
            input.lines.push_back(line);
            input.origin.push_back(origin);
          }
        stack.pop_back();
      }


      /// One statement as deal.II's parser sees it: lines ending in '\'
      /// joined to the next, comment cut off, tabs as blanks, trimmed.
      /// @p last is the index of its last line in the expanded input.
      struct Statement
      {
        std::string  code;
        unsigned int last;
      };

      std::vector<Statement>
      statements(const ExpandedInput &input)
      {
        std::vector<Statement> result;
        std::string            joined;
        for (unsigned int i = 0; i < input.lines.size(); ++i)
          {
            const std::string line = Utilities::trim(input.lines[i]);
            if (!line.empty() && line.back() == '\\')
              {
                joined += line.substr(0, line.size() - 1);
                continue;
              }
            std::string code = joined + line;
            joined.clear();
            code = code.substr(0, code.find('#'));
            for (auto &c : code)
              if (c == '\t')
                c = ' ';
            result.push_back({Utilities::trim(code), i});
          }
        return result;
      }

      bool
      starts_with_keyword(const std::string &code, const std::string &word)
      {
        std::string upper = word;
        for (auto &c : upper)
          c = std::toupper(static_cast<unsigned char>(c));
        return code.size() > word.size() &&
               (code.rfind(word, 0) == 0 || code.rfind(upper, 0) == 0) &&
               code[word.size()] == ' ';
      }

      /// The name of the subsection that @p code opens, blanks collapsed
      /// as deal.II does.
      std::string
      subsection_name(const std::string &code)
      {
        std::string name;
        for (const char c : Utilities::trim(code.substr(11)))
          if (!(c == ' ' && !name.empty() && name.back() == ' '))
            name += c;
        return name;
      }

      bool
      is_end(const std::string &code)
      {
        return code.rfind("end", 0) == 0 || code.rfind("END", 0) == 0;
      }

      /// A subsection open at some point of the input.
      struct OpenSubsection
      {
        std::string  name;
        unsigned int line;
      };

      /// The subsections open before line @p n of the expanded input
      /// (all of them at its end for n = size).
      std::vector<OpenSubsection>
      open_subsections(const std::vector<Statement> &all, const unsigned int n)
      {
        std::vector<OpenSubsection> open;
        for (const auto &s : all)
          {
            if (s.last >= n)
              break;
            if (starts_with_keyword(s.code, "subsection"))
              open.push_back({subsection_name(s.code), s.last});
            else if (is_end(s.code) && !open.empty())
              open.pop_back();
          }
        return open;
      }

      /// "Mesh/Boundary conditions/Bottom" for entry @p name (or the
      /// subsection path itself when it is empty).
      std::string
      path_of(const std::vector<OpenSubsection> &open,
              const std::string                 &name = "")
      {
        std::string path;
        for (const auto &s : open)
          path += (path.empty() ? "" : "/") + s.name;
        return name.empty() ? path : path.empty() ? name : path + "/" + name;
      }

      /// The statement ending on line @p n of the expanded input.
      std::string
      statement_at(const std::vector<Statement> &all, const unsigned int n)
      {
        for (const auto &s : all)
          if (s.last == n)
            return s.code;
        return "";
      }

      /// "from 0 to 1", ">= 0", "" for the range [@p low, @p high] whose
      /// unbounded ends deal.II writes as MAX_DOUBLE or the integer limits.
      std::string
      range_text(const std::string &low, const std::string &high)
      {
        const bool no_low  = low == "-MAX_DOUBLE" || low == "-2147483648";
        const bool no_high = high == "MAX_DOUBLE" || high == "2147483647";
        if (no_low && no_high)
          return "";
        if (no_high)
          return " >= " + low;
        if (no_low)
          return " <= " + high;
        return " from " + low + " to " + high;
      }

      /// What a pattern accepts, in words, from its machine description
      /// (what deal.II's exception carries): "a number from 0 to 1" for
      /// "[Double 0...1 (inclusive)]", "a comma-separated list of 2 numbers"
      /// for a point. @p plural: the form for the elements of a list.
      std::string
      describe_pattern(const std::string &machine, const bool plural = false)
      {
        std::smatch m;
        const auto  matches = [&](const char *expression) {
          return std::regex_match(machine, m, std::regex(expression));
        };
        if (matches("\\[Double (\\S+)\\.\\.\\.(\\S+) \\(inclusive\\)\\]"))
          return (plural ? "numbers" : "a number") +
                 range_text(m[1].str(), m[2].str());
        if (matches(
              "\\[Integer range (\\S+)\\.\\.\\.(\\S+) \\(inclusive\\)\\]"))
          return (plural ? "integers" : "an integer") +
                 range_text(m[1].str(), m[2].str());
        if (matches("\\[Selection (.*) \\]"))
          {
            std::string options = m[1].str();
            for (auto pos = options.find('|'); pos != std::string::npos;
                 pos      = options.find('|'))
              options.replace(pos, 1, ", ");
            return (plural ? "entries, each one of " : "one of ") + options;
          }
        if (matches("\\[Bool\\]"))
          return plural ? "true or false entries" : "true or false";
        if (matches("\\[Anything\\]"))
          return plural ? "entries" : "anything";
        if (matches("\\[List of <(.*)> of length (\\S+)\\.\\.\\.(\\S+) "
                    "\\(inclusive\\)( separated by <(.*)>)?\\]"))
          {
            const std::string low = m[2].str(), high = m[3].str();
            const bool        unbounded = high == "4294967295";
            const std::string count     = low == high               ? low + " "
                                          : unbounded && low == "0" ? ""
                                          : unbounded && low == "1" ? "one or more "
                                          : unbounded ? "at least " + low + " "
                                                      : low + " to " + high + " ";
            const std::string separator = m[5].matched && m[5].str() != ","
                                            ? "<" + m[5].str() + ">-separated"
                                            : "comma-separated";
            return "a " + separator + " list of " + count +
                   describe_pattern(m[1].str(), true);
          }
        // Anything else: deal.II's own words.
        try
          {
            std::string text = Patterns::pattern_factory(machine)->description(
              Patterns::PatternBase::Text);
            while (!text.empty() && (text.back() == '.' || text.back() == '\n'))
              text.pop_back();
            if (!text.empty())
              {
                text[0] = std::tolower(static_cast<unsigned char>(text[0]));
                return text;
              }
          }
        catch (...)
          {
          }
        return machine;
      }

      /// One readable line for deal.II's parse error @p e on @p input: the
      /// file and line the user wrote, the entry with its subsection path,
      /// the value and what is accepted; no exception names.
      std::string
      readable_parse_error(const ExceptionBase &e, const ExpandedInput &input)
      {
        const auto        all = statements(input);
        std::stringstream info;
        e.print_info(info);
        const std::string text = info.str();
        std::smatch       m;

        if (dynamic_cast<const ParameterHandler::ExcUnbalancedSubsections *>(
              &e))
          {
            const auto open = open_subsections(all, input.lines.size());
            if (!open.empty())
              return where(input.origin[open.back().line]) + "subsection <" +
                     path_of(open) +
                     "> is not closed: an 'end' line is missing.";
            return "the input has more 'end' lines than subsections.";
          }

        unsigned int n = input.lines.size();
        if (std::regex_search(text, m, std::regex("Line <([0-9]+)>")))
          n = std::stoul(m[1].str()) - 1;
        if (n >= input.lines.size())
          return "in the input: " + Utilities::trim(text);
        const std::string here = where(input.origin[n]);
        const auto        open = open_subsections(all, n);
        const std::string code = statement_at(all, n);

        if (dynamic_cast<const ParameterHandler::ExcNoSubsection *>(&e))
          return here + "unknown subsection <" +
                 path_of(open, subsection_name(code)) + ">.";

        // "set NAME = VALUE"
        const auto        equal = code.find('=');
        const std::string name  = equal == std::string::npos
                                    ? ""
                                    : Utilities::trim(code.substr(4, equal - 4));
        const std::string value = equal == std::string::npos
                                    ? ""
                                    : Utilities::trim(code.substr(equal + 1));
        if (dynamic_cast<const ParameterHandler::ExcInvalidEntryForPattern *>(
              &e))
          {
            std::string accepted;
            if (std::regex_search(
                  text,
                  m,
                  std::regex("does not match the given pattern:\\s*([^\\n]*)")))
              accepted =
                "; accepted: " + describe_pattern(Utilities::trim(m[1].str()));
            return here + "invalid value <" + value + "> for <" +
                   path_of(open, name) + ">" + accepted + ".";
          }
        if (dynamic_cast<const ParameterHandler::ExcCannotParseLine *>(&e))
          {
            if (text.find("No entry with name") != std::string::npos)
              return here + "unknown entry <" + path_of(open, name) + ">.";
            if (is_end(code) && open.empty())
              return here + "an 'end' line without an open subsection.";
            // deal.II's own reason, without its line prefix.
            std::string reason = text;
            if (std::regex_search(
                  text, m, std::regex("Line <[0-9]+> of file <[^>]*>:\\s*")))
              reason = m.suffix().str();
            return here + Utilities::trim(reason);
          }
        return here + Utilities::trim(text);
      }
    } // namespace


    void
    parse_file(ParameterHandler  &prm,
               const std::string &filename,
               const bool         skip_undefined)
    {
      ExpandedInput            input;
      std::vector<std::string> stack;
      expand_includes(fs::path(filename).lexically_normal(),
                      nullptr,
                      input,
                      stack);
      try
        {
          prm.parse_input_from_string(input.text, "", skip_undefined);
        }
      catch (const ExceptionBase &e)
        {
          throw ScarpError(readable_parse_error(e, input));
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
