#ifndef scarp_nonlocal_parameters_h
#define scarp_nonlocal_parameters_h

#include <deal.II/base/parameter_handler.h>

namespace scarp
{
  namespace nonlocal
  {
    using namespace dealii;

    /**
     * @brief Numerical parameters of the non-local average, in the
     * subsection "Non-local average" of a scene file.
     *
     * The physics (weight type and l_c) belongs to the material; these are
     * the knobs of the neighbour search, which change the cost but not the
     * answer, and the update interval, which trades a small, measured
     * change of the answer for cost.
     */
    struct NonlocalParameters
    {
      /// Skin distance as a fraction of the cut-off radius: neighbour lists
      /// hold pairs up to (1 + skin fraction) times the cut-off and are
      /// reused until some point has moved more than half the skin.
      double skin_fraction = 0.1;

      /// The average is computed every this many steps of a damage stage
      /// (and at its first step); the steps between reuse each point's last
      /// Ybar. 1: every step (exact). An approximation: see doc/nonlocal.md,
      /// "Update interval", for its measured effect.
      unsigned int update_interval = 1;

      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm);
    };
  } // namespace nonlocal
} // namespace scarp

#endif
