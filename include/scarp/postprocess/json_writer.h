#ifndef scarp_postprocess_json_writer_h
#define scarp_postprocess_json_writer_h

#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <string>
#include <utility>
#include <vector>

namespace scarp
{
  namespace postprocess
  {
    /**
     * @brief A flat-or-nested JSON object built up key by key, for
     * summary.json. Numbers are written as numbers (Boost's property tree
     * would quote them).
     */
    class JsonObject
    {
    public:
      void
      add(const std::string &key, const double value);
      void
      add(const std::string &key, const std::string &value);
      void
      add(const std::string &key, const JsonObject &object);

      std::string
      str(const unsigned int indent = 0) const;

      /// Write to a file via a temporary and a rename, so that a reader
      /// never sees half a file.
      void
      write(const std::string &filename) const;

      /// For checkpoints (boost serialization).
      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &entries;
      }

    private:
      std::vector<std::pair<std::string, std::string>> entries;
    };
  } // namespace postprocess
} // namespace scarp

#endif
