// The fast path of NonlocalAverager (grouped SIMD sums, doc/nonlocal.md
// "Speed") against the straightforward computation of test_tools.h
// (ReferenceAverage, brute force over all points in id order) on a random
// cloud with about 200 neighbours per point, 2D and 3D, bell and Gaussian,
// both compute() overloads (every point a source; every sixth point left out
// of the sums), some points no receiver, ids shuffled. Four calls: a build,
// a reuse after moves below skin/2 with new values, the same points in
// another order (reordering), and a rebuild after larger moves.
//
// Tolerance: each receiver adds the same products in the same (id) order in
// both; the extra sources of its group, and the points beyond the cut-off in
// the brute-force sum, have weight exactly 0 and add +-0, which changes no
// sum. So the averages should be bit-identical (measured: 0), unless a
// compiler contracts a product and a sum into a fused multiply-add in one of
// the two: that changes each of the ~200 terms by at most one rounding,
// 200 * 1.1e-16 ~ 2e-14 relative to the sum of |terms|, which for the fields
// below (|Y| within a factor ~10 of its average) stays far below the 1e-12
// that issue 10 allows for a change of the non-local average.

#include <deal.II/base/mpi.h>

#include "test_tools.h"

#include <random>

using namespace scarp_test;

template <int dim>
void
run(const WeightType type, const bool exclude)
{
  // R = sqrt(7) l_c (bell) or 3 l_c (Gaussian); density for ~200 points
  // within the cut-off radius on average (more inside, fewer at the faces).
  const double       l_c    = 1.;
  const unsigned int n      = 3000;
  const double       inside = dim == 2 ? 230. : 290.;
  const double       R      = (type == WeightType::bell ? std::sqrt(7.) : 3.);
  const double ball = dim == 2 ? M_PI * R * R : 4. / 3. * M_PI * R * R * R;
  const double side = std::pow(n * ball / inside, 1. / dim);
  std::mt19937 random(dim * 10 + (type == WeightType::bell) + 2 * exclude);
  std::uniform_real_distribution<double> uniform(0., 1.);

  PointSet<dim>                      points;
  std::vector<types::particle_index> ids(n);
  for (unsigned int i = 0; i < n; ++i)
    ids[i] = 7 * i + 3;
  std::shuffle(ids.begin(), ids.end(), random);
  for (unsigned int i = 0; i < n; ++i)
    {
      Point<dim> x;
      for (unsigned int d = 0; d < dim; ++d)
        x[d] = side * uniform(random);
      points.push_back(x,
                       0.5 + uniform(random),
                       0.,
                       i % 9 != 4, // some points are no receiver
                       ids[i]);
      if (exclude)
        points.sources.push_back(i % 6 != 1);
    }

  NonlocalAverager<dim> averager(MPI_COMM_SELF);
  averager.reinit(type, l_c, 0.1);
  const double          skin = averager.skin_distance();
  ReferenceAverage<dim> reference(averager.get_weight_function(),
                                  std::numeric_limits<double>::infinity());
  const auto            boxes = cube<dim>(-side, 2. * side);

  const std::string name = std::to_string(dim) + "D " + to_string(type) +
                           (exclude ? ", every sixth left out" : "");
  for (unsigned int step = 0; step < 4; ++step)
    {
      if (step == 1 || step == 3)
        // Below skin/2 (reuse), then up to 2 skin (rebuild).
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int d = 0; d < dim; ++d)
            points.positions[i][d] += (step == 1 ? 0.45 : 2.) * skin /
                                      std::sqrt(dim) *
                                      (2. * uniform(random) - 1.);
      if (step == 2)
        {
          // The same points in another order.
          PointSet<dim>             shuffled;
          std::vector<unsigned int> order(n);
          for (unsigned int i = 0; i < n; ++i)
            order[i] = i;
          std::shuffle(order.begin(), order.end(), random);
          for (const unsigned int i : order)
            {
              shuffled.push_back(points.positions[i],
                                 points.volumes[i],
                                 points.values[i],
                                 points.receivers[i],
                                 points.ids[i]);
              if (exclude)
                shuffled.sources.push_back(points.sources[i]);
            }
          points = shuffled;
        }
      for (unsigned int i = 0; i < n; ++i)
        {
          const auto &x = points.positions[i];
          points.values[i] =
            1. + std::sin(0.7 * x[0] + step) * std::cos(0.5 * x[dim - 1]) +
            0.1 * uniform(random);
          if (exclude && !points.sources[i])
            points.values[i] = 0.; // fully damaged: Y = 0
        }

      const auto ybar = points.average(averager, boxes);
      reference.build(points);
      const auto   expected   = reference.average(points);
      const double difference = max_relative_difference(ybar, expected);
      std::size_t  n_differ   = 0;
      for (unsigned int i = 0; i < n; ++i)
        n_differ += (ybar[i] != expected[i]);
      const double per_point =
        double(averager.n_interacting_pairs()) /
        std::count(points.receivers.begin(), points.receivers.end(), true);
      std::cout << name << ", call " << step << ": " << per_point
                << " neighbours per receiver, rebuilds "
                << averager.n_rebuilds() << ", reuses " << averager.n_reuses()
                << ", reorders " << averager.n_reorders()
                << ", max relative difference " << difference << " ("
                << n_differ << " of " << n << " not bit-identical)"
                << std::endl;
      check(difference <= 1e-12,
            name + ", call " + std::to_string(step) + ": fast == reference");
      check(per_point > 180. && per_point < 220.,
            name + ": about 200 neighbours per point");
    }
  check(averager.n_rebuilds() == 2 && averager.n_reuses() == 2 &&
          averager.n_reorders() == 2,
        name + ": rebuilds, reuses and reorders as planned");
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
  return n_failures == 0 ? 0 : 1;
}
