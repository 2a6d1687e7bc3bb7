// NonlocalAverager: set-up, and the average in its steps (the lists kept,
// patched or rebuilt; the exchange; the sums). The steps are in
// nonlocal_exchange.cc, nonlocal_neighbour_lists.cc and nonlocal_evaluate.cc.
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <scarp/nonlocal/nonlocal_averager.h>
#include <scarp/nonlocal/nonlocal_averager_internal.h>

#include <algorithm>
#include <limits>
#include <utility>

namespace scarp
{
  namespace nonlocal
  {
    using namespace internal;


    template <int dim>
    NonlocalAverager<dim>::NonlocalAverager(const MPI_Comm &comm)
      : communicator(Utilities::MPI::duplicate_communicator(comm))
      , n_ranks(Utilities::MPI::n_mpi_processes(comm))
      , my_rank(Utilities::MPI::this_mpi_process(comm))
    {
    }


    template <int dim>
    NonlocalAverager<dim>::~NonlocalAverager()
    {
      Utilities::MPI::free_communicator(communicator);
    }


    template <int dim>
    void
    NonlocalAverager<dim>::reinit(const WeightType weight_type,
                                  const double     length_scale,
                                  const double     skin_fraction)
    {
      AssertThrow(skin_fraction >= 0.,
                  ExcMessage("The skin fraction must not be negative."));
      weight      = WeightFunction(weight_type, length_scale);
      skin        = skin_fraction * weight.cutoff_radius();
      initialized = true;
      invalidate_neighbour_lists();
    }


    template <int dim>
    void
    NonlocalAverager<dim>::invalidate_neighbour_lists()
    {
      lists_valid = false;
    }


    template <int dim>
    void
    NonlocalAverager<dim>::compute(
      const std::vector<BoundingBox<dim>>      &local_boxes,
      const std::vector<Point<dim>>            &positions,
      const std::vector<double>                &volumes,
      const std::vector<double>                &values,
      const std::vector<bool>                  &is_receiver,
      const std::vector<types::particle_index> &ids,
      std::vector<double>                      &averages)
    {
      compute_all(local_boxes,
                  positions,
                  volumes,
                  values,
                  is_receiver,
                  nullptr,
                  ids,
                  averages);
    }


    template <int dim>
    void
    NonlocalAverager<dim>::compute(
      const std::vector<BoundingBox<dim>>      &local_boxes,
      const std::vector<Point<dim>>            &positions,
      const std::vector<double>                &volumes,
      const std::vector<double>                &values,
      const std::vector<bool>                  &is_receiver,
      const std::vector<bool>                  &is_source,
      const std::vector<types::particle_index> &ids,
      std::vector<double>                      &averages)
    {
      AssertDimension(is_source.size(), positions.size());
      compute_all(local_boxes,
                  positions,
                  volumes,
                  values,
                  is_receiver,
                  &is_source,
                  ids,
                  averages);
    }


    template <int dim>
    void
    NonlocalAverager<dim>::compute_all(
      const std::vector<BoundingBox<dim>>      &local_boxes,
      const std::vector<Point<dim>>            &positions,
      const std::vector<double>                &volumes,
      const std::vector<double>                &values,
      const std::vector<bool>                  &is_receiver,
      const std::vector<bool>                  *is_source,
      const std::vector<types::particle_index> &ids,
      std::vector<double>                      &averages)
    {
      const std::size_t n = positions.size();
      AssertDimension(volumes.size(), n);
      AssertDimension(values.size(), n);
      AssertDimension(is_receiver.size(), n);
      AssertDimension(ids.size(), n);
      AssertThrow(n < std::numeric_limits<unsigned int>::max(),
                  ExcMessage("Too many points for 32-bit slot indices."));

      // The local weight needs nothing else: no search, no messages, and
      // thus no collective call either.
      if (weight.type() == WeightType::local)
        {
          averages = values;
          return;
        }
      AssertThrow(initialized,
                  ExcMessage("Call NonlocalAverager::reinit() first."));
      if (n_ranks > 1)
        ++communicating_call_count;

      // The points arrive in cell order, which changes whenever one of them
      // crosses into another cell. If this rank still holds the same points,
      // reorder the input to the order of the last build instead of
      // rebuilding lists and messages (which would happen almost every step
      // while the debris flows).
      if (lists_valid && ids.size() == built_ids.size() && ids != built_ids)
        {
          bool same_points = true;
          permutation.resize(n);
          for (std::size_t i = 0; i < n && same_points; ++i)
            {
              const auto id = ids[i];
              same_points =
                id < built_index_of_id.size() &&
                built_index_of_id[id] != numbers::invalid_unsigned_int;
              if (same_points)
                permutation[i] = built_index_of_id[id];
            }
          if (same_points)
            {
              ordered_positions.resize(n);
              ordered_volumes.resize(n);
              ordered_values.resize(n);
              ordered_receivers.resize(n);
              ordered_sources.resize(is_source ? n : 0);
              for (std::size_t i = 0; i < n; ++i)
                {
                  const unsigned int b = permutation[i];
                  ordered_positions[b] = positions[i];
                  ordered_volumes[b]   = volumes[i];
                  ordered_values[b]    = values[i];
                  ordered_receivers[b] = is_receiver[i];
                  if (is_source)
                    ordered_sources[b] = (*is_source)[i];
                }
              ++reorder_count;
              compute_in_order(local_boxes,
                               ordered_positions,
                               ordered_volumes,
                               ordered_values,
                               ordered_receivers,
                               is_source ? &ordered_sources : nullptr,
                               built_ids,
                               ordered_averages);
              averages.resize(n);
              for (std::size_t i = 0; i < n; ++i)
                averages[i] = ordered_averages[permutation[i]];
              return;
            }
        }
      compute_in_order(local_boxes,
                       positions,
                       volumes,
                       values,
                       is_receiver,
                       is_source,
                       ids,
                       averages);
    }


    template <int dim>
    void
    NonlocalAverager<dim>::compute_in_order(
      const std::vector<BoundingBox<dim>>      &local_boxes,
      const std::vector<Point<dim>>            &positions,
      const std::vector<double>                &volumes,
      const std::vector<double>                &values,
      const std::vector<bool>                  &is_receiver,
      const std::vector<bool>                  *is_source,
      const std::vector<types::particle_index> &ids,
      std::vector<double>                      &averages)
    {
      const std::size_t n = positions.size();
      const ListAction  action =
        list_action(local_boxes, positions, is_receiver, ids);
      if (action == ListAction::rebuild)
        {
          setup_communication(local_boxes,
                              positions,
                              ids,
                              weight.cutoff_radius() + skin);
          exchange_source_data(positions, volumes, values, is_source);
          build_neighbour_lists(is_receiver);
          origin_ids       = slot_ids;
          origin_positions = source_positions;
          built_boxes      = local_boxes;
          built_positions  = positions;
          built_receivers  = is_receiver;
          ++rebuild_count;
        }
      else if (action == ListAction::patch)
        {
          // Each point may be up to skin/2 from its build position now and
          // another skin/2 the other way later: cut-off + 2 skin from our
          // region now covers every source that can come within the cut-off
          // of a receiver before the next rebuild.
          const std::vector<types::particle_index> old_slot_ids = slot_ids;
          setup_communication(local_boxes,
                              positions,
                              ids,
                              weight.cutoff_radius() + 2. * skin);
          exchange_source_data(positions, volumes, values, is_source);
          patch_neighbour_lists(is_receiver, ids, old_slot_ids);
          ++patch_count;
        }
      else
        {
          exchange_source_data(positions, volumes, values, is_source);
          ++reuse_count;
        }
      if (action != ListAction::reuse)
        {
          // built_positions and built_receivers are set above.
          for (const auto id : built_ids)
            built_index_of_id[id] = numbers::invalid_unsigned_int;
          built_ids   = ids;
          lists_valid = true;
          for (std::size_t i = 0; i < ids.size(); ++i)
            {
              if (ids[i] >= built_index_of_id.size())
                built_index_of_id.resize(ids[i] + 1,
                                         numbers::invalid_unsigned_int);
              built_index_of_id[ids[i]] = i;
            }
        }

      averages.resize(n);
      evaluate(values, is_receiver, averages);
    }


    template <int dim>
    typename NonlocalAverager<dim>::ListAction
    NonlocalAverager<dim>::list_action(
      const std::vector<BoundingBox<dim>>      &local_boxes,
      const std::vector<Point<dim>>            &positions,
      const std::vector<bool>                  &is_receiver,
      const std::vector<types::particle_index> &ids) const
    {
      const auto local_decision = [&]() {
        if (!lists_valid || local_boxes != built_boxes)
          return ListAction::rebuild;
        // Pairs closer than the cut-off now were closer than cut-off + skin
        // at the build as long as no point moved more than skin / 2.
        const double limit = 0.25 * skin * skin;
        if (ids == built_ids)
          {
            // A new receiver has no list yet; a former one is simply
            // skipped.
            for (std::size_t i = 0; i < ids.size(); ++i)
              if (is_receiver[i] && !built_receivers[i])
                return ListAction::rebuild;
            for (std::size_t i = 0; i < positions.size(); ++i)
              if (squared_distance(positions[i], built_positions[i]) > limit)
                return ListAction::rebuild;
            return ListAction::reuse;
          }
        // Other points: a patch if each one was here at the last rebuild,
        // as our own point or as a ghost, and has moved at most skin/2.
        for (std::size_t i = 0; i < ids.size(); ++i)
          {
            const auto         id = ids[i];
            const unsigned int b  = id < built_index_of_id.size()
                                      ? built_index_of_id[id]
                                      : numbers::invalid_unsigned_int;
            if (b != numbers::invalid_unsigned_int)
              {
                if ((is_receiver[i] && !built_receivers[b]) ||
                    squared_distance(positions[i], built_positions[b]) > limit)
                  return ListAction::rebuild;
                continue;
              }
            const auto it =
              std::lower_bound(origin_ids.begin(), origin_ids.end(), id);
            if (it == origin_ids.end() || *it != id ||
                squared_distance(positions[i],
                                 origin_positions[it - origin_ids.begin()]) >
                  limit)
              return ListAction::rebuild;
          }
        return ListAction::patch;
      };
      const unsigned int mine = static_cast<unsigned int>(local_decision());
      return static_cast<ListAction>(
        n_ranks > 1 ? Utilities::MPI::max(mine, communicator) : mine);
    }


    template class NonlocalAverager<2>;
    template class NonlocalAverager<3>;
  } // namespace nonlocal
} // namespace scarp
