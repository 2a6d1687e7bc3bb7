// The sort of the points into their new cells without the particle
// handler's full sort (particles/point_mover.h), against that sort.
//
// Two particle handlers hold the same points on a mesh refined twice in a
// band (coarse-fine faces in both directions, hanging nodes), in 2D and 3D,
// on any number of ranks. Every step moves the points of both by the same
// pseudo-random displacements (at most 0.2, under the finest cell of
// 0.25); one handler sorts with ParticleHandler::
// sort_particles_into_subdomains_and_cells(), the other with PointMover.
// After every step both must hold, cell by cell, the same points (ids) in
// the same order, with the same reference locations and properties, bit
// for bit: PointMover is meant to be an exact replacement, so the
// tolerance is zero.
//
// Steps of three kinds:
// - odd steps move only the points whose new place is in a locally owned
//   cell: PointMover must then move them itself (on every rank count);
// - even steps move every point: on several ranks some leave their rank,
//   and PointMover must hand them over itself (one exchange; the new
//   cells' points in the full sort's order: those that stayed on the
//   rank, then those received by ascending source rank);
// - the last step pushes one point out of the mesh: the full sort runs (it
//   drops the point) on every rank.
// A third handler, sorted by a PointMover with the default compaction (the
// full sort once the moved points exceed a tenth), must hold the same too,
// and must have handed over to the full sort.
#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/fe/mapping_cartesian.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/particles/particle_handler.h>

#include <scarp/particles/point_mover.h>

#include "../common/scene_runner.h"

#include <cstring>
#include <map>
#include <random>
#include <set>

namespace
{
  using namespace scarp_test;
  using scarp::particles::PointMover;

  constexpr unsigned int n_properties = 3;

  /// The displacement of point @p id in step @p step: each component
  /// uniform in [-0.2, 0.2], the same on every rank and for both handlers.
  template <int dim>
  Tensor<1, dim>
  displacement(const types::particle_index id, const unsigned int step)
  {
    std::mt19937_64                        random(1000003 * id + step);
    std::uniform_real_distribution<double> u(-0.2, 0.2);
    Tensor<1, dim>                         dx;
    for (unsigned int d = 0; d < dim; ++d)
      dx[d] = u(random);
    return dx;
  }

  /// The points of a rank, cell by cell in the order of the active cells:
  /// (active cell index, id, reference location and properties as bits).
  template <int dim>
  std::vector<std::vector<unsigned long long>>
  cell_contents(const parallel::distributed::Triangulation<dim> &tria,
                const Particles::ParticleHandler<dim>           &particles)
  {
    std::vector<std::vector<unsigned long long>> contents;
    const auto                                   bits = [](const double x) {
      unsigned long long b;
      std::memcpy(&b, &x, sizeof(b));
      return b;
    };
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto &point : particles.particles_in_cell(cell))
          {
            std::vector<unsigned long long> row = {cell->active_cell_index(),
                                                   point.get_id()};
            for (unsigned int d = 0; d < dim; ++d)
              row.push_back(bits(point.get_reference_location()[d]));
            for (const double p : point.get_properties())
              row.push_back(bits(p));
            contents.push_back(row);
          }
    return contents;
  }

  template <int dim>
  void
  against_full_sort()
  {
    parallel::distributed::Triangulation<dim> tria(
      MPI_COMM_WORLD, Triangulation<dim>::limit_level_difference_at_vertices);
    const unsigned int n = dim == 2 ? 8 : 4;
    GridGenerator::subdivided_hyper_cube(tria, n, 0., double(n));
    for (unsigned int k = 0; k < 2; ++k)
      {
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->is_locally_owned() && cell->center()[0] > 1.3 &&
              cell->center()[0] < 2.7 &&
              static_cast<unsigned int>(cell->level()) == k)
            cell->set_refine_flag();
        tria.execute_coarsening_and_refinement();
      }
    MappingCartesian<dim>           mapping;
    Particles::ParticleHandler<dim> full(tria, mapping, n_properties);
    Particles::ParticleHandler<dim> moved(tria, mapping, n_properties);
    Particles::ParticleHandler<dim> compacted(tria, mapping, n_properties);
    // 3 points per direction and coarse cell, ids from the lattice.
    const unsigned int m = 3 * n;
    for (unsigned int k = 0; k < std::pow(m, dim); ++k)
      {
        Point<dim>   x;
        unsigned int rest = k;
        for (unsigned int d = 0; d < dim; ++d, rest /= m)
          x[d] = (rest % m + 0.5) / 3.;
        const auto cell = GridTools::find_active_cell_around_point(tria, x);
        if (cell.state() != IteratorState::valid || !cell->is_locally_owned())
          continue;
        Point<dim> xi = mapping.transform_real_to_unit_cell(cell, x);
        const std::vector<double> p = {double(k), x[0] * x[1], -x[0]};
        full.insert_particle(x, xi, k, cell, p);
        moved.insert_particle(x, xi, k, cell, p);
        compacted.insert_particle(x, xi, k, cell, p);
      }
    full.update_cached_numbers();
    moved.update_cached_numbers();
    compacted.update_cached_numbers();
    const std::string where = std::to_string(dim) + "D: ";

    // Where each point's cell level goes, over all steps.
    unsigned int n_to_finer = 0, n_to_coarser = 0, n_moved = 0, n_sent = 0;
    unsigned int n_local_steps = 0, n_full_steps = 0;
    // Steps after which the handler's list was out of order (the same on
    // every rank), and in which that changed this rank's order of points.
    unsigned int n_stale = 0, n_out_of_order = 0;
    bool same = true, followed = true, gained_ok = true, count_ok = true,
         same_order = true, lost_ok = true;
    // Cells the mover left alone and cells whose points it changed.
    unsigned int n_unchanged_cells = 0, n_changed_cells = 0;
    // Without the compaction by the full sort (the test moves most points
    // every step; the runs of scarp a few in a thousand).
    PointMover<dim> mover(1e30);
    // With the default compaction (a tenth of the points): the full sort
    // takes over after a step or two here, and the points must be the same.
    PointMover<dim>    compacting;
    unsigned int       n_compacting_full = 0;
    const unsigned int n_steps           = 12;
    for (unsigned int step = 0; step <= n_steps; ++step)
      {
        std::map<types::particle_index, int> level_before;
        for (const auto &point : full)
          level_before[point.get_id()] = point.get_surrounding_cell()->level();
        const types::particle_index lowest =
          full.n_locally_owned_particles() > 0 ? full.begin()->get_id()
                                               : numbers::invalid_dof_index;
        for (Particles::ParticleHandler<dim> *handler :
             {&full, &moved, &compacted})
          for (auto &point : *handler)
            {
              Point<dim> x = point.get_location();
              if (step == n_steps)
                {
                  // Out of the mesh: the lowest id of the rank.
                  if (point.get_id() == lowest)
                    x[0] = -1.;
                }
              else
                {
                  Point<dim> y = x + displacement<dim>(point.get_id(), step);
                  for (unsigned int d = 0; d < dim; ++d)
                    y[d] = std::min(std::max(y[d], 1e-3), n - 1e-3);
                  if (step % 2 == 1)
                    {
                      const auto cell =
                        GridTools::find_active_cell_around_point(tria, y);
                      if (cell.state() != IteratorState::valid ||
                          !cell->is_locally_owned())
                        continue;
                    }
                  x = y;
                }
              point.set_location(x);
            }
        full.sort_particles_into_subdomains_and_cells();
        // The cells of this rank that hold points before the sort.
        const auto occupied = [&tria](const auto &handler) {
          std::set<CellId> cells;
          for (const auto &cell : tria.active_cell_iterators())
            if (cell->is_locally_owned() && handler.n_particles_in_cell(cell))
              cells.insert(cell->id());
          return cells;
        };
        const std::set<CellId> held = occupied(moved);
        // Each cell's points (id and property pool handle) in its order.
        const auto points_by_cell = [&tria](const auto &handler) {
          std::map<unsigned int,
                   std::vector<std::pair<types::particle_index, unsigned int>>>
            points;
          for (const auto &cell : tria.active_cell_iterators())
            if (cell->is_locally_owned())
              for (const auto &point : handler.particles_in_cell(cell))
                points[cell->active_cell_index()].emplace_back(
                  point.get_id(), point.get_local_index());
          return points;
        };
        const auto points_before = points_by_cell(moved);
        const bool local         = mover.sort(moved, tria, MPI_COMM_WORLD);
        if (local)
          {
            // What MpmTransfer relies on to skip the walk over all cells:
            // a cell holds points now only if it held some or gained some,
            // and every cell that gained points is this rank's and holds
            // them.
            std::set<CellId> candidates = held;
            for (const auto &cell : mover.cells_gained())
              {
                candidates.insert(cell->id());
                gained_ok = gained_ok && cell->is_locally_owned() &&
                            moved.n_particles_in_cell(cell) > 0;
              }
            for (const CellId &id : occupied(moved))
              gained_ok = gained_ok && candidates.count(id) == 1;
            // What MpmTransfer relies on to copy a cell's points from its
            // list before the sort: a cell neither gained nor lost holds
            // the same points, in the same order, in the same pool slots.
            std::set<unsigned int> changed;
            for (const auto &cell : mover.cells_gained())
              changed.insert(cell->active_cell_index());
            for (const auto &cell : mover.cells_lost())
              {
                changed.insert(cell->active_cell_index());
                lost_ok = lost_ok && cell->is_locally_owned();
              }
            const auto points_after = points_by_cell(moved);
            for (const auto &[index, points] : points_before)
              if (changed.count(index) == 0)
                {
                  const auto after = points_after.find(index);
                  lost_ok          = lost_ok && after != points_after.end() &&
                            after->second == points;
                  ++n_unchanged_cells;
                }
            for (const auto &[index, points] : points_after)
              if (changed.count(index) == 0)
                lost_ok = lost_ok && points_before.count(index) == 1;
            n_changed_cells += changed.size();
            // It takes the points out one at a time, not through
            // remove_particles(), which recounts them, and it does not
            // recount (also not after points changed ranks): the local count
            // it leaves must be the number of points held, and the global
            // count the sum of the local ones.
            const types::particle_index n_all =
              Utilities::MPI::sum(moved.n_locally_owned_particles(),
                                  MPI_COMM_WORLD);
            count_ok = count_ok &&
                       static_cast<types::particle_index>(
                         std::distance(moved.begin(), moved.end())) ==
                         moved.n_locally_owned_particles() &&
                       moved.n_global_particles() == n_all;
          }
        n_moved += mover.n_moved();
        n_sent += mover.n_sent();
        n_compacting_full +=
          compacting.sort(compacted, tria, MPI_COMM_WORLD) ? 0 : 1;
        (local ? n_local_steps : n_full_steps) += 1;
        if (step < n_steps)
          followed = followed && local;
        // Cell by cell (as the transfer reads them) the points are the full
        // sort's right after the move.
        same = same &&
               cell_contents(tria, full) == cell_contents(tria, moved) &&
               cell_contents(tria, full) == cell_contents(tria, compacted);
        // The handler's own order of the points (its list of cells, which
        // an iteration over all points follows: output, splitting) may lag
        // behind: a cell new to the list is at its end until
        // restore_order(), which the simulation calls before any such
        // iteration. Then it is the full sort's too.
        const auto ids_in_order = [](const auto &handler) {
          std::vector<types::particle_index> ids;
          for (const auto &point : handler)
            ids.push_back(point.get_id());
          return ids;
        };
        if (!mover.order_restored())
          {
            ++n_stale;
            n_out_of_order += ids_in_order(full) != ids_in_order(moved);
          }
        mover.restore_order(moved);
        compacting.restore_order(compacted);
        same_order = same_order && mover.order_restored() &&
                     compacting.order_restored() &&
                     ids_in_order(full) == ids_in_order(moved) &&
                     ids_in_order(full) == ids_in_order(compacted);
        for (const auto &point : full)
          {
            const auto before = level_before.find(point.get_id());
            if (before == level_before.end())
              continue;
            const int level = point.get_surrounding_cell()->level();
            n_to_finer += level > before->second;
            n_to_coarser += level < before->second;
          }
        if (step == n_steps)
          check(!local, where + "a point leaving the mesh takes the full sort");
      }
    n_moved      = Utilities::MPI::sum(n_moved, MPI_COMM_WORLD);
    n_sent       = Utilities::MPI::sum(n_sent, MPI_COMM_WORLD);
    n_to_finer   = Utilities::MPI::sum(n_to_finer, MPI_COMM_WORLD);
    n_to_coarser = Utilities::MPI::sum(n_to_coarser, MPI_COMM_WORLD);
    out() << "  " << where << full.n_global_particles() << " points, "
          << n_moved << " moved by PointMover (" << n_sent
          << " to another rank), " << n_local_steps << " steps moved by it and "
          << n_full_steps << " by the full sort on rank 0; " << n_to_finer
          << " moves into finer cells, " << n_to_coarser << " into coarser"
          << std::endl;
    check(same,
          where + "same points, order, reference locations and properties "
                  "in every cell as the full sort, bit for bit, every step "
                  "(with and without the compaction)");
    count_ok = Utilities::MPI::min(static_cast<int>(count_ok), MPI_COMM_WORLD);
    check(count_ok,
          where + "after each move the local count of points is the number "
                  "of points held, the global count their sum");
    same_order =
      Utilities::MPI::min(static_cast<int>(same_order), MPI_COMM_WORLD);
    check(same_order,
          where + "an iteration over all points meets them in the order of "
                  "the full sort, every step");
    n_out_of_order = Utilities::MPI::sum(n_out_of_order, MPI_COMM_WORLD);
    out() << "  " << where << n_stale
          << " steps left the handler's list out of order, " << n_out_of_order
          << " times a rank's order of points with it" << std::endl;
    check(n_stale > 0 && n_out_of_order > 0,
          where + "points entering empty cells leave the handler's list out "
                  "of order until restore_order() (which the check of the "
                  "order above therefore tests)");
    check(gained_ok,
          where + "after each move every cell with points held points "
                  "before or is among the cells gained, which hold points");
    lost_ok = Utilities::MPI::min(static_cast<int>(lost_ok), MPI_COMM_WORLD);
    n_unchanged_cells = Utilities::MPI::sum(n_unchanged_cells, MPI_COMM_WORLD);
    n_changed_cells   = Utilities::MPI::sum(n_changed_cells, MPI_COMM_WORLD);
    out() << "  " << where << n_unchanged_cells << " cells kept their points, "
          << n_changed_cells << " gained or lost some (over all moves)"
          << std::endl;
    check(lost_ok && n_unchanged_cells > 0 && n_changed_cells > 0,
          where + "after each move a cell neither gained nor lost holds the "
                  "same points in the same order and pool slots as before");
    check(followed,
          where + "PointMover moves the points itself in every step but the "
                  "last, also those that change ranks");
    if (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
      check(n_sent > 0, where + "points handed over to other ranks");
    else
      check(n_sent == 0, where + "no point handed over on one rank");
    check(n_compacting_full > 1,
          where + "the default compaction hands over to the full sort");
    check(n_moved > 0 && n_to_finer > 0 && n_to_coarser > 0,
          where + "points moved into finer and coarser cells");
    check(full.n_global_particles() == moved.n_global_particles() &&
            full.n_global_particles() ==
              Utilities::MPI::sum(full.n_locally_owned_particles(),
                                  MPI_COMM_WORLD),
          where + "the same number of points (one left the mesh)");
  }
} // namespace

int
main(int argc, char **argv)
{
  return run_cases(argc, argv, {{"against_full_sort", [] {
                                   against_full_sort<2>();
                                   against_full_sort<3>();
                                 }}});
}
