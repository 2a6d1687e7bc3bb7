// Verification item 12, first half: the average of a constant field is that
// constant at every point, including points at the free boundary (edges and
// corners of a block of points), because the weights are renormalised.
// Volumes vary from point to point so that the renormalisation, not a
// symmetry, is what is tested.

#include <deal.II/base/mpi.h>

#include "test_tools.h"

using namespace scarp_test;

template <int dim>
void
run(const WeightType type, const unsigned int n)
{
  const double h   = 0.1;
  const double l_c = 0.1; // R = 0.26 (bell), 0.3 (Gaussian): 2-3 spacings
  const double c   = 3.7;

  PointSet<dim> points = make_lattice<dim>(n, h);
  for (std::size_t i = 0; i < points.size(); ++i)
    {
      points.volumes[i] *= 1. + 0.5 * std::sin(1.3 * i);
      points.values[i] = c;
    }

  NonlocalAverager<dim> averager(MPI_COMM_SELF);
  averager.reinit(type, l_c, 0.1);
  const auto ybar = points.average(averager, cube<dim>(0., (n - 1) * h));

  // Numerator and denominator are sums of k terms (k < 120 neighbours here)
  // that differ only by the factor c, each with a relative rounding error
  // below (k + 2) eps; their quotient is c to within about 2 (k + 2) eps
  // = 2.7e-14. 1e-13 leaves a margin and is still 1e10 times smaller than
  // the error of a missing renormalisation at a corner.
  double max_error = 0.;
  for (std::size_t i = 0; i < points.size(); ++i)
    max_error = std::max(max_error, std::abs(ybar[i] - c) / c);
  std::cout << dim << "D " << to_string(type) << ", " << points.size()
            << " points, " << averager.n_interacting_pairs() / points.size()
            << " neighbours per point: max relative error " << max_error
            << std::endl;
  check(max_error <= 1e-13,
        std::to_string(dim) + "D " + to_string(type) + " constant field");
  check(averager.n_ghost_points() == 0, "no ghosts on one rank");
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  run<2>(WeightType::bell, 20);
  run<2>(WeightType::gaussian, 20);
  run<3>(WeightType::bell, 9);
  run<3>(WeightType::gaussian, 9);
  return n_failures == 0 ? 0 : 1;
}
