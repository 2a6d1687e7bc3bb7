#ifndef scarp_tests_nonlocal_test_tools_h
#define scarp_tests_nonlocal_test_tools_h

// Small helpers shared by the tests of the non-local average: a lattice of
// points, a failure counter, and the straightforward computation of the
// average that the fast one in the library is measured against.

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/point.h>

#include <scarp/nonlocal/nonlocal_averager.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
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

  /// The lattice of the parallel tests: make_lattice() with volumes varied
  /// by up to 30 %, every seventh point no receiver and, with @p exclude,
  /// every fifth point left out of the sums.
  template <int dim>
  PointSet<dim>
  make_varied_lattice(const unsigned int n, const double h, const bool exclude)
  {
    PointSet<dim> points = make_lattice<dim>(n, h);
    for (std::size_t i = 0; i < points.size(); ++i)
      {
        points.volumes[i] *= 1. + 0.3 * std::sin(0.7 * i);
        points.receivers[i] = (i % 7 != 3);
      }
    if (exclude)
      {
        points.sources.resize(points.size());
        for (std::size_t i = 0; i < points.size(); ++i)
          points.sources[i] = (i % 5 != 1);
      }
    return points;
  }

  /**
   * The straightforward non-local average, as NonlocalAverager computed it
   * before its sums were grouped (doc/nonlocal.md, "Speed"): for each
   * receiver, a list of the sources within @p reach (cut-off + skin; with
   * an infinite reach, all sources: brute force), sorted by id, and the sum
   * over that list one term at a time, the weight dispatched once per call.
   * Serial: every point of the PointSet given is a source; receivers may be
   * restricted to a subset (@p own, e.g. one rank's points).
   */
  template <int dim>
  class ReferenceAverage
  {
  public:
    ReferenceAverage(const WeightFunction &weight, const double reach)
      : weight(weight)
      , reach(reach)
    {
    }

    /// Lists for the receivers among @p own (all points if empty).
    void
    build(const PointSet<dim>             &points,
          const std::vector<unsigned int> &own = {})
    {
      const std::size_t n = points.size();
      receivers           = own;
      if (receivers.empty())
        for (unsigned int i = 0; i < n; ++i)
          receivers.push_back(i);
      lists.assign(receivers.size(), {});
      if (!std::isfinite(reach))
        {
          std::vector<unsigned int> all(n);
          for (unsigned int i = 0; i < n; ++i)
            all[i] = i;
          sort_by_id(all, points);
          for (std::size_t r = 0; r < receivers.size(); ++r)
            if (points.receivers[receivers[r]])
              lists[r] = all;
          return;
        }
      // Bins of size reach: the neighbours are in the 3^dim around a point.
      std::map<std::array<long, dim>, std::vector<unsigned int>> bins;
      const auto bin = [this](const Point<dim> &x) {
        std::array<long, dim> c;
        for (unsigned int d = 0; d < dim; ++d)
          c[d] = static_cast<long>(std::floor(x[d] / reach));
        return c;
      };
      for (unsigned int q = 0; q < n; ++q)
        bins[bin(points.positions[q])].push_back(q);
      for (std::size_t r = 0; r < receivers.size(); ++r)
        {
          const unsigned int p = receivers[r];
          if (!points.receivers[p])
            continue;
          const auto            c = bin(points.positions[p]);
          std::array<long, dim> k;
          for (unsigned int b = 0; b < std::pow(3, dim); ++b)
            {
              for (unsigned int d = 0, m = b; d < dim; ++d, m /= 3)
                k[d] = c[d] + long(m % 3) - 1;
              const auto it = bins.find(k);
              if (it != bins.end())
                for (const unsigned int q : it->second)
                  if (points.positions[p].distance_square(
                        points.positions[q]) <= reach * reach)
                    lists[r].push_back(q);
            }
          sort_by_id(lists[r], points);
        }
    }

    /// Ybar of the receivers of build() (Y for non-receivers), in the
    /// order of @p own, for the current positions, volumes and values.
    std::vector<double>
    average(const PointSet<dim> &points)
    {
      const std::size_t n = points.size();
      volumes.resize(n);
      weighted_values.resize(n);
      for (std::size_t q = 0; q < n; ++q)
        {
          volumes[q]         = (points.sources.empty() || points.sources[q])
                                 ? points.volumes[q]
                                 : 0.;
          weighted_values[q] = volumes[q] * points.values[q];
        }
      if (weight.type() == WeightType::bell)
        return sums(points,
                    [this](const double r2) { return weight.bell(r2); });
      return sums(points,
                  [this](const double r2) { return weight.gaussian(r2); });
    }

    /// Entries of the lists.
    std::size_t
    n_listed_pairs() const
    {
      std::size_t n = 0;
      for (const auto &list : lists)
        n += list.size();
      return n;
    }

  private:
    static void
    sort_by_id(std::vector<unsigned int> &list, const PointSet<dim> &points)
    {
      std::sort(list.begin(),
                list.end(),
                [&points](const unsigned int a, const unsigned int b) {
                  return points.ids[a] < points.ids[b];
                });
    }

    template <typename Weight>
    std::vector<double>
    sums(const PointSet<dim> &points, const Weight &w) const
    {
      std::vector<double> result(receivers.size());
      for (std::size_t r = 0; r < receivers.size(); ++r)
        {
          const unsigned int p = receivers[r];
          if (!points.receivers[p])
            {
              result[r] = points.values[p];
              continue;
            }
          const Point<dim> xp          = points.positions[p];
          double           numerator   = 0.;
          double           denominator = 0.;
          for (const unsigned int q : lists[r])
            {
              const double wq = w(xp.distance_square(points.positions[q]));
              numerator += wq * weighted_values[q];
              denominator += wq * volumes[q];
            }
          result[r] =
            denominator > 0. ? numerator / denominator : points.values[p];
        }
      return result;
    }

    WeightFunction                         weight;
    double                                 reach;
    std::vector<unsigned int>              receivers;
    std::vector<std::vector<unsigned int>> lists;
    std::vector<double>                    volumes, weighted_values;
  };

  /// max_i |a_i - b_i| / max(|b_i|, 1).
  inline double
  max_relative_difference(const std::vector<double> &a,
                          const std::vector<double> &b)
  {
    double difference = 0.;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
      difference =
        std::max(difference,
                 std::abs(a[i] - b[i]) / std::max(1., std::abs(b[i])));
    return difference;
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
