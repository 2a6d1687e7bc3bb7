#ifndef scarp_particles_body_seeder_h
#define scarp_particles_body_seeder_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/particles/particle_handler.h>

#include <functional>

namespace scarp
{
  namespace particles
  {
    using namespace dealii;

    /**
     * @brief Fills a region with material points: a regular lattice of
     * n x n (x n) points per active cell, the points at the centres of equal
     * sub-cells, each carrying the volume of its sub-cell.
     *
     * The region is given as a predicate, so that this layer does not depend
     * on the geometry builders. Ids are globally unique and contiguous over
     * the MPI ranks, starting from @p first_id.
     */
    template <int dim>
    class BodySeeder
    {
    public:
      /// Called for every new point with its position and volume; it fills
      /// the property array (of the handler's length).
      using Initializer =
        std::function<void(const Point<dim> &, double volume, double *)>;

      /**
       * Seed the locally owned cells. Returns the number of points seeded on
       * all ranks (collective call).
       */
      static types::particle_index
      seed(const parallel::distributed::Triangulation<dim> &tria,
           Particles::ParticleHandler<dim>                 &handler,
           const BoundingBox<dim>                          &region_box,
           const std::function<bool(const Point<dim> &)>   &inside,
           const unsigned int                               per_direction,
           const types::particle_index                      first_id,
           const Initializer                               &initialize);
    };
  } // namespace particles
} // namespace scarp

#endif
