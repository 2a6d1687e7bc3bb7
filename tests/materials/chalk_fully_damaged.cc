// Extreme residual stiffness (verification item 15): a fully damaged point
// (d = 1, r_t = 1e-9, r_c = 1e-2, r_g = 5e-3) under large compression,
// tension and shear keeps a finite stress equal to the degraded closed form;
// no NaN, driver 0, no further damage change.

#include <scarp/materials/chalk.h>
#include <scarp/materials/spectral_decomposition.h>

#include "test_tools.h"

using namespace dealii;
using namespace scarp::materials;
using scarp_test::check;
using scarp_test::check_close;

int
main()
{
  const Chalk::DamageParameters dp; // Joss Bay: r_t 1e-9, r_c 1e-2, r_g 5e-3
  // c = 0 would let plasticity cap the effective stress; keep the return
  // out of the way with a huge cohesion so that the closed form is elastic.
  MohrCoulombReturn::Parameters mc;
  mc.cohesion = 1e15;
  const IsotropicElasticity el(1e9, 0.24);
  const Chalk               chalk(1700., el, mc, dp);

  for (const double stretch : {0.5, 0.9, 1.1, 3.})
    for (const double shear : {0., 0.7})
      {
        scarp_test::SinglePoint p(chalk);
        chalk.set_fully_damaged(p.state.data());
        check("damage_can_change false at d = 1",
              !chalk.damage_can_change(p.state.data()));
        Tensor<2, 3> dF = unit_symmetric_tensor<3>();
        dF[0][0]        = stretch;
        dF[0][1]        = shear;
        // Several steps, with damage updates in between.
        for (unsigned int s = 0; s < 4; ++s)
          {
            Tensor<2, 3> inc = unit_symmetric_tensor<3>();
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int j = 0; j < 3; ++j)
                inc[i][j] += (dF[i][j] - (i == j ? 1. : 0.)) / 4.;
            p.step(inc * invert(p.F) * p.F); // = inc
            chalk.update_damage(1e12, 1e3, p.state.data());
          }
        // Closed form from the elastic log strain of the total F.
        const SymmetricTensor<2, 3> eps =
          0.5 * log_spd(symmetrize(p.F * transpose(p.F)));
        const SymmetricTensor<2, 3> tau_bar = el.stress(eps);
        const double                pb      = trace(tau_bar) / 3.;
        const double                rp      = pb > 0. ? 1e-9 : 1e-2;
        const SymmetricTensor<2, 3> expected =
          (rp * pb * unit_symmetric_tensor<3>() + 5e-3 * deviator(tau_bar)) /
          determinant(p.F);
        const std::string name = "stretch " + std::to_string(stretch) +
                                 " shear " + std::to_string(shear);
        bool finite = true;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            finite = finite && std::isfinite(p.stress[i][j]);
        check(name + ": finite stress", finite && std::isfinite(p.energy));
        // Round-off of the Hencky chain, relative to the effective stress.
        check_close(name + ": degraded stress",
                    (p.stress - expected).norm(),
                    0.,
                    1e-12 * tau_bar.norm() + 1e-6);
        check(name + ": stress magnitude bounded by residual stiffness",
              p.stress.norm() <=
                1e-2 * tau_bar.norm() / determinant(p.F) * 1.0001 + 1e-6);
        check_close(name + ": driver 0", p.driver, 0., 0.);
        check_close(name + ": d stays 1", chalk.damage(p.state.data()), 1., 0.);
      }
  return 0;
}
