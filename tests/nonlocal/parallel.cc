// The average does not depend on the number of MPI ranks (architecture:
// "parallel by construction"). A lattice in [0,1]^dim is split into slabs
// x in [r/P, (r+1)/P) on P ranks; every rank also computes the serial answer
// for all points (on MPI_COMM_SELF) and compares its own points with it.
// Three calls: a first build; a reuse with new values and small moves; a
// rebuild after moves larger than half the skin, which take some points out
// of their rank's box. With exclude = true every fifth point is left out
// of both sums (fully damaged points of the authors' variant): the ghosts
// must carry that, and the answer must still be the serial one.

#include <deal.II/base/mpi.h>

#include "test_tools.h"

using namespace scarp_test;

template <int dim>
void
run(const WeightType type, const bool exclude)
{
  const MPI_Comm     comm    = MPI_COMM_WORLD;
  const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
  const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);

  const unsigned int n   = dim == 2 ? 41 : 13;
  const double       h   = 1. / (n - 1);
  const double       l_c = dim == 2 ? 0.04 : 0.08; // R = 4 h (2D), 2.5 h (3D)

  PointSet<dim> all        = make_varied_lattice<dim>(n, h, exclude);
  const auto    set_values = [&all](const double t) {
    for (std::size_t i = 0; i < all.size(); ++i)
      {
        const auto &x = all.positions[i];
        all.values[i] =
          std::sin(3. * x[0] + t) * std::cos(2. * x[1]) + x[0] * x[1];
        // Points left out are fully damaged, whose Y the chalk model sets
        // to 0 (which is what dilutes the average when they are kept).
        if (!all.sources.empty() && !all.sources[i])
          all.values[i] = 0.;
      }
  };

  // Slabs of the "mesh" and the points each rank owns (by initial x).
  const auto owner = [n_ranks](const double x) {
    return std::min<unsigned int>(n_ranks - 1, x * n_ranks);
  };
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (owner(all.positions[i][0]) == rank)
      mine.push_back(i);
  Point<dim> lo, hi;
  for (unsigned int d = 0; d < dim; ++d)
    hi[d] = 1.;
  lo[0]                                        = double(rank) / n_ranks;
  hi[0]                                        = double(rank + 1) / n_ranks;
  const std::vector<BoundingBox<dim>> my_boxes = {
    BoundingBox<dim>(std::make_pair(lo, hi))};

  NonlocalAverager<dim> serial(MPI_COMM_SELF), parallel(comm);
  serial.reinit(type, l_c, 0.1);
  parallel.reinit(type, l_c, 0.1);
  const double skin = parallel.skin_distance();

  for (unsigned int step = 0; step < 3; ++step)
    {
      if (step > 0)
        // Step 1 moves by at most 0.4 skin (< skin/2: reuse), step 2 by up
        // to 3 skin (rebuild), with points crossing into other slabs.
        for (std::size_t i = 0; i < all.size(); ++i)
          for (unsigned int d = 0; d < dim; ++d)
            all.positions[i][d] += (step == 1 ? 0.4 : 3.) * skin /
                                   std::sqrt(dim) * std::sin(1.1 * i + 2. * d);
      set_values(step);

      const std::vector<double> reference =
        all.average(serial, cube<dim>(-0.1, 1.1));

      PointSet<dim> local;
      for (const auto i : mine)
        {
          local.push_back(all.positions[i],
                          all.volumes[i],
                          all.values[i],
                          all.receivers[i],
                          all.ids[i]);
          if (exclude)
            local.sources.push_back(all.sources[i]);
        }
      const std::vector<double> ybar = local.average(parallel, my_boxes);

      // Each receiver sums its neighbours in the order of their ids on any
      // number of ranks, so the results should even be bit-identical; the
      // requirement is round-off, relative 1e-12.
      double max_difference = 0.;
      for (std::size_t k = 0; k < mine.size(); ++k)
        max_difference = std::max(max_difference,
                                  std::abs(ybar[k] - reference[mine[k]]) /
                                    std::max(1., std::abs(reference[mine[k]])));
      max_difference = Utilities::MPI::max(max_difference, comm);
      const std::size_t n_ghosts =
        Utilities::MPI::sum(parallel.n_ghost_points(), comm);
      if (rank == 0)
        std::cout << dim << "D " << to_string(type)
                  << (exclude ? " every fifth left out" : "") << " step "
                  << step << " on " << n_ranks << " ranks: " << n_ghosts
                  << " ghosts, rebuilds " << parallel.n_rebuilds()
                  << ", reuses " << parallel.n_reuses()
                  << ", max relative difference to serial " << max_difference
                  << std::endl;
      const std::string name = std::to_string(dim) + "D " + to_string(type) +
                               (exclude ? " excluding" : "") + " step " +
                               std::to_string(step);
      if (exclude && step == 0)
        {
          // The flag must matter: the same points all kept differ.
          NonlocalAverager<dim> all_kept(MPI_COMM_SELF);
          all_kept.reinit(type, l_c, 0.1);
          PointSet<dim> kept = all;
          kept.sources.clear();
          const std::vector<double> other =
            kept.average(all_kept, cube<dim>(-0.1, 1.1));
          double change = 0.;
          for (std::size_t i = 0; i < all.size(); ++i)
            change = std::max(change, std::abs(other[i] - reference[i]));
          check(change > 1e-3, name + ": leaving points out changes Ybar");
        }
      check(max_difference <= 1e-12, name + ": parallel == serial");
      check(n_ranks == 1 || n_ghosts > 0, name + ": ghosts were exchanged");
      check(parallel.n_rebuilds() == (step < 2 ? 1u : 2u),
            name + ": number of rebuilds");
      check(parallel.n_reuses() == (step < 1 ? 0u : 1u),
            name + ": number of reuses");
    }
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  for (const bool exclude : {false, true})
    {
      run<2>(WeightType::bell, exclude);
      run<2>(WeightType::gaussian, exclude);
      run<3>(WeightType::bell, exclude);
      run<3>(WeightType::gaussian, exclude);
    }
  return Utilities::MPI::max(n_failures, MPI_COMM_WORLD) == 0 ? 0 : 1;
}
