// Cost of the non-local average for the chalk length scale: a 2D block of
// ~30k points at spacing 0.125 m, l_c = 0.18 m. Prints the number of points,
// neighbours per point, and the time per average with list reuse (small
// moves, new values every call) and without (lists rebuilt every call), for
// both weights. Also times a neighbour search with deal.II's Boost R-tree
// (pack_rtree) against the cell list, the reason the cell list is used.
// Prints figures for doc/nonlocal.md; asserts nothing. Runs on any number of
// ranks (slabs in x).

#include <deal.II/base/mpi.h>

#include <deal.II/numerics/rtree.h>

#include "test_tools.h"

#include <boost/geometry/index/rtree.hpp>

#include <chrono>
#include <iomanip>

using namespace scarp_test;

namespace
{
  double
  seconds_since(const std::chrono::steady_clock::time_point &start)
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                         start)
      .count();
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  const unsigned int n_ranks            = Utilities::MPI::n_mpi_processes(comm);
  const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
  constexpr int      dim  = 2;

  const unsigned int n       = 173; // 173^2 = 29929 points
  const double       h       = 0.125;
  const double       l_c     = 0.18;
  const double       length  = (n - 1) * h;
  const unsigned int n_calls = argc > 1 ? std::stoi(argv[1]) : 50;

  const PointSet<dim> all = make_lattice<dim>(n, h);
  PointSet<dim>       points;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (std::min<unsigned int>(n_ranks - 1,
                               all.positions[i][0] / length * n_ranks) == rank)
      points.push_back(
        all.positions[i], all.volumes[i], std::sin(0.01 * i), true, all.ids[i]);
  Point<dim> lo, hi;
  lo[0] = length * rank / n_ranks - 0.5 * h;
  hi[0] = length * (rank + 1) / n_ranks + 0.5 * h;
  lo[1] = -0.5 * h;
  hi[1] = length + 0.5 * h;
  const std::vector<BoundingBox<dim>> boxes = {
    BoundingBox<dim>(std::make_pair(lo, hi))};
  const std::vector<Point<dim>> initial = points.positions;

  if (rank == 0)
    std::cout << "Non-local average benchmark: " << all.size()
              << " points in 2D, spacing " << h << ", l_c " << l_c << ", "
              << n_ranks << " rank(s), " << n_calls << " calls per figure\n";

  std::vector<double> ybar;
  for (const auto type : {WeightType::bell, WeightType::gaussian})
    for (const bool reuse : {true, false})
      {
        NonlocalAverager<dim> averager(comm);
        averager.reinit(type, l_c, 0.1);
        points.average(averager, boxes); // first build, not timed
        MPI_Barrier(comm);
        const auto start = std::chrono::steady_clock::now();
        for (unsigned int call = 0; call < n_calls; ++call)
          {
            // Small moves (0.2 skin at most from the start) and new values,
            // as in a time step.
            const double amplitude =
              0.2 * averager.skin_distance() * std::sin(0.1 * call);
            for (std::size_t i = 0; i < points.size(); ++i)
              {
                points.positions[i][0] = initial[i][0] + amplitude;
                points.values[i]       = std::sin(0.01 * points.ids[i] + call);
              }
            if (!reuse)
              averager.invalidate_neighbour_lists();
            averager.compute(boxes,
                             points.positions,
                             points.volumes,
                             points.values,
                             points.receivers,
                             points.ids,
                             ybar);
          }
        const double time =
          Utilities::MPI::max(seconds_since(start), comm) / n_calls;
        const double listed =
          double(Utilities::MPI::sum(averager.n_listed_pairs(), comm)) /
          all.size();
        const double interacting =
          double(Utilities::MPI::sum(averager.n_interacting_pairs(), comm)) /
          all.size();
        const std::size_t ghosts =
          Utilities::MPI::sum(averager.n_ghost_points(), comm);
        if (rank == 0)
          std::cout << std::left << std::setw(9) << to_string(type)
                    << (reuse ? "reuse   " : "rebuild ") << "neighbours/point "
                    << std::setprecision(4) << interacting << " (listed "
                    << listed << "), ghosts " << ghosts << ", rebuilds "
                    << averager.n_rebuilds() << ", reuses "
                    << averager.n_reuses() << ", time per average "
                    << std::setprecision(3) << 1e3 * time << " ms" << std::endl;
      }

  // The same search with deal.II's R-tree, to compare with the cell list
  // (whose cost is "rebuild" minus "reuse" above), on rank 0's points only.
  if (rank == 0)
    {
      namespace bgi        = boost::geometry::index;
      const double reach   = 1.1 * std::sqrt(7.) * l_c; // bell cut-off + skin
      const double reach2  = reach * reach;
      const auto   start   = std::chrono::steady_clock::now();
      std::size_t  n_pairs = 0;
      const unsigned int n_repeat = 5;
      for (unsigned int repeat = 0; repeat < n_repeat; ++repeat)
        {
          const auto tree = pack_rtree_of_indices(points.positions);
          std::vector<unsigned int> row;
          n_pairs = 0;
          for (const auto &x : points.positions)
            {
              Point<dim> a = x, b = x;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  a[d] -= reach;
                  b[d] += reach;
                }
              row.clear();
              for (const auto j :
                   tree | bgi::adaptors::queried(bgi::intersects(
                            BoundingBox<dim>(std::make_pair(a, b)))))
                if (x.distance_square(points.positions[j]) <= reach2)
                  row.push_back(j);
              std::sort(row.begin(), row.end());
              n_pairs += row.size();
            }
        }
      std::cout << "R-tree search (bell, cut-off + skin) of rank 0's "
                << points.size()
                << " points: " << double(n_pairs) / points.size()
                << " neighbours/point, "
                << 1e3 * seconds_since(start) / n_repeat << " ms per build"
                << std::endl;
    }
  return 0;
}
