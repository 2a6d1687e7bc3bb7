// Driving stress of the damage driver Y (design note section 3, item 1):
// from the elastic trial stress ("Driving stress = elastic trial") or from
// the stress after the Mohr-Coulomb return ("plastically corrected", the
// default). One point, one step, plane strain, computed by hand:
//
//   E = 1e7 Pa, nu = 0.25: lambda = mu = 4e6 Pa; c = 1e4 Pa, phi = 30 deg
//   (k = 3, sigma_c = 2 c sqrt(3)), psi = 0; theta = 30 deg.
//   dF = diag(exp(-a), exp(b), 1), a = 6e-3, b = 2e-3: Hencky strains
//   (-a, b, 0), J = exp(b - a).
//   Trial Kirchhoff stress (lambda tr + 2 mu e): xx = -64 kPa, yy = 0,
//   zz = -16 kPa; s1 = yy, s2 = zz, s3 = xx; f = k s1 - s3 - sigma_c =
//   29.359 kPa > 0.
//   Plane return with psi = 0: D dg = 2 mu (1, 0, -1), df.D dg = 2 mu
//   (k + 1), so s_C = s - f/(k + 1) (1, 0, -1) = (-7.340, -16, -56.660)
//   kPa; both orderings hold (plane region), the trace is unchanged.
//   Y = 3/(3 + tan theta) (sqrt(3 J2) + I1 tan theta / 3) of tau / J:
//   trial 35.6 kPa, corrected 25.4 kPa.
// The degraded stress (d = 0: the corrected stress) must not depend on the
// option.

#include <scarp/materials/chalk.h>

#include "test_tools.h"

using namespace dealii;
using namespace scarp::materials;
using scarp_test::check;
using scarp_test::check_close;

namespace
{
  double
  driver(const std::array<double, 3> &tau, const double J, const double theta)
  {
    const double t  = std::tan(theta * M_PI / 180.);
    const double s1 = tau[0] / J, s2 = tau[1] / J, s3 = tau[2] / J;
    const double I1 = s1 + s2 + s3;
    const double J2 =
      ((s1 - s2) * (s1 - s2) + (s2 - s3) * (s2 - s3) + (s3 - s1) * (s3 - s1)) /
      6.;
    return std::max(0., 3. / (3. + t) * (std::sqrt(3. * J2) + I1 * t / 3.));
  }
} // namespace

int
main()
{
  const double lambda = 4e6, mu = 4e6, a = 6e-3, b = 2e-3, theta = 30.;
  const double k = 3., sigma_c = 2. * 1e4 * std::sqrt(3.);
  const double tr = b - a, J = std::exp(b - a);
  // Ordered principal stresses s1 >= s2 >= s3: yy, zz, xx.
  const std::array<double, 3> trial = {
    {lambda * tr + 2. * mu * b, lambda * tr, lambda * tr - 2. * mu * a}};
  const double f = k * trial[0] - trial[2] - sigma_c;
  check("trial stress yields (f > 0)", f > 0.);
  const std::array<double, 3> corrected = {
    {trial[0] - f / (k + 1.), trial[1], trial[2] + f / (k + 1.)}};
  check("plane region: the return keeps the order",
        corrected[0] >= corrected[1] && corrected[1] >= corrected[2]);
  const double Y_trial     = driver(trial, J, theta);
  const double Y_corrected = driver(corrected, J, theta);
  std::cout << "hand: Y trial " << Y_trial << " Pa, Y corrected " << Y_corrected
            << " Pa" << std::endl;

  MohrCoulombReturn::Parameters strength;
  strength.cohesion       = 1e4;
  strength.friction_angle = 30.;
  strength.dilation_angle = 0.;
  const IsotropicElasticity elasticity(1e7, 0.25);

  Tensor<2, 3> dF;
  dF[0][0] = std::exp(-a);
  dF[1][1] = std::exp(b);
  dF[2][2] = 1.;

  SymmetricTensor<2, 3> stress[2];
  for (const bool use_trial : {false, true})
    {
      Chalk::DamageParameters dp;
      dp.damage_angle = theta;
      dp.driving_stress =
        use_trial ? DrivingStress::trial : DrivingStress::corrected;
      const Chalk             chalk(1700., elasticity, strength, dp);
      scarp_test::SinglePoint point(chalk);
      point.step(dF);
      const double expected = use_trial ? Y_trial : Y_corrected;
      // The strains are ln(exp(x)) to round-off (1e-19 absolute), the
      // principal frame is exact (diagonal), so Y is exact to ~1e-16
      // relative; 1e-10 relative is far below the 29 % between the two.
      const std::string name =
        use_trial ? "elastic trial: " : "plastically corrected: ";
      check_close(name + "Y", point.driver, expected, 1e-10 * expected);
      check_close(name + "Y in the state",
                  point.state[Chalk::damage_driver],
                  expected,
                  1e-10 * expected);
      stress[use_trial] = point.stress;
      // The stress itself is the corrected one in both cases (d = 0).
      check_close(name + "stress xx = corrected / J",
                  point.stress[0][0],
                  corrected[2] / J,
                  1e-10 * 64e3);
      check_close(name + "stress yy = corrected / J",
                  point.stress[1][1],
                  corrected[0] / J,
                  1e-10 * 64e3);
    }
  check("the option changes Y only: same stress",
        (stress[0] - stress[1]).norm() == 0.);
  check("the two drivers differ by far more than the tolerance",
        Y_trial - Y_corrected > 0.2 * Y_trial);
  return 0;
}
