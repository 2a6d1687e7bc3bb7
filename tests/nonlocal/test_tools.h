#ifndef scarp_tests_nonlocal_test_tools_h
#define scarp_tests_nonlocal_test_tools_h

// Small helpers shared by the tests of the non-local average: a lattice of
// points and a failure counter.

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/point.h>

#include <scarp/nonlocal/nonlocal_averager.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace scarp_test
{
  using namespace dealii;
  using namespace scarp::nonlocal;

  inline unsigned int n_failures = 0;

  inline void
  check(const bool condition, const std::string &what)
  {
    if (!condition)
      {
        ++n_failures;
        std::cout << "FAILED: " << what << std::endl;
      }
  }

  /// |a - b| <= tol * max(|b|, floor): a relative check with an absolute
  /// floor for values near zero.
  inline bool
  close(const double a,
        const double b,
        const double tol,
        const double floor = 1.)
  {
    return std::abs(a - b) <= tol * std::max(std::abs(b), floor);
  }

  /// The per-point input of NonlocalAverager::compute().
  template <int dim>
  struct PointSet
  {
    std::vector<Point<dim>>            positions;
    std::vector<double>                volumes;
    std::vector<double>                values;
    std::vector<bool>                  receivers;
    std::vector<types::particle_index> ids;
    /// Empty: every point is a source; else one flag per point.
    std::vector<bool> sources;

    std::size_t
    size() const
    {
      return positions.size();
    }

    void
    push_back(const Point<dim>           &x,
              const double                V,
              const double                Y,
              const bool                  receiver,
              const types::particle_index id)
    {
      positions.push_back(x);
      volumes.push_back(V);
      values.push_back(Y);
      receivers.push_back(receiver);
      ids.push_back(id);
    }

    /// Run @p averager on these points and return the averages.
    std::vector<double>
    average(NonlocalAverager<dim>               &averager,
            const std::vector<BoundingBox<dim>> &boxes) const
    {
      std::vector<double> result;
      if (sources.empty())
        averager.compute(
          boxes, positions, volumes, values, receivers, ids, result);
      else
        averager.compute(
          boxes, positions, volumes, values, receivers, sources, ids, result);
      return result;
    }
  };

  /// Points x = origin + h (i_0, ..., i_dim-1), 0 <= i_d < n, with volume
  /// h^dim, value 0, all receivers, ids in lexicographic order.
  template <int dim>
  PointSet<dim>
  make_lattice(const unsigned int n, const double h)
  {
    PointSet<dim>                 points;
    std::array<unsigned int, dim> i{};
    types::particle_index         id = 0;
    while (true)
      {
        Point<dim> x;
        for (unsigned int d = 0; d < dim; ++d)
          x[d] = h * i[d];
        points.push_back(x, std::pow(h, dim), 0., true, id++);
        unsigned int d = 0;
        for (; d < dim; ++d)
          {
            if (++i[d] < n)
              break;
            i[d] = 0;
          }
        if (d == dim)
          break;
      }
    return points;
  }

  /// The box [lo, hi]^dim.
  template <int dim>
  std::vector<BoundingBox<dim>>
  cube(const double lo, const double hi)
  {
    Point<dim> a, b;
    for (unsigned int d = 0; d < dim; ++d)
      {
        a[d] = lo;
        b[d] = hi;
      }
    return {BoundingBox<dim>(std::make_pair(a, b))};
  }
} // namespace scarp_test

#endif
