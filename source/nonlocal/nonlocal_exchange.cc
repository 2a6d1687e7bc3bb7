// NonlocalAverager: which points each rank sends to which (the ghosts
// within the radius of a neighbour's region), and their exchange.
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <scarp/nonlocal/nonlocal_averager.h>
#include <scarp/nonlocal/nonlocal_averager_internal.h>

// BoundingBox serialises a std::pair of points (for all_gather).
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <algorithm>
#include <utility>

namespace scarp
{
  namespace nonlocal
  {
    using namespace internal;


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


    // Instantiations (the other members are in the other nonlocal_*.cc
    // files).
    template void
    NonlocalAverager<2>::setup_communication(
      const std::vector<BoundingBox<2>>        &local_boxes,
      const std::vector<Point<2>>              &positions,
      const std::vector<types::particle_index> &ids,
      const double                              reach);
    template void
    NonlocalAverager<3>::setup_communication(
      const std::vector<BoundingBox<3>>        &local_boxes,
      const std::vector<Point<3>>              &positions,
      const std::vector<types::particle_index> &ids,
      const double                              reach);
    template void
    NonlocalAverager<2>::exchange_source_data(
      const std::vector<Point<2>> &positions,
      const std::vector<double>   &volumes,
      const std::vector<double>   &values,
      const std::vector<bool>     *is_source);
    template void
    NonlocalAverager<3>::exchange_source_data(
      const std::vector<Point<3>> &positions,
      const std::vector<double>   &volumes,
      const std::vector<double>   &values,
      const std::vector<bool>     *is_source);
  } // namespace nonlocal
} // namespace scarp
