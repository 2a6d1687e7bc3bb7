#ifndef scarp_particles_point_splitter_h
#define scarp_particles_point_splitter_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/particles/particle_handler.h>

#include <scarp/particles/property_layout.h>

#include <utility>
#include <vector>

namespace scarp
{
  namespace particles
  {
    using namespace dealii;

    /**
     * @brief Splits the material points of refined cells, so that a refined
     * cell keeps the points per cell of the set-up.
     *
     * A point becomes 2^dim children with 1/2^dim of its mass and reference
     * volume. They sit at the centres of the 2^dim sub-boxes of the
     * point's domain (the axis-aligned box of its reference volume, as GIMP
     * sees it, clipped to the mesh box) and keep everything else of the
     * parent: velocity, APIC matrix, deformation gradient, stress, material
     * and body, and the whole material history. The reference position of
     * a child is the parent's moved by F^-1 times the child's offset. Mass
     * and linear and angular momentum are unchanged to round-off, and the
     * kinetic energy is unchanged: the children move with the parent's
     * velocity. The first child keeps the parent's id, the others get new
     * ids, unique over all ranks.
     */
    template <int dim>
    class PointSplitter
    {
    public:
      /// Remember the points of the locally owned cells that carry a refine
      /// flag (after Triangulation::prepare_coarsening_and_refinement()),
      /// with their cell's level.
      void
      record(const Particles::ParticleHandler<dim> &particles,
             const Triangulation<dim>              &tria);

      /// After the refinement (and the particle handler's unpack): split
      /// each recorded point whose cell is now finer than it was. Returns
      /// the number of points split on all ranks (collective). The caller
      /// sorts the particles into cells afterwards.
      types::particle_index
      split(Particles::ParticleHandler<dim> &particles,
            const PropertyLayout<dim>       &layout,
            const BoundingBox<dim>          &box,
            const MPI_Comm                   communicator);

    private:
      /// Sorted (id, level) of the recorded points.
      std::vector<std::pair<types::particle_index, unsigned int>> recorded;
    };
  } // namespace particles
} // namespace scarp

#endif
