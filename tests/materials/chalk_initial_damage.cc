// Initial damage (pre-damage band of the cliff): set_initial_damage(d)
// must leave the state as if the point had been loaded to d, i.e. kappa with
// d(kappa) = d; loading it a little further then grows d continuously
// from there, and not loading it changes nothing.
//
// Closed form: kappa = 2 sigma_f gives d = 1 - 1/2 exp(-2 / (eta - 1)) =
// 1 - exp(-1/2) / 2 = 0.69673 (eta = 5).

#include <scarp/materials/chalk.h>

#include "test_tools.h"

using namespace dealii;
using namespace scarp::materials;
using scarp_test::check;
using scarp_test::check_close;

int
main()
{
  const Chalk::DamageParameters dp; // Joss Bay: sigma_f = 20 kPa, eta = 5
  const Chalk                   chalk(1700.,
                    IsotropicElasticity(1e9, 0.24),
                    MohrCoulombReturn::Parameters(),
                    dp);
  const double                  sf = dp.initiation_stress;

  // The closed form; the bisection ends at round-off (1e-16 relative).
  {
    std::vector<double> state(chalk.n_state_variables());
    chalk.initialize_state({}, state.data());
    const double d = 1. - 0.5 * std::exp(-0.5);
    chalk.set_initial_damage(state.data(), d);
    check_close("d = 1 - exp(-1/2)/2: kappa = 2 sigma_f",
                state[Chalk::kappa],
                2. * sf,
                1e-12 * sf);
    check_close("d kept", state[Chalk::damage_variable], d, 0.);
  }

  for (const double d : {0., 1e-6, 1e-3, 0.3, 0.9, 0.999, 1. - 2e-6})
    {
      std::vector<double> state(chalk.n_state_variables());
      chalk.initialize_state({}, state.data());
      chalk.set_initial_damage(state.data(), d);
      const std::string name = "d = " + std::to_string(d) + ": ";
      // d itself, or d(kappa) where that is larger by round-off.
      check_close(name + "damage", state[Chalk::damage_variable], d, 1e-15);
      if (d == 0.)
        {
          check_close(name + "kappa stays 0", state[Chalk::kappa], 0., 0.);
          continue;
        }
      // d(kappa) to round-off: kappa is exact to ~1e-16 relative and
      // kappa dd/dkappa = (1 - d) (1 + 2 kappa / ((eta - 1) sigma_f)) < 2
      // here, so d is exact to ~1e-15; 1e-12 leaves room.
      check_close(name + "d(kappa) = d",
                  chalk.damage_from_kappa(state[Chalk::kappa]),
                  d,
                  1e-12);
      check(name + "kappa > sigma_f", state[Chalk::kappa] > sf);
      // Unloaded (Ybar = 0) nothing changes; loaded slightly beyond kappa
      // (tau = 1 s, dt = 100 s: kappa -> Ybar), d grows only slightly.
      const double kappa = state[Chalk::kappa];
      const double d0    = state[Chalk::damage_variable];
      chalk.update_damage(0., 100., state.data());
      check_close(name + "unloaded: d unchanged",
                  state[Chalk::damage_variable],
                  d0,
                  0.);
      check_close(name + "unloaded: kappa unchanged",
                  state[Chalk::kappa],
                  kappa,
                  0.);
      chalk.update_damage(kappa * (1. + 1e-6), 100., state.data());
      const double grown = state[Chalk::damage_variable] - d0;
      check(name + "loaded past kappa: d grows continuously from d",
            grown > 0. && grown < 1e-3);
    }

  // d = 1 (and d > 1 - 1e-6, rounded as update_damage does): kappa is
  // the smallest history that the rounding turns into 1.
  for (const double d : {1., 1. - 5e-7})
    {
      std::vector<double> state(chalk.n_state_variables());
      chalk.initialize_state({}, state.data());
      chalk.set_initial_damage(state.data(), d);
      check_close("d > 1 - 1e-6 is 1", state[Chalk::damage_variable], 1., 0.);
      check_close("its kappa gives d = 1 - 1e-6",
                  chalk.damage_from_kappa(state[Chalk::kappa]),
                  1. - 1e-6,
                  1e-12);
      check("d = 1 is left out of the average only when asked",
            chalk.is_nonlocal_source(state.data()));
    }
  Chalk::DamageParameters excluding = dp;
  excluding.exclude_fully_damaged   = true;
  const Chalk         chalk_x(1700.,
                      IsotropicElasticity(1e9, 0.24),
                      MohrCoulombReturn::Parameters(),
                      excluding);
  std::vector<double> state(chalk_x.n_state_variables());
  chalk_x.initialize_state({}, state.data());
  chalk_x.set_initial_damage(state.data(), 0.999);
  check("exclude: d < 1 is a source", chalk_x.is_nonlocal_source(state.data()));
  chalk_x.set_fully_damaged(state.data());
  check("exclude: d = 1 is no source",
        !chalk_x.is_nonlocal_source(state.data()));

  // Out of range is refused.
  bool thrown = false;
  try
    {
      chalk.set_initial_damage(state.data(), 1.5);
    }
  catch (const std::exception &)
    {
      thrown = true;
    }
  check("d = 1.5 is refused", thrown);
  return 0;
}
