// Hencky elasticity under large rigid rotations (verification item 2 at a
// point): a pre-stressed point rotated by 90 degrees in 9 increments carries
// exactly R sigma R^T; a stress-free point stays stress-free. Run for the
// three Hencky-based models, which share the predictor.

#include <deal.II/base/numbers.h>

#include <scarp/materials/chalk.h>
#include <scarp/materials/linear_elastic.h>
#include <scarp/materials/mohr_coulomb.h>

#include "test_tools.h"

using namespace dealii;
using namespace scarp::materials;
using scarp_test::check_close;

namespace
{
  /// Rotation by angle a about unit axis n (Rodrigues).
  Tensor<2, 3>
  rotation(const Tensor<1, 3> &n, const double a)
  {
    Tensor<2, 3> R;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        R[i][j] =
          (i == j ? std::cos(a) : 0.) + (1. - std::cos(a)) * n[i] * n[j];
    R[0][1] -= std::sin(a) * n[2];
    R[1][0] += std::sin(a) * n[2];
    R[0][2] += std::sin(a) * n[1];
    R[2][0] -= std::sin(a) * n[1];
    R[1][2] -= std::sin(a) * n[0];
    R[2][1] += std::sin(a) * n[0];
    return R;
  }

  void
  run(const Material &material, const std::string &name)
  {
    const double E = 1e9;
    // A general stress well inside the Mohr-Coulomb surface (c = 1 MPa).
    SymmetricTensor<2, 3> sigma0;
    sigma0[0][0] = -2.e5;
    sigma0[1][1] = -5.e5;
    sigma0[2][2] = -3.e5;
    sigma0[0][1] = 1.e5;
    sigma0[1][2] = -4.e4;
    sigma0[0][2] = 2.e4;

    Tensor<1, 3> axis({1., 2., 3.});
    axis /= axis.norm();
    const unsigned int n_steps = 9;
    const Tensor<2, 3> dR      = rotation(axis, numbers::PI / 2. / n_steps);

    scarp_test::SinglePoint loaded(material, sigma0);
    scarp_test::SinglePoint unloaded(material);
    for (unsigned int s = 0; s < n_steps; ++s)
      {
        loaded.step(dR);
        unloaded.step(dR);
      }
    const Tensor<2, 3>          R = rotation(axis, numbers::PI / 2.);
    const SymmetricTensor<2, 3> expected =
      symmetrize(R * Tensor<2, 3>(sigma0) * transpose(R));
    // Tolerance: each increment takes exp/log of tensors with entries ~1
    // (b_e) to double precision, so strain errors are ~1e-16 per step and
    // stress errors ~1e-16 E per step: 1e-12 E is 1e3 margin over 9 steps.
    check_close(name + " rotated pre-stress |sigma - R sigma0 R^T|",
                (loaded.stress - expected).norm(),
                0.,
                1e-12 * E);
    check_close(name + " rotated stress-free point |sigma|",
                unloaded.stress.norm(),
                0.,
                1e-12 * E);

    // Stretch, then rotate: the stretched stress rotates exactly.
    scarp_test::SinglePoint stretched(material);
    Tensor<2, 3>            U = unit_symmetric_tensor<3>();
    U[0][0]                   = 1.0002;
    U[1][1]                   = 0.9999;
    stretched.step(U);
    const SymmetricTensor<2, 3> sigma_s = stretched.stress;
    for (unsigned int s = 0; s < n_steps; ++s)
      stretched.step(dR);
    check_close(name + " rotated stretched point",
                (stretched.stress -
                 symmetrize(R * Tensor<2, 3>(sigma_s) * transpose(R)))
                  .norm(),
                0.,
                1e-12 * E);
  }
} // namespace

int
main()
{
  const IsotropicElasticity elasticity(1e9, 0.24);
  run(LinearElastic(1700., elasticity), "linear elastic");
  run(MohrCoulomb(1700., elasticity, MohrCoulombReturn::Parameters()),
      "Mohr-Coulomb");
  // The chalk point stays below sigma_f only if its driver is small: the
  // driver is not used here (no update_damage), so d = 0 throughout.
  run(Chalk(1700.,
            elasticity,
            MohrCoulombReturn::Parameters(),
            Chalk::DamageParameters()),
      "chalk");
  return 0;
}
