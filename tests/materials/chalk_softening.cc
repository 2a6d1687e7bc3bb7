// Softening law at a point (verification item 10): uniaxial tension with
// the local driver (Ybar = Y) and no delay. The stress peaks at sigma_f,
// then follows sigma = sigma_f exp(-2 (kappa - sigma_f) / ((eta - 1)
// sigma_f)) with kappa = E eps, and the energy dissipated per volume tends to
// eta sigma_f^2 / (2 E).

#include <scarp/materials/chalk.h>
#include <scarp/materials/point_driver.h>

#include "test_tools.h"

using namespace dealii;
using namespace scarp::materials;
using scarp_test::check;
using scarp_test::check_close;

int
main()
{
  const double            E = 1e9, nu = 0.24, sf = 20e3, eta = 5.;
  Chalk::DamageParameters dp;
  dp.initiation_stress   = sf;
  dp.ductility           = eta;
  dp.characteristic_time = 1.; // with dt = 50 s: exp(-dt/tau) = 2e-22
  dp.nonlocal_weight     = NonlocalWeight::local;
  // Equal residual ratios keep the effective stress uniaxial (the split
  // is tested separately), so the closed form is exact.
  dp.residual_tensile_ratio = dp.residual_compressive_ratio =
    dp.residual_shear_ratio = 1e-9;
  const Chalk  chalk(1700.,
                    IsotropicElasticity(E, nu),
                    MohrCoulombReturn::Parameters(),
                    dp);
  const double g_f = eta * sf * sf / (2. * E); // 1.0 J/m^3

  std::vector<double> dissipated;
  for (const unsigned int n_steps : {2500u, 5000u, 10000u, 20000u})
    {
      PointDriver::Parameters path;
      path.type            = PointDriver::PathType::uniaxial_tension;
      path.max_strain      = 1e-3; // d reaches 1 near eps = 4.4e-4
      path.n_steps         = n_steps;
      path.duration        = 50. * n_steps;
      const auto   records = PointDriver(chalk, path).run();
      const double de      = path.max_strain / n_steps;

      double peak = 0., max_law_error = 0., max_lag_error = 0.;
      for (unsigned int i = 1; i < records.size(); ++i)
        {
          const auto  &r   = records[i];
          const double tau = determinant(r.F) * r.stress[0][0];
          peak             = std::max(peak, r.stress[0][0]);
          // Exact discrete relation: the stress of step i uses d of step
          // i-1, d = d(kappa_{i-1}), kappa_{i-1} = Y_{i-1} (no delay).
          const double d_prev  = records[i - 1].damage;
          const double tau_bar = E * std::log(r.F[0][0]);
          max_lag_error =
            std::max(max_lag_error,
                     std::abs(tau - (1. - (1. - 1e-9) * d_prev) * tau_bar));
          // The continuous law in terms of kappa = Y (Cauchy effective).
          if (records[i - 1].kappa > sf && d_prev < 1.)
            {
              const double law =
                sf *
                std::exp(-2. * (records[i - 1].kappa - sf) / ((eta - 1.) * sf));
              max_law_error =
                std::max(max_law_error, std::abs(r.stress[0][0] - law));
            }
        }
      const std::string n = std::to_string(n_steps);
      // The driver is the uniaxial effective stress (Y = sigma), up to the
      // lateral stresses left by the Newton tolerance 1e-12 M.
      check_close("steps " + n + ": Y = sigma_xx in the elastic range",
                  records[1].damage_driver,
                  records[1].stress[0][0],
                  1e-12 * chalk.p_wave_modulus());
      // Exact discrete relation: Newton tolerance 1e-12 M + round-off.
      check_close("steps " + n + ": stress = (1 - d_n) E eps (max error)",
                  max_lag_error,
                  0.,
                  1e-3);
      // Peak: sigma_f overshot by at most one strain increment, E de, since
      // the damage of the step before is used.
      check_close("steps " + n + ": peak stress", peak, sf, 1.01 * E * de);
      // Post-peak law: the stress of step i is the law at kappa_{i-1}
      // times eps_i / eps_{i-1}: error <= sigma_f de / eps_f ~ E de.
      check_close("steps " + n + ": post-peak exponential law (max error)",
                  max_law_error,
                  0.,
                  1.01 * E * de);
      const auto &last = records.back();
      check("steps " + n + ": fully damaged at the end", last.damage == 1.);
      // Energy: the end-point rule psi_0(eps_{n+1}) (d_{n+1} - d_n) and the
      // lag of d both shift the dissipation by O(de / eps_f): de / eps_f =
      // 2e-8 / 2e-5 = 1e-3 .. 2e-2 here. Tolerance 2 E de / sigma_f relative.
      check_close("steps " + n + ": damage dissipation -> eta sigma_f^2/(2E)",
                  last.damage_dissipation,
                  g_f,
                  2. * E * de / sf * g_f);
      // Energy balance: work = stored + dissipated (stored ~ r E eps^2).
      check_close("steps " + n + ": work = stored + dissipated",
                  last.external_work,
                  last.stored_energy + last.damage_dissipation,
                  2. * E * de / sf * g_f);
      // After d = 1 the effective stress reaches the tensile strength of the
      // c = 1 MPa surface (E eps = 1 MPa at the end), but it acts through
      // the residual ratio 1e-9: negligible plastic dissipation.
      check_close("steps " + n + ": plastic dissipation negligible",
                  last.plastic_dissipation,
                  0.,
                  1e-5 * g_f);
      dissipated.push_back(last.damage_dissipation);
    }
  // First-order convergence of the dissipated energy in the strain step.
  const double e1 = std::abs(dissipated[2] - g_f),
               e2 = std::abs(dissipated[3] - g_f);
  std::cout << "dissipation error 10000 steps " << e1 << ", 20000 steps " << e2
            << ", ratio " << e1 / e2 << std::endl;
  check("dissipated energy converges at first order (ratio 1.6 .. 2.4)",
        e1 / e2 > 1.6 && e1 / e2 < 2.4);
  return 0;
}
