// Four points whose averages are computed by hand (verification item 12,
// a configuration small enough to check every term):
//
//   p0 = (0, 0), p1 = (0.5, 0), p2 = (0, 0.8), p3 = (5, 5)
//   V  = 1, 2, 0.5, 1;  Y = 1, 4, 10, 7;  p2 is not a receiver.
//
// Bell with l_c = 1/sqrt(7), so R = 1: w(r) = (1 - r^2)^2,
//   w01 = 0.75^2 = 0.5625, w02 = 0.36^2 = 0.1296,
//   w12 = (1 - 0.89)^2 = 0.0121, p3 is farther than R from all others.
//   Ybar0 = (1 + 0.5625*2*4 + 0.1296*0.5*10) / (1 + 0.5625*2 + 0.1296*0.5)
//         = 6.148 / 2.1898
//   Ybar1 = (0.5625*1 + 2*4 + 0.0121*0.5*10) / (0.5625 + 2 + 0.0121*0.5)
//         = 8.623 / 2.56855
//   Ybar2 = Y2 = 10 (not a receiver; still a source for p0 and p1)
//   Ybar3 = Y3 = 7 (alone)
// Gaussian with l_c = 0.5 (cut at 1.5): w = exp(-2 r^2),
//   w01 = e^-0.5, w02 = e^-1.28, w12 = e^-1.78, p3 again alone.
//
// The same points in 3D, in the x-z plane, give the same numbers.
//
// Fully damaged points left out of both sums (the authors' variant): p2
// becomes a fully damaged point, Y2 = 0 (as the chalk model writes it) and
// no source; p3 is no source either (a receiver without any source
// neighbour keeps its own value):
//   bell      Ybar0 = (1 + 0.5625*2*4) / (1 + 0.5625*2) = 5.5 / 2.125
//             Ybar1 = (0.5625*1 + 2*4) / (0.5625 + 2)   = 8.5625 / 2.5625
//   kept in the denominator with Y2 = 0 instead (today's default):
//             Ybar0 = 5.5 / 2.1898, Ybar1 = 8.5625 / 2.56855
//   gaussian  Ybar0 = (1 + w01*2*4) / (1 + w01*2), Ybar1 = (w01 + 8)/(w01 + 2)

#include <deal.II/base/mpi.h>

#include "test_tools.h"

using namespace scarp_test;

template <int dim>
void
run()
{
  PointSet<dim> points;
  Point<dim>    x0, x1, x2, x3;
  x1[0]       = 0.5;
  x2[dim - 1] = 0.8; // y in 2D, z in 3D
  x3[0]       = 5.;
  x3[1]       = 5.;
  points.push_back(x0, 1., 1., true, 10);
  points.push_back(x1, 2., 4., true, 11);
  points.push_back(x2, 0.5, 10., false, 12);
  points.push_back(x3, 1., 7., true, 13);
  const auto boxes = cube<dim>(-1., 6.);

  // The inputs are exact decimals, the weights involve l_c = 1/sqrt(7)
  // (R = 1 up to an ulp) or exp(): the computed results agree with the hand
  // values to a few ulps; 1e-14 allows for that and nothing more.
  const double tol = 1e-14;

  NonlocalAverager<dim> averager(MPI_COMM_SELF);
  averager.reinit(WeightType::bell, 1. / std::sqrt(7.), 0.1);
  std::vector<double> ybar = points.average(averager, boxes);
  const std::string   name = std::to_string(dim) + "D bell ";
  check(close(ybar[0], 6.148 / 2.1898, tol), name + "Ybar0");
  check(close(ybar[1], 8.623 / 2.56855, tol), name + "Ybar1");
  check(ybar[2] == 10., name + "non-receiver keeps Y");
  check(ybar[3] == 7., name + "isolated point keeps Y");
  std::cout << name << ybar[0] << ' ' << ybar[1] << ' ' << ybar[2] << ' '
            << ybar[3] << std::endl;

  averager.reinit(WeightType::gaussian, 0.5, 0.1);
  ybar             = points.average(averager, boxes);
  const double w01 = std::exp(-0.5), w02 = std::exp(-1.28),
               w12 = std::exp(-1.78);
  const double g0 =
    (1. + w01 * 2. * 4. + w02 * 0.5 * 10.) / (1. + w01 * 2. + w02 * 0.5);
  const double g1 =
    (w01 * 1. + 2. * 4. + w12 * 0.5 * 10.) / (w01 * 1. + 2. + w12 * 0.5);
  const std::string gname = std::to_string(dim) + "D gaussian ";
  check(close(ybar[0], g0, tol), gname + "Ybar0");
  check(close(ybar[1], g1, tol), gname + "Ybar1");
  check(ybar[2] == 10., gname + "non-receiver keeps Y");
  check(ybar[3] == 7., gname + "isolated point keeps Y");
  std::cout << gname << ybar[0] << ' ' << ybar[1] << ' ' << ybar[2] << ' '
            << ybar[3] << std::endl;

  // Fully damaged p2 (Y = 0), kept or left out of the sums.
  PointSet<dim> damaged = points;
  damaged.values[2]     = 0.;
  averager.reinit(WeightType::bell, 1. / std::sqrt(7.), 0.1);
  ybar                    = damaged.average(averager, boxes);
  const std::string xname = std::to_string(dim) + "D bell, d = 1 kept ";
  check(close(ybar[0], 5.5 / 2.1898, tol), xname + "Ybar0");
  check(close(ybar[1], 8.5625 / 2.56855, tol), xname + "Ybar1");
  damaged.sources         = {true, true, false, false};
  ybar                    = damaged.average(averager, boxes);
  const std::string ename = std::to_string(dim) + "D bell, d = 1 left out ";
  check(close(ybar[0], 5.5 / 2.125, tol), ename + "Ybar0");
  check(close(ybar[1], 8.5625 / 2.5625, tol), ename + "Ybar1");
  check(ybar[2] == 0., ename + "non-receiver keeps Y");
  check(ybar[3] == 7., ename + "receiver without sources keeps Y");
  std::cout << ename << ybar[0] << ' ' << ybar[1] << std::endl;
  averager.reinit(WeightType::gaussian, 0.5, 0.1);
  ybar = damaged.average(averager, boxes);
  check(close(ybar[0], (1. + w01 * 8.) / (1. + w01 * 2.), tol),
        gname + "d = 1 left out Ybar0");
  check(close(ybar[1], (w01 + 8.) / (w01 + 2.), tol),
        gname + "d = 1 left out Ybar1");
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  run<2>();
  run<3>();
  return n_failures == 0 ? 0 : 1;
}
