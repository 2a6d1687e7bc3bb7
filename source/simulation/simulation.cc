// Simulation: construction and the stage loop (run, run_until). The
// other jobs are in simulation_parameters.cc, simulation_setup.cc,
// simulation_step.cc, simulation_refinement.cc, simulation_output.cc,
// simulation_cliff.cc and simulation_checkpoint.cc (doc/architecture.md).
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/filtered_iterator.h>
#include <deal.II/grid/grid_tools.h>

#include <scarp/base/exceptions.h>
#include <scarp/base/parameter_tools.h>
#include <scarp/grid/refinement_marker.h>
#include <scarp/materials/chalk.h>
#include <scarp/materials/material_factory.h>
#include <scarp/particles/body_seeder.h>
#include <scarp/scenes/shape_factory.h>
#include <scarp/simulation/simulation.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>

namespace scarp
{
  namespace simulation
  {
    template <int dim>
    Simulation<dim>::Simulation(MPI_Comm communicator, const SceneLists &lists)
      : communicator(communicator)
      , lists(lists)
      , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
      , timer(pcout, TimerOutput::never, TimerOutput::wall_times)
      , grid(communicator)
      , checkpoint(communicator)
    {
    }


    template <int dim>
    Simulation<dim>::~Simulation() = default;


    template <int dim>
    void
    Simulation<dim>::run_until(const double t)
    {
      outputs_enabled = false;
      if (!mpm)
        setup();
      Stage stage = stages.front();
      for (const auto &s : stages)
        if (loop.time < s.end_time)
          {
            stage = s;
            break;
          }
      stage.end_time = t;
      while (loop.time < t * (1 - 1e-12))
        advance(stage);
    }


    template <int dim>
    void
    Simulation<dim>::run()
    {
      if (Utilities::MPI::this_mpi_process(communicator) == 0)
        std::filesystem::create_directories(output_directory);
      MPI_Barrier(communicator);
      wall_clock.restart();
      setup();
      if (!checkpoint.resuming())
        run_setup_passes();
      pcout << "scarp: " << dim << "D, "
            << grid.triangulation().n_global_active_cells() << " cells, "
            << last_report.n_points << " material points on "
            << Utilities::MPI::n_mpi_processes(communicator) << " rank(s)"
            << std::endl;
      vtu = std::make_unique<postprocess::VtuOutput<dim>>(output_directory,
                                                          communicator);
      std::vector<std::string> columns{"step",
                                       "time",
                                       "dt",
                                       "stage",
                                       "kinetic_energy",
                                       "strain_energy",
                                       "gravitational_energy",
                                       "internal_work",
                                       "damping_dissipation",
                                       "boundary_dissipation",
                                       "transfer_dissipation",
                                       "plastic_dissipation",
                                       "damage_dissipation",
                                       "material_dissipation",
                                       "energy_residual",
                                       "momentum_x",
                                       "momentum_y",
                                       "momentum_z",
                                       "angular_momentum_x",
                                       "angular_momentum_y",
                                       "angular_momentum_z",
                                       "material_points",
                                       "mass",
                                       "max_speed",
                                       "max_damage",
                                       "damaged_volume",
                                       "wall_time"};
      if (body_force)
        columns.push_back("body_force_work");
      if (any_mass_scaling())
        columns.push_back("mass_scaling_dissipation");
      if (removes_points)
        columns.push_back("removed_energy");
      if (reference_displacement)
        columns.push_back("reference_error");
      for (const auto &name :
           grid.boundary_conditions().reaction_column_names())
        columns.push_back(name);
      // Resumed: statistics.csv and the PVD files as they were at the
      // checkpoint (the rows and outputs after it drop out), then appended.
      statistics = std::make_unique<postprocess::StatisticsFile>(
        output_directory + "/statistics.csv",
        columns,
        Utilities::MPI::this_mpi_process(communicator) == 0,
        checkpoint.resuming());
      if (checkpoint.resuming())
        {
          vtu->restore_records(restored_records);
          first_step = loop.step;
          first_time = loop.time;
          pcout << "Resumed from " << checkpoint.loaded_directory()
                << " at step " << loop.step << ", t = " << loop.time << " s"
                << std::endl;
        }
      else
        {
          // A history left by an earlier run in this directory goes.
          if (Utilities::MPI::this_mpi_process(communicator) == 0 &&
              outputs_enabled)
            std::filesystem::remove(output_directory + "/cliff_history.csv");
          write_statistics(last_report, stages.front());
          write_output();
          loop.next_output = output_interval;
          loop.stage.index = 0;
        }
      checkpoint.start();

      for (; loop.stage.index < stages.size(); ++loop.stage.index)
        {
          const Stage &stage = stages[loop.stage.index];
          if (!loop.stage.in_progress)
            {
              loop.stage.start_time      = loop.time;
              loop.stage.start_step      = loop.step;
              loop.stage.peak_kinetic    = 0;
              loop.stage.settled_since   = -1;
              loop.stage.in_progress     = true;
              loop.mass_scaling.ended    = false;
              loop.mass_scaling.end_time = -1;
              loop.deposit               = DepositRestState();
            }
          const double start_wall = wall_clock.wall_time();
          std::string  reason     = "end time";
          pcout << "Stage " << stage.name << " (to t = " << stage.end_time
                << " s)" << std::endl;
          if (cliff && stage.damage && loop.failure.damage_stage_start < 0)
            {
              loop.failure.damage_stage_start = loop.time;
              cliff_snapshot("start");
            }
          while (loop.time < stage.end_time * (1 - 1e-12))
            {
              advance(stage);
              if (loop.step % statistics_interval == 0)
                write_statistics(last_report, stage);
              if (output_interval > 0 &&
                  loop.time >= loop.next_output * (1 - 1e-12))
                {
                  write_output();
                  while (loop.next_output <= loop.time * (1 + 1e-12))
                    loop.next_output += output_interval;
                }
              print_progress(last_report, stage, false);
              if (loop.failure.onset_time >= 0 && after_failure_delay >= 0 &&
                  !loop.failure.after_failure_taken &&
                  loop.time >= loop.failure.onset_time + after_failure_delay)
                {
                  loop.failure.after_failure_taken = true;
                  cliff_snapshot("after_failure");
                  if (stop_after_failure)
                    {
                      reason = "stopped after failure";
                      break;
                    }
                }
              if (stage.settle && stage_settled(stage))
                {
                  reason = "kinetic energy settled";
                  break;
                }
              if (stage.deposit_rest && deposit_settled(stage))
                {
                  reason = "deposit at rest";
                  break;
                }
              checkpoint_if_due();
            }
          if (stage.reset_displacement)
            for (auto &particle : particles)
              layout.set_vector(particle.get_properties().data(),
                                layout.reference_position,
                                particle.get_location());
          write_statistics(last_report, stage);
          write_output();
          print_progress(last_report, stage, true);
          stage_summaries.add(
            stage.name,
            stage_record(stage, reason, wall_clock.wall_time() - start_wall));
          pcout << "Stage " << stage.name << " ended (" << reason
                << ") at t = " << loop.time << " s after "
                << loop.step - loop.stage.start_step << " steps" << std::endl;
          loop.stage.in_progress = false;
          if (loop.failure.after_failure_taken && stop_after_failure)
            break;
          if (checkpoint.at_stage_ends() &&
              loop.stage.index + 1 < stages.size())
            write_checkpoint();
        }
      // The points in the handler's order for whoever reads them after the
      // run (particle_handler()).
      order_points();
      gather_part_statistics();
      if (cliff && loop.failure.after_failure_taken && stop_after_failure)
        {
          // The debris is still moving: only the onset means something.
          const double onset =
            loop.failure.onset_time - loop.failure.damage_stage_start;
          cliff_summary.add("failure_onset_s", onset);
          cliff_summary.add("max_damage", last_report.max_damage);
          pcout << "Cliff: failure onset " << onset
                << " s after the start of damage; stopped "
                << after_failure_delay << " s later (no debris diagnostics)"
                << std::endl;
          write_summary("stopped after failure");
        }
      else
        {
          if (cliff)
            cliff_snapshot("end");
          write_summary("completed");
        }
      timer.print_wall_time_statistics(communicator);
      print_part_statistics();
      pcout << "Wall time " << format_seconds(wall_clock.wall_time()) << ", "
            << loop.step << " steps";
      if (first_step > 0)
        pcout << " (" << loop.step - first_step << " in this run)";
      pcout << ", "
            << last_report.n_points * (loop.step - first_step) /
                 std::max(wall_clock.wall_time(), 1e-9)
            << " particle-steps/s. Output in " << output_directory << "/"
            << std::endl;
    }


    template <int dim>
    bool
    Simulation<dim>::stage_settled(const Stage &stage)
    {
      loop.stage.peak_kinetic =
        std::max(loop.stage.peak_kinetic, last_report.kinetic_energy);
      const bool quiet = loop.step - loop.stage.start_step > 20 &&
                         last_report.kinetic_energy <=
                           stage.kinetic_ratio * loop.stage.peak_kinetic;
      if (!quiet)
        loop.stage.settled_since = -1;
      else if (loop.stage.settled_since < 0)
        loop.stage.settled_since = loop.time;
      return quiet && loop.time - loop.stage.settled_since >= stage.settle_time;
    }


    template <int dim>
    void
    Simulation<dim>::run_setup_passes()
    {
      const Stage &stage   = stages.front();
      const bool   outputs = outputs_enabled;
      outputs_enabled      = false;
      for (unsigned int pass = 1; pass <= grid.setup_passes; ++pass)
        {
          const unsigned int passes_before = loop.counters.refinement_passes;
          const double       start_wall    = wall_clock.wall_time();
          loop.stage.in_progress           = true;
          while (loop.time < stage.end_time * (1 - 1e-12))
            {
              advance(stage);
              if (stage.settle && stage_settled(stage))
                break;
            }
          const unsigned int refined =
            loop.counters.refinement_passes - passes_before;
          pcout << "Set-up pass " << pass << ": stage " << stage.name << ", "
                << loop.step << " steps to t = " << loop.time << " s, "
                << refined << " refinement passes, "
                << grid.triangulation().n_global_active_cells() << " cells ("
                << format_seconds(wall_clock.wall_time() - start_wall) << ")"
                << std::endl;
          // The points of the pass are discarded in any case: the run proper
          // starts from the seeding, not from a loaded state.
          RunCounters counters = loop.counters;
          ++counters.setup_passes;
          counters.setup_steps += loop.step;
          counters.refinement_checks = 0;
          counters.refinement_passes = 0;
          counters.points_split      = 0;
          particles.clear();
          seed_bodies();
          if (Utilities::MPI::n_mpi_processes(communicator) > 1)
            balance_load();
          mpm->setup();
          local_boxes.clear();
          precursor_ids.clear();
          if (averager)
            averager->invalidate_neighbour_lists();
          start_loop_state();
          loop.counters = counters;
          pcout << "Set-up pass " << pass << ": bodies seeded anew, "
                << static_cast<unsigned long long>(last_report.n_points)
                << " material points" << std::endl;
          if (refined == 0)
            break;
        }
      outputs_enabled = outputs;
    }


    template class Simulation<2>;
    template class Simulation<3>;
  } // namespace simulation
} // namespace scarp
