#include <scarp/base/exceptions.h>
#include <scarp/postprocess/statistics_file.h>

#include <iomanip>

namespace scarp
{
  namespace postprocess
  {
    StatisticsFile::StatisticsFile(const std::string              &filename,
                                   const std::vector<std::string> &columns,
                                   const bool                      is_writer,
                                   const bool                      append)
      : n_columns(columns.size())
      , is_writer(is_writer)
    {
      if (!is_writer)
        return;
      if (append)
        {
          file.open(filename, std::ios::app);
          if (!file)
            throw ScarpError("Cannot append to <" + filename + ">.");
          return;
        }
      file.open(filename);
      if (!file)
        throw ScarpError("Cannot write <" + filename + ">.");
      for (std::size_t k = 0; k < columns.size(); ++k)
        file << (k ? "," : "") << columns[k];
      file << std::endl;
    }


    void
    StatisticsFile::write_row(const std::vector<double> &values)
    {
      if (!is_writer)
        return;
      file << std::setprecision(10);
      for (std::size_t k = 0; k < values.size() && k < n_columns; ++k)
        file << (k ? "," : "") << values[k];
      file << std::endl;
    }
  } // namespace postprocess
} // namespace scarp
