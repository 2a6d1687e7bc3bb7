// Simulation: the cliff snapshots (points gathered on rank 0, written as
// CSV; at the end the profile and the cliff diagnostics).
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

#include <array>
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
    std::vector<postprocess::CliffDiagnostics::Particle>
    Simulation<dim>::gather_cliff_points()
    {
      order_points();
      std::vector<double> local;
      for (const auto &particle : particles)
        {
          const double *p = particle.get_properties().data();
          if (!bodies[static_cast<unsigned int>(p[layout.body_id])].cliff)
            continue;
          const auto &m =
            *materials[static_cast<unsigned int>(p[layout.material_id])];
          const Point<dim> x = particle.get_location();
          const double     J =
            determinant(layout.get_matrix(p, layout.deformation_gradient));
          local.insert(local.end(),
                       {x[0],
                        x[1],
                        p[layout.reference_position],
                        p[layout.reference_position + 1],
                        p[layout.reference_volume] * J,
                        p[layout.reference_volume],
                        m.damage(p + layout.state)});
        }
      const auto all = Utilities::MPI::gather(communicator, local, 0);
      std::vector<postprocess::CliffDiagnostics::Particle> points;
      for (const auto &chunk : all)
        for (std::size_t k = 0; k + 6 < chunk.size(); k += 7)
          {
            postprocess::CliffDiagnostics::Particle q;
            q.position         = Point<2>(chunk[k], chunk[k + 1]);
            q.initial_position = Point<2>(chunk[k + 2], chunk[k + 3]);
            q.volume           = chunk[k + 4];
            q.reference_volume = chunk[k + 5];
            q.damage           = chunk[k + 6];
            points.push_back(q);
          }
      return points;
    }


    template <int dim>
    void
    Simulation<dim>::cliff_snapshot(const std::string &tag)
    {
      if (!outputs_enabled || !cliff || dim != 2)
        return;
      TimerOutput::Scope scope(timer, "cliff diagnostics");
      const auto         points = gather_cliff_points();
      if (Utilities::MPI::this_mpi_process(communicator) != 0)
        return;
      postprocess::CliffDiagnostics::write_particles_csv(
        output_directory + "/cliff_" + tag + "_particles.csv", points);
      if (tag != "end")
        return;
      const auto profile = cliff_surface_profile(points);
      const auto r       = cliff_diagnostics.analyse(profile, points, *cliff);
      postprocess::CliffDiagnostics::write_profile_csv(
        output_directory + "/cliff_profile.csv", profile, &r);
      const double onset =
        loop.failure.onset_time >= 0
          ? loop.failure.onset_time - loop.failure.damage_stage_start
          : -1;
      cliff_summary.add("debris_angle_deg", r.debris_angle);
      cliff_summary.add("run_out_m", r.run_out);
      cliff_summary.add("debris_toe_x_m", r.debris_toe);
      cliff_summary.add("failed_area_m2", r.failed_area);
      cliff_summary.add("failed_reference_area_m2", r.failed_reference_area);
      cliff_summary.add("scarp_position_x_m", r.scarp_position);
      cliff_summary.add("scarp_retreat_m", r.scarp_retreat);
      cliff_summary.add("failed_mass_centroid_x_m", r.failed_mass_centroid);
      cliff_summary.add("failed_mass_x95_m", r.failed_mass_x95);
      cliff_summary.add("failed_mass_x99_m", r.failed_mass_x99);
      cliff_summary.add("mass_run_out_m", r.mass_run_out);
      cliff_summary.add("failure_onset_s", onset);
      cliff_summary.add("max_damage", last_report.max_damage);
      cliff_summary.add("dissipated_energy_J",
                        last_report.plastic_dissipation +
                          last_report.damage_dissipation);
      cliff_summary.add("plastic_dissipation_J",
                        last_report.plastic_dissipation);
      cliff_summary.add("damage_dissipation_J", last_report.damage_dissipation);
      std::ostringstream s;
      s << std::setprecision(4) << "Cliff: debris angle " << r.debris_angle
        << " deg, run-out " << r.run_out << " m, failed area " << r.failed_area
        << " m^2 (" << r.failed_reference_area
        << " m^2 before it moved), scarp at x = " << r.scarp_position
        << " m, failure onset " << onset << " s after the start of damage, "
        << "max damage " << last_report.max_damage << ", dissipated "
        << last_report.plastic_dissipation + last_report.damage_dissipation
        << " J/m";
      if (r.failed_reference_area > 0.)
        s << "\nCliff: failed mass centroid at x = " << r.failed_mass_centroid
          << " m, 95 and 99 % of it landward of x = " << r.failed_mass_x95
          << " and " << r.failed_mass_x99 << " m (mass run-out "
          << r.mass_run_out << " m)";
      std::cout << s.str() << std::endl;
    }


    template <int dim>
    void
    Simulation<dim>::write_cliff_history()
    {
      if (!outputs_enabled || !cliff || dim != 2 ||
          !cliff_diagnostics.get_parameters().write_history)
        return;
      TimerOutput::Scope scope(timer, "cliff diagnostics");
      const auto         points = gather_cliff_points();
      if (Utilities::MPI::this_mpi_process(communicator) != 0)
        return;
      postprocess::CliffDiagnostics::append_history_row(
        output_directory + "/cliff_history.csv",
        loop.time,
        last_report.kinetic_energy,
        last_report.max_speed,
        cliff_diagnostics.analyse(cliff_surface_profile(points),
                                  points,
                                  *cliff));
    }


    template <int dim>
    bool
    Simulation<dim>::deposit_settled(const Stage &stage)
    {
      auto &state = loop.deposit;
      if (!cliff || dim != 2 || loop.failure.onset_time < 0)
        return false;
      // The checks fall on multiples of the interval (as the outputs do
      // on theirs), the first right after the onset.
      if (state.next_check < 0)
        state.next_check =
          std::floor(loop.time / stage.deposit_check_interval) *
          stage.deposit_check_interval;
      if (loop.time < state.next_check * (1 - 1e-12))
        return false;
      while (state.next_check <= loop.time * (1 + 1e-12))
        state.next_check += stage.deposit_check_interval;

      TimerOutput::Scope scope(timer, "cliff diagnostics");
      const auto         points = gather_cliff_points();
      // Rank 0 measures; every rank then holds the same state (it goes
      // into the checkpoints).
      std::array<double, 5> measured{{0, 0, 0, 0, 0}};
      if (Utilities::MPI::this_mpi_process(communicator) == 0)
        {
          const auto r =
            cliff_diagnostics.analyse(cliff_surface_profile(points),
                                      points,
                                      *cliff);
          // The toe or the scarp may be undefined (nan) in a measurement;
          // nan against nan is no change.
          const auto near = [](const double a, const double b, double tol) {
            return (std::isnan(a) && std::isnan(b)) || std::abs(a - b) <= tol;
          };
          const double tol = stage.deposit_shift_tolerance;
          const double rel = stage.deposit_area_tolerance;
          // Nothing has failed yet (no point has moved further than the
          // displacement threshold): the deposit is still to form.
          const bool quiet =
            r.failed_reference_area > 0. && state.since >= 0 &&
            near(r.debris_toe, state.toe, tol) &&
            near(r.scarp_position, state.scarp, tol) &&
            near(r.failed_area, state.area, rel * std::abs(state.area)) &&
            near(r.failed_reference_area,
                 state.area_before,
                 rel * std::abs(state.area_before));
          if (r.failed_reference_area <= 0.)
            measured = {{-1, 0, 0, 0, 0}};
          else if (quiet)
            measured = {{state.since,
                         state.toe,
                         state.scarp,
                         state.area,
                         state.area_before}};
          else
            measured = {{loop.time,
                         r.debris_toe,
                         r.scarp_position,
                         r.failed_area,
                         r.failed_reference_area}};
        }
      measured          = Utilities::MPI::broadcast(communicator, measured, 0);
      state.since       = measured[0];
      state.toe         = measured[1];
      state.scarp       = measured[2];
      state.area        = measured[3];
      state.area_before = measured[4];
      return state.since >= 0 &&
             loop.time - state.since >= stage.deposit_settle_time * (1 - 1e-12);
    }


    template <int dim>
    postprocess::CliffDiagnostics::Profile
    Simulation<dim>::cliff_surface_profile(
      const std::vector<postprocess::CliffDiagnostics::Particle> &points) const
    {
      return cliff_diagnostics.surface_profile(
        points,
        cliff->get_parameters().beach_level,
        grid.domain().lower_bound(0),
        grid.domain().upper_bound(0));
    }


    // Instantiations (the other members are in the other
    // simulation_*.cc files).
    template std::vector<postprocess::CliffDiagnostics::Particle>
    Simulation<2>::gather_cliff_points();
    template std::vector<postprocess::CliffDiagnostics::Particle>
    Simulation<3>::gather_cliff_points();
    template void
    Simulation<2>::cliff_snapshot(const std::string &tag);
    template void
    Simulation<3>::cliff_snapshot(const std::string &tag);
    template bool
    Simulation<2>::deposit_settled(const Stage &stage);
    template bool
    Simulation<3>::deposit_settled(const Stage &stage);
    template void
    Simulation<2>::write_cliff_history();
    template void
    Simulation<3>::write_cliff_history();
  } // namespace simulation
} // namespace scarp
