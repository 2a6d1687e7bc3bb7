#include <scarp/nonlocal/parameters.h>

namespace scarp
{
  namespace nonlocal
  {
    void
    NonlocalParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Non-local average");
      {
        prm.declare_entry(
          "Skin distance fraction",
          "0.1",
          Patterns::Double(0.),
          "Skin distance of the neighbour lists, as a fraction of the "
          "cut-off radius of the weight (sqrt(7) l_c for the bell, 3 l_c for "
          "the Gaussian). The lists hold all pairs up to cut-off + skin and "
          "are reused until a point has moved more than half the skin, the "
          "points or the mesh partition change. Larger: fewer rebuilds, "
          "longer lists. 0 rebuilds whenever a point moves. Does not change "
          "the result.");
        prm.declare_entry(
          "Update interval",
          "1",
          Patterns::Integer(1),
          "The non-local average is computed every this many steps of a "
          "damage stage, and at the stage's first step and before every "
          "refinement check; in the steps between, each point's damage is "
          "driven by the Ybar of the last average (kappa and d are still "
          "updated every step). 1 (the default) computes it every step. "
          "Larger values cut the cost of the average by about this factor "
          "and change the result slightly: Ybar lags by less than this many "
          "steps, while kappa follows Ybar at the rate 1/tau "
          "(doc/nonlocal.md, \"Update interval\", has the measured effect "
          "on the Joss Bay failure onset).");
      }
      prm.leave_subsection();
    }


    void
    NonlocalParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Non-local average");
      {
        skin_fraction   = prm.get_double("Skin distance fraction");
        update_interval = prm.get_integer("Update interval");
      }
      prm.leave_subsection();
    }
  } // namespace nonlocal
} // namespace scarp
