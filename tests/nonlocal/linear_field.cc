// Verification item 12, second half: the average of a linear field
// Y = a + b.x is exact at points farther than the cut-off radius from the
// boundary of a uniform lattice (there the stencil is symmetric and
// sum_q w V (x_q - x_p) = 0), and is not exact next to the boundary (which
// shows that the test can fail).

#include <deal.II/base/mpi.h>

#include "test_tools.h"

using namespace scarp_test;

template <int dim>
void
run(const WeightType type)
{
  // h = 0.125 is a power of two: lattice positions, and thus the symmetry
  // of each interior stencil, are exact in floating point.
  const double       h   = 0.125;
  const unsigned int n   = dim == 2 ? 24 : 12;
  const double       l_c = 0.18; // the chalk value: R = 0.476, 3 l_c = 0.54
  const double       a   = 1.;
  Tensor<1, dim>     b;
  for (unsigned int d = 0; d < dim; ++d)
    b[d] = 0.3 - 0.25 * d;

  PointSet<dim> points = make_lattice<dim>(n, h);
  double        y_max  = 0.;
  for (std::size_t i = 0; i < points.size(); ++i)
    {
      points.values[i] = a + b * points.positions[i];
      y_max            = std::max(y_max, std::abs(points.values[i]));
    }

  NonlocalAverager<dim> averager(MPI_COMM_SELF);
  averager.reinit(type, l_c, 0.1);
  const auto   ybar   = points.average(averager, cube<dim>(0., (n - 1) * h));
  const double R      = averager.cutoff_radius();
  const double length = (n - 1) * h;

  // Interior points: the weighted sums have k < 400 terms of size up to
  // max|Y|, so their rounding error is below k eps max|Y| ~ 1e-13 max|Y|;
  // the symmetric stencil makes the exact result Y_p. 1e-12 max|Y| is
  // 1e9 times smaller than the boundary bias checked below.
  double       max_error      = 0.;
  double       boundary_error = 0.;
  unsigned int n_interior     = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    {
      bool interior = true;
      for (unsigned int d = 0; d < dim; ++d)
        interior = interior && points.positions[i][d] > R &&
                   points.positions[i][d] < length - R;
      const double error = std::abs(ybar[i] - points.values[i]);
      if (interior)
        {
          max_error = std::max(max_error, error);
          ++n_interior;
        }
      else
        boundary_error = std::max(boundary_error, error);
    }
  std::cout << dim << "D " << to_string(type) << ": " << n_interior
            << " interior points, max error " << max_error
            << "; max error near the boundary " << boundary_error << std::endl;
  check(n_interior > 0, "there are interior points");
  check(max_error <= 1e-12 * y_max,
        std::to_string(dim) + "D " + to_string(type) + " linear field");
  // At a corner the stencil is one-sided: the average is biased inwards by
  // a fraction of R |b|, far above round-off.
  check(boundary_error > 1e-2,
        std::to_string(dim) + "D " + to_string(type) + " boundary bias");
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  run<2>(WeightType::bell);
  run<2>(WeightType::gaussian);
  run<3>(WeightType::bell);
  run<3>(WeightType::gaussian);
  return n_failures == 0 ? 0 : 1;
}
