#ifndef scarp_postprocess_statistics_file_h
#define scarp_postprocess_statistics_file_h

#include <fstream>
#include <string>
#include <vector>

namespace scarp
{
  namespace postprocess
  {
    /**
     * @brief statistics.csv: one row per statistics interval, flushed at once
     * so that the file is complete up to the last step even if a run stops.
     * Only rank 0 writes.
     */
    class StatisticsFile
    {
    public:
      /// With @p append the file exists (restored from a checkpoint) and
      /// rows are appended to it; else it is created with a header line.
      StatisticsFile(const std::string              &filename,
                     const std::vector<std::string> &columns,
                     const bool                      is_writer,
                     const bool                      append = false);

      /// Append a row (values in the order of the columns).
      void
      write_row(const std::vector<double> &values);

    private:
      std::ofstream file;
      std::size_t   n_columns;
      bool          is_writer;
    };
  } // namespace postprocess
} // namespace scarp

#endif
