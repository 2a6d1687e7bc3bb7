// The local weight: Ybar == Y exactly, no search and no communication. Run
// on 2 ranks that call compute() a different number of times, with no boxes:
// any collective call inside would hang or fail; the counters must stay 0.

#include <deal.II/base/mpi.h>

#include "test_tools.h"

using namespace scarp_test;

template <int dim>
void
run()
{
  const unsigned int rank   = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  PointSet<dim>      points = make_lattice<dim>(6, 0.1);
  for (std::size_t i = 0; i < points.size(); ++i)
    {
      points.values[i]    = std::sin(1. + i) * 1e3;
      points.receivers[i] = (i % 3 != 0);
    }

  NonlocalAverager<dim> averager(MPI_COMM_WORLD);
  // l_c plays no role for the local weight; 0 is accepted.
  averager.reinit(WeightType::local, 0., 0.1);
  const unsigned int n_calls = rank == 0 ? 3 : 1;
  for (unsigned int call = 0; call < n_calls; ++call)
    {
      for (auto &x : points.positions)
        x[0] += 0.05 * call;
      const std::vector<double> ybar = points.average(averager, {});
      check(ybar == points.values, "Ybar == Y bit for bit");
    }
  check(averager.n_communicating_calls() == 0, "no communication");
  check(averager.n_rebuilds() == 0 && averager.n_reuses() == 0,
        "no neighbour search");
  check(averager.n_ghost_points() == 0, "no ghosts");
  std::cout << "rank " << rank << ", " << dim << "D: " << n_calls
            << " local averages, " << averager.n_communicating_calls()
            << " communicating calls" << std::endl;
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  run<2>();
  run<3>();
  return n_failures == 0 ? 0 : 1;
}
