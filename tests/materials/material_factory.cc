// MaterialFactory: defaults are Joss Bay chalk, every model can be created,
// and impossible values stop with a message naming the entry.

#include <deal.II/base/parameter_handler.h>

#include <scarp/materials/chalk.h>
#include <scarp/materials/linear_elastic.h>
#include <scarp/materials/material_factory.h>
#include <scarp/materials/mohr_coulomb.h>
#include <scarp/materials/neo_hookean.h>

#include "test_tools.h"

using namespace dealii;
using namespace scarp::materials;
using scarp_test::check;
using scarp_test::check_close;

namespace
{
  std::unique_ptr<Material>
  create(const std::string &input)
  {
    ParameterHandler prm;
    prm.enter_subsection("Material chalk");
    MaterialFactory::declare_parameters(prm);
    prm.leave_subsection();
    prm.parse_input_from_string("subsection Material chalk\n" + input +
                                "\nend\n");
    prm.enter_subsection("Material chalk");
    auto m = MaterialFactory::create(prm);
    prm.leave_subsection();
    return m;
  }

  /// True if create() throws and the message names @p entry.
  bool
  fails_naming(const std::string &input, const std::string &entry)
  {
    try
      {
        create(input);
      }
    catch (const std::exception &e)
      {
        const bool named =
          std::string(e.what()).find(entry) != std::string::npos;
        std::cout << "  rejected (" << entry << "): "
                  << (named ? "named" : std::string("NOT named: ") + e.what())
                  << std::endl;
        return named;
      }
    return false;
  }
} // namespace

int
main()
{
  // Defaults: Joss Bay chalk.
  {
    const auto   m     = create("");
    const Chalk *chalk = dynamic_cast<const Chalk *>(m.get());
    check("default model is chalk", chalk != nullptr);
    check_close("density", chalk->density(), 1700., 0.);
    check_close("E", chalk->get_elasticity().youngs_modulus(), 1e9, 0.);
    check_close("nu", chalk->get_elasticity().poisson_ratio(), 0.24, 0.);
    // sigma_c = 2 c sqrt(k), c = 1 MPa, phi = 50 deg.
    const double s = std::sin(50. * M_PI / 180.);
    check_close("sigma_c (c = 1 MPa)",
                chalk->get_return_mapping().compressive_strength(),
                2e6 * std::sqrt((1. + s) / (1. - s)),
                1e-6);
    check_close("nonlocal length", chalk->nonlocal_length(), 0.18, 0.);
    check("nonlocal weight bell",
          chalk->nonlocal_weight() == NonlocalWeight::bell);
    const auto &dp = chalk->get_damage_parameters();
    check("damage defaults",
          dp.damage_angle == 60. && dp.initiation_stress == 20e3 &&
            dp.ductility == 5. && dp.characteristic_time == 1. &&
            dp.residual_tensile_ratio == 1e-9 &&
            dp.residual_compressive_ratio == 1e-2 &&
            dp.residual_shear_ratio == 5e-3);
    check("has_damage, has_plasticity",
          chalk->has_damage() && chalk->has_plasticity());
    const auto names = chalk->state_variable_names();
    for (const std::string n : {"damage", "kappa", "plastic_strain"})
      check("state variable " + n,
            std::find(names.begin(), names.end(), n) != names.end());
  }
  // Other models.
  check("linear elastic",
        dynamic_cast<LinearElastic *>(
          create("set Model = linear elastic").get()) != nullptr);
  check("neo-Hookean",
        dynamic_cast<NeoHookean *>(create("set Model = neo-Hookean").get()) !=
          nullptr);
  check("Mohr-Coulomb (sand, c = 0)",
        dynamic_cast<MohrCoulomb *>(
          create("set Model = Mohr-Coulomb\nsubsection Mohr-Coulomb\nset "
                 "Cohesion = 0\nset Friction angle = 35\nend")
            .get()) != nullptr);
  check(
    "gaussian weight",
    dynamic_cast<Chalk *>(
      create("subsection Damage\nset Nonlocal weight = gaussian\nend").get())
        ->nonlocal_weight() == NonlocalWeight::gaussian);
  check("local weight: nonlocal_length 0",
        create("subsection Damage\nset Nonlocal weight = local\nend")
            ->nonlocal_length() == 0.);

  // Impossible values name their entry.
  check("dilation > friction",
        fails_naming("subsection Mohr-Coulomb\nset Dilation angle = "
                     "40\nset Friction angle = 30\nend",
                     "Dilation angle"));
  check("ductility = 1",
        fails_naming("subsection Damage\nset Ductility = 1\nend", "Ductility"));
  check("Poisson's ratio = 0.5",
        fails_naming("subsection Elasticity\nset Poisson's ratio = 0.5\nend",
                     "Poisson's ratio"));
  check("friction angle = 90",
        fails_naming("subsection Mohr-Coulomb\nset Friction angle = 90\nend",
                     "Friction angle"));
  check("Young's modulus = 0",
        fails_naming("subsection Elasticity\nset Young's modulus = 0\nend",
                     "Young's modulus"));
  check("unknown entry", fails_naming("set Youngs modulus = 1", "Youngs"));
  check("unknown model", fails_naming("set Model = granite", "granite"));
  return 0;
}
