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
        if (current_time < s.end_time)
          {
            stage = s;
            break;
          }
      stage.end_time = t;
      while (current_time < t * (1 - 1e-12))
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
          pcout << "Resumed from " << checkpoint.loaded_directory()
                << " at step " << step << ", t = " << current_time << " s"
                << std::endl;
        }
      else
        {
          write_statistics(last_report, stages.front());
          write_output();
          next_output   = output_interval;
          current_stage = 0;
        }
      checkpoint.start();

      for (; current_stage < stages.size(); ++current_stage)
        {
          const Stage &stage = stages[current_stage];
          if (!stage_in_progress)
            {
              stage_start_time      = current_time;
              stage_start_step      = step;
              stage_peak_kinetic    = 0;
              settled_since         = -1;
              stage_in_progress     = true;
              mass_scaling_ended    = false;
              mass_scaling_end_time = -1;
            }
          const double       start_time = stage_start_time;
          const unsigned int start_step = stage_start_step;
          const double       start_wall = wall_clock.wall_time();
          std::string        reason     = "end time";
          pcout << "Stage " << stage.name << " (to t = " << stage.end_time
                << " s)" << std::endl;
          if (cliff && stage.damage && damage_stage_start < 0)
            {
              damage_stage_start = current_time;
              cliff_snapshot("start");
            }
          while (current_time < stage.end_time * (1 - 1e-12))
            {
              advance(stage);
              if (step % statistics_interval == 0)
                write_statistics(last_report, stage);
              if (output_interval > 0 &&
                  current_time >= next_output * (1 - 1e-12))
                {
                  write_output();
                  while (next_output <= current_time * (1 + 1e-12))
                    next_output += output_interval;
                }
              print_progress(last_report, stage, false);
              if (failure_time >= 0 && after_failure_delay >= 0 &&
                  !after_failure_taken &&
                  current_time >= failure_time + after_failure_delay)
                {
                  after_failure_taken = true;
                  cliff_snapshot("after_failure");
                  if (stop_after_failure)
                    {
                      reason = "stopped after failure";
                      break;
                    }
                }
              if (stage.settle)
                {
                  stage_peak_kinetic =
                    std::max(stage_peak_kinetic, last_report.kinetic_energy);
                  const bool quiet = step - start_step > 20 &&
                                     last_report.kinetic_energy <=
                                       stage.kinetic_ratio * stage_peak_kinetic;
                  if (!quiet)
                    settled_since = -1;
                  else if (settled_since < 0)
                    settled_since = current_time;
                  if (quiet &&
                      current_time - settled_since >= stage.settle_time)
                    {
                      reason = "kinetic energy settled";
                      break;
                    }
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
          postprocess::JsonObject s;
          s.add("end_reason", reason);
          s.add("start_time", start_time);
          s.add("end_time", current_time);
          s.add("steps", double(step - start_step));
          s.add("wall_time", wall_clock.wall_time() - start_wall);
          s.add("kinetic_energy", last_report.kinetic_energy);
          if (stage.mass_scaling > 1)
            {
              s.add("mass_scaling", stage.mass_scaling);
              s.add("mass_scaling_end_time", mass_scaling_end_time);
            }
          stage_summaries.add(stage.name, s);
          pcout << "Stage " << stage.name << " ended (" << reason
                << ") at t = " << current_time << " s after "
                << step - start_step << " steps" << std::endl;
          stage_in_progress = false;
          if (after_failure_taken && stop_after_failure)
            break;
          if (checkpoint.at_stage_ends() && current_stage + 1 < stages.size())
            write_checkpoint();
        }
      if (cliff && after_failure_taken && stop_after_failure)
        {
          // The debris is still moving: only the onset means something.
          const double onset = failure_time - damage_stage_start;
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
      pcout << "Wall time " << format_seconds(wall_clock.wall_time()) << ", "
            << step << " steps, "
            << last_report.n_points * step /
                 std::max(wall_clock.wall_time(), 1e-9)
            << " particle-steps/s. Output in " << output_directory << "/"
            << std::endl;
    }


    template class Simulation<2>;
    template class Simulation<3>;
  } // namespace simulation
} // namespace scarp
