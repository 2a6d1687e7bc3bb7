#ifndef scarp_postprocess_run_progress_h
#define scarp_postprocess_run_progress_h

namespace scarp
{
  namespace postprocess
  {
    /**
     * The wall time left until simulated time @p t_end at the pace of this
     * run: @p wall seconds of wall time took the simulation from
     * @p t_start to @p t. A resumed run passes the time of its checkpoint
     * as @p t_start, so that its estimate does not count the simulated
     * time of the runs before it as done in its own wall time. Zero before
     * any simulated time has passed or at the end.
     */
    double
    remaining_wall_time(const double wall,
                        const double t_start,
                        const double t,
                        const double t_end);
  } // namespace postprocess
} // namespace scarp

#endif
