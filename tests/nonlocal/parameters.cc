// NonlocalParameters: declared with defaults, parsed from a scene file, bad
// values (negative skin, update interval < 1 or not an integer) rejected;
// the weight names round-trip and a bad name is rejected with a message.

#include <deal.II/base/mpi.h>

#include <scarp/nonlocal/parameters.h>

#include "test_tools.h"

using namespace scarp_test;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  {
    ParameterHandler prm;
    NonlocalParameters::declare_parameters(prm);
    NonlocalParameters parameters;
    parameters.parse_parameters(prm);
    check(parameters.skin_fraction == 0.1, "default skin fraction");

    prm.parse_input_from_string("subsection Non-local average\n"
                                "  set Skin distance fraction = 0.25\n"
                                "end\n");
    parameters.parse_parameters(prm);
    check(parameters.skin_fraction == 0.25, "parsed skin fraction");

    bool rejected = false;
    try
      {
        prm.parse_input_from_string("subsection Non-local average\n"
                                    "  set Skin distance fraction = -1\n"
                                    "end\n");
      }
    catch (const std::exception &)
      {
        rejected = true;
      }
    check(rejected, "negative skin fraction rejected");

    check(parameters.update_interval == 1, "default update interval 1");
    prm.parse_input_from_string("subsection Non-local average\n"
                                "  set Update interval = 4\n"
                                "end\n");
    parameters.parse_parameters(prm);
    check(parameters.update_interval == 4, "parsed update interval");
    for (const std::string bad : {"0", "-2", "1.5"})
      {
        rejected = false;
        try
          {
            prm.parse_input_from_string("subsection Non-local average\n"
                                        "  set Update interval = " +
                                        bad + "\nend\n");
          }
        catch (const std::exception &)
          {
            rejected = true;
          }
        check(rejected, "update interval " + bad + " rejected");
      }
  }

  for (const auto type :
       {WeightType::local, WeightType::bell, WeightType::gaussian})
    check(parse_weight_type(to_string(type)) == type,
          "weight name round trip " + to_string(type));
  bool rejected = false;
  try
    {
      parse_weight_type("tophat");
    }
  catch (const std::exception &e)
    {
      rejected =
        std::string(e.what()).find("local|bell|gaussian") != std::string::npos;
    }
  check(rejected, "unknown weight rejected with the accepted names");

  // Cut-off radii: sqrt(7) l_c for the bell, 3 l_c for the Gaussian.
  check(close(WeightFunction(WeightType::bell, 0.18).cutoff_radius(),
              std::sqrt(7.) * 0.18,
              1e-15),
        "bell cut-off");
  check(WeightFunction(WeightType::gaussian, 0.18).cutoff_radius() == 3. * 0.18,
        "gaussian cut-off");
  check(WeightFunction(WeightType::bell, 0.18)
            .value_from_squared_distance(7. * 0.18 * 0.18) < 1e-30,
        "bell vanishes at R (up to the rounding of R^2)");

  std::cout << (n_failures == 0 ? "OK" : "FAILED") << std::endl;
  return n_failures == 0 ? 0 : 1;
}
