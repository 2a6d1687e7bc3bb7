#ifndef scarp_grid_refinement_marker_h
#define scarp_grid_refinement_marker_h

#include <deal.II/distributed/tria.h>

#include <vector>

namespace scarp
{
  namespace grid
  {
    using namespace dealii;

    /**
     * @brief Sets the refine flags of a pass from the cells that hold a
     * point meeting a criterion ("seeds"), the same on any number of ranks.
     *
     * The seeds of every rank are gathered on all ranks, and each rank flags
     * its own cells whose box lies within @p buffer (in the max norm, which
     * covers the Euclidean ball) of a seed's box. The result depends on the
     * set of seeds only, never on the partition; the triangulation's
     * smoothing then adds what the level balance needs, also independently
     * of the partition (p4est exchanges the flags).
     */
    template <int dim>
    class RefinementMarker
    {
    public:
      /// Flag the locally owned cells below @p max_level that are seeds or
      /// lie within @p buffer of a seed of any rank. Returns the number of
      /// cells flagged on all ranks (collective).
      static unsigned int
      mark(parallel::distributed::Triangulation<dim> &tria,
           const std::vector<typename Triangulation<dim>::active_cell_iterator>
                             &seeds,
           const double       buffer,
           const unsigned int max_level);
    };
  } // namespace grid
} // namespace scarp

#endif
