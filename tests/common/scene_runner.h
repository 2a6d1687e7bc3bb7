// The helpers every scene test shares (core, chalk, methods, layout,
// refinement): scene text numbers and the mesh subsection, building a scene
// from parameter text on a communicator, sums and maxima over its material
// points, output and checks on rank 0, and the case dispatcher of the test
// executables. Keep them here only, so that all tests build and judge scenes
// the same way.
#ifndef scarp_tests_scene_runner_h
#define scarp_tests_scene_runner_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <scarp/base/parameter_tools.h>
#include <scarp/simulation/scene_lists.h>
#include <scarp/simulation/simulation.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace scarp_test
{
  using namespace dealii;
  using namespace scarp;

  /// A number as scene text, without loss.
  inline std::string
  num(const double x)
  {
    std::ostringstream o;
    o << std::setprecision(17) << x;
    return o.str();
  }

  /// "a, b[, c]" from numbers.
  inline std::string
  list(const std::vector<double> &x)
  {
    std::string s;
    for (const double v : x)
      s += (s.empty() ? "" : ", ") + num(v);
    return s;
  }

  /// Mesh subsection; @p faces: Left, Right, Bottom, Top[, Front, Back].
  /// @p boundary_entries go into the boundary subsection after the faces
  /// (e.g. a friction coefficient).
  inline std::string
  mesh_text(const std::vector<double>      &lower,
            const std::vector<double>      &upper,
            const double                    h,
            const std::vector<std::string> &faces,
            const std::string              &boundary_entries = "")
  {
    static const char *names[] = {
      "Left", "Right", "Bottom", "Top", "Front", "Back"};
    std::string s = "subsection Mesh\n  set Lower corner = " + list(lower) +
                    "\n  set Upper corner = " + list(upper) +
                    "\n  set Cell size = " + num(h) +
                    "\n  subsection Boundary conditions\n";
    for (unsigned int f = 0; f < faces.size(); ++f)
      s += "    set " + std::string(names[f]) + " = " + faces[f] + "\n";
    return s + boundary_entries + "  end\nend\n";
  }

  /// Build a simulation from parameter text (the same two passes as the
  /// scarp command line) and set it up. With @p communicator =
  /// MPI_COMM_SELF every rank builds its own serial copy of the scene (to
  /// compare a parallel run with a serial one). @p tag names the scene file
  /// (tag_rank.prm), so that scenes built one after another, or tests
  /// running at the same time in one directory, do not share a file.
  template <int dim>
  std::unique_ptr<simulation::Simulation<dim>>
  make_scene(const std::string &text,
             const MPI_Comm     communicator = MPI_COMM_WORLD,
             const std::string &tag          = "scene")
  {
    const std::string filename =
      tag + "_" +
      std::to_string(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD)) + ".prm";
    {
      std::ofstream file(filename);
      file << text;
    }
    const auto       lists = simulation::SceneLists::read(filename);
    ParameterHandler prm;
    simulation::Simulation<dim>::declare_parameters(prm, lists);
    ParameterTools::parse_file(prm, filename);
    auto sim =
      std::make_unique<simulation::Simulation<dim>>(communicator, lists);
    sim->parse_parameters(prm);
    sim->setup();
    return sim;
  }

  /// The message of the @p Exception that @p f throws, "" if it throws
  /// none (any other exception passes through and fails the test): a test
  /// of a refusal checks that the message names the cause.
  template <typename Exception = std::exception>
  std::string
  error_message(const std::function<void()> &f)
  {
    try
      {
        f();
      }
    catch (const Exception &e)
      {
        return e.what();
      }
    return "";
  }

  /// The message of the @p Exception with which the scene of @p text is
  /// refused while it is read or set up, "" if it is accepted.
  template <int dim, typename Exception = std::exception>
  std::string
  refusal_message(const std::string &text,
                  const MPI_Comm     communicator = MPI_COMM_WORLD,
                  const std::string &tag          = "refused")
  {
    return error_message<Exception>(
      [&]() { make_scene<dim>(text, communicator, tag); });
  }

  /// The communicator a simulation runs on.
  template <int dim>
  MPI_Comm
  communicator_of(const simulation::Simulation<dim> &sim)
  {
    return sim.background_grid().dof_handler().get_communicator();
  }

  /// Sum over all points (all ranks of the simulation) of
  /// f(properties, location).
  template <int dim>
  double
  sum_over_points(
    const simulation::Simulation<dim>                               &sim,
    const std::function<double(const double *, const Point<dim> &)> &f)
  {
    double s = 0;
    for (const auto &particle : sim.particle_handler())
      s += f(particle.get_properties().data(), particle.get_location());
    return Utilities::MPI::sum(s, communicator_of(sim));
  }

  /// Max over all points (all ranks of the simulation) of
  /// f(properties, location).
  template <int dim>
  double
  max_over_points(
    const simulation::Simulation<dim>                               &sim,
    const std::function<double(const double *, const Point<dim> &)> &f)
  {
    double s = -1e300;
    for (const auto &particle : sim.particle_handler())
      s =
        std::max(s,
                 f(particle.get_properties().data(), particle.get_location()));
    return Utilities::MPI::max(s, communicator_of(sim));
  }

  /// Print on rank 0 of MPI_COMM_WORLD.
  inline std::ostream &
  out()
  {
    static std::ostringstream sink;
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      return std::cout;
    sink.str("");
    return sink;
  }

  /// Fail the test (non-zero exit on all ranks) unless @p condition.
  inline void
  check(const bool condition, const std::string &what)
  {
    const bool all = Utilities::MPI::min(condition ? 1 : 0, MPI_COMM_WORLD);
    out() << (all ? "  ok:   " : "  FAIL: ") << what << std::endl;
    if (!all)
      {
        MPI_Finalize();
        std::exit(1);
      }
  }

  /// Run the named case of @p cases (argv[1]); all of them without one.
  /// Further arguments go to the case.
  inline int
  run_cases_with_args(
    int    argc,
    char **argv,
    const std::map<std::string,
                   std::function<void(const std::vector<std::string> &)>>
      &cases)
  {
    Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
    try
      {
        std::vector<std::string> args;
        for (int k = 2; k < argc; ++k)
          args.push_back(argv[k]);
        if (argc > 1)
          {
            const auto c = cases.find(argv[1]);
            if (c == cases.end())
              {
                std::cerr << "unknown case " << argv[1] << std::endl;
                return 1;
              }
            c->second(args);
          }
        else
          for (const auto &[name, f] : cases)
            {
              out() << "== " << name << std::endl;
              f(args);
            }
      }
    catch (const std::exception &e)
      {
        std::cerr << "exception: " << e.what() << std::endl;
        return 1;
      }
    return 0;
  }

  /// The same for cases that take no arguments. Not an overload of the
  /// above: a braced list of cases would then also try std::map's
  /// comparator constructor and warn about missing braces.
  inline int
  run_cases(int                                                 argc,
            char                                              **argv,
            const std::map<std::string, std::function<void()>> &cases)
  {
    std::map<std::string, std::function<void(const std::vector<std::string> &)>>
      with_args;
    for (const auto &[name, f] : cases)
      with_args[name] = [f](const std::vector<std::string> &) { f(); };
    return run_cases_with_args(argc, argv, with_args);
  }
} // namespace scarp_test

#endif
