// PointMover: the sort of the points into their new cells when they all
// stay on this rank (see the class documentation).

#include <deal.II/base/array_view.h>

#include <scarp/particles/checked_sort.h>
#include <scarp/particles/point_mover.h>
#include <scarp/particles/pool_growth.h>

#include <algorithm>
#include <cstring>
#include <iterator>
#include <map>

namespace scarp
{
  namespace particles
  {
    namespace
    {
      /// The lowest vertex of an axis-aligned cell and its extents, as
      /// MappingCartesian reads them (vertex 1, 2, 4 for x, y, z).
      template <int dim>
      void
      cell_frame(const typename Triangulation<dim>::cell_iterator &cell,
                 Point<dim>                                       &start,
                 Tensor<1, dim>                                   &extent)
      {
        start = cell->vertex(0);
        for (unsigned int d = 0; d < dim; ++d)
          extent[d] = cell->vertex(1u << d)[d] - start[d];
      }

      /// The reference location of @p x, in the same arithmetic as
      /// MappingCartesian::transform_real_to_unit_cell(), so that a point
      /// gets the same bits whichever sort places it.
      template <int dim>
      inline Point<dim>
      unit_point(const Point<dim>     &x,
                 const Point<dim>     &start,
                 const Tensor<1, dim> &extent)
      {
        Point<dim> xi = x;
        xi -= start;
        for (unsigned int d = 0; d < dim; ++d)
          xi[d] /= extent[d];
        return xi;
      }

      /// The face through which @p xi leaves the unit cell, or
      /// numbers::invalid_unsigned_int if it is inside (closed, as
      /// GeometryInfo::is_inside_unit_cell()).
      template <int dim>
      unsigned int
      exit_face(const Point<dim> &xi)
      {
        for (unsigned int d = 0; d < dim; ++d)
          {
            if (xi[d] < 0.)
              return 2 * d;
            if (xi[d] > 1.)
              return 2 * d + 1;
          }
        return numbers::invalid_unsigned_int;
      }

      /**
       * The active cell holding @p x, walked to from @p start_cell through
       * face neighbours (into the child on the side of @p x where the
       * neighbour is finer), possibly through ghost cells: locally owned or
       * a ghost cell (another rank's). False if the walk leaves the mesh,
       * meets an artificial cell or does not end within a few cells (a
       * point moves less than a cell per step): the full sort then decides.
       */
      template <int dim>
      bool
      walk_to_cell(
        const typename Triangulation<dim>::active_cell_iterator &start_cell,
        const Point<dim>                                        &x,
        typename Triangulation<dim>::active_cell_iterator       &found,
        Point<dim>                                              &xi)
      {
        typename Triangulation<dim>::cell_iterator cell = start_cell;
        Point<dim>                                 start;
        Tensor<1, dim>                             extent;
        for (unsigned int hop = 0; hop < 4 * dim; ++hop)
          {
            cell_frame<dim>(cell, start, extent);
            xi                      = unit_point(x, start, extent);
            const unsigned int face = exit_face(xi);
            if (face == numbers::invalid_unsigned_int)
              {
                found = cell;
                return true;
              }
            if (cell->at_boundary(face))
              return false;
            cell = cell->neighbor(face);
            while (cell->has_children())
              {
                // Children are numbered lexicographically: bit d set for
                // the upper half in direction d.
                const Point<dim> centre = cell->center();
                unsigned int     child  = 0;
                for (unsigned int d = 0; d < dim; ++d)
                  if (x[d] > centre[d])
                    child |= 1u << d;
                cell = cell->child(child);
              }
            // Ghost cells are walked through (a corner crossing may pass
            // one); artificial cells are not known well enough.
            if (cell->is_artificial())
              return false;
          }
        return false;
      }
    } // namespace


    template <int dim>
    bool
    PointMover<dim>::find_new_cells(Particles::ParticleHandler<dim> &particles,
                                    const std::vector<CellPoints>   &cells,
                                    const std::vector<unsigned int> &handles)
    {
      moves.clear();
      n_leaving_rank       = 0;
      new_cell_entry       = false;
      auto          &pool  = particles.get_property_pool();
      bool           local = true;
      Point<dim>     start;
      Tensor<1, dim> extent;
      // In the order of the particle handler's sort: active cells, then
      // the points of a cell in its order.
      for (const CellPoints &c : cells)
        {
          cell_frame<dim>(c.cell, start, extent);
          for (unsigned int q = c.begin; q < c.end; ++q)
            {
              const unsigned int handle = handles[q];
              const Point<dim>  &x      = pool.get_location(handle);
              const Point<dim>   xi     = unit_point(x, start, extent);
              if (exit_face(xi) == numbers::invalid_unsigned_int)
                {
                  pool.set_reference_location(handle, xi);
                  continue;
                }
              if (!local)
                continue;
              // The handler's iterator, needed for the few that move only.
              Move move;
              move.point = particles.particles_in_cell(c.cell).begin();
              std::advance(move.point, q - c.begin);
              move.old_cell      = c.cell;
              move.index_in_cell = q - c.begin;
              local = walk_to_cell<dim>(c.cell, x, move.cell, move.reference);
              if (local)
                {
                  // A ghost cell: the point goes to the rank that owns it.
                  move.destination = move.cell->is_locally_owned()
                                       ? numbers::invalid_subdomain_id
                                       : move.cell->subdomain_id();
                  n_leaving_rank +=
                    move.destination != numbers::invalid_subdomain_id;
                  new_cell_entry =
                    new_cell_entry ||
                    (move.destination == numbers::invalid_subdomain_id &&
                     particles.n_particles_in_cell(move.cell) == 0);
                  moves.push_back(move);
                }
            }
        }
      if (!local)
        moves.clear();
      return local;
    }


    template <int dim>
    void
    PointMover<dim>::move_points(Particles::ParticleHandler<dim> &particles,
                                 const Triangulation<dim>        &triangulation,
                                 const bool                       exchange,
                                 const MPI_Comm                   communicator)
    {
      // What a point that changes ranks takes along: its new cell, its
      // location and reference location there, its id and properties,
      // one record of this size each (packed and read below in this order).
      const unsigned int n_properties = particles.n_properties_per_particle();
      const std::size_t  record_size =
        sizeof(CellId::binary_type) + 2 * sizeof(Point<dim>) +
        sizeof(types::particle_index) + n_properties * sizeof(double);
      std::map<unsigned int, std::vector<char>> outgoing;
      const auto append = [](std::vector<char> &data, const auto &value) {
        const char *bytes = reinterpret_cast<const char *>(&value);
        data.insert(data.end(), bytes, bytes + sizeof(value));
      };
      // The points of this rank go in before the cells they leave free
      // their slots: room for them first.
      PoolGrowth::reserve(particles, moves.size() - n_leaving_rank);
      gained.clear();
      for (const Move &move : moves)
        {
          // Copies first: inserting may grow the pool's storage.
          const Point<dim>            x          = move.point->get_location();
          const types::particle_index id         = move.point->get_id();
          const auto                  properties = move.point->get_properties();
          if (move.destination == numbers::invalid_subdomain_id)
            {
              buffer.assign(properties.begin(), properties.end());
              particles.insert_particle(
                x, move.reference, id, move.cell, make_array_view(buffer));
              gained.push_back(move.cell);
            }
          else
            {
              std::vector<char> &data = outgoing[move.destination];
              append(data, move.cell->id().template to_binary<dim>());
              append(data, x);
              append(data, move.reference);
              append(data, id);
              const std::size_t n = properties.size() * sizeof(double);
              data.insert(data.end(),
                          reinterpret_cast<const char *>(properties.data()),
                          reinterpret_cast<const char *>(properties.data()) +
                            n);
            }
        }
      // As in the full sort: the points that stay on their rank are in
      // their new cells first, then those received, by ascending source
      // rank, each source's in its order.
      if (exchange)
        {
          const std::map<unsigned int, std::vector<char>> incoming =
            Utilities::MPI::some_to_some(communicator, outgoing);
          std::size_t n_incoming = 0;
          for (const auto &source : incoming)
            n_incoming += source.second.size() / record_size;
          PoolGrowth::reserve(particles, n_incoming);
          for (const auto &source : incoming)
            {
              const char *data = source.second.data();
              const char *end  = data + source.second.size();
              const auto  take = [&data](auto &value) {
                std::memcpy(&value, data, sizeof(value));
                data += sizeof(value);
              };
              while (data < end)
                {
                  CellId::binary_type   cell_id;
                  Point<dim>            x, reference;
                  types::particle_index id;
                  take(cell_id);
                  take(x);
                  take(reference);
                  take(id);
                  buffer.resize(n_properties);
                  std::memcpy(buffer.data(),
                              data,
                              n_properties * sizeof(double));
                  data += n_properties * sizeof(double);
                  const typename Triangulation<dim>::active_cell_iterator cell =
                    triangulation.create_cell_iterator(CellId(cell_id));
                  particles.insert_particle(
                    x, reference, id, cell, make_array_view(buffer));
                  gained.push_back(cell);
                }
            }
        }
      // The points leave their old cells one at a time, in the order in
      // which ParticleHandler::remove_particles() takes them (by cell, then
      // by position in the cell, from the last), so that the points left in
      // a cell are reordered alike. remove_particles() would then call
      // update_cached_numbers(); here the counts stay right without it
      // (remove_particle() and insert_particle() keep the local count, and
      // the global count and the largest id do not change: no point left
      // the mesh; only the largest number of points per cell,
      // n_global_max_particles_per_cell(), which scarp does not use, is
      // left as it was), and the order of the list waits for
      // restore_order().
      std::sort(moves.begin(), moves.end(), [](const Move &a, const Move &b) {
        return a.old_cell > b.old_cell ||
               (a.old_cell == b.old_cell && a.index_in_cell > b.index_in_cell);
      });
      lost.clear();
      for (const Move &move : moves)
        {
          lost.push_back(move.old_cell);
          particles.remove_particle(move.point);
        }
      n_last_moved = moves.size();
      n_last_sent  = n_leaving_rank;
      moves.clear();
    }


    template <int dim>
    bool
    PointMover<dim>::sort(Particles::ParticleHandler<dim> &particles,
                          const Triangulation<dim>        &triangulation,
                          const std::vector<CellPoints>   &cells,
                          const std::vector<unsigned int> &handles,
                          const MPI_Comm                   communicator)
    {
      // 2: move here; 1: the points could move here, but their slots are
      // to be put in order again; 0: a point leaves the mesh or cannot be
      // followed. Twice that, plus one if no point leaves this rank: one
      // reduction tells both.
      unsigned int verdict = find_new_cells(particles, cells, handles) ? 2 : 0;
      if (verdict == 2 &&
          double(n_moved_since_full_sort + moves.size()) >
            compaction_fraction * particles.n_locally_owned_particles())
        verdict = 1;
      // With it, in the same reduction: whether a rank's moves add a cell
      // to the particle handler's list (0) or not (1).
      const unsigned int mine[2] = {2 * verdict + (n_leaving_rank == 0 ? 1 : 0),
                                    new_cell_entry ? 0u : 1u};
      unsigned int       least[2];
      Utilities::MPI::min(mine, communicator, least);
      const unsigned int all = least[0];
      if (all >= 4)
        {
          move_points(particles, triangulation, all == 4, communicator);
          // A cell new to a rank's list, from this rank or another, is at
          // the end of that list.
          order_stale = order_stale || all == 4 || least[1] == 0;
          n_moved_since_full_sort += n_last_moved;
          return true;
        }
      // The full sort walks the points in the order of the list.
      restore_order(particles);
      moves.clear();
      gained.clear();
      lost.clear();
      n_last_moved            = 0;
      n_last_sent             = 0;
      n_moved_since_full_sort = 0;
      CheckedSort<dim>::sort(particles,
                             triangulation,
                             numbers::invalid_unsigned_int,
                             "of the points into their new cells",
                             communicator);
      return false;
    }


    template <int dim>
    void
    PointMover<dim>::restore_order(Particles::ParticleHandler<dim> &particles)
    {
      if (!order_stale)
        return;
      particles.update_cached_numbers();
      order_stale = false;
    }


    template <int dim>
    bool
    PointMover<dim>::sort(Particles::ParticleHandler<dim> &particles,
                          const Triangulation<dim>        &triangulation,
                          const MPI_Comm                   communicator)
    {
      own_cells.clear();
      own_handles.clear();
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const auto range = particles.particles_in_cell(cell);
            if (range.begin() == range.end())
              continue;
            CellPoints c;
            c.cell  = cell;
            c.begin = own_handles.size();
            for (const auto &point : range)
              own_handles.push_back(point.get_local_index());
            c.end = own_handles.size();
            own_cells.push_back(c);
          }
      return sort(
        particles, triangulation, own_cells, own_handles, communicator);
    }


    template class PointMover<2>;
    template class PointMover<3>;
  } // namespace particles
} // namespace scarp
