#ifndef scarp_particles_point_mover_h
#define scarp_particles_point_mover_h

#include <deal.II/base/mpi.h>
#include <deal.II/particles/particle_handler.h>

#include <vector>

namespace scarp
{
  namespace particles
  {
    using namespace dealii;

    /**
     * @brief Sorts the points that left their cells into their new cells,
     * also on other ranks, without the particle handler's full sort when
     * every point can be followed; otherwise calls it.
     *
     * ParticleHandler::sort_particles_into_subdomains_and_cells() maps every
     * point to its cell's unit cell (a virtual call each), searches the
     * cells around the closest vertex for those that left, and then
     * rearranges the property memory of all points
     * (PropertyPool::sort_memory_slots): about a tenth of a refined Joss Bay
     * run. Here the reference locations are computed in place, the few
     * points that left find their cell by walking through face neighbours
     * (into the child on their side where the neighbour is finer, through
     * ghost cells too), and only they are moved: inserted into their new
     * cells, those whose new cell is a ghost cell sent to the rank that
     * owns it (one exchange with the ranks that have any), and removed
     * from the old cells, all in the order the full sort uses (on each
     * rank: the points that stay on it, then those received by ascending
     * source rank). So every cell ends up with the same points in the same
     * order and with the same reference locations, bit for bit
     * (tests/refinement/point_mover.cc). Only the property slots of the
     * moved points differ.
     *
     * Meshes of axis-aligned boxes only (MappingCartesian).
     */
    template <int dim>
    class PointMover
    {
    public:
      /// @p compaction_fraction: when the points moved here since the last
      /// full sort exceed this fraction of a rank's points, the full sort
      /// runs again to put the property slots back in order.
      explicit PointMover(const double compaction_fraction = 0.1)
        : compaction_fraction(compaction_fraction)
      {
      }

      /// A cell with points: its points are the entries [begin, end) of a
      /// list of property pool handles (ParticleAccessor::
      /// get_local_index()), in the cell's order.
      struct CellPoints
      {
        typename Triangulation<dim>::active_cell_iterator cell;
        unsigned int                                      begin, end;
      };

      /**
       * Sort the points of @p particles into their cells. @p cells are this
       * rank's active cells that hold points, in the order of the active
       * cell iteration (the particle handler's sort works through them in
       * that order), with their points' @p handles (a caller that keeps
       * them, as MpmTransfer does, spares the walk through the handler's
       * cells). If every point is found in a locally owned or ghost cell
       * on every rank, the points are moved here; otherwise, or when
       * the points moved here since the last full sort exceed the
       * compaction fraction of the points of a rank (their property slots
       * scatter, which slows the sweeps over the points), the particle
       * handler's sort runs on every rank. Collective. Returns true if the
       * points were moved here.
       */
      bool
      sort(Particles::ParticleHandler<dim> &particles,
           const Triangulation<dim>        &triangulation,
           const std::vector<CellPoints>   &cells,
           const std::vector<unsigned int> &handles,
           const MPI_Comm                   communicator);

      /// The same, with the cells and handles gathered from @p particles
      /// on @p triangulation (its mesh).
      bool
      sort(Particles::ParticleHandler<dim> &particles,
           const Triangulation<dim>        &triangulation,
           const MPI_Comm                   communicator);

      /**
       * Put the particle handler's list of cells back in the order of the
       * active cells if a sort() left it out of order, and count the points
       * again (ParticleHandler::update_cached_numbers()). Collective.
       *
       * A point moved into a cell that held none, here or on another rank,
       * adds the cell at the end of the handler's list. The transfer does
       * not mind (it reaches the points cell by cell, in the order of the
       * active cells), and the counts stay right (the point is removed and
       * inserted on its ranks, and none leaves the mesh), but an iteration
       * over all points follows the list: output, diagnostics, splitting,
       * the full sort. The handler's own recount walks every active cell,
       * rebuilds its list and visits every point, which at the front of a
       * flowing debris happened nearly every step (a tenth of the step of
       * the rank holding the front); it now waits until something reads the
       * list. The full sort calls this itself.
       */
      void
      restore_order(Particles::ParticleHandler<dim> &particles);

      /// Whether the handler's list of cells is in order (restore_order()
      /// has nothing to do).
      bool
      order_restored() const
      {
        return !order_stale;
      }

      /// The points moved by the last sort() on this rank (0 if the full
      /// sort ran).
      std::size_t
      n_moved() const
      {
        return n_last_moved;
      }

      /// Of those, the points sent to other ranks.
      std::size_t
      n_sent() const
      {
        return n_last_sent;
      }

      /// The locally owned cells the last sort() put points into (from
      /// this rank or another; repeats possible, in no order). Valid only
      /// if that sort() returned true: then every cell of this rank that
      /// holds points held them before or is in this list, which spares a
      /// caller that keeps its occupied cells the walk over all cells.
      const std::vector<typename Triangulation<dim>::active_cell_iterator> &
      cells_gained() const
      {
        return gained;
      }

      /// The locally owned cells the last sort() took points out of (to
      /// this rank's cells or another's; repeats possible, in no order).
      /// Valid only if that sort() returned true: then a cell in neither
      /// this list nor cells_gained() holds the same points in the same
      /// order as before it.
      const std::vector<typename Triangulation<dim>::active_cell_iterator> &
      cells_lost() const
      {
        return lost;
      }

    private:
      /// Set the reference locations of the points that stay and find the
      /// cells of those that left; false if one leaves this rank's cells or
      /// the mesh (then nothing is to be moved here).
      bool
      find_new_cells(Particles::ParticleHandler<dim> &particles,
                     const std::vector<CellPoints>   &cells,
                     const std::vector<unsigned int> &handles);

      /// Move the points of @p moves; with @p exchange (collective) hand
      /// those bound for other ranks over to them.
      void
      move_points(Particles::ParticleHandler<dim> &particles,
                  const Triangulation<dim>        &triangulation,
                  const bool                       exchange,
                  const MPI_Comm                   communicator);

      /// A point leaving its cell.
      struct Move
      {
        typename Particles::ParticleHandler<dim>::particle_iterator point;
        /// The cell the point leaves and its position in that cell's list.
        typename Triangulation<dim>::active_cell_iterator old_cell;
        unsigned int                                      index_in_cell;
        typename Triangulation<dim>::active_cell_iterator cell;
        Point<dim>                                        reference;
        /// The rank the point goes to, or invalid_subdomain_id if it
        /// stays on this one.
        types::subdomain_id destination;
      };
      std::vector<Move> moves;
      /// The properties of one moving point (the pool may grow while it is
      /// copied).
      std::vector<double> buffer;
      double              compaction_fraction;
      std::size_t         n_last_moved = 0;
      /// Points of @p moves that go to another rank.
      std::size_t n_leaving_rank = 0;
      /// Whether a point of @p moves goes into a cell of this rank that
      /// holds none: the handler then adds the cell at the end of its list,
      /// out of order.
      bool        new_cell_entry = false;
      std::size_t n_last_sent    = 0;
      /// Whether a sort() left the handler's list of cells out of order
      /// (the same on every rank: decided from reduced values).
      bool order_stale = false;
      /// Points moved here since the last full sort.
      std::size_t n_moved_since_full_sort = 0;
      /// See cells_gained() and cells_lost().
      std::vector<typename Triangulation<dim>::active_cell_iterator> gained,
        lost;
      /// The cells and handles of sort(particles, communicator).
      std::vector<CellPoints>   own_cells;
      std::vector<unsigned int> own_handles;
    };
  } // namespace particles
} // namespace scarp

#endif
