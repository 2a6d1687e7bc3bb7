#ifndef scarp_tests_materials_test_tools_h
#define scarp_tests_materials_test_tools_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <scarp/materials/material.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace scarp_test
{
  using namespace dealii;

  /// Print "name: value (expected, |error| <= tol)" and fail if not close.
  inline void
  check_close(const std::string &name,
              const double       value,
              const double       expected,
              const double       tolerance)
  {
    const double error = std::abs(value - expected);
    std::cout << name << ": " << value << " expected " << expected
              << " |error| " << error << " tol " << tolerance << std::endl;
    if (!(error <= tolerance))
      {
        std::cerr << "FAILED: " << name << std::endl;
        std::exit(1);
      }
  }

  inline void
  check(const std::string &name, const bool ok)
  {
    std::cout << name << ": " << (ok ? "ok" : "FAILED") << std::endl;
    if (!ok)
      {
        std::cerr << "FAILED: " << name << std::endl;
        std::exit(1);
      }
  }

  /**
   * One material point with its own state, stepped by deformation
   * increments through Material::update().
   */
  struct SinglePoint
  {
    const scarp::materials::Material &material;
    std::vector<double>               state;
    Tensor<2, 3>                      F;
    SymmetricTensor<2, 3>             stress;
    double                            energy = 0.;
    double                            driver = 0.;

    SinglePoint(const scarp::materials::Material &m,
                const SymmetricTensor<2, 3>      &sigma0 = {})
      : material(m)
      , state(m.n_state_variables())
      , F(unit_symmetric_tensor<3>())
      , stress(sigma0)
    {
      material.initialize_state(sigma0, state.data());
    }

    void
    step(const Tensor<2, 3> &delta_F, const double dt = 1.)
    {
      F                                 = delta_F * F;
      double                         *s = state.data();
      scarp::materials::MaterialBatch b;
      b.n             = 1;
      b.dt            = dt;
      b.delta_F       = &delta_F;
      b.F             = &F;
      b.state         = &s;
      b.stress        = &stress;
      b.stored_energy = &energy;
      b.damage_driver = material.has_damage() ? &driver : nullptr;
      material.update(b);
    }
  };
} // namespace scarp_test

#endif
