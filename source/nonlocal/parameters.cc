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
      }
      prm.leave_subsection();
    }


    void
    NonlocalParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Non-local average");
      {
        skin_fraction = prm.get_double("Skin distance fraction");
      }
      prm.leave_subsection();
    }
  } // namespace nonlocal
} // namespace scarp
