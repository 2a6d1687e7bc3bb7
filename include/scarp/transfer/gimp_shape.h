#ifndef scarp_transfer_gimp_shape_h
#define scarp_transfer_gimp_shape_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <cmath>

namespace scarp
{
  namespace transfer
  {
    using namespace dealii;

    /**
     * @brief Uniform GIMP weights (Bardenhagen & Kober 2004): the Q1 hat
     * functions of a uniform grid of spacing h convolved with the
     * characteristic function of the particle domain, a box of half-width
     * l <= h/2 per direction (kept constant: "uniform" GIMP).
     *
     * A point in cell K (reference coordinate xi in [0,1]^dim) touches
     * nodes up to a distance h + l <= 3h/2, i.e. the patch of 4 nodes per
     * direction at offsets -1, 0, 1, 2 cells from the lower vertex of K (at
     * most 3 of them are non-zero). Node i of the patch has the offsets
     * offset(i, d) = (i / 4^d) % 4 - 1.
     *
     * Weights and gradients are C^1 in the point position: a point crossing
     * a cell face sees no jump in grad S, which removes the cell-crossing
     * noise of Q1. For l -> 0 the weights become those of Q1.
     */
    template <int dim>
    struct GimpShape
    {
      static constexpr unsigned int n_1d = 4;
      static constexpr unsigned int n = dim == 1 ? 4u : (dim == 2 ? 16u : 64u);
      double                        value[n];
      Tensor<1, dim>                gradient[n];

      /// Offset in cells of patch node @p i from the lower vertex of the
      /// cell, in direction @p d.
      static int
      offset(const unsigned int i, const unsigned int d)
      {
        unsigned int k = i;
        for (unsigned int e = 0; e < d; ++e)
          k /= n_1d;
        return static_cast<int>(k % n_1d) - 1;
      }

      /// The 1D weight S(r) and its derivative dS/dx_p for a point at
      /// signed distance r = x_p - x_i from the node.
      static void
      weight_1d(const double r,
                const double h,
                const double l,
                double      &s,
                double      &ds)
      {
        const double a    = std::abs(r);
        const double sign = r < 0 ? -1. : 1.;
        if (a >= h + l)
          {
            s  = 0;
            ds = 0;
          }
        else if (a >= h - l)
          {
            const double b = h + l - a;
            s              = b * b / (4. * h * l);
            ds             = -sign * b / (2. * h * l);
          }
        else if (a >= l)
          {
            s  = 1. - a / h;
            ds = -sign / h;
          }
        else
          {
            s  = 1. - (r * r + l * l) / (2. * h * l);
            ds = -r / (h * l);
          }
      }

      /// Evaluate at the reference point @p xi of a cell of edge @p h for a
      /// particle domain of half-width @p l (0 <= l <= h/2).
      void
      evaluate(const Point<dim> &xi, const double h, const double l)
      {
        double ld[dim];
        for (unsigned int d = 0; d < dim; ++d)
          ld[d] = l;
        evaluate(xi, h, ld);
      }

      /// The same with a half-width per direction (l[d] = 0 gives the Q1
      /// weights in that direction).
      void
      evaluate(const Point<dim> &xi, const double h, const double (&l)[dim])
      {
        double f[dim][n_1d], df[dim][n_1d];
        for (unsigned int d = 0; d < dim; ++d)
          for (unsigned int a = 0; a < n_1d; ++a)
            weight_1d(h * (xi[d] - (static_cast<double>(a) - 1.)),
                      h,
                      l[d],
                      f[d][a],
                      df[d][a]);
        for (unsigned int i = 0; i < n; ++i)
          {
            unsigned int idx[dim];
            unsigned int k = i;
            for (unsigned int d = 0; d < dim; ++d)
              {
                idx[d] = k % n_1d;
                k /= n_1d;
              }
            double v = 1.;
            for (unsigned int d = 0; d < dim; ++d)
              v *= f[d][idx[d]];
            value[i] = v;
            for (unsigned int d = 0; d < dim; ++d)
              {
                double g = df[d][idx[d]];
                for (unsigned int e = 0; e < dim; ++e)
                  if (e != d)
                    g *= f[e][idx[e]];
                gradient[i][d] = g;
              }
          }
      }
    };
  } // namespace transfer
} // namespace scarp

#endif
