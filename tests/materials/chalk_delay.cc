// Delayed damage history: kappa_dot = <Ybar - kappa> / tau integrated
// exactly, so kappa(t) = Ybar (1 - exp(-t/tau)) for any step size, the
// initial rate is Ybar / tau, large dt/tau stays bounded, and the history
// and the damage never decrease.

#include <scarp/materials/chalk.h>

#include "test_tools.h"

using namespace dealii;
using namespace scarp::materials;
using scarp_test::check;
using scarp_test::check_close;

int
main()
{
  const double            tau = 1., sf = 20e3, Ybar = 3. * sf;
  Chalk::DamageParameters dp;
  dp.characteristic_time = tau;
  dp.initiation_stress   = sf;
  const Chalk        chalk(1700.,
                    IsotropicElasticity(),
                    MohrCoulombReturn::Parameters(),
                    dp);
  const unsigned int K = Chalk::kappa, D = Chalk::damage_variable;

  // 1. Exact in time, whatever the step: 1000 steps of 1e-3 s, 10 of
  //    0.1 s and 1 of 1 s all give kappa(1 s) = Ybar (1 - e^-1).
  for (const unsigned int n : {1u, 10u, 1000u})
    {
      std::vector<double> state(chalk.n_state_variables());
      chalk.initialize_state(SymmetricTensor<2, 3>(), state.data());
      for (unsigned int i = 0; i < n; ++i)
        chalk.update_damage(Ybar, tau / n, state.data());
      // Products of exp(-dt/tau): round-off ~n eps.
      check_close("kappa(tau) with " + std::to_string(n) + " steps",
                  state[K],
                  Ybar * (1. - std::exp(-1.)),
                  1e-12 * Ybar);
      check_close("damage = d(kappa)",
                  state[D],
                  chalk.damage_from_kappa(state[K]),
                  1e-15);
    }

  // 2. Rate: over a step dt << tau the increase is Ybar dt / tau (1 -
  //    dt/(2 tau) + ...): relative error dt / (2 tau).
  {
    std::vector<double> state(chalk.n_state_variables());
    chalk.initialize_state(SymmetricTensor<2, 3>(), state.data());
    const double dt = 1e-6;
    chalk.update_damage(Ybar, dt, state.data());
    check_close("initial rate dkappa/dt = Ybar / tau",
                state[K] / dt,
                Ybar / tau,
                dt / tau * Ybar / tau);
  }

  // 3. Large dt / tau: bounded, kappa = Ybar, d = d(Ybar) <= 1, no NaN.
  for (const double dt : {1e3, 1e300})
    {
      std::vector<double> state(chalk.n_state_variables());
      chalk.initialize_state(SymmetricTensor<2, 3>(), state.data());
      chalk.update_damage(Ybar, dt, state.data());
      check_close(std::string("dt/tau = ") + (dt > 1e10 ? "1e300" : "1e3") +
                    ": kappa = Ybar",
                  state[K],
                  Ybar,
                  1e-15 * Ybar);
      check("dt/tau large: 0 <= d <= 1, finite",
            std::isfinite(state[D]) && state[D] >= 0. && state[D] <= 1.);
    }

  // 4. Irreversibility: a lower driver changes neither kappa nor d.
  {
    std::vector<double> state(chalk.n_state_variables());
    chalk.initialize_state(SymmetricTensor<2, 3>(), state.data());
    chalk.update_damage(Ybar, 10. * tau, state.data());
    const double k0 = state[K], d0 = state[D];
    chalk.update_damage(0.5 * Ybar, 10. * tau, state.data());
    check("lower driver: kappa unchanged", state[K] == k0);
    check("lower driver: damage unchanged", state[D] == d0);
  }

  // 5. tau = 0: no delay (factor 1).
  {
    Chalk::DamageParameters dp0 = dp;
    dp0.characteristic_time     = 0.;
    const Chalk         c0(1700.,
                   IsotropicElasticity(),
                   MohrCoulombReturn::Parameters(),
                   dp0);
    std::vector<double> state(c0.n_state_variables());
    c0.initialize_state(SymmetricTensor<2, 3>(), state.data());
    c0.update_damage(Ybar, 1e-9, state.data());
    check_close("tau = 0: kappa = Ybar at once", state[K], Ybar, 0.);
  }
  return 0;
}
