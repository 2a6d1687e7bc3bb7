#include <deal.II/base/exceptions.h>

#include <scarp/materials/isotropic_elasticity.h>

namespace scarp
{
  namespace materials
  {
    IsotropicElasticity::IsotropicElasticity()
      : IsotropicElasticity(1.e9, 0.24)
    {
    }


    IsotropicElasticity::IsotropicElasticity(const double youngs_modulus,
                                             const double poisson_ratio)
      : E(youngs_modulus)
      , nu(poisson_ratio)
    {
      compute_lame();
    }


    void
    IsotropicElasticity::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Young's modulus",
                        "1e9",
                        Patterns::Double(0.),
                        "Young's modulus E of the undamaged material [Pa], "
                        "> 0. Joss Bay chalk: 1e9.");
      prm.declare_entry("Poisson's ratio",
                        "0.24",
                        Patterns::Double(-1., 0.5),
                        "Poisson's ratio nu [-], in the open interval "
                        "(-1, 0.5). Joss Bay chalk: 0.24.");
    }


    void
    IsotropicElasticity::parse_parameters(ParameterHandler &prm)
    {
      E  = prm.get_double("Young's modulus");
      nu = prm.get_double("Poisson's ratio");
      compute_lame();
    }


    void
    IsotropicElasticity::compute_lame()
    {
      AssertThrow(E > 0.,
                  ExcMessage("Material: 'Young's modulus' must be > 0 Pa, "
                             "got " +
                             std::to_string(E) + "."));
      AssertThrow(nu > -1. && nu < 0.5,
                  ExcMessage("Material: 'Poisson's ratio' must lie in the "
                             "open interval (-1, 0.5), got " +
                             std::to_string(nu) + "."));
      lambda_ = E * nu / ((1. + nu) * (1. - 2. * nu));
      mu      = E / (2. * (1. + nu));
    }
  } // namespace materials
} // namespace scarp
