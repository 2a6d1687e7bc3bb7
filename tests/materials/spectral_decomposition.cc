// The closed-form plane-strain branch of spectral_decomposition() (used by
// the Hencky predictor and the Mohr-Coulomb return at every point and step):
// eigenpairs of random symmetric tensors with xz = yz = 0 reproduce the
// tensor, are orthonormal, come in descending order and match eigenvalues
// computed in long double; off-diagonals far below the diagonal (1e-162 was
// met in the Joss Bay cliff, whose square underflows) give finite, exact
// results. exp_symmetric() of plane tensors, in closed form, matches the
// same formula in long double; of general 3D tensors, by scaling and
// squaring a Taylor series, the series summed in long double.

#include <deal.II/base/symmetric_tensor.h>

#include <scarp/materials/spectral_decomposition.h>

#include <algorithm>
#include <array>
#include <functional>
#include <limits>
#include <random>

#include "test_tools.h"

using namespace dealii;
using namespace scarp::materials;
using scarp_test::check;
using scarp_test::check_close;

int
main()
{
  std::mt19937                           random(42);
  std::uniform_real_distribution<double> unit(-1., 1.);
  double worst_reconstruction = 0, worst_orthonormality = 0,
         worst_eigenvalue = 0;
  bool all_finite = true, all_sorted = true;
  for (unsigned int k = 0; k < 200000; ++k)
    {
      // Diagonal of order 1 with in-plane differences and off-diagonals
      // from 1 down to 1e-320 (denormal), and some exactly equal diagonals.
      SymmetricTensor<2, 3> A;
      const double spread = std::pow(10., -16. * std::abs(unit(random)));
      const double off    = std::pow(10., -320. * std::abs(unit(random)));
      A[0][0]             = 1. + spread * unit(random);
      A[1][1]             = (k % 4 == 0) ? A[0][0] : 1. + spread * unit(random);
      A[2][2]             = 1. + unit(random);
      A[0][1]             = off * unit(random);
      const SpectralDecomposition s    = spectral_decomposition(A);
      const double                norm = A.norm();
      for (unsigned int i = 0; i < 3; ++i)
        {
          all_finite = all_finite && std::isfinite(s.values[i]) &&
                       std::isfinite(s.vectors[i].norm_square());
          if (i > 0)
            all_sorted = all_sorted && s.values[i - 1] >= s.values[i];
          for (unsigned int j = 0; j < 3; ++j)
            worst_orthonormality =
              std::max(worst_orthonormality,
                       std::abs(s.vectors[i] * s.vectors[j] - (i == j)));
        }
      worst_reconstruction =
        std::max(worst_reconstruction,
                 (compose(s.values, s.vectors) - A).norm() / norm);
      // Reference eigenvalues in long double (the 2x2 block in closed
      // form; deal.II's eigenvalues() uses Cardano's formula, which loses
      // half the digits at nearly repeated eigenvalues).
      const long double          mean = 0.5L * ((long double)A[0][0] + A[1][1]);
      const long double          half = 0.5L * ((long double)A[0][0] - A[1][1]);
      const long double          b    = A[0][1];
      const long double          r    = std::sqrt(half * half + b * b);
      std::array<long double, 3> reference = {{mean + r, mean - r, A[2][2]}};
      std::sort(reference.begin(), reference.end(), std::greater<>());
      for (unsigned int i = 0; i < 3; ++i)
        worst_eigenvalue =
          std::max(worst_eigenvalue,
                   static_cast<double>(std::abs(s.values[i] - reference[i]) /
                                       norm));
    }
  check("all eigenpairs finite (off-diagonals down to 1e-320)", all_finite);
  check("eigenvalues in descending order", all_sorted);
  // A backward-stable closed form: a few ulps of |A| (2.2e-16 each); 1e-14
  // leaves a factor of ~50 for the compose() round-off.
  check_close("max |V diag(l) V^T - A| / |A|", worst_reconstruction, 0., 1e-14);
  check_close("max |v_i . v_j - delta_ij|", worst_orthonormality, 0., 1e-14);
  check_close("max |l_i - l_i(long double)| / |A|",
              worst_eigenvalue,
              0.,
              1e-14);

  // The case met in the cliff: identity plus an off-diagonal of 1.2e-162.
  SymmetricTensor<2, 3> A       = unit_symmetric_tensor<3>();
  A[0][1]                       = 1.17782e-162;
  const SpectralDecomposition s = spectral_decomposition(A);
  check_close("identity + 1.2e-162: largest eigenvalue",
              s.values[0],
              1.,
              1e-15);
  check_close("identity + 1.2e-162: |V diag(l) V^T - A|",
              (compose(s.values, s.vectors) - A).norm(),
              0.,
              1e-15);

  // exp_symmetric() of plane tensors in closed form (the Hencky predictor's
  // exp(2 eps) at every point and step): against the same formula,
  // e^m (cosh r I + sinh r / r (A - m I)), in long double, for strain-like
  // tensors (entries up to 0.5) with in-plane differences and off-diagonals
  // down to 1e-320, and exp(log) back to the tensor.
  double worst_exp = 0, worst_round_trip = 0;
  bool   exp_finite = true;
  for (unsigned int k = 0; k < 200000; ++k)
    {
      SymmetricTensor<2, 3> B;
      const double spread = std::pow(10., -16. * std::abs(unit(random)));
      const double off    = std::pow(10., -320. * std::abs(unit(random)));
      B[0][0]             = 0.5 * unit(random);
      B[1][1] = (k % 4 == 0) ? B[0][0] : B[0][0] + spread * unit(random);
      B[2][2] = 0.5 * unit(random);
      B[0][1] = (k % 7 == 0) ? 0. : 0.5 * off * unit(random);
      const SymmetricTensor<2, 3> E = exp_symmetric(B);
      const long double           m = 0.5L * ((long double)B[0][0] + B[1][1]);
      const long double           h = 0.5L * ((long double)B[0][0] - B[1][1]);
      const long double           b = B[0][1];
      const long double           r = std::sqrt(h * h + b * b);
      const long double           sinhc = (r == 0.L) ? 1.L : std::sinh(r) / r;
      const long double           em    = std::exp(m);
      const long double           ref00 = em * (std::cosh(r) + sinhc * h);
      const long double           ref11 = em * (std::cosh(r) - sinhc * h);
      const long double           ref01 = em * sinhc * b;
      const long double           ref22 = std::exp((long double)B[2][2]);
      const double                error = static_cast<double>(
        std::max({std::abs(E[0][0] - ref00),
                                 std::abs(E[1][1] - ref11),
                                 std::abs(E[0][1] - ref01),
                                 std::abs(E[2][2] - ref22)}) /
        std::sqrt(ref00 * ref00 + ref11 * ref11 + ref22 * ref22));
      worst_exp = std::max(worst_exp, error);
      exp_finite =
        exp_finite && std::isfinite(E.norm()) && E[0][2] == 0. && E[1][2] == 0.;
      worst_round_trip =
        std::max(worst_round_trip, (log_spd(E) - B).norm() / E.norm());
    }
  check("exp of plane tensors finite and plane", exp_finite);
  // exp, expm1 and sqrt are correctly rounded to about 1 ulp in glibc; the
  // formula adds a few operations: 1e-15 of |exp(A)| is ~5 ulps.
  check_close("max |exp(A) - exp(A)(long double)| / |exp(A)|",
              worst_exp,
              0.,
              1e-15);
  // log(exp(A)) = A: the decomposition's 1e-14 budget above.
  check_close("max |log(exp(A)) - A| / |exp(A)|", worst_round_trip, 0., 1e-14);

  // General 3D tensors (spectral_decomposition_general()): A = Q diag(l)
  // Q^T for random rotations Q, eigenvalues distinct, pairwise and triply
  // (nearly) repeated with spreads from 1 down to 1e-16 and exactly, about
  // a mean of 0 or of 1 (b = exp(2 eps) near I), and scales from 1e-150 to
  // 1e150. Reference eigenvalues of the tensor as rounded to double: cyclic
  // Jacobi in long double until the off-diagonal no longer changes.
  {
    double worst_reconstruction_3d = 0, worst_orthonormality_3d = 0,
           worst_eigenvalue_3d = 0;
    bool finite_3d = true, sorted_3d = true;
    for (unsigned int k = 0; k < 200000; ++k)
      {
        long double q[4], qn = 0;
        for (long double &x : q)
          {
            x = unit(random);
            qn += x * x;
          }
        for (long double &x : q)
          x /= std::sqrt(qn);
        const long double Q[3][3] = {{1 - 2 * (q[2] * q[2] + q[3] * q[3]),
                                      2 * (q[1] * q[2] - q[0] * q[3]),
                                      2 * (q[1] * q[3] + q[0] * q[2])},
                                     {2 * (q[1] * q[2] + q[0] * q[3]),
                                      1 - 2 * (q[1] * q[1] + q[3] * q[3]),
                                      2 * (q[2] * q[3] - q[0] * q[1])},
                                     {2 * (q[1] * q[3] - q[0] * q[2]),
                                      2 * (q[2] * q[3] + q[0] * q[1]),
                                      1 - 2 * (q[1] * q[1] + q[2] * q[2])}};
        const double      spread =
          (k % 5 == 0) ? 0. : std::pow(10., -16. * std::abs(unit(random)));
        const double mean  = (k % 2 == 0) ? 0. : 1.;
        const double scale = std::pow(10., 150. * unit(random));
        long double  l[3]  = {unit(random), unit(random), unit(random)};
        if (k % 4 == 1) // a pair (nearly) repeated
          l[1] = l[0] + spread * unit(random);
        else if (k % 4 == 2) // all three (nearly) repeated
          l[1] = l[0] + spread * unit(random),
          l[2] = l[0] + spread * unit(random);
        SymmetricTensor<2, 3> A;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            {
              long double a = 0;
              for (unsigned int n = 0; n < 3; ++n)
                a += Q[i][n] * (mean + (k % 3 == 0 ? 1e-6L : 1.L) * l[n]) *
                     Q[j][n];
              A[i][j] = static_cast<double>(a * scale);
            }
        if (A[0][2] == 0. && A[1][2] == 0.)
          continue; // the plane branch, tested above
        const SpectralDecomposition d    = spectral_decomposition(A);
        const double                norm = A.norm();
        for (unsigned int i = 0; i < 3; ++i)
          {
            finite_3d = finite_3d && std::isfinite(d.values[i]) &&
                        std::isfinite(d.vectors[i].norm_square());
            if (i > 0)
              sorted_3d = sorted_3d && d.values[i - 1] >= d.values[i];
            for (unsigned int j = 0; j < 3; ++j)
              worst_orthonormality_3d =
                std::max(worst_orthonormality_3d,
                         std::abs(d.vectors[i] * d.vectors[j] - (i == j)));
          }
        worst_reconstruction_3d =
          std::max(worst_reconstruction_3d,
                   (compose(d.values, d.vectors) - A).norm() / norm);
        // Cyclic Jacobi in long double on A / |A|.
        long double a[3][3];
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            a[i][j] = (long double)A[i][j] / norm;
        for (unsigned int sweep = 0; sweep < 50; ++sweep)
          {
            const long double off =
              std::abs(a[0][1]) + std::abs(a[0][2]) + std::abs(a[1][2]);
            if (off == 0)
              break;
            for (unsigned int p = 0; p < 2; ++p)
              for (unsigned int r = p + 1; r < 3; ++r)
                {
                  if (a[p][r] == 0)
                    continue;
                  const long double theta = (a[r][r] - a[p][p]) / (2 * a[p][r]);
                  const long double t =
                    (theta >= 0 ? 1 : -1) /
                    (std::abs(theta) + std::sqrt(theta * theta + 1));
                  const long double c  = 1 / std::sqrt(t * t + 1);
                  const long double sn = t * c;
                  for (unsigned int n = 0; n < 3; ++n)
                    {
                      const long double x = a[n][p], y = a[n][r];
                      a[n][p] = c * x - sn * y;
                      a[n][r] = sn * x + c * y;
                    }
                  for (unsigned int n = 0; n < 3; ++n)
                    {
                      const long double x = a[p][n], y = a[r][n];
                      a[p][n] = c * x - sn * y;
                      a[r][n] = sn * x + c * y;
                    }
                  a[p][r] = a[r][p] = 0;
                }
          }
        std::array<long double, 3> reference = {{a[0][0], a[1][1], a[2][2]}};
        std::sort(reference.begin(), reference.end(), std::greater<>());
        for (unsigned int i = 0; i < 3; ++i)
          worst_eigenvalue_3d =
            std::max(worst_eigenvalue_3d,
                     static_cast<double>(std::abs(
                       (long double)d.values[i] / norm - reference[i])));
      }
    check("3D: all eigenpairs finite (scales 1e-150 to 1e150)", finite_3d);
    // A NaN or an infinity in the tensor must come out (the step's
    // finiteness check stops the run on it), not be hidden by the scaling
    // or the clamp of the Lode angle.
    bool bad_propagates = true;
    for (const double bad : {std::numeric_limits<double>::quiet_NaN(),
                             std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity()})
      for (unsigned int entry = 0; entry < 6; ++entry)
        {
          SymmetricTensor<2, 3> B;
          B[0][0] = 1., B[1][1] = 2., B[2][2] = 3.;
          B[0][1] = 0.1, B[1][2] = 0.2, B[0][2] = 0.3;
          B.access_raw_entry(entry)     = bad;
          const SpectralDecomposition d = spectral_decomposition(B);
          bad_propagates = bad_propagates && !(std::isfinite(d.values[0]) &&
                                               std::isfinite(d.values[1]) &&
                                               std::isfinite(d.values[2]));
        }
    check("3D: a NaN or infinite entry gives a non-finite eigenvalue",
          bad_propagates);
    check("3D: eigenvalues in descending order", sorted_3d);
    // Backward stable: a few ulps of |A| (2.2e-16 each); measured 1.2e-15
    // (deal.II's QL method: 2.3e-15 on the benchmark's tensors), 1e-14
    // leaves a factor of ~8.
    check_close("3D: max |V diag(l) V^T - A| / |A|",
                worst_reconstruction_3d,
                0.,
                1e-14);
    check_close("3D: max |v_i . v_j - delta_ij|",
                worst_orthonormality_3d,
                0.,
                1e-14);
    check_close("3D: max |l_i - l_i(long double)| / |A|",
                worst_eigenvalue_3d,
                0.,
                1e-14);
  }

  // exp_symmetric() of general 3D tensors (scaling and squaring of a Taylor
  // polynomial of adaptive degree): against the series summed term by term
  // in long double without scaling (another evaluation of the same
  // function: 64-bit mantissa, terms until they no longer change the sum),
  // against decomposing with deal.II's eigenvectors() and composing, and
  // log(exp(A)) back to A. Strain-like tensors (entries up to 0.5, the
  // scaled series alone or one squaring), larger ones (entries up to 1.5,
  // up to five squarings) and tiny ones (entries down to 1e-12, a series of
  // one or two terms).
  double worst_series = 0, worst_decomposition = 0, worst_round_trip_3d = 0;
  bool   series_finite = true;
  for (unsigned int k = 0; k < 100000; ++k)
    {
      const double          size = (k % 3 == 0) ? 0.5
                                   : (k % 3 == 1)
                                     ? 1.5
                                     : std::pow(10., -12. * std::abs(unit(random)));
      SymmetricTensor<2, 3> B;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i; j < 3; ++j)
          B[i][j] = size * unit(random);
      const SymmetricTensor<2, 3> E = exp_symmetric(B);
      long double                 reference[3][3], term[3][3];
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          reference[i][j] = term[i][j] = (i == j) ? 1.L : 0.L;
      for (unsigned int n = 1; n < 200; ++n)
        {
          long double next[3][3];
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              {
                next[i][j] = 0.L;
                for (unsigned int l = 0; l < 3; ++l)
                  next[i][j] += term[i][l] * (long double)B[l][j];
                next[i][j] /= n;
              }
          bool changed = false;
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              {
                term[i][j]                = next[i][j];
                const long double updated = reference[i][j] + term[i][j];
                changed         = changed || updated != reference[i][j];
                reference[i][j] = updated;
              }
          if (!changed)
            break;
        }
      long double error = 0, norm = 0;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          {
            error = std::max(error, std::abs(E[i][j] - reference[i][j]));
            norm += reference[i][j] * reference[i][j];
          }
      worst_series =
        std::max(worst_series, static_cast<double>(error / std::sqrt(norm)));
      series_finite = series_finite && std::isfinite(E.norm());
      const auto                  eig = eigenvectors(B);
      std::array<double, 3>       values;
      std::array<Tensor<1, 3>, 3> vectors;
      for (unsigned int i = 0; i < 3; ++i)
        {
          values[i]  = std::exp(eig[i].first);
          vectors[i] = eig[i].second;
        }
      worst_decomposition =
        std::max(worst_decomposition,
                 (compose(values, vectors) - E).norm() / E.norm());
      worst_round_trip_3d =
        std::max(worst_round_trip_3d,
                 (log_spd(E) - B).norm() / std::max(1., B.norm()));
    }
  check("exp of 3D tensors finite", series_finite);
  // Horner's 12 steps at most and up to five squarings, each a few ulps
  // (2.2e-16) and doubled by the squaring that follows: measured 4.6e-15;
  // 2e-14 leaves a factor of about 4.
  check_close("3D: max |exp(A) - series(long double)| / |exp(A)|",
              worst_series,
              0.,
              2e-14);
  // The decomposition's own budget (1e-14 above) plus the series'.
  check_close("3D: max |exp(A) - V exp(l) V^T| / |exp(A)|",
              worst_decomposition,
              0.,
              3e-14);
  // Bounded by the logarithm's decomposition, not by the series: exp(A)
  // whose eigenvalues spread by up to e^9 loses digits of its smallest one
  // in any decomposition; measured 2.1e-14 here, and 2.4e-14 with the
  // series against 3.3e-14 with exp by decomposition on another 1e5
  // tensors of entries up to 1.5.
  check_close("3D: max |log(exp(A)) - A| / max(1, |A|)",
              worst_round_trip_3d,
              0.,
              1e-13);
  return 0;
}
