// The estimate of the wall time left, for the progress line.

#include <scarp/postprocess/run_progress.h>

#include <algorithm>

namespace scarp
{
  namespace postprocess
  {
    double
    remaining_wall_time(const double wall,
                        const double t_start,
                        const double t,
                        const double t_end)
    {
      const double done = t - t_start;
      if (!(done > 0.))
        return 0.;
      return wall * std::max(t_end - t, 0.) / done;
    }
  } // namespace postprocess
} // namespace scarp
