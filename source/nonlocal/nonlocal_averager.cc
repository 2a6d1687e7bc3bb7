#include <deal.II/base/exceptions.h>

#include <scarp/nonlocal/nonlocal_averager.h>

// BoundingBox serialises a std::pair of points (for all_gather).
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <utility>

namespace scarp
{
  namespace nonlocal
  {
    namespace
    {
      // Tags of our own messages; the communicator is a private duplicate.
      constexpr int tag_ids  = 4101;
      constexpr int tag_data = 4102;

      // Doubles sent per ghost and call: position, volume, value.
      template <int dim>
      constexpr unsigned int doubles_per_ghost = dim + 2;

      template <int dim>
      double
      squared_distance(const Point<dim> &a, const Point<dim> &b)
      {
        double r2 = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double dx = a[d] - b[d];
            r2 += dx * dx;
          }
        return r2;
      }

      // Squared distance from a point to a box (0 inside).
      template <int dim>
      double
      squared_distance(const Point<dim> &p, const BoundingBox<dim> &box)
      {
        const auto &lo = box.get_boundary_points().first;
        const auto &hi = box.get_boundary_points().second;
        double      r2 = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double dx = std::max({0., lo[d] - p[d], p[d] - hi[d]});
            r2 += dx * dx;
          }
        return r2;
      }

      // Squared distance between two boxes (0 if they overlap).
      template <int dim>
      double
      squared_distance(const BoundingBox<dim> &a, const BoundingBox<dim> &b)
      {
        double r2 = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double dx = std::max({0.,
                                        b.get_boundary_points().first[d] -
                                          a.get_boundary_points().second[d],
                                        a.get_boundary_points().first[d] -
                                          b.get_boundary_points().second[d]});
            r2 += dx * dx;
          }
        return r2;
      }

      void
      check_mpi(const int ierr)
      {
        AssertThrowMPI(ierr);
        (void)ierr;
      }
    } // namespace


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


    template <int dim>
    void
    NonlocalAverager<dim>::setup_communication(
      const std::vector<BoundingBox<dim>>      &local_boxes,
      const std::vector<Point<dim>>            &positions,
      const std::vector<types::particle_index> &ids,
      const double                              reach)
    {
      const std::size_t n_local = positions.size();
      destinations.clear();
      send_indices.clear();
      sources.clear();
      ghosts_per_source.clear();
      ghost_ids.clear();

      if (n_ranks > 1)
        {
          // Our region: the boxes, plus the bounding box of any point outside
          // them (round-off at a cell face, or a point not yet sorted into
          // its cell), so that every receiver lies inside our region.
          std::vector<BoundingBox<dim>> region = local_boxes;
          Point<dim>                    lo, hi;
          bool                          any_outside = false, any_point = false;
          Point<dim>                    all_lo, all_hi;
          for (const auto &p : positions)
            {
              if (!any_point)
                all_lo = all_hi = p;
              any_point = true;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  all_lo[d] = std::min(all_lo[d], p[d]);
                  all_hi[d] = std::max(all_hi[d], p[d]);
                }
              const bool inside =
                std::any_of(local_boxes.begin(),
                            local_boxes.end(),
                            [&p](const BoundingBox<dim> &b) {
                              return squared_distance(p, b) == 0.;
                            });
              if (inside)
                continue;
              if (!any_outside)
                lo = hi = p;
              any_outside = true;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  lo[d] = std::min(lo[d], p[d]);
                  hi[d] = std::max(hi[d], p[d]);
                }
            }
          if (any_outside)
            region.emplace_back(std::make_pair(lo, hi));

          const std::vector<std::vector<BoundingBox<dim>>> global_regions =
            Utilities::MPI::all_gather(communicator, region);

          // A source goes to every rank whose region is within the reach
          // (cut-off + skin at a rebuild); a receiver there may then have it
          // in its list.
          const double reach2 = reach * reach;
          if (any_point)
            {
              const BoundingBox<dim> point_box(std::make_pair(all_lo, all_hi));
              std::vector<BoundingBox<dim>> candidates;
              for (unsigned int r = 0; r < n_ranks; ++r)
                {
                  if (r == my_rank)
                    continue;
                  candidates.clear();
                  for (const auto &b : global_regions[r])
                    if (squared_distance(point_box, b) <= reach2)
                      candidates.push_back(b);
                  if (candidates.empty())
                    continue;
                  std::vector<unsigned int> list;
                  for (unsigned int i = 0; i < n_local; ++i)
                    for (const auto &b : candidates)
                      if (squared_distance(positions[i], b) <= reach2)
                        {
                          list.push_back(i);
                          break;
                        }
                  if (!list.empty())
                    {
                      destinations.push_back(r);
                      send_indices.push_back(std::move(list));
                    }
                }
            }

          sources =
            Utilities::MPI::compute_point_to_point_communication_pattern(
              communicator, destinations);
          std::sort(sources.begin(), sources.end());

          // Ids once per build; positions and values follow on every call.
          std::vector<std::vector<types::particle_index>> id_buffers(
            destinations.size());
          std::vector<MPI_Request> requests(destinations.size());
          for (unsigned int k = 0; k < destinations.size(); ++k)
            {
              for (const unsigned int i : send_indices[k])
                id_buffers[k].push_back(ids[i]);
              check_mpi(MPI_Isend(id_buffers[k].data(),
                                  id_buffers[k].size(),
                                  DEAL_II_PARTICLE_INDEX_MPI_TYPE,
                                  destinations[k],
                                  tag_ids,
                                  communicator,
                                  &requests[k]));
            }
          for (const unsigned int source : sources)
            {
              MPI_Status status;
              check_mpi(MPI_Probe(source, tag_ids, communicator, &status));
              int count = 0;
              check_mpi(MPI_Get_count(&status,
                                      DEAL_II_PARTICLE_INDEX_MPI_TYPE,
                                      &count));
              const std::size_t start = ghost_ids.size();
              ghost_ids.resize(start + count);
              check_mpi(MPI_Recv(ghost_ids.data() + start,
                                 count,
                                 DEAL_II_PARTICLE_INDEX_MPI_TYPE,
                                 source,
                                 tag_ids,
                                 communicator,
                                 MPI_STATUS_IGNORE));
              ghosts_per_source.push_back(count);
            }
          check_mpi(
            MPI_Waitall(requests.size(), requests.data(), MPI_STATUSES_IGNORE));
        }

      // Number all sources in the order of their ids: a list sorted by slot
      // then sums in the same order on any number of ranks.
      const std::size_t n_ghost = ghost_ids.size();
      std::vector<std::pair<types::particle_index, unsigned int>> order(
        n_local + n_ghost);
      for (unsigned int i = 0; i < n_local; ++i)
        order[i] = {ids[i], i};
      for (unsigned int g = 0; g < n_ghost; ++g)
        order[n_local + g] = {ghost_ids[g], n_local + g};
      std::sort(order.begin(), order.end());
      Assert(std::adjacent_find(order.begin(),
                                order.end(),
                                [](const auto &a, const auto &b) {
                                  return a.first == b.first;
                                }) == order.end(),
             ExcMessage("The point ids are not unique over all ranks."));
      slot_of_local.resize(n_local);
      slot_of_ghost.resize(n_ghost);
      slot_ids.resize(order.size());
      for (unsigned int s = 0; s < order.size(); ++s)
        {
          slot_ids[s]          = order[s].first;
          const unsigned int k = order[s].second;
          if (k < n_local)
            slot_of_local[k] = s;
          else
            slot_of_ghost[k - n_local] = s;
        }
    }


    template <int dim>
    void
    NonlocalAverager<dim>::exchange_source_data(
      const std::vector<Point<dim>> &positions,
      const std::vector<double>     &volumes,
      const std::vector<double>     &values,
      const std::vector<bool>       *is_source)
    {
      // A point left out of the sums counts with volume 0, here and on the
      // ranks it is a ghost of, which keeps the result rank-independent.
      const auto volume = [&](const std::size_t i) {
        return (is_source == nullptr || (*is_source)[i]) ? volumes[i] : 0.;
      };
      const std::size_t n_local  = positions.size();
      const std::size_t n_ghost  = ghost_ids.size();
      const unsigned    n_values = doubles_per_ghost<dim>;
      source_positions.resize(n_local + n_ghost);
      source_data.resize(n_local + n_ghost);

      for (std::size_t i = 0; i < n_local; ++i)
        {
          const unsigned int s = slot_of_local[i];
          source_positions[s]  = positions[i];
          auto &data           = source_data[s];
          for (unsigned int d = 0; d < dim; ++d)
            data[d] = positions[i][d];
          data[dim]     = volume(i);
          data[dim + 1] = volume(i) * values[i];
        }

      if (destinations.empty() && sources.empty())
        return;

      requests.clear();
      receive_buffer.resize(n_values * n_ghost);
      std::size_t offset = 0;
      for (unsigned int k = 0; k < sources.size(); ++k)
        {
          requests.emplace_back();
          check_mpi(MPI_Irecv(receive_buffer.data() + n_values * offset,
                              n_values * ghosts_per_source[k],
                              MPI_DOUBLE,
                              sources[k],
                              tag_data,
                              communicator,
                              &requests.back()));
          offset += ghosts_per_source[k];
        }
      send_buffers.resize(destinations.size());
      for (unsigned int k = 0; k < destinations.size(); ++k)
        {
          auto &buffer = send_buffers[k];
          buffer.resize(n_values * send_indices[k].size());
          double *b = buffer.data();
          for (const unsigned int i : send_indices[k])
            {
              for (unsigned int d = 0; d < dim; ++d)
                *b++ = positions[i][d];
              *b++ = volume(i);
              *b++ = values[i];
            }
          requests.emplace_back();
          check_mpi(MPI_Isend(buffer.data(),
                              buffer.size(),
                              MPI_DOUBLE,
                              destinations[k],
                              tag_data,
                              communicator,
                              &requests.back()));
        }
      check_mpi(
        MPI_Waitall(requests.size(), requests.data(), MPI_STATUSES_IGNORE));

      const double *b = receive_buffer.data();
      for (std::size_t g = 0; g < n_ghost; ++g)
        {
          const unsigned int s    = slot_of_ghost[g];
          auto              &data = source_data[s];
          for (unsigned int d = 0; d < dim; ++d)
            data[d] = source_positions[s][d] = *b++;
          data[dim] = b[0];
          // The same product as on the owner, so bit-identical.
          data[dim + 1] = b[0] * b[1];
          b += 2;
        }
    }


    template <int dim>
    void
    NonlocalAverager<dim>::build_neighbour_lists(
      const std::vector<bool> &is_receiver)
    {
      const std::size_t n_local = slot_of_local.size();
      group_slots.clear();
      group_members.clear();
      group_start.assign(1, 0);
      group_neighbours.clear();
      list_length.assign(n_local, 0);
      std::vector<unsigned int> receivers;
      for (unsigned int i = 0; i < n_local; ++i)
        if (is_receiver[i])
          receivers.push_back(i);
      append_groups(std::move(receivers), weight.cutoff_radius() + skin);
    }


    template <int dim>
    void
    NonlocalAverager<dim>::patch_neighbour_lists(
      const std::vector<bool>                  &is_receiver,
      const std::vector<types::particle_index> &ids,
      const std::vector<types::particle_index> &old_slot_ids)
    {
      const std::size_t  n_local = ids.size();
      const unsigned int invalid = numbers::invalid_unsigned_int;

      // Old slot -> new slot: both numberings ascend with the id.
      std::vector<unsigned int> new_slot(old_slot_ids.size(), invalid);
      for (std::size_t o = 0, n = 0; o < old_slot_ids.size(); ++o)
        {
          while (n < slot_ids.size() && slot_ids[n] < old_slot_ids[o])
            ++n;
          if (n < slot_ids.size() && slot_ids[n] == old_slot_ids[o])
            new_slot[o] = n;
        }
      // Old local index -> new one; the points without one arrived.
      std::vector<unsigned int> new_local(built_ids.size(), invalid);
      std::vector<unsigned int> arrived;
      std::vector<Point<dim>>   positions_at_build(n_local);
      std::vector<bool>         receivers_at_build(n_local);
      std::vector<unsigned int> lengths(n_local, 0);
      for (unsigned int i = 0; i < n_local; ++i)
        {
          const auto         id = ids[i];
          const unsigned int b =
            id < built_index_of_id.size() ? built_index_of_id[id] : invalid;
          if (b != invalid)
            {
              new_local[b]          = i;
              positions_at_build[i] = built_positions[b];
              receivers_at_build[i] = built_receivers[b];
              lengths[i]            = list_length[b];
            }
          else
            {
              // list_action() found it among the sources of the rebuild.
              const auto it =
                std::lower_bound(origin_ids.begin(), origin_ids.end(), id);
              positions_at_build[i] = origin_positions[it - origin_ids.begin()];
              receivers_at_build[i] = is_receiver[i];
              if (is_receiver[i])
                arrived.push_back(i);
            }
        }

      // The kept groups, renumbered; groups whose members all left go.
      std::vector<unsigned int> slots, members, neighbours;
      std::vector<std::size_t>  start(1, 0);
      slots.reserve(group_slots.size());
      members.reserve(group_members.size());
      neighbours.reserve(group_neighbours.size());
      const std::size_t n_groups = group_start.size() - 1;
      for (std::size_t g = 0; g < n_groups; ++g)
        {
          std::array<unsigned int, group_size> lane;
          unsigned int                         first = invalid;
          for (unsigned int l = 0; l < group_size; ++l)
            {
              const unsigned int i = group_members[g * group_size + l];
              lane[l]              = i == invalid ? invalid : new_local[i];
              if (first == invalid && lane[l] != invalid)
                first = lane[l];
            }
          if (first == invalid)
            continue;
          for (unsigned int l = 0; l < group_size; ++l)
            {
              members.push_back(lane[l]);
              // Unused lanes repeat a member; never read out.
              slots.push_back(
                slot_of_local[lane[l] == invalid ? first : lane[l]]);
            }
          // Sources no longer here are beyond the cut-off of every
          // receiver here until the next rebuild (compute()): dropped.
          for (std::size_t e = group_start[g]; e < group_start[g + 1]; ++e)
            if (const unsigned int s = new_slot[group_neighbours[e]];
                s != invalid)
              neighbours.push_back(s);
          start.push_back(neighbours.size());
        }
      group_slots.swap(slots);
      group_members.swap(members);
      group_start.swap(start);
      group_neighbours.swap(neighbours);
      list_length.swap(lengths);
      built_positions.swap(positions_at_build);
      built_receivers.swap(receivers_at_build);

      // The arrived receivers, listed from where they are now: they and
      // their sources may each move by up to skin before the next rebuild.
      if (!arrived.empty())
        append_groups(std::move(arrived), weight.cutoff_radius() + 2. * skin);
    }


    template <int dim>
    void
    NonlocalAverager<dim>::append_groups(std::vector<unsigned int> receivers,
                                         const double              reach)
    {
      const std::size_t n_source = source_positions.size();
      const double      reach2   = reach * reach;
      if (n_source == 0 || receivers.empty())
        return;
      // Uniform bins of size >= reach / k over the bounding box of all
      // sources: the neighbours of a point are then in the bins up to k
      // away. k = 2: (5/2)^dim reach^dim scanned per point instead of 3^dim
      // (the distance tests are most of a build).
      constexpr std::size_t k_bins = 2;
      Point<dim>            lo = source_positions[0], hi = source_positions[0];
      for (const auto &p : source_positions)
        for (unsigned int d = 0; d < dim; ++d)
          {
            lo[d] = std::min(lo[d], p[d]);
            hi[d] = std::max(hi[d], p[d]);
          }
      std::array<std::size_t, dim> n_bins;
      for (unsigned int d = 0; d < dim; ++d)
        n_bins[d] = std::max<std::size_t>(1,
                                          static_cast<std::size_t>(std::floor(
                                            k_bins * (hi[d] - lo[d]) / reach)));
      // Far-apart clusters would give mostly empty bins: cap their number
      // at a few per source by making them larger.
      const double max_bins = 4. * n_source + 64.;
      double       total    = 1.;
      for (unsigned int d = 0; d < dim; ++d)
        total *= n_bins[d];
      if (total > max_bins)
        {
          const double factor = std::pow(total / max_bins, 1. / dim);
          for (unsigned int d = 0; d < dim; ++d)
            n_bins[d] = std::max<std::size_t>(
              1, static_cast<std::size_t>(n_bins[d] / factor));
        }
      std::array<double, dim> inverse_bin_size;
      for (unsigned int d = 0; d < dim; ++d)
        inverse_bin_size[d] = hi[d] > lo[d] ? n_bins[d] / (hi[d] - lo[d]) : 0.;
      std::array<std::size_t, dim> stride;
      std::size_t                  n_total = 1;
      for (unsigned int d = 0; d < dim; ++d)
        {
          stride[d] = n_total;
          n_total *= n_bins[d];
        }

      const auto bin_coordinates = [&](const Point<dim> &p) {
        std::array<std::size_t, dim> c;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double x = (p[d] - lo[d]) * inverse_bin_size[d];
            c[d] =
              std::min<std::size_t>(n_bins[d] - 1,
                                    x > 0. ? static_cast<std::size_t>(x) : 0);
          }
        return c;
      };

      // Counting sort of the sources into bins.
      std::vector<std::size_t>  bin_of_source(n_source);
      std::vector<std::size_t>  bin_start(n_total + 1, 0);
      std::vector<unsigned int> bin_items(n_source);
      for (std::size_t s = 0; s < n_source; ++s)
        {
          const auto  c = bin_coordinates(source_positions[s]);
          std::size_t b = 0;
          for (unsigned int d = 0; d < dim; ++d)
            b += c[d] * stride[d];
          bin_of_source[s] = b;
          ++bin_start[b + 1];
        }
      std::partial_sum(bin_start.begin(), bin_start.end(), bin_start.begin());
      {
        std::vector<std::size_t> fill(bin_start.begin(), bin_start.end() - 1);
        for (std::size_t s = 0; s < n_source; ++s)
          bin_items[fill[bin_of_source[s]]++] = s;
      }
      // The positions in bin order: the distance tests below then read
      // memory in sequence (through bin_items they jumped across all
      // sources, the larger part of a rebuild's time).
      std::vector<Point<dim>> binned_position(n_source);
      for (std::size_t j = 0; j < n_source; ++j)
        binned_position[j] = source_positions[bin_items[j]];

      // Group the receivers: Morton (Z) order of their positions on a
      // 2^(63/dim) grid over the sources' box, then consecutive runs of
      // group_size. Close members share most of their neighbours, so the
      // union each group sums over is little longer than one list. Ties
      // (same grid cell) go by local index: the order is deterministic.
      constexpr unsigned int  bits = 63 / dim;
      std::array<double, dim> inverse_key_size;
      for (unsigned int d = 0; d < dim; ++d)
        inverse_key_size[d] =
          hi[d] > lo[d] ? ((std::uint64_t(1) << bits) - 1) / (hi[d] - lo[d])
                        : 0.;
      std::vector<std::pair<std::uint64_t, unsigned int>> order;
      order.reserve(receivers.size());
      for (const unsigned int i : receivers)
        {
          const Point<dim>              &x = source_positions[slot_of_local[i]];
          std::array<std::uint64_t, dim> c;
          for (unsigned int d = 0; d < dim; ++d)
            c[d] = static_cast<std::uint64_t>(
              std::max(0., (x[d] - lo[d]) * inverse_key_size[d]));
          std::uint64_t key = 0;
          for (unsigned int b = bits; b-- > 0;)
            for (unsigned int d = 0; d < dim; ++d)
              key = (key << 1) | ((c[d] >> b) & 1);
          order.emplace_back(key, i);
        }
      std::sort(order.begin(), order.end());

      const std::size_t first_group = group_start.size() - 1;
      const std::size_t n_groups = (order.size() + group_size - 1) / group_size;
      group_slots.resize((first_group + n_groups) * group_size);
      group_members.resize((first_group + n_groups) * group_size,
                           numbers::invalid_unsigned_int);
      group_start.reserve(first_group + n_groups + 1);
      // The union of a group's lists as a bit per source slot: set without
      // a branch (about a third of the candidates hit, at random), read out
      // in ascending slot order (and cleared) once the group is done, which
      // is the order the sums need, with no sort.
      std::vector<std::uint64_t> listed((n_source + 63) / 64, 0);
      for (std::size_t g = 0; g < n_groups; ++g)
        {
          const std::size_t lanes      = (first_group + g) * group_size;
          std::size_t       first_word = listed.size(), last_word = 0;
          for (unsigned int l = 0; l < group_size; ++l)
            {
              const std::size_t k = g * group_size + l;
              if (k >= order.size())
                {
                  // Unused lanes repeat the first member; never read out.
                  group_slots[lanes + l] = group_slots[lanes];
                  continue;
                }
              const unsigned int i     = order[k].second;
              const unsigned int s     = slot_of_local[i];
              group_members[lanes + l] = i;
              group_slots[lanes + l]   = s;

              const Point<dim>            &xp = source_positions[s];
              const auto                   c  = bin_coordinates(xp);
              std::array<std::size_t, dim> from, to;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  from[d] = c[d] > k_bins ? c[d] - k_bins : 0;
                  to[d]   = std::min(c[d] + k_bins, n_bins[d] - 1);
                }
              // Loop over the (up to) (2 k + 1)^dim bins around, a row along
              // x at a time: its bins are consecutive in bin order.
              std::array<std::size_t, dim> b_k = from;
              while (true)
                {
                  std::size_t b = 0;
                  for (unsigned int d = 1; d < dim; ++d)
                    b += b_k[d] * stride[d];
                  const std::size_t j0    = bin_start[b + from[0]];
                  const std::size_t j1    = bin_start[b + to[0] + 1];
                  unsigned int      n_hit = 0;
                  for (std::size_t j = j0; j < j1; ++j)
                    {
                      const unsigned int  q = bin_items[j];
                      const std::uint64_t hit =
                        squared_distance(xp, binned_position[j]) <= reach2;
                      listed[q / 64] |= hit << (q % 64);
                      n_hit += hit;
                    }
                  list_length[i] += n_hit;
                  // The words to read out: each bin ascends in slot.
                  for (std::size_t bb = b + from[0]; bb <= b + to[0]; ++bb)
                    if (bin_start[bb + 1] > bin_start[bb])
                      {
                        first_word =
                          std::min<std::size_t>(first_word,
                                                bin_items[bin_start[bb]] / 64);
                        last_word = std::max<std::size_t>(
                          last_word, bin_items[bin_start[bb + 1] - 1] / 64);
                      }
                  unsigned int d = 1;
                  for (; d < dim; ++d)
                    {
                      if (b_k[d] < to[d])
                        {
                          ++b_k[d];
                          break;
                        }
                      b_k[d] = from[d];
                    }
                  if (d == dim)
                    break;
                }
            }
          // Slot order is id order: each lane sums in id order, which
          // makes the result independent of the partition.
          for (std::size_t w = first_word; w <= last_word; ++w)
            {
              std::uint64_t bits = listed[w];
              listed[w]          = 0;
              while (bits != 0)
                {
                  group_neighbours.push_back(
                    static_cast<unsigned int>(64 * w + __builtin_ctzll(bits)));
                  bits &= bits - 1;
                }
            }
          group_start.push_back(group_neighbours.size());
        }
    }


    // No fused multiply-add in the sums, even where the instruction set has
    // one (avx512f implies fma in GCC): it would round differently from the
    // plain loop, and from the same loop without FMA on another rank.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC push_options
#pragma GCC optimize("fp-contract=off")
#endif
    namespace
    {
      // Vectors of 2, 4 and 8 doubles: SSE2 (or NEON), AVX2 and AVX-512
      // registers.
      using v2d = double __attribute__((vector_size(16)));
      using v4d = double __attribute__((vector_size(32)));
      using v8d = double __attribute__((vector_size(64)));

      // The bell of WeightFunction for a vector of squared distances, with
      // the same operations, so bit-identical to the scalar one.
      struct BellWeights
      {
        // As in WeightFunction: 1 / R^2 and R^2.
        double inverse_cutoff_squared, cutoff_squared;

        template <typename VD>
        __attribute__((always_inline)) inline VD
        operator()(const VD r2) const
        {
          using VI    = decltype(r2 < r2);
          const VD t  = 1. - r2 * inverse_cutoff_squared;
          const VD tt = t * t;
          return (VD)((VI)tt & (r2 < cutoff_squared));
        }
      };

      /**
       * The sums of groups of G receivers, G / lanes vectors VD of lanes
       * doubles. Lane l of group g is the receiver at slot slots[G g + l];
       * it adds w V_q Y_q and w V_q of every source q of the group's list,
       * one term at a time in list (= id) order, exactly as a loop over its
       * own list would: the other sources of the union are beyond the
       * cut-off now (each point moved less than skin/2 since the build) and
       * add +-0, which leaves a sum unchanged.
       *
       * The bell is evaluated in the vectors. The Gaussian's std::exp is
       * not vectorised (a vector exp rounds differently): its weights are
       * computed in a separate scalar pass over a buffer, since a call
       * inside the vector loop would spill all live vectors.
       *
       * Written as one inline body so that it is compiled for each
       * instruction set, all without FMA: a fused multiply-add rounds
       * differently from the plain loop.
       */
      template <int dim, typename VD, unsigned int G>
      __attribute__((always_inline)) inline void
      group_sums(const WeightFunction              &weight,
                 const std::array<double, dim + 2> *data,
                 const unsigned int                *slots,
                 const std::size_t                 *start,
                 const unsigned int                *list,
                 const unsigned char               *active,
                 const std::size_t                  n_groups,
                 std::vector<double>               &buffer,
                 std::vector<unsigned int>         &inside,
                 double                            *numerators,
                 double                            *denominators,
                 std::int64_t                      *interacting)
      {
        using VI                    = decltype(VD() < VD());
        constexpr unsigned int L    = sizeof(VD) / sizeof(double);
        constexpr unsigned int V    = G / L;
        const bool             bell = weight.type() == WeightType::bell;
        const double      R2 = weight.cutoff_radius() * weight.cutoff_radius();
        const BellWeights bell_weights{1. / R2, R2};
        for (std::size_t g = 0; g < n_groups; ++g)
          {
            if (!active[g])
              continue;
            VD x[V][dim];
            for (unsigned int v = 0; v < V; ++v)
              for (unsigned int l = 0; l < L; ++l)
                for (unsigned int d = 0; d < dim; ++d)
                  x[v][d][l] = data[slots[G * g + L * v + l]][d];
            const auto squared_distances = [&x](const double      *q,
                                                const unsigned int v) {
              // As squared_distance(x_p, x_q): 0 + dx^2 is dx^2.
              VD dx = x[v][0] - q[0];
              VD r2 = dx * dx;
              for (unsigned int d = 1; d < dim; ++d)
                {
                  dx = x[v][d] - q[d];
                  r2 += dx * dx;
                }
              return r2;
            };

            const std::size_t begin = start[g], end = start[g + 1];
            if (!bell)
              {
                // Gaussian weights of the whole group, scalar.
                // (memcpy: the buffer is not aligned for a VD.)
                buffer.resize(G * (end - begin));
                double *b = buffer.data();
                for (std::size_t j = begin; j < end; ++j)
                  for (unsigned int v = 0; v < V; ++v, b += L)
                    {
                      const VD r2 = squared_distances(data[list[j]].data(), v);
                      std::memcpy(b, &r2, sizeof(VD));
                    }
                // List those within the cut-off (R2, as in WeightFunction)
                // and zero the others without a branch, then take the exps
                // of the listed: no mispredicted branch per lane.
                std::size_t n_inside = 0;
                inside.resize(buffer.size());
                for (std::size_t k = 0; k < buffer.size(); ++k)
                  {
                    const bool in    = buffer[k] < R2;
                    inside[n_inside] = k;
                    n_inside += in;
                    buffer[k] = in ? buffer[k] : 0.;
                  }
                for (std::size_t k = 0; k < n_inside; ++k)
                  buffer[inside[k]] = weight.gaussian(buffer[inside[k]]);
              }
            const double *b = buffer.data();

            VD num[V], den[V];
            VI count[V];
            for (unsigned int v = 0; v < V; ++v)
              {
                num[v]   = VD{};
                den[v]   = VD{};
                count[v] = VI{};
              }
            for (std::size_t j = begin; j < end; ++j)
              {
                const double *q = data[list[j]].data();
                for (unsigned int v = 0; v < V; ++v)
                  {
                    VD w;
                    if (bell)
                      w = bell_weights(squared_distances(q, v));
                    else
                      {
                        std::memcpy(&w, b, sizeof(VD));
                        b += L;
                      }
                    num[v] += w * q[dim + 1];
                    den[v] += w * q[dim];
                    count[v] -= (w > 0.); // true is -1
                  }
              }
            for (unsigned int v = 0; v < V; ++v)
              for (unsigned int l = 0; l < L; ++l)
                {
                  const std::size_t k = G * g + L * v + l;
                  numerators[k]       = num[v][l];
                  denominators[k]     = den[v][l];
                  interacting[k]      = count[v][l];
                }
          }
      }

#define SCARP_NONLOCAL_GROUP_SUMS(name, attributes, VD)                 \
  template <int dim, unsigned int G>                                    \
  attributes void name(const WeightFunction              &weight,       \
                       const std::array<double, dim + 2> *data,         \
                       const unsigned int                *slots,        \
                       const std::size_t                 *start,        \
                       const unsigned int                *list,         \
                       const unsigned char               *active,       \
                       const std::size_t                  n_groups,     \
                       std::vector<double>               &buffer,       \
                       std::vector<unsigned int>         &inside,       \
                       double                            *numerators,   \
                       double                            *denominators, \
                       std::int64_t                      *interacting)  \
  {                                                                     \
    group_sums<dim, VD, G>(weight,                                      \
                           data,                                        \
                           slots,                                       \
                           start,                                       \
                           list,                                        \
                           active,                                      \
                           n_groups,                                    \
                           buffer,                                      \
                           inside,                                      \
                           numerators,                                  \
                           denominators,                                \
                           interacting);                                \
  }

      SCARP_NONLOCAL_GROUP_SUMS(group_sums_default, , v2d)
#if defined(__GNUC__) && defined(__x86_64__)
#define SCARP_NONLOCAL_X86
      // The same for AVX2 and AVX-512 (neither with FMA), chosen at run time.
      SCARP_NONLOCAL_GROUP_SUMS(group_sums_avx2,
                                __attribute__((target("avx2"))),
                                v4d)
      SCARP_NONLOCAL_GROUP_SUMS(group_sums_avx512,
                                __attribute__((target("avx512f"))),
                                v8d)
#endif
#undef SCARP_NONLOCAL_GROUP_SUMS
    } // namespace
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC pop_options
#endif


    template <int dim>
    void
    NonlocalAverager<dim>::evaluate(const std::vector<double> &values,
                                    const std::vector<bool>   &is_receiver,
                                    std::vector<double>       &averages)
    {
      const std::size_t n_local  = slot_of_local.size();
      const std::size_t n_groups = group_start.size() - 1;

      std::size_t listed = 0;
      for (std::size_t i = 0; i < n_local; ++i)
        if (is_receiver[i])
          listed += list_length[i];
        else
          averages[i] = values[i];

      // Groups of former receivers only are skipped.
      group_active.assign(n_groups, 0);
      for (std::size_t k = 0; k < group_members.size(); ++k)
        if (group_members[k] != numbers::invalid_unsigned_int &&
            is_receiver[group_members[k]])
          group_active[k / group_size] = 1;
      group_numerators.resize(group_members.size());
      group_denominators.resize(group_members.size());
      group_interacting.resize(group_members.size());

      auto sums = &group_sums_default<dim, group_size>;
#ifdef SCARP_NONLOCAL_X86
      if (__builtin_cpu_supports("avx512f"))
        sums = &group_sums_avx512<dim, group_size>;
      else if (__builtin_cpu_supports("avx2"))
        sums = &group_sums_avx2<dim, group_size>;
#endif
      sums(weight,
           source_data.data(),
           group_slots.data(),
           group_start.data(),
           group_neighbours.data(),
           group_active.data(),
           n_groups,
           weight_buffer,
           inside_buffer,
           group_numerators.data(),
           group_denominators.data(),
           group_interacting.data());

      std::size_t interacting = 0;
      for (std::size_t k = 0; k < group_members.size(); ++k)
        {
          const unsigned int i = group_members[k];
          if (i == numbers::invalid_unsigned_int || !is_receiver[i])
            continue;
          const double denominator = group_denominators[k];
          interacting += group_interacting[k];
          // The point itself has weight 1; only zero volumes (or points
          // left out of the sums) can leave the denominator at zero, and
          // then there is nothing to average.
          averages[i] =
            denominator > 0. ? group_numerators[k] / denominator : values[i];
        }
      listed_pair_count      = listed;
      interacting_pair_count = interacting;
    }


    template class NonlocalAverager<2>;
    template class NonlocalAverager<3>;
  } // namespace nonlocal
} // namespace scarp
