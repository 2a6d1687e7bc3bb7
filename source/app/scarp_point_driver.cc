// scarp_point_driver: drive one material point along a deformation path and
// write the stress-strain curve as CSV (calibration; doc/materials.md).

#include <deal.II/base/parameter_handler.h>

#include <scarp/base/exceptions.h>
#include <scarp/base/parameter_tools.h>
#include <scarp/materials/material_factory.h>
#include <scarp/materials/point_driver.h>

#include <cstring>
#include <fstream>
#include <iostream>

using namespace dealii;
using namespace scarp::materials;

namespace
{
  void
  declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Material");
    MaterialFactory::declare_parameters(prm);
    prm.leave_subsection();
    prm.enter_subsection("Path");
    PointDriver::Parameters::declare_parameters(prm);
    prm.leave_subsection();
  }
} // namespace

int
main(int argc, char **argv)
{
  ParameterHandler prm;
  declare(prm);
  if (argc == 2 && std::strcmp(argv[1], "--print-parameters") == 0)
    {
      prm.print_parameters(std::cout, ParameterHandler::PRM);
      return 0;
    }
  if (argc != 2)
    {
      std::cerr << "Usage: " << argv[0] << " <file.prm> | --print-parameters\n";
      return 2;
    }
  try
    {
      // The scene reader's parser: includes relative to the including
      // file, errors as one line with file, line, entry and what is
      // accepted.
      scarp::ParameterTools::parse_file(prm, argv[1]);

      prm.enter_subsection("Material");
      const std::unique_ptr<Material> material = MaterialFactory::create(prm);
      prm.leave_subsection();
      PointDriver::Parameters path;
      prm.enter_subsection("Path");
      path.parse_parameters(prm);
      prm.leave_subsection();

      const PointDriver driver(*material, path);
      const auto        records = driver.run();
      std::ofstream     out(path.output_file);
      AssertThrow(out,
                  ExcMessage("Cannot write 'Output file' " + path.output_file +
                             "."));
      PointDriver::write_csv(records, out);
      std::cout << "Wrote " << records.size() << " rows to " << path.output_file
                << '\n';
    }
  catch (const scarp::ScarpError &exc)
    {
      std::cerr << "scarp_point_driver: error: " << exc.what() << std::endl;
      return 1;
    }
  catch (const std::exception &exc)
    {
      std::cerr << "scarp_point_driver: error in " << argv[1] << ":\n"
                << exc.what() << std::endl;
      return 1;
    }
  return 0;
}
