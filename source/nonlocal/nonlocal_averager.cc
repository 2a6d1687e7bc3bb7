#include <deal.II/base/exceptions.h>

#include <scarp/nonlocal/nonlocal_averager.h>

// BoundingBox serialises a std::pair of points (for all_gather).
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <algorithm>
#include <array>
#include <cmath>
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
      const bool        rebuild =
        needs_rebuild(local_boxes, positions, is_receiver, ids);
      if (rebuild)
        setup_communication(local_boxes, positions, ids);
      exchange_source_data(positions, volumes, values, is_source);
      if (rebuild)
        {
          build_neighbour_lists(is_receiver);
          built_boxes     = local_boxes;
          built_ids       = ids;
          built_positions = positions;
          built_receivers = is_receiver;
          lists_valid     = true;
          built_index_of_id.clear();
          for (std::size_t i = 0; i < ids.size(); ++i)
            {
              if (ids[i] >= built_index_of_id.size())
                built_index_of_id.resize(ids[i] + 1,
                                         numbers::invalid_unsigned_int);
              built_index_of_id[ids[i]] = i;
            }
          ++rebuild_count;
        }
      else
        ++reuse_count;

      averages.resize(n);
      // Dispatch once on the weight so that the pair loop inlines it.
      if (weight.type() == WeightType::bell)
        evaluate([this](const double r2) { return weight.bell(r2); },
                 values,
                 is_receiver,
                 averages);
      else
        evaluate([this](const double r2) { return weight.gaussian(r2); },
                 values,
                 is_receiver,
                 averages);
    }


    template <int dim>
    bool
    NonlocalAverager<dim>::needs_rebuild(
      const std::vector<BoundingBox<dim>>      &local_boxes,
      const std::vector<Point<dim>>            &positions,
      const std::vector<bool>                  &is_receiver,
      const std::vector<types::particle_index> &ids) const
    {
      const auto local_decision = [&]() {
        if (!lists_valid || ids != built_ids || local_boxes != built_boxes)
          return true;
        // A new receiver has no list yet; a former one is simply skipped.
        for (std::size_t i = 0; i < ids.size(); ++i)
          if (is_receiver[i] && !built_receivers[i])
            return true;
        // Pairs closer than the cut-off now were closer than cut-off + skin
        // at the build as long as no point moved more than skin / 2.
        const double limit = 0.25 * skin * skin;
        for (std::size_t i = 0; i < positions.size(); ++i)
          if (squared_distance(positions[i], built_positions[i]) > limit)
            return true;
        return false;
      };
      const unsigned int mine = local_decision() ? 1 : 0;
      return (n_ranks > 1 ? Utilities::MPI::max(mine, communicator) : mine) > 0;
    }


    template <int dim>
    void
    NonlocalAverager<dim>::setup_communication(
      const std::vector<BoundingBox<dim>>      &local_boxes,
      const std::vector<Point<dim>>            &positions,
      const std::vector<types::particle_index> &ids)
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

          // A source goes to every rank whose region is within cut-off +
          // skin; a receiver there may then have it in its list.
          const double reach  = weight.cutoff_radius() + skin;
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
      for (unsigned int s = 0; s < order.size(); ++s)
        {
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
      source_volumes.resize(n_local + n_ghost);
      source_weighted_values.resize(n_local + n_ghost);

      for (std::size_t i = 0; i < n_local; ++i)
        {
          const unsigned int s      = slot_of_local[i];
          source_positions[s]       = positions[i];
          source_volumes[s]         = volume(i);
          source_weighted_values[s] = volume(i) * values[i];
        }

      if (destinations.empty() && sources.empty())
        return;

      std::vector<MPI_Request> requests;
      requests.reserve(sources.size() + destinations.size());
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
          const unsigned int s = slot_of_ghost[g];
          for (unsigned int d = 0; d < dim; ++d)
            source_positions[s][d] = *b++;
          source_volumes[s] = b[0];
          // The same product as on the owner, so bit-identical.
          source_weighted_values[s] = b[0] * b[1];
          b += 2;
        }
    }


    template <int dim>
    void
    NonlocalAverager<dim>::build_neighbour_lists(
      const std::vector<bool> &is_receiver)
    {
      const std::size_t n_local  = slot_of_local.size();
      const std::size_t n_source = source_positions.size();
      const double      reach    = weight.cutoff_radius() + skin;
      const double      reach2   = reach * reach;

      row_start.assign(n_local + 1, 0);
      neighbours.clear();
      if (n_source == 0)
        return;

      // Uniform bins of size >= reach over the bounding box of all sources:
      // the neighbours of a point are then in its bin and the adjacent ones.
      Point<dim> lo = source_positions[0], hi = source_positions[0];
      for (const auto &p : source_positions)
        for (unsigned int d = 0; d < dim; ++d)
          {
            lo[d] = std::min(lo[d], p[d]);
            hi[d] = std::max(hi[d], p[d]);
          }
      std::array<std::size_t, dim> n_bins;
      for (unsigned int d = 0; d < dim; ++d)
        n_bins[d] = std::max<std::size_t>(
          1, static_cast<std::size_t>(std::floor((hi[d] - lo[d]) / reach)));
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

      // Counting sort of the sources into bins, in slot order within a bin.
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

      neighbours.reserve(n_local * 64);
      std::vector<unsigned int> row;
      for (std::size_t i = 0; i < n_local; ++i)
        {
          if (is_receiver[i])
            {
              const unsigned int           s  = slot_of_local[i];
              const Point<dim>            &xp = source_positions[s];
              const auto                   c  = bin_coordinates(xp);
              std::array<std::size_t, dim> from, to;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  from[d] = c[d] > 0 ? c[d] - 1 : 0;
                  to[d]   = std::min(c[d] + 1, n_bins[d] - 1);
                }
              row.clear();
              // Loop over the (up to) 3^dim adjacent bins.
              std::array<std::size_t, dim> k = from;
              while (true)
                {
                  std::size_t b = 0;
                  for (unsigned int d = 0; d < dim; ++d)
                    b += k[d] * stride[d];
                  for (std::size_t j = bin_start[b]; j < bin_start[b + 1]; ++j)
                    {
                      const unsigned int q = bin_items[j];
                      if (squared_distance(xp, source_positions[q]) <= reach2)
                        row.push_back(q);
                    }
                  unsigned int d = 0;
                  for (; d < dim; ++d)
                    {
                      if (k[d] < to[d])
                        {
                          ++k[d];
                          break;
                        }
                      k[d] = from[d];
                    }
                  if (d == dim)
                    break;
                }
              // Slot order is id order: the sum is independent of the
              // partition.
              std::sort(row.begin(), row.end());
              neighbours.insert(neighbours.end(), row.begin(), row.end());
            }
          row_start[i + 1] = neighbours.size();
        }
    }


    template <int dim>
    template <typename Weight>
    void
    NonlocalAverager<dim>::evaluate(const Weight              &w,
                                    const std::vector<double> &values,
                                    const std::vector<bool>   &is_receiver,
                                    std::vector<double>       &averages)
    {
      const std::size_t n_local = slot_of_local.size();
      std::size_t       listed = 0, interacting = 0;
      for (std::size_t i = 0; i < n_local; ++i)
        {
          if (!is_receiver[i])
            {
              averages[i] = values[i];
              continue;
            }
          const Point<dim> xp        = source_positions[slot_of_local[i]];
          double           numerator = 0., denominator = 0.;
          for (std::size_t j = row_start[i]; j < row_start[i + 1]; ++j)
            {
              const unsigned int q = neighbours[j];
              const double wq = w(squared_distance(xp, source_positions[q]));
              numerator += wq * source_weighted_values[q];
              denominator += wq * source_volumes[q];
              interacting += (wq > 0.);
            }
          listed += row_start[i + 1] - row_start[i];
          // The point itself has weight 1; only zero volumes (or points
          // left out of the sums) can leave the denominator at zero, and
          // then there is nothing to average.
          averages[i] = denominator > 0. ? numerator / denominator : values[i];
        }
      listed_pair_count      = listed;
      interacting_pair_count = interacting;
    }


    template class NonlocalAverager<2>;
    template class NonlocalAverager<3>;
  } // namespace nonlocal
} // namespace scarp
