// The scarp command line:
//   scarp [--help | --print-parameters [format] | --resume DIR] scene.prm
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <scarp/base/exceptions.h>
#include <scarp/base/parameter_tools.h>
#include <scarp/simulation/scene_lists.h>
#include <scarp/simulation/simulation.h>

#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

namespace
{
  using namespace dealii;
  using namespace scarp;

  void
  print_help()
  {
    std::cout
      << "scarp: explicit material point method for brittle cliff collapse\n"
         "\n"
         "Usage:\n"
         "  scarp scene.prm                  run a scene\n"
         "  mpirun -np N scarp scene.prm     the same on N MPI ranks\n"
         "  scarp --resume DIR scene.prm     resume the scene from the\n"
         "                                   checkpoint DIR (a checkpoint\n"
         "                                   directory, or the output\n"
         "                                   directory that holds one), on\n"
         "                                   any number of ranks\n"
         "  scarp --print-parameters [FORMAT] [--dimension D]\n"
         "                                   print every entry with its\n"
         "                                   documentation, default and\n"
         "                                   accepted values; FORMAT is prm\n"
         "                                   (default), json or description\n"
         "  scarp --help                     this text\n"
         "\n"
         "A run writes to its <Output directory>: particles_*.vtu/pvtu and\n"
         "particles.pvd, mesh_*.vtu/pvtu and mesh.pvd (open the .pvd files\n"
         "in ParaView), statistics.csv and summary.json, and checkpoints\n"
         "in checkpoint/ (at the end of each stage, at <Checkpoint>\n"
         "intervals, and on SIGTERM or SIGINT, after which the run stops\n"
         "with exit status 1).\n";
  }


  template <int dim>
  void
  run_scene(const std::string            &filename,
            const simulation::SceneLists &lists,
            const std::string            &resume)
  {
    ParameterHandler prm;
    simulation::Simulation<dim>::declare_parameters(prm, lists);
    ParameterTools::parse_file(prm, filename);
    simulation::Simulation<dim> sim(MPI_COMM_WORLD, lists);
    if (!resume.empty())
      sim.set_resume_directory(resume);
    sim.parse_parameters(prm);
    sim.run();
  }


  void
  print_parameters(const std::string &format, const unsigned int dim)
  {
    simulation::SceneLists lists;
    lists.dimension = dim;
    ParameterHandler prm;
    if (dim == 2)
      simulation::Simulation<2>::declare_parameters(prm, lists);
    else
      simulation::Simulation<3>::declare_parameters(prm, lists);
    const auto style = format == "json"          ? ParameterHandler::JSON
                       : format == "description" ? ParameterHandler::Description
                                                 : ParameterHandler::PRM;
    prm.print_parameters(std::cout, style);
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool is_root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  // deal.II's own error texts name the entry and the accepted values; the
  // stack trace they would add helps nobody who mistyped a parameter.
  deal_II_exceptions::disable_abort_on_exception();
  deal_II_exceptions::suppress_stacktrace_in_exceptions();
  try
    {
      std::vector<std::string> args(argv + 1, argv + argc);
      if (args.empty() || args[0] == "--help" || args[0] == "-h")
        {
          if (is_root)
            print_help();
          return args.empty() ? 1 : 0;
        }
      if (args[0] == "--print-parameters")
        {
          std::string  format = "prm";
          unsigned int dim    = 2;
          for (std::size_t k = 1; k < args.size(); ++k)
            if (args[k] == "--dimension" && k + 1 < args.size())
              dim = std::stoi(args[++k]);
            else
              format = args[k];
          if (format != "prm" && format != "json" && format != "description")
            throw ScarpError("unknown format <" + format +
                             "> for --print-parameters: use prm, json or "
                             "description.");
          if (dim != 2 && dim != 3)
            throw ScarpError("--dimension must be 2 or 3.");
          if (is_root)
            print_parameters(format, dim);
          return 0;
        }
      std::string resume;
      if (args[0] == "--resume")
        {
          if (args.size() < 2)
            throw ScarpError("--resume needs a checkpoint directory; see "
                             "scarp --help.");
          resume = args[1];
          args.erase(args.begin(), args.begin() + 2);
        }
      if (args.size() != 1 || args[0].rfind("-", 0) == 0)
        throw ScarpError("expected one scene file; see scarp --help.");
      // An unreadable file is reported by the parser, in the format of
      // every other input error.
      const std::string filename = args[0];
      const auto        lists    = simulation::SceneLists::read(filename);
      if (lists.dimension == 2)
        run_scene<2>(filename, lists, resume);
      else
        run_scene<3>(filename, lists, resume);
    }
  catch (const ScarpError &e)
    {
      if (is_root)
        std::cerr << "\nscarp: error: " << e.what() << std::endl;
      return 1;
    }
  catch (const ExceptionBase &e)
    {
      // Input errors arrive as ScarpError with a readable line; a deal.II
      // exception here is a bug or an unforeseen case: its own text (not
      // what() with the source location and exception name) is what helps.
      if (is_root)
        {
          std::ostringstream info;
          e.print_info(info);
          std::cerr << "\nscarp: error: " << Utilities::trim(info.str())
                    << std::endl;
        }
      return 1;
    }
  catch (const std::exception &e)
    {
      if (is_root)
        std::cerr << "\nscarp: error: " << e.what() << std::endl;
      return 1;
    }
  return 0;
}
