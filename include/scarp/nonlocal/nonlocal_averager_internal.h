#ifndef scarp_nonlocal_nonlocal_averager_internal_h
#define scarp_nonlocal_nonlocal_averager_internal_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/point.h>

#include <algorithm>

namespace scarp
{
  namespace nonlocal
  {
    using namespace dealii;

    /**
     * @brief Small helpers shared by the nonlocal_*.cc files (the steps of
     * NonlocalAverager: exchange, neighbour lists, sums); not part of
     * scarp's interface. Declared inline, so that the loops that call
     * them keep them inlined (doc/performance/exchange_and_ranks.md, "The
     * parts of the MPM step rank by rank; MpmTransfer in files by part").
     */
    namespace internal
    {
      // Tags of our own messages; the communicator is a private duplicate.
      constexpr int tag_ids  = 4101;
      constexpr int tag_data = 4102;

      // Doubles sent per ghost and call: position, volume, value.
      template <int dim>
      constexpr unsigned int doubles_per_ghost = dim + 2;

      template <int dim>
      inline double
      squared_distance(const Point<dim> &a, const Point<dim> &b)
      {
        double r2 = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double dx = a[d] - b[d];
            r2 += dx * dx;
          }
        return r2;
      }

      // Squared distance from a point to a box (0 inside).
      template <int dim>
      inline double
      squared_distance(const Point<dim> &p, const BoundingBox<dim> &box)
      {
        const auto &lo = box.get_boundary_points().first;
        const auto &hi = box.get_boundary_points().second;
        double      r2 = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double dx = std::max({0., lo[d] - p[d], p[d] - hi[d]});
            r2 += dx * dx;
          }
        return r2;
      }

      // Squared distance between two boxes (0 if they overlap).
      template <int dim>
      inline double
      squared_distance(const BoundingBox<dim> &a, const BoundingBox<dim> &b)
      {
        double r2 = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double dx = std::max({0.,
                                        b.get_boundary_points().first[d] -
                                          a.get_boundary_points().second[d],
                                        a.get_boundary_points().first[d] -
                                          b.get_boundary_points().second[d]});
            r2 += dx * dx;
          }
        return r2;
      }

      inline void
      check_mpi(const int ierr)
      {
        AssertThrowMPI(ierr);
        (void)ierr;
      }
    } // namespace internal
  }   // namespace nonlocal
} // namespace scarp

#endif
