#ifndef scarp_transfer_q1_shape_h
#define scarp_transfer_q1_shape_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

namespace scarp
{
  namespace transfer
  {
    using namespace dealii;

    /**
     * @brief Values and gradients of the FE_Q(1) shape functions of an
     * axis-aligned square (cubic) cell at one reference point, in deal.II's
     * vertex (= dof) order.
     *
     * This is exactly what FE_Q<dim>(1) with MappingCartesian computes
     * (a test checks it against them), written out so the per-particle work
     * in the hot loops is a few multiplications.
     */
    template <int dim>
    struct Q1Shape
    {
      static constexpr unsigned int n = 1u << dim;
      double                        value[n];
      Tensor<1, dim>                gradient[n];

      /// Offset of node i from the cell's lowest vertex in direction d, in
      /// cells (deal.II's vertex numbering: bit d of i).
      static constexpr int
      offset(const unsigned int i, const unsigned int d)
      {
        return static_cast<int>((i >> d) & 1u);
      }

      /// Evaluate at the reference point @p xi of a cell of edge @p h.
      void
      evaluate(const Point<dim> &xi, const double h)
      {
        const double inv_h = 1. / h;
        for (unsigned int i = 0; i < n; ++i)
          {
            double f[dim], df[dim];
            for (unsigned int d = 0; d < dim; ++d)
              {
                const bool upper = (i >> d) & 1u;
                f[d]             = upper ? xi[d] : 1. - xi[d];
                df[d]            = upper ? inv_h : -inv_h;
              }
            double v = 1.;
            for (unsigned int d = 0; d < dim; ++d)
              v *= f[d];
            value[i] = v;
            for (unsigned int d = 0; d < dim; ++d)
              {
                double g = df[d];
                for (unsigned int e = 0; e < dim; ++e)
                  if (e != d)
                    g *= f[e];
                gradient[i][d] = g;
              }
          }
      }
    };
  } // namespace transfer
} // namespace scarp

#endif
