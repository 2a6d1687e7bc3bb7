#ifndef scarp_transfer_f_bar_h
#define scarp_transfer_f_bar_h

#include <deal.II/base/tensor.h>

#include <cmath>

namespace scarp
{
  namespace transfer
  {
    using namespace dealii;

    /**
     * @brief F-bar of the points of one cell: the volume change of each
     * point's deformation increment is replaced by the cell's mean, its
     * isochoric part is kept.
     *
     * With dJ_p = det(dF_p) and the points' volumes V_p at the start of the
     * step, dJbar = sum V_p dJ_p / sum V_p (the cell's points then change
     * their total volume exactly as without the average) and
     *
     *     dFbar_p = (dJbar / dJ_p)^(1/dim) dF_p,   det dFbar_p = dJbar,
     *
     * as in Coombs, Charlton, Cortis and Augarde (2018), CMAME 333. In
     * plane strain (dim = 2) the in-plane block is scaled and the
     * out-of-plane stretch stays 1, so the 3x3 determinant is dJbar too.
     *
     * If a point's dJ_p is not positive and finite the cell is left as it
     * is: the step's J check then reports the inverted point instead of a
     * NaN from a root of a negative ratio.
     *
     * @return dJbar, or 0 if the cell was left unchanged.
     */
    template <int dim>
    double
    apply_f_bar(Tensor<2, dim>    *delta_F,
                const double      *volume,
                const unsigned int n)
    {
      double sum_v = 0, sum_vj = 0;
      for (unsigned int p = 0; p < n; ++p)
        {
          const double dJ = determinant(delta_F[p]);
          if (!(dJ > 0) || !std::isfinite(dJ))
            return 0;
          sum_v += volume[p];
          sum_vj += volume[p] * dJ;
        }
      if (!(sum_v > 0))
        return 0;
      const double dJ_bar = sum_vj / sum_v;
      for (unsigned int p = 0; p < n; ++p)
        delta_F[p] *=
          std::pow(dJ_bar / determinant(delta_F[p]), 1. / double(dim));
      return dJ_bar;
    }
  } // namespace transfer
} // namespace scarp

#endif
