// MpmTransfer: the grid update, the nodal solve with damping and boundary
// conditions, and MUSL's remapped velocities.

#include <scarp/transfer/mpm_transfer.h>
#include <scarp/transfer/mpm_transfer_internal.h>

#include <cmath>

namespace scarp
{
  namespace transfer
  {
    using namespace internal;


    template <int dim>
    double
    MpmTransfer<dim>::solve_grid(const double   dt,
                                 const Damping &damping,
                                 StepReport    &report)
    {
      const unsigned int n_owned      = mass.locally_owned_size();
      double             damping_work = 0, body_work = 0;
      for (unsigned int k = 0; k < n_owned; ++k)
        {
          const double m = mass.local_element(k);
          if (!(m > node_cutoff[k]))
            {
              // A nearly empty node keeps the (bounded) mass-weighted
              // velocity of its points and falls with gravity, but takes no
              // internal force: f/m is what becomes unbounded as m -> 0.
              // Zeroing its velocity instead would shear every point near
              // it (a uniform motion would create stress).
              for (unsigned int d = 0; d < dim; ++d)
                {
                  const double v =
                    m > 0 ? momentum[d].local_element(k) / m : 0.;
                  velocity_old[d].local_element(k) = v;
                  velocity_new[d].local_element(k) =
                    m > 0 ? v + dt * gravity_for_empty_nodes[d] / mass_scale
                          : 0.;
                  force[d].local_element(k) = 0;
                }
              continue;
            }
          // Mass scaling: the inertia (and with it viscous damping, a rate)
          // is m_s m; the weight in f is the real one.
          const double m_inertia = mass_scale * m;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double v_old  = momentum[d].local_element(k) / m;
              double       f      = force[d].local_element(k);
              double       f_damp = 0;
              if (damping.type == Damping::Type::viscous)
                f_damp = -damping.coefficient * m_inertia * v_old;
              else if (damping.type == Damping::Type::local)
                f_damp = -damping.coefficient * std::abs(f) *
                         (v_old > 0 ? 1. : (v_old < 0 ? -1. : 0.));
              f += f_damp;
              const double v_new = v_old + dt * f / m_inertia;
              // Keep the damping force: its work is taken after the
              // boundary conditions, with the velocities the nodes have.
              force[d].local_element(k)        = f_damp;
              velocity_old[d].local_element(k) = v_old;
              velocity_new[d].local_element(k) = v_new;
            }
        }
      std::array<Vector *, dim> old_ptr, new_ptr, damp_ptr;
      for (unsigned int d = 0; d < dim; ++d)
        {
          old_ptr[d]  = &velocity_old[d];
          new_ptr[d]  = &velocity_new[d];
          damp_ptr[d] = &force[d]; // holds the damping force here
        }
      // Constrains the start velocity too. The reaction impulses act on the
      // inertia m_s m.
      report.boundary_dissipation +=
        mass_scale * grid.boundary_conditions().apply(
                       mass, new_ptr, &old_ptr, dt, &damp_ptr, mass_scale);
      // The work of the damping and body forces over the constrained
      // velocities, (v_start + v) / 2, as that of the internal forces
      // (the stress power at the points sees the constrained velocities).
      if (damping.type != Damping::Type::none || body_force)
        for (unsigned int k = 0; k < n_owned; ++k)
          if (mass.local_element(k) > node_cutoff[k])
            for (unsigned int d = 0; d < dim; ++d)
              {
                damping_work += dt * force[d].local_element(k) * 0.5 *
                                (velocity_old[d].local_element(k) +
                                 velocity_new[d].local_element(k));
                if (body_force)
                  body_work += dt * body_force_nodal[d].local_element(k) * 0.5 *
                               (velocity_old[d].local_element(k) +
                                velocity_new[d].local_element(k));
              }
      report.damping_dissipation -= damping_work;
      report.body_force_work += body_work;

      std::vector<Vector *> velocities;
      for (unsigned int d = 0; d < dim; ++d)
        {
          velocities.push_back(&velocity_old[d]);
          velocities.push_back(&velocity_new[d]);
        }
      distribute_and_update_ghosts(velocities, {&mass});
      return damping_work;
    }


    template <int dim>
    void
    MpmTransfer<dim>::remap_momentum()
    {
      // The momentum of the new point velocities was gathered by the
      // kinematic sweep of grid_to_particles(); the mass is this step's.
      const auto            start = Clock::now();
      std::vector<Vector *> sums;
      for (unsigned int d = 0; d < dim; ++d)
        sums.push_back(&momentum[d]);
      compress_add(sums, times.exchange);
      const unsigned int n_owned = mass.locally_owned_size();
      for (unsigned int k = 0; k < n_owned; ++k)
        {
          const double m = mass.local_element(k);
          for (unsigned int d = 0; d < dim; ++d)
            velocity_remapped[d].local_element(k) =
              (m > 0) ? momentum[d].local_element(k) / m : 0.;
        }
      std::array<Vector *, dim> ptr;
      for (unsigned int d = 0; d < dim; ++d)
        ptr[d] = &velocity_remapped[d];
      // The boundary acts on the remapped velocity too; what it removes was
      // counted in the solve already.
      grid.boundary_conditions().apply(mass, ptr);
      std::vector<Vector *> remapped;
      for (unsigned int d = 0; d < dim; ++d)
        remapped.push_back(&velocity_remapped[d]);
      distribute_and_update_ghosts(remapped, {});
      times.grid_update += seconds_since(start);
    }


    // Instantiations (the other members are in the other mpm_transfer*.cc
    // files).
    template double
    MpmTransfer<2>::solve_grid(const double   dt,
                               const Damping &damping,
                               StepReport    &report);
    template double
    MpmTransfer<3>::solve_grid(const double   dt,
                               const Damping &damping,
                               StepReport    &report);
    template void
    MpmTransfer<2>::remap_momentum();
    template void
    MpmTransfer<3>::remap_momentum();
  } // namespace transfer
} // namespace scarp
