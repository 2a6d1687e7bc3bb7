// Helpers for the core tests: run a scene given as parameter text and look
// at its material points.
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
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

namespace scarp_test
{
  using namespace dealii;
  using namespace scarp;

  /// Build a simulation from parameter text (the same two passes as the
  /// scarp command line) and set it up. With @p communicator =
  /// MPI_COMM_SELF every rank builds its own serial copy of the scene (to
  /// compare a parallel run with a serial one).
  template <int dim>
  std::unique_ptr<simulation::Simulation<dim>>
  make_scene(const std::string &text,
             const MPI_Comm     communicator = MPI_COMM_WORLD)
  {
    const std::string filename =
      "scene_" +
      std::to_string(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD)) +
      ".prm";
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
    const simulation::Simulation<dim>                            &sim,
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
    const simulation::Simulation<dim>                            &sim,
    const std::function<double(const double *, const Point<dim> &)> &f)
  {
    double s = -1e300;
    for (const auto &particle : sim.particle_handler())
      s = std::max(s, f(particle.get_properties().data(), particle.get_location()));
    return Utilities::MPI::max(s, communicator_of(sim));
  }

  /// Print on rank 0.
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
} // namespace scarp_test

#endif
