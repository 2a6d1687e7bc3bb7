// Degradation split (paper Eq. 4): with damage d, a tensile mean stress is
// degraded by 1 - (1 - r_t) d, a compressive one by 1 - (1 - r_c) d, the
// deviator by 1 - (1 - r_g) d, using d of the start of the step.

#include <scarp/materials/chalk.h>
#include <scarp/materials/spectral_decomposition.h>

#include "test_tools.h"

using namespace dealii;
using namespace scarp::materials;
using scarp_test::check_close;

int
main()
{
  Chalk::DamageParameters dp;
  dp.residual_tensile_ratio     = 0.1;
  dp.residual_compressive_ratio = 0.3;
  dp.residual_shear_ratio       = 0.2;
  const IsotropicElasticity el(1e9, 0.24);
  const Chalk  chalk(1700., el, MohrCoulombReturn::Parameters(), dp);
  const double d = 0.6;

  for (const double volumetric : {+1e-4, -1e-4})
    {
      // Volumetric plus shear deformation.
      Tensor<2, 3> dF =
        (1. + volumetric) * Tensor<2, 3>(unit_symmetric_tensor<3>());
      dF[0][1] += 2e-4;
      dF[2][1] -= 1e-4;

      scarp_test::SinglePoint undamaged(chalk), damaged(chalk);
      damaged.state[Chalk::damage_variable] = d;
      undamaged.step(dF);
      damaged.step(dF);

      const SymmetricTensor<2, 3> &sb   = undamaged.stress; // effective
      const double                 pb   = trace(sb) / 3.;
      const double                 r    = pb > 0. ? 0.1 : 0.3;
      const double                 gp   = 1. - (1. - r) * d;
      const double                 gs   = 1. - (1. - 0.2) * d;
      const std::string            name = pb > 0. ? "tension" : "compression";
      // Same effective state; round-off relative to the stress.
      const double tol = 1e-12 * sb.norm();
      check_close(name + ": mean stress factor",
                  trace(damaged.stress) / 3.,
                  gp * pb,
                  tol);
      check_close(name + ": deviator factor",
                  (deviator(damaged.stress) - gs * deviator(sb)).norm(),
                  0.,
                  tol);
      check_close(name + ": degrade() agrees with update()",
                  (chalk.degrade(sb, d) - damaged.stress).norm(),
                  0.,
                  tol);
      // The driver is computed from the effective stress, not the degraded.
      check_close(name + ": driver from the effective stress",
                  damaged.driver,
                  chalk.local_driver(sb),
                  tol);
      // Stored energy: degraded volumetric and deviatoric parts.
      const SymmetricTensor<2, 3> eps =
        0.5 * log_spd(symmetrize(dF * transpose(dF)));
      const double psi =
        gp * 0.5 * el.bulk_modulus() * trace(eps) * trace(eps) +
        gs * el.shear_modulus() * (deviator(eps) * deviator(eps));
      check_close(name + ": stored energy", damaged.energy, psi, 1e-10 * psi);
    }

  // Damage of the step is used only from the next update on.
  {
    scarp_test::SinglePoint p(chalk);
    Tensor<2, 3>            dF = unit_symmetric_tensor<3>();
    dF[0][0]                   = 1.001;
    p.step(dF);
    const SymmetricTensor<2, 3> before = p.stress;
    chalk.update_damage(1e9, 1e6, p.state.data()); // drives d to 1
    check_close("update_damage does not change the stress of the step",
                (p.stress - before).norm(),
                0.,
                0.);
    p.step(unit_symmetric_tensor<3>());
    check_close("next update degrades: tensile mean stress ratio",
                trace(p.stress) / trace(before),
                0.1,
                1e-10);
  }
  return 0;
}
