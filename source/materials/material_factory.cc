#include <scarp/materials/chalk.h>
#include <scarp/materials/linear_elastic.h>
#include <scarp/materials/material_factory.h>
#include <scarp/materials/mohr_coulomb.h>
#include <scarp/materials/neo_hookean.h>

namespace scarp
{
  namespace materials
  {
    void
    MaterialFactory::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Model",
                        "chalk",
                        Patterns::Selection(
                          "linear elastic|neo-Hookean|Mohr-Coulomb|chalk"),
                        "Constitutive model: linear elastic (Hencky, "
                        "logarithmic strain), neo-Hookean (compressible), "
                        "Mohr-Coulomb (Hencky elasticity, perfect "
                        "plasticity) or chalk (Mohr-Coulomb plasticity with "
                        "non-local scalar damage).");
      prm.declare_entry("Density",
                        "1700",
                        Patterns::Double(0.),
                        "Mass density in the reference configuration "
                        "[kg/m^3], > 0. Joss Bay chalk: 1700.");
      prm.enter_subsection("Elasticity");
      IsotropicElasticity::declare_parameters(prm);
      prm.leave_subsection();
      prm.enter_subsection("Mohr-Coulomb");
      MohrCoulombReturn::Parameters::declare_parameters(prm);
      prm.leave_subsection();
      prm.enter_subsection("Damage");
      Chalk::DamageParameters::declare_parameters(prm);
      prm.leave_subsection();
    }


    std::unique_ptr<Material>
    MaterialFactory::create(ParameterHandler &prm)
    {
      const std::string model   = prm.get("Model");
      const double      density = prm.get_double("Density");
      AssertThrow(density > 0.,
                  ExcMessage("Material: 'Density' must be > 0 kg/m^3."));

      IsotropicElasticity elasticity;
      prm.enter_subsection("Elasticity");
      elasticity.parse_parameters(prm);
      prm.leave_subsection();

      if (model == "linear elastic")
        return std::make_unique<LinearElastic>(density, elasticity);
      if (model == "neo-Hookean")
        return std::make_unique<NeoHookean>(density, elasticity);

      MohrCoulombReturn::Parameters strength;
      prm.enter_subsection("Mohr-Coulomb");
      strength.parse_parameters(prm);
      prm.leave_subsection();
      if (model == "Mohr-Coulomb")
        return std::make_unique<MohrCoulomb>(density, elasticity, strength);

      Chalk::DamageParameters damage;
      prm.enter_subsection("Damage");
      damage.parse_parameters(prm);
      prm.leave_subsection();
      AssertThrow(model == "chalk",
                  ExcMessage("Material: unknown 'Model' " + model + "."));
      return std::make_unique<Chalk>(density, elasticity, strength, damage);
    }
  } // namespace materials
} // namespace scarp
