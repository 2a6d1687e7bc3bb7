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
     *
     * With @p current_volume the point's size is that of the larger of its
     * current volume V0 det F and V0: a point that dilated past twice its
     * cell's share splits without a refinement. Its children sit at F times
     * the offsets of the sub-boxes of its reference box, inside the
     * parallelogram it has become (reference offsets +-V0^(1/dim)/4), and a
     * point splits this way only while V0 is at least half its cell's
     * share, so at most once below it: children keep F, and those of a
     * point dilated a thousandfold would otherwise split at every pass.
     * By the current volume every offset is at most half the parent's cell
     * along each axis, so that a child lies in its parent's cell or one
     * touching it (owned or ghost): the sort cannot lose it.
     */
    template <int dim>
    class PointSplitter
    {
    public:
      /// Split every locally owned point that is too large for its cell:
      /// its domain side V0^(1/dim) exceeds sqrt(2) h_K / n_b, with h_K the
      /// edge of its cell and n_b the points per cell direction of its body
      /// (@p points_per_direction, by body id). After a refinement this is
      /// every point of a refined cell; a point that drifted into a finer
      /// cell is split at the next pass too. With @p current_volume the
      /// side is max(V0, V0 |det F|)^(1/dim), and points with V0 below half
      /// of (h_K / n_b)^dim are left alone. The rule reads only the point
      /// and its cell, so it gives the same points on any partition.
      /// Returns the number of points split on all ranks (collective); the
      /// caller sorts the particles into cells afterwards.
      static types::particle_index
      split(Particles::ParticleHandler<dim> &particles,
            const PropertyLayout<dim>       &layout,
            const std::vector<unsigned int> &points_per_direction,
            const BoundingBox<dim>          &box,
            const MPI_Comm                   communicator,
            const bool                       current_volume = false);
    };
  } // namespace particles
} // namespace scarp

#endif
