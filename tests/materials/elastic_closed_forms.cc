// Closed forms of the elastic models: Hencky uniaxial strain and uniaxial
// stress (small strain: linear elasticity), initial stress round trip, and
// the neo-Hookean stress and energy.

#include <scarp/materials/linear_elastic.h>
#include <scarp/materials/neo_hookean.h>
#include <scarp/materials/point_driver.h>

#include "test_tools.h"

using namespace dealii;
using namespace scarp::materials;
using scarp_test::check_close;

int
main()
{
  const double              E = 1e9, nu = 0.24;
  const IsotropicElasticity elasticity(E, nu);
  const double              lambda = elasticity.lambda();
  const double              mu     = elasticity.shear_modulus();
  const double              M      = lambda + 2. * mu;
  const LinearElastic       hencky(1700., elasticity);

  // 1. Uniaxial strain F = diag(1 + e, 1, 1): tau_xx = M ln(1 + e), sigma =
  //    tau / J exactly; linear elasticity M e up to O(e) relative.
  for (const double e : {1e-6, -1e-6, 1e-2})
    {
      scarp_test::SinglePoint p(hencky);
      Tensor<2, 3>            dF = unit_symmetric_tensor<3>();
      dF[0][0]                   = 1. + e;
      p.step(dF);
      const double eps = std::log1p(e);
      // Exact Hencky up to round-off: ln of b_e ~ 1 has an absolute error
      // ~1e-16, i.e. ~1e-16 M in stress, plus 1e-12 relative.
      check_close("Hencky uniaxial strain sigma_xx (e=" + std::to_string(e) +
                    ")",
                  p.stress[0][0],
                  M * eps / (1. + e),
                  1e-12 * M * std::abs(e) + 1e-15 * M);
      check_close("Hencky uniaxial strain sigma_yy",
                  p.stress[1][1],
                  lambda * eps / (1. + e),
                  1e-12 * M * std::abs(e) + 1e-15 * M);
      check_close("Hencky uniaxial strain energy",
                  p.energy,
                  0.5 * M * eps * eps,
                  1e-10 * M * e * e + 1e-15 * M * std::abs(e));
      if (std::abs(e) < 1e-3)
        // Linear elasticity: Hencky differs by O(e) relative (ln(1+e)/(1+e)
        // = e - 3/2 e^2 ...), so 2e-6 relative for e = 1e-6.
        check_close("small strain: sigma_xx = M e",
                    p.stress[0][0],
                    M * e,
                    2. * std::abs(e) * M * std::abs(e));
    }

  // 2. Uniaxial stress through the point driver (lateral stress-free): the
  //    lateral log strains are -nu eps, tau_xx = E eps, J = exp((1-2nu) eps).
  {
    PointDriver::Parameters path;
    path.type            = PointDriver::PathType::uniaxial_tension;
    path.max_strain      = 1e-2;
    path.n_steps         = 10;
    const auto   records = PointDriver(hencky, path).run();
    const auto  &r       = records.back();
    const double eps     = path.max_strain;
    // Newton tolerance on the lateral stress is 1e-12 M: relative 1e-9.
    check_close("Hencky uniaxial stress sigma_xx",
                r.stress[0][0],
                E * eps * std::exp(-(1. - 2. * nu) * eps),
                1e-9 * E * eps);
    check_close("Hencky uniaxial stress lateral stretch ln F_yy",
                std::log(r.F[1][1]),
                -nu * eps,
                1e-9 * eps);
    check_close("uniaxial stress: stored energy = external work",
                r.stored_energy,
                0.5 * E * eps * eps,
                1e-8 * E * eps * eps);
    // Trapezoidal rule on a path where tau is linear in ln stretch; the
    // driver's d dt = 2 (l1 - l0)/(l1 + l0) differs from ln(l1/l0) by
    // de^3/12 per step: relative de^2/12 ~ 1e-7 for de = 1e-3.
    check_close("uniaxial stress: external work",
                r.external_work,
                0.5 * E * eps * eps,
                1e-6 * E * eps * eps);
  }

  // 3. Initial stress round trip: initialize, then dF = I keeps sigma0.
  {
    SymmetricTensor<2, 3> sigma0;
    sigma0[0][0] = -1e6;
    sigma0[1][1] = 2e5;
    sigma0[0][1] = 3e5;
    sigma0[1][2] = -1e5;
    scarp_test::SinglePoint p(hencky, sigma0);
    p.step(unit_symmetric_tensor<3>());
    check_close("initial stress round trip",
                (p.stress - sigma0).norm(),
                0.,
                1e-12 * E);
  }

  // 4. Neo-Hookean: P = mu (F - F^-T) + lambda ln J F^-T, sigma = P F^T/J.
  {
    const NeoHookean nh(1., IsotropicElasticity(1e4, 0.3));
    const double     l2 = nh.p_wave_modulus() - 2. * 1e4 / 2.6;
    const double     m2 = 1e4 / 2.6;
    Tensor<2, 3>     F;
    F[0][0]                       = 1.1;
    F[0][1]                       = 0.2;
    F[1][0]                       = 0.05;
    F[1][1]                       = 0.95;
    F[1][2]                       = 0.1;
    F[2][1]                       = 0.03;
    F[2][2]                       = 1.02;
    const double            J     = determinant(F);
    const Tensor<2, 3>      Ft    = transpose(invert(F));
    const Tensor<2, 3>      P     = m2 * (F - Ft) + l2 * std::log(J) * Ft;
    const Tensor<2, 3>      sigma = P * transpose(F) / J;
    scarp_test::SinglePoint p(nh);
    p.step(F);
    double err = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        err = std::max(err, std::abs(p.stress[i][j] - sigma[i][j]));
    // Two algebraically equal forms evaluated in double precision.
    check_close("neo-Hookean Cauchy stress", err, 0., 1e-12 * 1e4);
    // Energy: P = dpsi/dF by central differences (h = 1e-6: truncation
    // O(h^2 psi''') ~ 1e-12 E, round-off 1e-16 psi / h ~ 1e-10 E).
    double       err_P = 0.;
    const double h     = 1e-6;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          Tensor<2, 3> Fp = F, Fm = F;
          Fp[i][j] += h;
          Fm[i][j] -= h;
          const double dpsi =
            (nh.stored_energy(Fp) - nh.stored_energy(Fm)) / (2. * h);
          err_P = std::max(err_P, std::abs(dpsi - P[i][j]));
        }
    check_close("neo-Hookean P = dpsi/dF", err_P, 0., 1e-7 * 1e4);
    check_close("neo-Hookean energy at F = I",
                nh.stored_energy(unit_symmetric_tensor<3>()),
                0.,
                1e-14);
  }
  return 0;
}
