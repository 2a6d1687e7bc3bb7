// Simulation: one time step (the MPM step, mass scaling, the non-local
// damage step, the sort) and its checks (stability, energy balance).
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
    transfer::StepReport
    Simulation<dim>::measure() const
    {
      transfer::StepReport report = mpm->measure(gravity);
      report.reduce(communicator);
      return report;
    }


    template <int dim>
    double
    Simulation<dim>::stable_time_step() const
    {
      double c = 0;
      for (const auto &m : materials)
        c = std::max(c, std::sqrt(m->p_wave_modulus() / m->density()));
      // Mass scaling slows the waves by the square root of its factor.
      return std::min(max_time_step,
                      cfl * grid.minimum_cell_size() /
                        (c / std::sqrt(loop.mass_scaling.inertia_scale) +
                         last_report.max_speed));
    }


    template <int dim>
    void
    Simulation<dim>::nonlocal_damage_step(const Stage &stage)
    {
      const bool gather_precursors = precursors_due(loop.step);
      if (!averager || !(stage.damage || gather_precursors))
        return;
      TimerOutput::Scope scope(timer, "non-local damage");
      // Between two averages (Update interval > 1) every point's damage is
      // driven by its last Ybar. The average is always taken at the first
      // step of a stage (the Ybar kept from before is not this stage's) and
      // for the refinement criterion. The rule depends on the step only, so
      // a restarted run repeats it.
      if (stage.damage && !gather_precursors && nonlocal_update_interval > 1 &&
          loop.step > loop.stage.start_step + 1 &&
          loop.step % nonlocal_update_interval != 0)
        {
          for (std::size_t k = 0; k < damage_points.position.size(); ++k)
            if (damage_points.receiver[k])
              {
                double     *p = damage_points.properties[k];
                const auto &m =
                  *materials[static_cast<unsigned int>(p[layout.material_id])];
                m.update_damage(m.last_nonlocal_driver(p + layout.state),
                                loop.dt,
                                p + layout.state);
              }
          return;
        }
      // Without damage (gravity loading) no point is a receiver; for the
      // refinement criterion every point that is not fully damaged is.
      if (!stage.damage)
        for (std::size_t k = 0; k < damage_points.receiver.size(); ++k)
          damage_points.receiver[k] =
            materials[static_cast<unsigned int>(
                        damage_points.properties[k][layout.material_id])]
              ->damage(damage_points.properties[k] + layout.state) < 1.;
      // This rank's region: the bounding box of its locally owned cells.
      // (GridTools::compute_mesh_predicate_bounding_box() at refinement
      // level 1 reads past the last level of an unrefined mesh and
      // crashed; at level 0 its merge is cubic in the number of coarse
      // cells. One box is always a cover, which is all the averager needs.)
      if (local_boxes.empty())
        {
          Point<dim> lower, upper;
          for (unsigned int d = 0; d < dim; ++d)
            {
              lower[d] = std::numeric_limits<double>::max();
              upper[d] = std::numeric_limits<double>::lowest();
            }
          bool any = false;
          for (const auto &cell : grid.triangulation().active_cell_iterators())
            if (cell->is_locally_owned())
              {
                any = true;
                for (const unsigned int v : cell->vertex_indices())
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      lower[d] = std::min(lower[d], cell->vertex(v)[d]);
                      upper[d] = std::max(upper[d], cell->vertex(v)[d]);
                    }
              }
          if (any)
            local_boxes.emplace_back(std::make_pair(lower, upper));
        }
      // Fully damaged points of materials with 'Nonlocal exclude fully
      // damaged' are left out of both sums of the average (damage_points'
      // source, from G2P: the damage has not changed since; asking the
      // materials here cost a cache miss per point on its record).
      averager->compute(local_boxes,
                        damage_points.position,
                        damage_points.volume,
                        damage_points.driver,
                        damage_points.receiver,
                        damage_points.source,
                        damage_points.id,
                        nonlocal_driver);
      // Points whose driver approaches their damage threshold seed the
      // refinement pass at the end of this step (before the update: the
      // threshold the driver is compared with is the one it had to pass).
      for (std::size_t k = 0; k < damage_points.position.size(); ++k)
        if (damage_points.receiver[k])
          {
            double     *p = damage_points.properties[k];
            const auto &m =
              *materials[static_cast<unsigned int>(p[layout.material_id])];
            if (gather_precursors &&
                nonlocal_driver[k] > grid.refinement_driver_fraction *
                                       m.damage_threshold(p + layout.state))
              precursor_ids.push_back(damage_points.id[k]);
            if (stage.damage)
              m.update_damage(nonlocal_driver[k], loop.dt, p + layout.state);
          }
      if (gather_precursors)
        std::sort(precursor_ids.begin(), precursor_ids.end());
    }


    template <int dim>
    void
    Simulation<dim>::check(const transfer::StepReport &report,
                           const Stage                &stage)
    {
      std::string cause;
      std::string failure = report.failure_message();
      if (report.n_outside > 0 && remove_outside &&
          report.n_failures() == report.n_outside)
        failure.clear();
      if (!failure.empty())
        {
          if (report.n_outside > 0 && report.n_failures() == report.n_outside)
            cause = "a body leaves the background mesh: enlarge the <Mesh> "
                    "box, or set <Points leaving the mesh> = remove.";
          else if (report.n_inverted > 0 && report.n_not_finite == 0 &&
                   report.n_too_fast == 0)
            cause = "extreme distortion of a material point: a time step "
                    "too large for the stiffness (<CFL number>), or a "
                    "material too soft for the load.";
          else
            cause = "an unstable step: the <CFL number> (" +
                    std::to_string(cfl) +
                    ") is too large for the stiffness and speed, or nodes "
                    "with tiny mass (<Small mass cutoff>, USL).";
        }
      else
        {
          // Energy balance: everything that entered minus what left.
          // With mass scaling the kinetic energy of the scaled inertia.
          // The transfers' loss and the boundary's are exact discrete
          // bookings; what remains is the time (and MUSL stress-velocity)
          // error of the internal and gravitational work (doc/user_guide.md).
          const double kinetic =
            loop.mass_scaling.inertia_scale * report.kinetic_energy;
          const double balance =
            kinetic + report.gravitational_energy + loop.energy.internal_work +
            loop.energy.damping_dissipation + loop.energy.boundary_dissipation +
            loop.energy.mass_scaling_dissipation +
            loop.energy.transfer_dissipation + loop.energy.removed_energy -
            loop.energy.body_force_work;
          loop.energy.residual = balance - loop.energy.initial;
          loop.energy.scale    = std::max(
            {loop.energy.scale,
                kinetic,
                std::abs(report.gravitational_energy -
                      (loop.energy.initial - last_report.kinetic_energy * 0)),
                std::abs(loop.energy.internal_work),
                std::abs(loop.energy.body_force_work),
                report.stored_energy});
          if (loop.energy.residual > growth_tolerance * loop.energy.scale &&
              loop.energy.scale > 0)
            {
              std::ostringstream s;
              s << "The energy grew by " << loop.energy.residual << " J ("
                << 100 * loop.energy.residual / loop.energy.scale
                << " % of the largest energy of the run, tolerance "
                << 100 * growth_tolerance << " %).";
              failure = s.str();
              cause   = "an unstable step: the <CFL number> (" +
                      std::to_string(cfl) +
                      ") is too large for the stiffness and speed.";
            }
        }
      if (failure.empty())
        return;
      std::ostringstream message;
      message << "Stage " << stage.name << ", step " << loop.step
              << " (t = " << loop.time << " s, dt = " << loop.dt
              << " s): " << failure << " Likely cause: " << cause;
      write_summary("error: " + message.str());
      throw ScarpError(message.str());
    }


    template <int dim>
    double
    Simulation<dim>::fast_volume(const double speed)
    {
      order_points();
      double volume = 0;
      for (const auto &particle : particles)
        {
          const double *p = particle.get_properties().data();
          if (layout.get_vector(p, layout.velocity).norm() > speed)
            volume += p[layout.reference_volume];
        }
      return Utilities::MPI::sum(volume, communicator);
    }


    template <int dim>
    void
    Simulation<dim>::advance(const Stage &stage)
    {
      const double scale = (stage.mass_scaling > 1 && !loop.mass_scaling.ended)
                             ? stage.mass_scaling
                             : 1;
      if (scale > loop.mass_scaling.inertia_scale)
        {
          // Mass scaling begins: the kinetic energy is kept (velocities
          // times sqrt(old / new)). Keeping the velocities would multiply
          // the energy of the vibrations left from the previous stage by
          // m_s, and real time would get it back as m_s times stronger
          // vibrations when the scaling ends.
          const double f = std::sqrt(loop.mass_scaling.inertia_scale / scale);
          for (auto &particle : particles)
            {
              double *p = particle.get_properties().data();
              for (unsigned int d = 0; d < dim; ++d)
                p[layout.velocity + d] *= f;
              if (layout.has_affine)
                for (unsigned int i = 0; i < dim * dim; ++i)
                  p[layout.affine + i] *= f;
            }
          last_report.kinetic_energy *= f * f;
          last_report.max_speed *= f;
          loop.mass_scaling.inertia_scale = scale;
        }
      else if (scale < loop.mass_scaling.inertia_scale)
        {
          // Mass scaling ends: the velocities (the failure's motion) are
          // kept, and the kinetic energy of the inertia that goes is booked
          // so that the balance stays closed.
          loop.energy.mass_scaling_dissipation +=
            (loop.mass_scaling.inertia_scale - scale) *
            last_report.kinetic_energy;
          loop.mass_scaling.inertia_scale = scale;
        }
      mpm->set_mass_scale(loop.mass_scaling.inertia_scale);
      loop.dt = stable_time_step();
      if (loop.time + loop.dt > stage.end_time)
        loop.dt = std::max(stage.end_time - loop.time, 1e-300);

      if (body_force)
        body_force->set_time(loop.time);
      transfer::StepReport report;
      {
        TimerOutput::Scope scope(timer, "MPM step");
        // Points of damage materials are gathered for the non-local step:
        // in damage stages every step; in the others (gravity loading) in
        // the step before a refinement check, so that cells refine where
        // the driver approaches the threshold while the loading is still
        // damped (their transients die out before the collapse starts).
        const bool gather =
          any_damage && (stage.damage || precursors_due(loop.step + 1));
        report = mpm->step(loop.dt,
                           gravity,
                           stage.damping,
                           stage.inelastic_switches(),
                           gather ? &damage_points : nullptr);
        report.reduce(communicator);
      }
      loop.energy.internal_work += report.internal_work;
      loop.energy.damping_dissipation += report.damping_dissipation;
      loop.energy.boundary_dissipation += report.boundary_dissipation;
      loop.energy.transfer_dissipation += report.transfer_dissipation;
      loop.energy.body_force_work += report.body_force_work;
      loop.time += loop.dt;
      ++loop.step;
      check(report, stage);
      // Points that left the mesh are gone from the next step's measures:
      // the balance keeps their energy from then on.
      loop.energy.removed_energy +=
        loop.mass_scaling.inertia_scale * report.removed_kinetic_energy +
        report.removed_gravitational_energy;
      // The volume test runs only when a point is fast (report.max_speed is
      // reduced, so every rank takes the same branch).
      if (loop.mass_scaling.inertia_scale > 1 &&
          stage.mass_scaling_end_speed > 0 &&
          report.max_speed > stage.mass_scaling_end_speed &&
          (stage.mass_scaling_end_volume == 0 ||
           fast_volume(stage.mass_scaling_end_speed) >
             stage.mass_scaling_end_volume))
        {
          // Real time from the next step on.
          loop.mass_scaling.ended    = true;
          loop.mass_scaling.end_time = loop.time;
          pcout << "Stage " << stage.name << ": points move faster than "
                << stage.mass_scaling_end_speed << " m/s (largest speed "
                << report.max_speed
                << " m/s): mass scaling ends at t = " << loop.time << " s"
                << std::endl;
        }
      nonlocal_damage_step(stage);
      {
        TimerOutput::Scope scope(timer, "sort particles");
        // Removed points were moved out of the mesh: the sort drops them.
        if (report.n_changed_cell > 0 || report.n_removed_stretched > 0)
          mpm->sort_points(communicator);
        else
          mpm->update_reference_locations();
      }
      if (report.n_outside > 0)
        loop.counters.points_removed += report.n_outside;
      if (report.n_removed_stretched > 0)
        {
          if (!removal_reported)
            pcout << "Stage " << stage.name << ": t = " << loop.time
                  << " s: removing damaged points stretched beyond their "
                     "material's <Remove points stretched beyond> ("
                  << report.n_removed_stretched
                  << " in this step; the total is in summary.json)"
                  << std::endl;
          removal_reported = true;
          loop.counters.points_removed += report.n_removed_stretched;
        }
      if (loop.failure.first_damage_time < 0 && report.max_damage > 0.5 &&
          stage.damage && any_damage)
        loop.failure.first_damage_time = loop.time;
      last_report = report;
      if (cliff && stage.damage && loop.failure.onset_time < 0 &&
          report.max_speed > failure_speed &&
          (failure_volume == 0 || fast_volume(failure_speed) > failure_volume))
        {
          loop.failure.onset_time = loop.time;
          cliff_snapshot("failure");
          pcout << "Cliff: failure onset at t = " << loop.time << " s, "
                << loop.time - loop.failure.damage_stage_start
                << " s after the start of damage (step " << loop.step << ")"
                << std::endl;
        }
      if (refinement_due())
        refine_mesh();
      else if (balance_interval > 0 && loop.step % balance_interval == 0)
        rebalance_if_needed();
      if (loop.step >= max_steps)
        {
          write_summary("error: maximum number of steps reached");
          throw ScarpError("Stage " + stage.name +
                           ": the run reached <Maximum "
                           "steps> = " +
                           std::to_string(max_steps) +
                           " at t = " + std::to_string(loop.time) + " s.");
        }
    }


    // Instantiations (the other members are in the other
    // simulation_*.cc files).
    template transfer::StepReport
    Simulation<2>::measure() const;
    template transfer::StepReport
    Simulation<3>::measure() const;
    template double
    Simulation<2>::stable_time_step() const;
    template double
    Simulation<3>::stable_time_step() const;
    template void
    Simulation<2>::nonlocal_damage_step(const Stage &stage);
    template void
    Simulation<3>::nonlocal_damage_step(const Stage &stage);
    template void
    Simulation<2>::check(const transfer::StepReport &report,
                         const Stage                &stage);
    template void
    Simulation<3>::check(const transfer::StepReport &report,
                         const Stage                &stage);
    template void
    Simulation<2>::advance(const Stage &stage);
    template void
    Simulation<3>::advance(const Stage &stage);
  } // namespace simulation
} // namespace scarp
