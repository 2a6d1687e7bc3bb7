// Cost of the non-local average for the chalk length scale l_c = 0.18 m
// (bell cut-off 0.476 m), with ~30k points per scene: 2D at point spacings
// 0.0625 m (~180 neighbours per point: 0.125 m cells with 2x2 points) and
// 0.03125 m (~700), bell and Gaussian, every fifth point left out of the sums
// (the second compute()), and 3D at 0.125 m (~230). For each scene, n calls
// with small moves (< skin/2, lists reused) and new values are timed, for
// NonlocalAverager::compute() ("fast") and for the straightforward sums of
// test_tools.h ("reference": one receiver at a time over its list sorted by
// id, as the library did before), on the same input; the largest relative
// difference of the two is printed. The first build of the lists is timed
// on its own. Also times a neighbour search with deal.II's Boost R-tree
// (pack_rtree), the reason the cell list is used. Prints figures for
// doc/nonlocal.md; asserts nothing. Runs on any number of ranks (slabs in x;
// the reference sums each rank's own receivers over all points).
//
// Usage: test_nonlocal_benchmark [calls per scene, default 20]

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


  template <int dim>
  void
  run_scene(const WeightType   type,
            const unsigned int n,
            const double       h,
            const bool         exclude,
            const unsigned int n_calls)
  {
    const MPI_Comm     comm    = MPI_COMM_WORLD;
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
    const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);
    const double       l_c     = 0.18;
    const double       length  = (n - 1) * h;

    PointSet<dim> all = make_lattice<dim>(n, h);
    for (std::size_t i = 0; i < all.size(); ++i)
      {
        all.volumes[i] *= 1. + 0.2 * std::sin(0.3 * i);
        all.receivers[i] = (i % 11 != 5);
      }
    if (exclude)
      for (std::size_t i = 0; i < all.size(); ++i)
        all.sources.push_back(i % 5 != 1);
    std::vector<unsigned int> own;
    for (unsigned int i = 0; i < all.size(); ++i)
      if (std::min<unsigned int>(n_ranks - 1,
                                 all.positions[i][0] / length * n_ranks) ==
          rank)
        own.push_back(i);
    Point<dim> lo, hi;
    for (unsigned int d = 0; d < dim; ++d)
      {
        lo[d] = -0.5 * h;
        hi[d] = length + 0.5 * h;
      }
    lo[0] = length * rank / n_ranks - 0.5 * h;
    hi[0] = length * (rank + 1) / n_ranks + 0.5 * h;
    const std::vector<BoundingBox<dim>> boxes = {
      BoundingBox<dim>(std::make_pair(lo, hi))};
    const std::vector<Point<dim>> initial = all.positions;

    NonlocalAverager<dim> averager(comm);
    averager.reinit(type, l_c, 0.1);
    const double          skin = averager.skin_distance();
    ReferenceAverage<dim> reference(averager.get_weight_function(),
                                    averager.cutoff_radius() + skin);

    // Call 0 builds; the others move every point by less than skin/2.
    const auto set_call = [&](const unsigned int call) {
      for (std::size_t i = 0; i < all.size(); ++i)
        {
          for (unsigned int d = 0; d < dim; ++d)
            all.positions[i][d] =
              initial[i][d] + (call == 0 ? 0.
                                         : 0.45 * skin / std::sqrt(dim) *
                                             std::sin(1.3 * i + call + d));
          all.values[i] = 1. + std::sin(0.01 * all.ids[i] + call);
          if (exclude && !all.sources[i])
            all.values[i] = 0.;
        }
    };
    PointSet<dim> mine;
    const auto    set_mine = [&]() {
      mine = PointSet<dim>();
      for (const auto i : own)
        {
          mine.push_back(all.positions[i],
                         all.volumes[i],
                         all.values[i],
                         all.receivers[i],
                         all.ids[i]);
          if (exclude)
            mine.sources.push_back(all.sources[i]);
        }
    };

    std::vector<double> ybar;
    double              fast_time = 0., reference_time = 0., build_time = 0.;
    double              difference = 0.;
    for (unsigned int call = 0; call <= n_calls; ++call)
      {
        set_call(call);
        set_mine();
        MPI_Barrier(comm);
        auto start = std::chrono::steady_clock::now();
        ybar       = mine.average(averager, boxes);
        (call == 0 ? build_time : fast_time) += seconds_since(start);

        if (call == 0)
          reference.build(all, own); // lists of the same pairs, not timed
        start               = std::chrono::steady_clock::now();
        const auto expected = reference.average(all);
        reference_time += (call > 0 ? seconds_since(start) : 0.);
        difference =
          std::max(difference, max_relative_difference(ybar, expected));
      }
    fast_time      = Utilities::MPI::max(fast_time, comm) / n_calls;
    reference_time = Utilities::MPI::max(reference_time, comm) / n_calls;
    build_time     = Utilities::MPI::max(build_time, comm);
    difference     = Utilities::MPI::max(difference, comm);
    const double n_receivers = Utilities::MPI::sum(
      double(std::count(mine.receivers.begin(), mine.receivers.end(), true)),
      comm);
    const double interacting =
      double(Utilities::MPI::sum(averager.n_interacting_pairs(), comm));
    const double listed =
      double(Utilities::MPI::sum(averager.n_listed_pairs(), comm));
    const std::size_t ghosts =
      Utilities::MPI::sum(averager.n_ghost_points(), comm);
    if (rank == 0)
      std::cout << std::fixed << dim << "D " << std::left << std::setw(8)
                << to_string(type) << std::right << std::setw(8)
                << std::setprecision(5) << h
                << (exclude ? " 1/5 out" : "        ") << std::setw(7)
                << all.size() << std::setw(7) << std::setprecision(1)
                << interacting / n_receivers << std::setw(7)
                << listed / n_receivers << std::setw(7) << ghosts
                << std::setw(9) << std::setprecision(2) << 1e3 * reference_time
                << std::setw(8) << 1e9 * reference_time / interacting * n_ranks
                << std::setw(9) << 1e3 * fast_time << std::setw(8)
                << 1e9 * fast_time / interacting * n_ranks << std::setw(7)
                << std::setprecision(1) << reference_time / fast_time
                << std::setw(9) << std::setprecision(1) << 1e3 * build_time
                << std::setw(10) << std::scientific << std::setprecision(1)
                << difference << std::endl;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  const unsigned int n_ranks            = Utilities::MPI::n_mpi_processes(comm);
  const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);
  const unsigned int n_calls = argc > 1 ? std::stoi(argv[1]) : 20;

  if (rank == 0)
    std::cout
      << "Non-local average benchmark: l_c 0.18, skin 0.1 cut-off, " << n_ranks
      << " rank(s), " << n_calls << " calls per scene (lists reused)\n"
      << "   weight   spacing   out points  neigh listed ghosts"
      << "   ref ms  ref ns   new ms  new ns  x  build ms  max rel diff\n"
      << "  (neigh: sources within the cut-off per receiver, self "
         "included; listed: within cut-off + skin;\n"
      << "   ms per call, ns per neighbour pair and rank; x: speed-up; "
         "build: first call, lists built)\n";
  run_scene<2>(WeightType::bell, 173, 0.0625, false, n_calls);
  run_scene<2>(WeightType::bell, 173, 0.0625, true, n_calls);
  run_scene<2>(WeightType::gaussian, 173, 0.0625, false, n_calls);
  run_scene<2>(WeightType::bell, 173, 0.03125, false, n_calls);
  run_scene<3>(WeightType::bell, 31, 0.125, false, n_calls);
  run_scene<3>(WeightType::gaussian, 31, 0.125, false, n_calls);

  // The same search with deal.II's R-tree, to compare with the cell list,
  // on a 173 x 173 lattice at 0.125 m (rank 0's slab).
  const unsigned int n      = 173;
  const double       h      = 0.125;
  const double       l_c    = 0.18;
  const double       length = (n - 1) * h;
  const PointSet<2>  all    = make_lattice<2>(n, h);
  PointSet<2>        points;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (std::min<unsigned int>(n_ranks - 1,
                               all.positions[i][0] / length * n_ranks) == rank)
      points.push_back(all.positions[i], 1., 0., true, all.ids[i]);
  constexpr int dim = 2;
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
