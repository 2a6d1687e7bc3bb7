#include <scarp/base/exceptions.h>
#include <scarp/postprocess/json_writer.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace scarp
{
  namespace postprocess
  {
    namespace
    {
      std::string
      quote(const std::string &s)
      {
        std::string r = "\"";
        for (const char c : s)
          {
            if (c == '"' || c == '\\')
              r += '\\';
            if (c == '\n')
              {
                r += "\\n";
                continue;
              }
            r += c;
          }
        return r + "\"";
      }
    } // namespace


    void
    JsonObject::add(const std::string &key, const double value)
    {
      std::ostringstream s;
      s.precision(10);
      if (std::isfinite(value))
        s << value;
      else
        s << "null";
      entries.emplace_back(key, s.str());
    }


    void
    JsonObject::add(const std::string &key, const std::string &value)
    {
      entries.emplace_back(key, quote(value));
    }


    void
    JsonObject::add(const std::string &key, const JsonObject &object)
    {
      entries.emplace_back(key, "\x01" + object.str(1));
    }


    std::string
    JsonObject::str(const unsigned int indent) const
    {
      const std::string pad(2 * (indent + 1), ' ');
      std::string       r = "{\n";
      for (std::size_t k = 0; k < entries.size(); ++k)
        {
          std::string value = entries[k].second;
          if (!value.empty() && value[0] == '\x01')
            {
              // Re-indent a nested object one level deeper.
              value = value.substr(1);
              std::string shifted;
              for (const char c : value)
                {
                  shifted += c;
                  if (c == '\n')
                    shifted += std::string(2 * indent, ' ');
                }
              value = shifted;
            }
          r += pad + quote(entries[k].first) + ": " + value +
               (k + 1 < entries.size() ? ",\n" : "\n");
        }
      return r + std::string(2 * indent, ' ') + "}";
    }


    void
    JsonObject::write(const std::string &filename) const
    {
      const std::string temporary = filename + ".tmp";
      {
        std::ofstream file(temporary);
        if (!file)
          throw ScarpError("Cannot write <" + filename + ">.");
        file << str() << std::endl;
      }
      std::rename(temporary.c_str(), filename.c_str());
    }
  } // namespace postprocess
} // namespace scarp
