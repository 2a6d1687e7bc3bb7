// Simulation: what a run reports (VTU output, statistics.csv, the
// progress line, summary.json, the error against a reference solution).
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
#include <scarp/postprocess/run_progress.h>
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
    std::string
    format_seconds(const double s)
    {
      const long         t = static_cast<long>(s + 0.5);
      std::ostringstream o;
      o << std::setfill('0') << std::setw(2) << t / 3600 << ":" << std::setw(2)
        << (t / 60) % 60 << ":" << std::setw(2) << t % 60;
      return o.str();
    }


    template <int dim>
    double
    Simulation<dim>::reference_error(double *norm) const
    {
      if (!reference_displacement)
        return -1;
      reference_displacement->set_time(loop.time);
      double sums[3] = {0, 0, 0};
      for (const auto &particle : particles)
        {
          const double    *p = particle.get_properties().data();
          const Point<dim> X(layout.get_vector(p, layout.reference_position));
          const double     V0 = p[layout.reference_volume];
          double           e2 = 0, u2 = 0;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double u = reference_displacement->value(X, d);
              const double e = particle.get_location()[d] - X[d] - u;
              e2 += e * e;
              u2 += u * u;
            }
          sums[0] += V0 * e2;
          sums[1] += V0 * u2;
          sums[2] += V0;
        }
      Utilities::MPI::sum(ArrayView<const double>(sums, 3),
                          communicator,
                          ArrayView<double>(sums, 3));
      if (norm)
        *norm = std::sqrt(sums[1] / std::max(sums[2], 1e-300));
      return std::sqrt(sums[0] / std::max(sums[2], 1e-300));
    }


    template <int dim>
    void
    Simulation<dim>::write_output()
    {
      if (!outputs_enabled)
        return;
      TimerOutput::Scope scope(timer, "output");
      order_points();
      vtu->write_particles(particles, layout, loop.time, loop.output_index);
      if (write_mesh_files)
        vtu->write_mesh(grid,
                        mpm->nodal_mass(),
                        mpm->nodal_velocity(),
                        loop.time,
                        loop.output_index);
      write_cliff_history();
      ++loop.output_index;
    }


    template <int dim>
    void
    Simulation<dim>::write_statistics(const transfer::StepReport &r,
                                      const Stage                &stage)
    {
      (void)stage;
      if (!statistics)
        return;
      const double material_dissipation =
        loop.energy.internal_work - r.stored_energy;
      std::vector<double> row({double(loop.step),
                               loop.time,
                               loop.dt,
                               double(loop.stage.index),
                               r.kinetic_energy,
                               r.stored_energy,
                               r.gravitational_energy,
                               loop.energy.internal_work,
                               loop.energy.damping_dissipation,
                               loop.energy.boundary_dissipation,
                               loop.energy.transfer_dissipation,
                               r.plastic_dissipation,
                               r.damage_dissipation,
                               material_dissipation,
                               loop.energy.residual,
                               r.momentum[0],
                               r.momentum[1],
                               r.momentum[2],
                               r.angular_momentum[0],
                               r.angular_momentum[1],
                               r.angular_momentum[2],
                               r.n_points,
                               r.mass,
                               r.max_speed,
                               r.max_damage,
                               r.damaged_volume,
                               wall_clock.wall_time()});
      if (body_force)
        row.push_back(loop.energy.body_force_work);
      if (any_mass_scaling())
        row.push_back(loop.energy.mass_scaling_dissipation);
      if (removes_points)
        row.push_back(loop.energy.removed_energy);
      if (reference_displacement)
        {
          double norm = 0;
          order_points();
          const double e            = reference_error(&norm);
          loop.reference_error.last = e;
          loop.reference_error.max  = std::max(loop.reference_error.max, e);
          loop.reference_error.norm_max =
            std::max(loop.reference_error.norm_max, norm);
          row.push_back(e);
        }
      if (grid.boundary_conditions().has_prescribed_velocity())
        {
          const auto f = grid.boundary_conditions().take_reaction(communicator);
          for (unsigned int d = 0; d < dim; ++d)
            row.push_back(f[d]);
        }
      statistics->write_row(row);
    }


    template <int dim>
    void
    Simulation<dim>::print_progress(const transfer::StepReport &r,
                                    const Stage                &stage,
                                    const bool                  force)
    {
      const double wall = wall_clock.wall_time();
      if (!force && wall - last_progress_wall < 2.)
        return;
      last_progress_wall = wall;
      // Of this run only: a resumed run counts from its checkpoint.
      const double eta = postprocess::remaining_wall_time(
        wall, first_time, loop.time, stages.back().end_time);
      pcout << "  " << std::setw(8) << stage.name << "  step " << std::setw(7)
            << loop.step << "  t = " << std::setw(10) << std::setprecision(5)
            << loop.time << " s  dt = " << std::setw(9) << std::setprecision(3)
            << loop.dt << " s  E_kin = " << std::setw(10) << r.kinetic_energy
            << " J  max d = " << std::setw(5) << std::setprecision(3)
            << r.max_damage << "  wall " << format_seconds(wall)
            << "  ETA <= " << format_seconds(eta) << std::endl;
    }


    template <int dim>
    void
    Simulation<dim>::gather_part_statistics()
    {
      if (!mpm)
        return;
      const auto &t     = mpm->part_times();
      auto        parts = t.named();
      parts.emplace_back("compute", t.compute());
      part_statistics.clear();
      for (const auto &[name, seconds] : parts)
        part_statistics.emplace_back(name,
                                     Utilities::MPI::min_max_avg(seconds,
                                                                 communicator));
    }


    template <int dim>
    void
    Simulation<dim>::print_part_statistics() const
    {
      if (part_statistics.empty())
        return;
      std::ostringstream table;
      table << "Parts of the MPM step, wall s over the ranks (exchange: the "
               "ghost rounds of P2G and the grid update, waits included)\n";
      table << std::left << std::setw(22) << "  part" << std::right
            << std::setw(10) << "min" << std::setw(6) << "rank" << std::setw(10)
            << "avg" << std::setw(10) << "max" << std::setw(6) << "rank"
            << "\n";
      for (const auto &[name, m] : part_statistics)
        table << "  " << std::left << std::setw(20) << name << std::right
              << std::fixed << std::setprecision(2) << std::setw(10) << m.min
              << std::setw(6) << m.min_index << std::setw(10) << m.avg
              << std::setw(10) << m.max << std::setw(6) << m.max_index << "\n";
      pcout << table.str() << std::flush;
    }


    template <int dim>
    void
    Simulation<dim>::write_summary(const std::string &how_it_ended)
    {
      if (!outputs_enabled ||
          Utilities::MPI::this_mpi_process(communicator) != 0)
        return;
      postprocess::JsonObject summary;
      summary.add("ended", how_it_ended);
      summary.add("dimension", double(dim));
      summary.add("mpi_ranks",
                  double(Utilities::MPI::n_mpi_processes(communicator)));
      summary.add("steps", double(loop.step));
      summary.add("load_rebalances", double(loop.counters.rebalances));
      if (grid.adaptive_refinement)
        {
          postprocess::JsonObject refinement;
          refinement.add("checks", double(loop.counters.refinement_checks));
          refinement.add("passes", double(loop.counters.refinement_passes));
          refinement.add("points_split", double(loop.counters.points_split));
          refinement.add("finest_cell", grid.minimum_cell_size());
          if (grid.setup_passes > 0)
            {
              refinement.add("setup_passes",
                             double(loop.counters.setup_passes));
              refinement.add("setup_steps", double(loop.counters.setup_steps));
            }
          summary.add("refinement", refinement);
        }
      summary.add("time", loop.time);
      summary.add("material_points", last_report.n_points);
      summary.add("cells",
                  double(grid.triangulation().n_global_active_cells()));
      summary.add("wall_time", wall_clock.wall_time());
      const double point_steps =
        last_report.n_points * double(loop.step - first_step);
      summary.add("particle_steps_per_second",
                  point_steps / std::max(wall_clock.wall_time(), 1e-9));
      postprocess::JsonObject energies;
      energies.add("kinetic", last_report.kinetic_energy);
      energies.add("strain", last_report.stored_energy);
      energies.add("gravitational", last_report.gravitational_energy);
      energies.add("internal_work", loop.energy.internal_work);
      energies.add("damping_dissipation", loop.energy.damping_dissipation);
      if (loop.energy.mass_scaling_dissipation != 0)
        energies.add("mass_scaling_dissipation",
                     loop.energy.mass_scaling_dissipation);
      energies.add("boundary_dissipation", loop.energy.boundary_dissipation);
      energies.add("transfer_dissipation", loop.energy.transfer_dissipation);
      if (removes_points)
        energies.add("removed_energy", loop.energy.removed_energy);
      if (body_force)
        energies.add("body_force_work", loop.energy.body_force_work);
      energies.add("plastic_dissipation", last_report.plastic_dissipation);
      energies.add("damage_dissipation", last_report.damage_dissipation);
      energies.add("balance_residual", loop.energy.residual);
      summary.add("energies", energies);
      postprocess::JsonObject phases;
      for (const auto &[name, seconds] :
           timer.get_summary_data(TimerOutput::total_wall_time))
        phases.add(name, seconds);
      summary.add("wall_time_per_phase", phases);
      // The parts of the MPM step (this rank's, as the phases above).
      if (mpm)
        {
          postprocess::JsonObject parts;
          for (const auto &[name, seconds] : mpm->part_times().named())
            parts.add(name, seconds);
          summary.add("mpm_step_parts", parts);
        }
      if (!part_statistics.empty())
        {
          postprocess::JsonObject over_ranks;
          for (const auto &[name, m] : part_statistics)
            {
              postprocess::JsonObject entry;
              entry.add("min", m.min);
              entry.add("min_rank", double(m.min_index));
              entry.add("avg", m.avg);
              entry.add("max", m.max);
              entry.add("max_rank", double(m.max_index));
              over_ranks.add(name, entry);
            }
          summary.add("mpm_step_parts_over_ranks", over_ranks);
        }
      // A run that ends inside a stage (interrupted, or stopped by an
      // error) still reports what that stage has measured so far: its
      // start, the end of its mass scaling, and the failure onset.
      const bool ended_inside_stage =
        how_it_ended != "completed" && how_it_ended != "stopped after failure";
      postprocess::JsonObject stages_so_far = stage_summaries;
      if (ended_inside_stage && loop.stage.in_progress &&
          loop.stage.index < stages.size())
        {
          const Stage &stage = stages[loop.stage.index];
          stages_so_far.add(stage.name,
                            stage_record(stage, "in progress", std::nullopt));
        }
      summary.add("stages", stages_so_far);
      if (cliff)
        {
          postprocess::JsonObject c = cliff_summary;
          if (ended_inside_stage && loop.failure.onset_time >= 0)
            c.add("failure_onset_s",
                  loop.failure.onset_time - loop.failure.damage_stage_start);
          summary.add("cliff", c);
        }
      summary.add("max_damage", last_report.max_damage);
      summary.add("first_damage_time", loop.failure.first_damage_time);
      summary.add("points_removed", loop.counters.points_removed);
      if (averager)
        {
          // How often the non-local lists were rebuilt, patched after
          // points changed ranks, reused as they were, or reused for the
          // same points in a new order.
          postprocess::JsonObject lists;
          lists.add("rebuilds", double(averager->n_rebuilds()));
          lists.add("patches", double(averager->n_patches()));
          lists.add("reuses", double(averager->n_reuses()));
          lists.add("reorders", double(averager->n_reorders()));
          summary.add("nonlocal_lists", lists);
        }
      if (reference_displacement)
        {
          postprocess::JsonObject ref;
          ref.add("final", loop.reference_error.last);
          ref.add("max", loop.reference_error.max);
          ref.add("norm_max", loop.reference_error.norm_max);
          ref.add("relative_max",
                  loop.reference_error.max /
                    std::max(loop.reference_error.norm_max, 1e-300));
          summary.add("reference_error", ref);
        }
      summary.write(output_directory + "/summary.json");
    }


    template <int dim>
    postprocess::JsonObject
    Simulation<dim>::stage_record(const Stage                 &stage,
                                  const std::string           &end_reason,
                                  const std::optional<double> &wall_time) const
    {
      postprocess::JsonObject s;
      s.add("end_reason", end_reason);
      s.add("start_time", loop.stage.start_time);
      s.add("end_time", loop.time);
      if (wall_time)
        {
          s.add("steps", double(loop.step - loop.stage.start_step));
          s.add("wall_time", *wall_time);
          s.add("kinetic_energy", last_report.kinetic_energy);
        }
      if (stage.mass_scaling > 1)
        {
          s.add("mass_scaling", stage.mass_scaling);
          s.add("mass_scaling_end_time", loop.mass_scaling.end_time);
        }
      return s;
    }


    // Instantiations (the other members are in the other
    // simulation_*.cc files).
    template double
    Simulation<2>::reference_error(double *norm) const;
    template double
    Simulation<3>::reference_error(double *norm) const;
    template void
    Simulation<2>::write_output();
    template void
    Simulation<3>::write_output();
    template void
    Simulation<2>::write_statistics(const transfer::StepReport &r,
                                    const Stage                &stage);
    template void
    Simulation<3>::write_statistics(const transfer::StepReport &r,
                                    const Stage                &stage);
    template void
    Simulation<2>::print_progress(const transfer::StepReport &r,
                                  const Stage                &stage,
                                  const bool                  force);
    template void
    Simulation<3>::print_progress(const transfer::StepReport &r,
                                  const Stage                &stage,
                                  const bool                  force);
    template void
    Simulation<2>::gather_part_statistics();
    template void
    Simulation<2>::print_part_statistics() const;
    template void
    Simulation<3>::print_part_statistics() const;
    template void
    Simulation<3>::gather_part_statistics();
    template void
    Simulation<2>::write_summary(const std::string &how_it_ended);
    template void
    Simulation<3>::write_summary(const std::string &how_it_ended);
    template postprocess::JsonObject
    Simulation<2>::stage_record(const Stage                 &stage,
                                const std::string           &end_reason,
                                const std::optional<double> &wall_time) const;
    template postprocess::JsonObject
    Simulation<3>::stage_record(const Stage                 &stage,
                                const std::string           &end_reason,
                                const std::optional<double> &wall_time) const;
  } // namespace simulation
} // namespace scarp
