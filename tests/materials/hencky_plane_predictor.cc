// The Hencky predictor of plane strain (hencky_trial_strain_plane(), the
// path of every 2D point): its principal strains and directions against
// the same predictor computed in long double with the 2x2 block in closed
// form (atan2, exp, log of long double), on random plane strains and
// increments; the out-of-plane strain equal to eps_e_n's zz exactly; the
// general path (exp, product, 3x3 decomposition, log) beside it; and the
// predictors by chunks (hencky_trial_strains()) equal to one at a time.

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <scarp/materials/hencky_strain.h>

#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "test_tools.h"

using namespace dealii;
using namespace scarp::materials;
using scarp_test::check_close;

namespace
{
  using Real = long double;

  /// Eigen-decomposition of the symmetric 2x2 block (a, b; b, d) in long
  /// double: values l[0] >= l[1], unit vector (c, s) of l[0].
  void
  eigen_2x2(const Real a,
            const Real b,
            const Real d,
            Real (&l)[2],
            Real &c,
            Real &s)
  {
    const Real m = (a + d) / 2, h = (a - d) / 2;
    const Real r = std::sqrt(h * h + b * b);
    l[0]         = m + r;
    l[1]         = m - r;
    const Real t = std::atan2(b, h) / 2;
    c            = std::cos(t);
    s            = std::sin(t);
  }

  /// f applied to the eigenvalues of the block (a, b; b, d), in long
  /// double: out = V diag(f(l)) V^T.
  template <typename F>
  void
  apply_2x2(const Real a, const Real b, const Real d, F f, Real (&out)[2][2])
  {
    Real l[2], c, s;
    eigen_2x2(a, b, d, l, c, s);
    const Real f0 = f(l[0]), f1 = f(l[1]);
    out[0][0] = f0 * c * c + f1 * s * s;
    out[1][1] = f0 * s * s + f1 * c * c;
    out[0][1] = out[1][0] = (f0 - f1) * c * s;
  }

  /// The predictor's strain tensor in long double: the in-plane block of
  /// 1/2 ln(dF exp(2 eps) dF^T), and zz = eps_zz.
  void
  reference(const Tensor<2, 3>          &dF,
            const SymmetricTensor<2, 3> &two_eps,
            Real (&eps)[2][2])
  {
    Real b_n[2][2];
    apply_2x2(
      two_eps[0][0],
      two_eps[0][1],
      two_eps[1][1],
      [](const Real x) { return std::exp(x); },
      b_n);
    Real b[2][2];
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = 0; j < 2; ++j)
        {
          b[i][j] = 0;
          for (unsigned int k = 0; k < 2; ++k)
            for (unsigned int m = 0; m < 2; ++m)
              b[i][j] += Real(dF[i][k]) * b_n[k][m] * Real(dF[j][m]);
        }
    apply_2x2(
      b[0][0],
      (b[0][1] + b[1][0]) / 2,
      b[1][1],
      [](const Real x) { return std::log(x) / 2; },
      eps);
  }

  /// Largest entry of the difference between a decomposition composed in
  /// long double and a reference tensor (in-plane block and zz).
  Real
  composed_error(const SpectralDecomposition &s,
                 const Real (&eps)[2][2],
                 const Real eps_zz)
  {
    Real error = 0;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        {
          Real a = 0;
          for (unsigned int k = 0; k < 3; ++k)
            a +=
              Real(s.values[k]) * Real(s.vectors[k][i]) * Real(s.vectors[k][j]);
          const Real expected =
            (i < 2 && j < 2) ? eps[i][j] : (i == 2 && j == 2 ? eps_zz : 0);
          error = std::max(error, std::abs(a - expected));
        }
    return error;
  }

  /// The general path of the predictor, as hencky_trial_strain_of() takes
  /// it when the increment is not plane: exp of the whole tensor, the
  /// product, the 3x3 decomposition, the logarithms.
  SpectralDecomposition
  general_path(const Tensor<2, 3> &dF, const SymmetricTensor<2, 3> &two_eps)
  {
    const SymmetricTensor<2, 3> b_n = exp_symmetric(two_eps);
    const Tensor<2, 3>          Fb  = dF * Tensor<2, 3>(b_n);
    SymmetricTensor<2, 3>       b;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        {
          double v = 0.;
          for (unsigned int k = 0; k < 3; ++k)
            v += Fb[i][k] * dF[j][k];
          b[i][j] = v;
        }
    SpectralDecomposition s = spectral_decomposition(b);
    for (double &v : s.values)
      v = 0.5 * std::log(v);
    return s;
  }
} // namespace

int
main()
{
  std::mt19937_64                        rng(20261207);
  std::uniform_real_distribution<double> unit(-1., 1.);
  Real               worst_plane = 0, worst_general = 0, worst_order = 0;
  Real               worst_zz_general = 0;
  unsigned int       zz_not_exact     = 0;
  const unsigned int n                = 200000;
  for (unsigned int k = 0; k < n; ++k)
    {
      // Elastic strains from 1e-8 to 0.3 (chalk at its strength: 1e-3),
      // increments from 1e-9 to 0.05 with rotations up to 1 rad; a tenth
      // diagonal, a tenth with eps_zz equal to an in-plane strain.
      const double          strain = std::pow(10., -8. + 7.5 * (k % 16) / 15.);
      SymmetricTensor<2, 3> two_eps;
      two_eps[0][0] = 2. * strain * unit(rng);
      two_eps[1][1] = 2. * strain * unit(rng);
      two_eps[2][2] = 2. * strain * unit(rng);
      two_eps[0][1] = (k % 10 == 3) ? 0. : 2. * strain * unit(rng);
      if (k % 10 == 7)
        two_eps[2][2] = two_eps[1][1];
      const double increment = std::pow(10., -9. + 7.7 * (k % 13) / 12.);
      const double angle     = (k % 3 == 0) ? unit(rng) : 0.;
      Tensor<2, 3> dF;
      dF[0][0] = std::cos(angle) + increment * unit(rng);
      dF[0][1] = -std::sin(angle) + increment * unit(rng);
      dF[1][0] = std::sin(angle) + increment * unit(rng);
      dF[1][1] = std::cos(angle) + increment * unit(rng);
      if (k % 10 == 3 && angle == 0.)
        dF[0][1] = dF[1][0] = 0.;
      dF[2][2] = 1.;

      const SpectralDecomposition s = hencky_trial_strain_of(dF, two_eps);
      Real                        eps[2][2];
      reference(dF, two_eps, eps);
      const Real zz = Real(two_eps[2][2]) / 2;
      worst_plane   = std::max(worst_plane, composed_error(s, eps, zz));
      // The out-of-plane strain is eps_e_n's own, bit for bit, and it has
      // one unit direction e_z.
      bool found = false;
      for (unsigned int i = 0; i < 3; ++i)
        if (s.vectors[i][2] == 1. && s.values[i] == 0.5 * two_eps[2][2])
          found = true;
      zz_not_exact += found ? 0 : 1;
      // Principal strains in descending order.
      worst_order = std::max({worst_order,
                              Real(s.values[1] - s.values[0]),
                              Real(s.values[2] - s.values[1])});

      const SpectralDecomposition g = general_path(dF, two_eps);
      worst_general = std::max(worst_general, composed_error(g, eps, zz));
      for (unsigned int i = 0; i < 3; ++i)
        if (g.vectors[i][2] == 1.)
          worst_zz_general =
            std::max(worst_zz_general, std::abs(Real(g.values[i]) - zz));
    }
  std::cout << n << " plane predictors; the general path (exp, 3x3, log) "
            << "differs from exact in zz by up to "
            << static_cast<double>(worst_zz_general) << std::endl;
  // Tolerance: the strains are logarithms of stretches of order 1, each
  // rounded a few times to 1.1e-16 relative (exp, two products, the
  // decomposition's square roots, log): a few 1e-16 absolute; 2e-15 is
  // several times the worst of the general path over the same tensors,
  // which the next check prints.
  check_close("plane predictor: largest entry error of the strain tensor",
              static_cast<double>(worst_plane),
              0.,
              2e-15);
  check_close("general path over the same tensors (reference for the "
              "tolerance above)",
              static_cast<double>(worst_general),
              0.,
              2e-15);
  // Exactly: the zz strain is passed through, not rounded through exp and
  // log.
  check_close("plane predictor: points whose zz strain is not eps_zz "
              "exactly",
              zz_not_exact,
              0.,
              0.);
  check_close("plane predictor: principal strains out of order",
              std::max(0., static_cast<double>(worst_order)),
              0.,
              0.);

  // The predictors by chunks (hencky_trial_strains(), the materials'
  // path) against one at a time (hencky_trial_strain()): the same
  // operations per point, so the same numbers bit for bit (tolerance 0).
  // Chunks of 1 to hencky_chunk points; among the points diagonal ones,
  // ones with an out-of-plane shear (xz) or dF_zz != 1 (the general path)
  // and stress-free ones (exp of a zero block).
  {
    const unsigned int        m = 20000;
    std::vector<double>       stored(6 * m);
    std::vector<double *>     state(m);
    std::vector<Tensor<2, 3>> dF(m);
    for (unsigned int k = 0; k < m; ++k)
      {
        double *e           = &stored[6 * k];
        state[k]            = e;
        const double strain = std::pow(10., -8. + 7.5 * (k % 16) / 15.);
        const bool   zero   = k % 23 == 5;
        e[0]                = zero ? 0. : strain * unit(rng);
        e[1]                = zero ? 0. : strain * unit(rng);
        e[2]                = zero ? 0. : strain * unit(rng);
        e[3]                = (zero || k % 10 == 3) ? 0. : strain * unit(rng);
        e[4]                = 0.;
        e[5]                = (k % 17 == 4) ? strain * unit(rng) : 0.;
        const double increment = std::pow(10., -9. + 7.7 * (k % 13) / 12.);
        for (unsigned int i = 0; i < 2; ++i)
          for (unsigned int j = 0; j < 2; ++j)
            dF[k][i][j] = (i == j ? 1. : 0.) + increment * unit(rng);
        if (k % 10 == 3)
          dF[k][0][1] = dF[k][1][0] = 0.;
        dF[k][2][2] = (k % 19 == 7) ? 1. + increment * unit(rng) : 1.;
      }
    unsigned int          differ = 0, n_chunks = 0;
    SpectralDecomposition chunk[hencky_chunk];
    for (unsigned int k = 0; k < m; ++n_chunks)
      {
        const unsigned int size = std::min(1 + n_chunks % hencky_chunk, m - k);
        hencky_trial_strains(&dF[k], &state[k], size, chunk);
        for (unsigned int c = 0; c < size; ++c)
          {
            const SpectralDecomposition one =
              hencky_trial_strain(dF[k + c], state[k + c]);
            for (unsigned int i = 0; i < 3; ++i)
              {
                differ += one.values[i] != chunk[c].values[i];
                for (unsigned int j = 0; j < 3; ++j)
                  differ += one.vectors[i][j] != chunk[c].vectors[i][j];
              }
          }
        k += size;
      }
    std::cout << m << " predictors in " << n_chunks << " chunks of 1 to "
              << hencky_chunk << " points" << std::endl;
    check_close("predictors by chunks: entries that differ from one at a "
                "time",
                differ,
                0.,
                0.);
  }
  return 0;
}
