// NonlocalAverager: the lists of neighbours within the radius, built,
// patched after points changed ranks, and grouped for the sums.

#include <scarp/nonlocal/nonlocal_averager.h>
#include <scarp/nonlocal/nonlocal_averager_internal.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <utility>

namespace scarp
{
  namespace nonlocal
  {
    using namespace internal;


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


    // Instantiations (the other members are in the other nonlocal_*.cc
    // files).
    template void
    NonlocalAverager<2>::build_neighbour_lists(
      const std::vector<bool> &is_receiver);
    template void
    NonlocalAverager<3>::build_neighbour_lists(
      const std::vector<bool> &is_receiver);
    template void
    NonlocalAverager<2>::patch_neighbour_lists(
      const std::vector<bool>                  &is_receiver,
      const std::vector<types::particle_index> &ids,
      const std::vector<types::particle_index> &old_slot_ids);
    template void
    NonlocalAverager<3>::patch_neighbour_lists(
      const std::vector<bool>                  &is_receiver,
      const std::vector<types::particle_index> &ids,
      const std::vector<types::particle_index> &old_slot_ids);
    template void
    NonlocalAverager<2>::append_groups(std::vector<unsigned int> receivers,
                                       const double              reach);
    template void
    NonlocalAverager<3>::append_groups(std::vector<unsigned int> receivers,
                                       const double              reach);
  } // namespace nonlocal
} // namespace scarp
