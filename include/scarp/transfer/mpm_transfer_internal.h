#ifndef scarp_transfer_mpm_transfer_internal_h
#define scarp_transfer_mpm_transfer_internal_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <chrono>
#include <cmath>
#include <vector>

namespace scarp
{
  namespace transfer
  {
    using namespace dealii;

    /**
     * @brief Small helpers shared by the mpm_transfer*.cc files (the parts
     * of MpmTransfer: occupied cells, P2G, grid update, G2P); not part of
     * scarp's interface.
     *
     * Each is declared inline: as templates of one translation unit in an
     * anonymous namespace GCC inlined them into the hot loops, as shared
     * templates without the keyword it called stress_times() out of line
     * per point and node (P2G 20 % slower on the 1e6-point column).
     */
    namespace internal
    {
      using Clock = std::chrono::steady_clock;

      /// How many points ahead the sweeps prefetch a point's properties.
      constexpr std::size_t prefetch_distance = 4;

      /// Seconds since @p start.
      inline double
      seconds_since(const Clock::time_point &start)
      {
        return std::chrono::duration<double>(Clock::now() - start).count();
      }

      /// Write the 3x3 embedding of a dim x dim tensor into @p b (plane
      /// strain: zz = 1), entry by entry: a temporary returned by value was
      /// built on the stack in overlapping pieces and read back whole, a
      /// failed store-to-load forwarding per tensor (perf: a tenth of the
      /// samples of grid_to_particles in the main job).
      template <int dim>
      inline void
      embed_into(Tensor<2, 3> &b, const Tensor<2, dim> &a, const double zz)
      {
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            b[i][j] = (i < dim && j < dim) ? a[i % dim][j % dim]
                      : (i == j)           ? zz
                                           : 0.;
      }

      /// Ask for the property record of the point @p ahead places on in
      /// the sweep's order while this one is worked on: a record spans
      /// three cache lines, and the sweeps read every point's from memory.
      inline void
      prefetch_record(const std::vector<double *> &records,
                      const std::size_t            ahead,
                      const unsigned int           n_doubles)
      {
        if (ahead < records.size())
          for (unsigned int i = 0; i < n_doubles; i += 8)
            __builtin_prefetch(records[ahead] + i, 1, 3);
      }

      /// sigma : e for e with zero entries out of the dim x dim block: the
      /// sum of scalar_product() of the embedded e, in its order, without
      /// its zero terms (the same number).
      template <int dim>
      inline double
      stress_power(const SymmetricTensor<2, 3> &sigma, const Tensor<2, dim> &e)
      {
        double s = 0.;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            s += sigma[i][j] * e[i][j];
        return s;
      }

      template <int dim>
      inline Tensor<1, dim>
      stress_times(const SymmetricTensor<2, 3> &s, const Tensor<1, dim> &g)
      {
        Tensor<1, dim> r;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            r[i] += s[i][j] * g[j];
        return r;
      }

      /// GIMP: half-widths of a point's domain from its reference volume,
      /// V0 = (2 l)^dim (the seeding lattice gives l = h / (2 n)), at most
      /// h/2 (the patch holds nodes up to h + l <= 3h/2 away), and clipped
      /// to the mesh box: a domain never reaches past the boundary, so
      /// that at the boundary the weights become those of Q1 and a point
      /// next to a fixed face does not keep moving through it.
      template <int dim>
      inline void
      gimp_half_width(const double            V0,
                      const double            h,
                      const Point<dim>       &x,
                      const BoundingBox<dim> &box,
                      double (&l)[dim])
      {
        const double side = dim == 2 ? std::sqrt(V0) : std::cbrt(V0);
        const double l0   = std::min(0.5 * side, 0.5 * h);
        for (unsigned int d = 0; d < dim; ++d)
          l[d] = std::max(0.,
                          std::min({l0,
                                    x[d] - box.lower_bound(d),
                                    box.upper_bound(d) - x[d]}));
      }

      using Vector = LinearAlgebra::distributed::Vector<double>;

      /// compress(add) of several vectors with one round of messages: all
      /// sends start before the first wait (each on its own channel, < 100).
      /// Its wall time, the waits for the other ranks included, is added to
      /// @p seconds.
      inline void
      compress_add(const std::vector<Vector *> &vectors, double &seconds)
      {
        const auto start = Clock::now();
        for (unsigned int c = 0; c < vectors.size(); ++c)
          vectors[c]->compress_start(c, VectorOperation::add);
        for (Vector *v : vectors)
          v->compress_finish(VectorOperation::add);
        seconds += seconds_since(start);
      }

      /// update_ghost_values() of several vectors with one round of
      /// messages; its wall time is added to @p seconds.
      inline void
      update_ghosts(const std::vector<Vector *> &vectors, double &seconds)
      {
        const auto start = Clock::now();
        for (unsigned int c = 0; c < vectors.size(); ++c)
          vectors[c]->update_ghost_values_start(c);
        for (Vector *v : vectors)
          v->update_ghost_values_finish();
        seconds += seconds_since(start);
      }
    } // namespace internal
  }   // namespace transfer
} // namespace scarp

#endif
