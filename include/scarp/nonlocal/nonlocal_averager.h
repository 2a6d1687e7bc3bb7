#ifndef scarp_nonlocal_nonlocal_averager_h
#define scarp_nonlocal_nonlocal_averager_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/types.h>

#include <deal.II/particles/property_pool.h>

#include <scarp/nonlocal/weight_function.h>

#include <array>
#include <cstdint>
#include <vector>

namespace scarp
{
  namespace nonlocal
  {
    using namespace dealii;

    /**
     * @brief Volume-weighted, renormalised non-local average of a scalar over
     * material points on all MPI ranks:
     * Ybar_p = sum_q w(|x_p - x_q|) V_q Y_q / sum_q w(|x_p - x_q|) V_q.
     *
     * Every rank passes its locally owned points. Sources closer than the
     * cut-off radius to another rank's region are sent there (ghosts), so the
     * answer does not depend on the number of ranks. Each receiver sums its
     * neighbours in the order of their global ids, which makes the result
     * bit-identical on any number of ranks.
     *
     * Neighbour lists (pairs closer than cut-off + skin) come from a uniform
     * cell list and are reused between calls until a rebuild is needed; see
     * compute() for the conditions. Weights are always evaluated from the
     * current positions, and ghost positions, volumes and values are
     * exchanged on every call.
     *
     * The receivers are summed in groups of group_size spatially close
     * points (Morton order), one SIMD lane per receiver, over the union of
     * their lists: each lane still adds its terms one by one in id order,
     * and the sources of the union that are not in its own list are beyond
     * the cut-off and add exactly 0, so every average is bit-identical to
     * the straightforward one-receiver-at-a-time sum (doc/nonlocal.md,
     * "Speed").
     *
     * compute() is collective over the communicator unless the weight is
     * WeightType::local, in which case it neither searches nor communicates.
     */
    template <int dim>
    class NonlocalAverager
    {
    public:
      /// The averager works on a duplicate of @p communicator, so its
      /// messages never mix with anyone else's.
      explicit NonlocalAverager(const MPI_Comm &communicator);

      ~NonlocalAverager();

      NonlocalAverager(const NonlocalAverager &) = delete;
      NonlocalAverager &
      operator=(const NonlocalAverager &) = delete;

      /**
       * Set the weight, its length scale l_c [m] and the skin distance as a
       * fraction of the cut-off radius (NonlocalParameters::skin_fraction).
       * Drops the neighbour lists. Must be called, with the same arguments,
       * on all ranks before compute().
       */
      void
      reinit(const WeightType weight_type,
             const double     length_scale,
             const double     skin_fraction);

      /**
       * Compute the averages of the locally owned points.
       *
       * @param local_boxes Boxes covering this rank's owned part of the mesh,
       *   as from GridTools::compute_mesh_predicate_bounding_box() with
       *   IteratorFilters::LocallyOwnedCell(). Points outside them are
       *   allowed (their bounding box is added), but cost extra ghosts.
       * @param positions Current position of each owned point.
       * @param volumes Current volume of each point (> 0 for at least the
       *   point itself, otherwise its average is its own value).
       * @param values The local field Y of each point.
       * @param is_receiver Whether a point needs its average (damage can still
       *   change). Every point, receiver or not, is a source.
       * @param ids Stable global id of each point, unique over all ranks.
       * @param averages Output, resized to the number of points: Ybar for
       *   receivers, Y itself for non-receivers.
       *
       * The neighbour lists are rebuilt, on all ranks together, if on any
       * rank: there are no lists yet (first call, reinit(),
       * invalidate_neighbour_lists()); the ids differ from those of the last
       * build (other points, or the same in another order); @p local_boxes
       * differ; a receiver was not a receiver at the last build; or a point
       * has moved more than half the skin distance since the last build.
       * Otherwise they are reused: every pair now closer than the cut-off
       * was closer than cut-off + skin at the build, because neither point
       * moved more than skin/2.
       *
       * Points that only changed ranks (the flowing debris crossing the
       * partition) do not rebuild the lists: if every point of every rank
       * was a source of the last build on that rank (own or ghost) and
       * moved at most skin/2 since, the lists are patched instead (see
       * n_patches()): the ghosts are chosen anew with a reach of cut-off +
       * 2 skin, the kept lists are renumbered to the new slots (dropping
       * sources no longer present, which are beyond the cut-off of every
       * receiver here), departed receivers leave their lanes, and the
       * arrived receivers get lists of the sources within cut-off + 2 skin
       * of their present position. Every pair now closer than the cut-off
       * is still listed, in id order, so the averages are bit-identical to
       * a rebuild.
       */
      void
      compute(const std::vector<BoundingBox<dim>>      &local_boxes,
              const std::vector<Point<dim>>            &positions,
              const std::vector<double>                &volumes,
              const std::vector<double>                &values,
              const std::vector<bool>                  &is_receiver,
              const std::vector<types::particle_index> &ids,
              std::vector<double>                      &averages);

      /**
       * As above, but points with @p is_source false are left out of both
       * sums (numerator and denominator), on every rank: they act as if
       * their volume were zero. Such a point may still be a receiver; if
       * it has no source neighbour at all, its average is its own value.
       * Used for fully damaged points (the authors' variant of the
       * average, doc/nonlocal.md).
       */
      void
      compute(const std::vector<BoundingBox<dim>>      &local_boxes,
              const std::vector<Point<dim>>            &positions,
              const std::vector<double>                &volumes,
              const std::vector<double>                &values,
              const std::vector<bool>                  &is_receiver,
              const std::vector<bool>                  &is_source,
              const std::vector<types::particle_index> &ids,
              std::vector<double>                      &averages);

      /// Force a rebuild of the neighbour lists at the next compute(). Must
      /// be called on all ranks alike.
      void
      invalidate_neighbour_lists();

      const WeightFunction &
      get_weight_function() const
      {
        return weight;
      }

      /// Cut-off radius of the weight [m].
      double
      cutoff_radius() const
      {
        return weight.cutoff_radius();
      }

      /// Skin distance [m]: lists hold pairs up to cutoff_radius() + skin.
      double
      skin_distance() const
      {
        return skin;
      }

      /// Number of compute() calls that rebuilt the neighbour lists.
      unsigned int
      n_rebuilds() const
      {
        return rebuild_count;
      }

      /// Number of compute() calls that reused the neighbour lists.
      unsigned int
      n_reuses() const
      {
        return reuse_count;
      }

      /// Number of compute() calls that patched the lists after points
      /// changed ranks (see compute()).
      unsigned int
      n_patches() const
      {
        return patch_count;
      }

      /// Number of compute() calls that reused the lists for the same points
      /// in another order (points that changed cells).
      unsigned int
      n_reorders() const
      {
        return reorder_count;
      }

      /// Number of compute() calls that communicated (all but the local
      /// weight's calls, when there is more than one rank).
      unsigned int
      n_communicating_calls() const
      {
        return communicating_call_count;
      }

      /// Ghost sources received from other ranks at the last compute().
      std::size_t
      n_ghost_points() const
      {
        return ghost_ids.size();
      }

      /// Entries of the lists of the receivers of the last compute() (pairs
      /// closer than cut-off + skin at the build, each point included once
      /// as its own neighbour).
      std::size_t
      n_listed_pairs() const
      {
        return listed_pair_count;
      }

      /// Pairs of the last compute() with a non-zero weight (closer than
      /// the cut-off now), self included.
      std::size_t
      n_interacting_pairs() const
      {
        return interacting_pair_count;
      }

    private:
      /// Both compute()s; @p is_source nullptr: every point is a source.
      void
      compute_all(const std::vector<BoundingBox<dim>>      &local_boxes,
                  const std::vector<Point<dim>>            &positions,
                  const std::vector<double>                &volumes,
                  const std::vector<double>                &values,
                  const std::vector<bool>                  &is_receiver,
                  const std::vector<bool>                  *is_source,
                  const std::vector<types::particle_index> &ids,
                  std::vector<double>                      &averages);

      /// Decide (collectively) whether the lists must be rebuilt.
      /// compute() for points in the order of the last build (or any order
      /// when the lists are rebuilt).
      void
      compute_in_order(const std::vector<BoundingBox<dim>>      &local_boxes,
                       const std::vector<Point<dim>>            &positions,
                       const std::vector<double>                &volumes,
                       const std::vector<double>                &values,
                       const std::vector<bool>                  &is_receiver,
                       const std::vector<bool>                  *is_source,
                       const std::vector<types::particle_index> &ids,
                       std::vector<double>                      &averages);
      /// What compute() does with the lists, in increasing cost.
      enum class ListAction
      {
        reuse,
        patch,
        rebuild
      };

      /// Decide (collectively) what to do with the lists.
      ListAction
      list_action(const std::vector<BoundingBox<dim>>      &local_boxes,
                  const std::vector<Point<dim>>            &positions,
                  const std::vector<bool>                  &is_receiver,
                  const std::vector<types::particle_index> &ids) const;

      /// Choose the sources within @p reach of our region to send to each
      /// rank, learn whom we receive from, exchange ids and number all
      /// sources in the order of their ids.
      void
      setup_communication(const std::vector<BoundingBox<dim>>      &local_boxes,
                          const std::vector<Point<dim>>            &positions,
                          const std::vector<types::particle_index> &ids,
                          const double                              reach);

      /// Send positions, volumes and values of the ghosts, and fill the
      /// source arrays (local and ghost) in id order. Points that are no
      /// source (@p is_source, nullptr: all are) get volume 0.
      void
      exchange_source_data(const std::vector<Point<dim>> &positions,
                           const std::vector<double>     &volumes,
                           const std::vector<double>     &values,
                           const std::vector<bool>       *is_source);

      /// Build the neighbour lists of the receivers with a cell list.
      void
      build_neighbour_lists(const std::vector<bool> &is_receiver);

      /// Renumber the lists to the sources of a new communication pattern
      /// and list the receivers that arrived from other ranks (see
      /// compute()). @p ids are this rank's points now, built_ids those of
      /// the lists, @p old_slot_ids the ids of the lists' slots.
      void
      patch_neighbour_lists(
        const std::vector<bool>                  &is_receiver,
        const std::vector<types::particle_index> &ids,
        const std::vector<types::particle_index> &old_slot_ids);

      /// Append groups of the receivers @p members (local indices, grouped
      /// in Morton order), each group listing the sources within @p reach
      /// of one of its members, in slot order.
      void
      append_groups(std::vector<unsigned int> members, const double reach);

      /// The weighted sums and the averages.
      void
      evaluate(const std::vector<double> &values,
               const std::vector<bool>   &is_receiver,
               std::vector<double>       &averages);

      /// Receivers summed together, one SIMD lane each (see the class
      /// documentation).
      static constexpr unsigned int group_size = 8;

      MPI_Comm       communicator;
      unsigned int   n_ranks;
      unsigned int   my_rank;
      WeightFunction weight;
      double         skin        = 0.;
      bool           initialized = false;
      bool           lists_valid = false;

      // The state of the last build, to decide on reuse.
      std::vector<BoundingBox<dim>>      built_boxes;
      std::vector<types::particle_index> built_ids;
      std::vector<Point<dim>>            built_positions;
      std::vector<bool>                  built_receivers;
      /// Index in built_ids of each id (invalid: not a point of this rank).
      std::vector<unsigned int> built_index_of_id;
      /// Reordering of the input to the built order (see compute()).
      std::vector<unsigned int> permutation;
      std::vector<Point<dim>>   ordered_positions;
      std::vector<double> ordered_volumes, ordered_values, ordered_averages;
      std::vector<bool>   ordered_receivers, ordered_sources;
      /// The sources (own and ghost) of the last rebuild: ids ascending and
      /// positions, to find the build position of a point that has since
      /// come from another rank.
      std::vector<types::particle_index> origin_ids;
      std::vector<Point<dim>>            origin_positions;

      // Communication pattern: the local indices sent to each destination,
      // and the number of ghosts from each source rank (ascending ranks).
      std::vector<unsigned int>              destinations;
      std::vector<std::vector<unsigned int>> send_indices;
      std::vector<unsigned int>              sources;
      std::vector<unsigned int>              ghosts_per_source;
      std::vector<types::particle_index>     ghost_ids;

      // All sources (local, then ghosts) are numbered in the order of their
      // ids ("slots"), so that a list sorted by slot sums in id order.
      std::vector<unsigned int>          slot_of_local;
      std::vector<unsigned int>          slot_of_ghost;
      std::vector<types::particle_index> slot_ids;
      std::vector<Point<dim>>            source_positions;
      /// Per slot, what the sums read: position, volume V, V Y (one cache
      /// line in 2D).
      std::vector<std::array<double, dim + 2>> source_data;

      // Receivers in groups of group_size (Morton order at the build); the
      // slot of each lane (the first member's for unused lanes), the local
      // index of each lane (invalid for unused lanes), and the union of the
      // members' lists in compressed rows, sorted by slot.
      std::vector<unsigned int> group_slots;
      std::vector<unsigned int> group_members;
      std::vector<std::size_t>  group_start;
      std::vector<unsigned int> group_neighbours;
      /// Length of each local point's own list (0: no receiver at the build).
      std::vector<unsigned int> list_length;

      // Per-call work arrays and communication buffers, kept to avoid
      // reallocation.
      std::vector<unsigned char>       group_active;
      std::vector<double>              group_numerators, group_denominators;
      std::vector<std::int64_t>        group_interacting;
      std::vector<double>              weight_buffer;
      std::vector<unsigned int>        inside_buffer;
      std::vector<MPI_Request>         requests;
      std::vector<std::vector<double>> send_buffers;
      std::vector<double>              receive_buffer;

      unsigned int rebuild_count            = 0;
      unsigned int reuse_count              = 0;
      unsigned int reorder_count            = 0;
      unsigned int patch_count              = 0;
      unsigned int communicating_call_count = 0;
      std::size_t  listed_pair_count        = 0;
      std::size_t  interacting_pair_count   = 0;
    };
  } // namespace nonlocal
} // namespace scarp

#endif
