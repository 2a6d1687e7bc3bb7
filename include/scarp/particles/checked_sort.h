#ifndef scarp_particles_checked_sort_h
#define scarp_particles_checked_sort_h

#include <deal.II/base/mpi.h>
#include <deal.II/particles/particle_handler.h>

#include <string>

namespace scarp
{
  namespace particles
  {
    using namespace dealii;

    /**
     * @brief Sorts the points into their subdomains and cells, and stops the
     * run if the sort lost any.
     *
     * deal.II's ParticleHandler::sort_particles_into_subdomains_and_cells()
     * deletes a point it cannot place and only signals it. A point that
     * left the mesh goes that way on purpose (the removal of stretched
     * points puts them beyond the mesh's corner); a point inside the mesh
     * is lost only when it lies beyond the cells its rank owns or has as
     * ghosts, which is lost mass and a bug. So the sort is collective, and
     * if any rank lost a point inside the bounding box of the mesh
     * (by more than 1e-10 of its size), every rank throws an ExcMessage
     * naming how many were lost, the mass they carried, where the first of
     * them was, and @p when (what the run was doing).
     */
    template <int dim>
    class CheckedSort
    {
    public:
      /// Sort @p particles; throws on every rank if a point was lost.
      /// @p mass_index is the property that holds a point's mass
      /// (numbers::invalid_unsigned_int: the message leaves the mass out).
      static void
      sort(Particles::ParticleHandler<dim> &particles,
           const Triangulation<dim>        &triangulation,
           const unsigned int               mass_index,
           const std::string               &when,
           const MPI_Comm                   communicator);
    };
  } // namespace particles
} // namespace scarp

#endif
