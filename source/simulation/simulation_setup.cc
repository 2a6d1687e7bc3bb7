// Simulation: building the mesh and seeding the bodies, the initial
// displacement, and the load balance (cells weighted by their points).
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
    void
    Simulation<dim>::setup()
    {
      if (mpm)
        return;
      TimerOutput::Scope scope(timer, "setup");
      if (checkpoint.resuming())
        load_checkpoint();
      else
        {
          grid.create_mesh();
          grid.setup_dofs();
          particles.initialize(grid.triangulation(),
                               grid.mapping(),
                               layout.n_properties());
          seed_bodies();
          balance_load();
        }
      mpm = std::make_unique<transfer::MpmTransfer<dim>>(
        grid, particles, layout, material_pointers, transfer_parameters);
      mpm->setup();
      mpm->set_body_force(body_force.get());
      double rho_max = 0;
      for (const auto &m : materials)
        rho_max = std::max(rho_max, m->density());
      mpm->set_mass_cutoff_density(transfer_parameters.mass_cutoff * rho_max);
      if (checkpoint.resuming())
        return; // the loop state came with the checkpoint
      start_loop_state();
    }


    template <int dim>
    void
    Simulation<dim>::start_loop_state()
    {
      loop        = LoopState();
      last_report = measure();
      loop.energy.initial =
        last_report.kinetic_energy + last_report.gravitational_energy;
      loop.energy.scale = last_report.kinetic_energy;
    }


    template <int dim>
    bool
    Simulation<dim>::points_out_of_balance() const
    {
      const unsigned int n_ranks =
        Utilities::MPI::n_mpi_processes(communicator);
      if (n_ranks == 1)
        return false;
      const double n_local = particles.n_locally_owned_particles();
      const double n_max   = Utilities::MPI::max(n_local, communicator);
      const double n_mean =
        Utilities::MPI::sum(n_local, communicator) / n_ranks;
      return n_max > (1. + balance_tolerance) * n_mean;
    }


    template <int dim>
    void
    Simulation<dim>::rebalance_if_needed()
    {
      if (!points_out_of_balance())
        return;
      TimerOutput::Scope scope(timer, "load balancing");
      order_points();
      balance_load();
      mpm->setup();
      local_boxes.clear();
      if (averager)
        averager->invalidate_neighbour_lists();
      ++loop.counters.rebalances;
    }


    template <int dim>
    void
    Simulation<dim>::balance_load()
    {
      if (Utilities::MPI::n_mpi_processes(communicator) == 1)
        return;
      // The work is per material point, not per cell: weigh cells by their
      // points (as in step-68), so that a cliff filling part of the box is
      // shared evenly. deal.II 9.4 adds no base weight once a function is
      // connected, so the empty-cell cost is ours too. The connection stays
      // for every later refinement.
      if (!weight_connection.connected())
        weight_connection = grid.triangulation().signals.weight.connect(
          [this](const typename Triangulation<dim>::cell_iterator &cell,
                 const typename Triangulation<dim>::CellStatus     status)
            -> unsigned int {
            unsigned int n = 0;
            if (status == Triangulation<dim>::CELL_COARSEN)
              {
                for (const auto &child : cell->child_iterators())
                  if (child->is_active())
                    n += particles.n_particles_in_cell(child);
              }
            else if (cell->is_active())
              n = particles.n_particles_in_cell(cell);
            return 10 + 100 * n;
          });
      particles.prepare_for_coarsening_and_refinement();
      grid.triangulation().repartition();
      particles.unpack_after_coarsening_and_refinement();
      // The unpack leaves the pool's slots out of the order of the cells
      // (on 2 ranks nearly every point: test refinement_pool_growth), and
      // the transfers, walking cell by cell, then wait on memory; the full
      // sort puts the pool in that order (PropertyPool::sort_memory_slots).
      particles.sort_particles_into_subdomains_and_cells();
      grid.setup_dofs();
    }


    template <int dim>
    void
    Simulation<dim>::seed_bodies()
    {
      types::particle_index next_id = 0;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          const Body                &body     = bodies[b];
          const materials::Material &material = *materials[body.material];
          const auto                 inside   = [&](const Point<dim> &x) {
            if (!body.shape->contains(x))
              return false;
            for (unsigned int c = 0; c < b; ++c)
              if (bodies[c].shape->contains(x))
                return false;
            return true;
          };
          const auto initialize =
            [&](const Point<dim> &x, const double volume, double *p) {
              p[layout.mass]             = material.density() * volume;
              p[layout.reference_volume] = volume;
              Vector<double> v(dim), s(6);
              body.velocity->vector_value(x, v);
              body.stress->vector_value(x, s);
              for (unsigned int d = 0; d < dim; ++d)
                {
                  p[layout.velocity + d]                       = v[d];
                  p[layout.reference_position + d]             = x[d];
                  p[layout.deformation_gradient + d * dim + d] = 1.;
                }
              // APIC: the affine matrix starts as the gradient of the
              // initial velocity (else the first step is a PIC step).
              if (layout.has_affine)
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    const Tensor<1, dim> g = body.velocity->gradient(x, d);
                    for (unsigned int e = 0; e < dim; ++e)
                      p[layout.affine + d * dim + e] = g[e];
                  }
              SymmetricTensor<2, 3> sigma;
              for (unsigned int k = 0; k < 6; ++k)
                sigma.access_raw_entry(k) = s[k];
              layout.set_stress(p, layout.stress, sigma);
              p[layout.material_id] = body.material;
              p[layout.body_id]     = b;
              material.initialize_state(sigma, p + layout.state);
              bool damaged = false;
              for (const auto &region : predamaged)
                damaged = damaged || region->contains(x);
              if constexpr (dim == 2)
                if (body.cliff && body.cliff->has_crack())
                  {
                    // A pre-damage band replaces the fully damaged box.
                    if (body.cliff->has_crack_band())
                      {
                        const double d = body.cliff->crack_band_damage(x);
                        if (d > 0. && !damaged)
                          material.set_initial_damage(p + layout.state, d);
                      }
                    else if (body.cliff->crack_region().contains(x))
                      damaged = true;
                  }
              if (damaged)
                material.set_fully_damaged(p + layout.state);
            };
          const auto n =
            particles::BodySeeder<dim>::seed(grid.triangulation(),
                                             particles,
                                             body.shape->bounding_box(),
                                             inside,
                                             body.per_direction,
                                             next_id,
                                             initialize);
          if (n == 0)
            throw ScarpError("Body " + body.name +
                             " has no material point inside the background "
                             "mesh: is it outside the mesh, or smaller than "
                             "a cell?");
          // Any part of the body outside the mesh would be silently lost.
          const BoundingBox<dim> box = body.shape->bounding_box();
          for (unsigned int d = 0; d < dim; ++d)
            if (box.lower_bound(d) < grid.domain().lower_bound(d) - 1e-12 ||
                box.upper_bound(d) > grid.domain().upper_bound(d) + 1e-12)
              throw ScarpError("Body " + body.name +
                               " reaches outside the background mesh in "
                               "direction " +
                               std::to_string(d) +
                               ": enlarge the <Mesh> box or move the body.");
          pcout << "Body " << body.name << ": " << n << " material points"
                << std::endl;
          next_id += n;
        }
      particles.update_cached_numbers();
      apply_initial_displacement();
    }


    template <int dim>
    void
    Simulation<dim>::apply_initial_displacement()
    {
      bool any = false;
      for (const auto &body : bodies)
        any = any || body.displacement;
      if (!any)
        return;
      for (auto &particle : particles)
        {
          double     *p = particle.get_properties().data();
          const Body &body =
            bodies[static_cast<unsigned int>(p[layout.body_id])];
          if (!body.displacement)
            continue;
          const Point<dim> X(layout.get_vector(p, layout.reference_position));
          Tensor<2, dim>   F = unit_symmetric_tensor<dim>();
          Point<dim>       x = X;
          for (unsigned int d = 0; d < dim; ++d)
            {
              x[d] += body.displacement->value(X, d);
              F[d] += body.displacement->gradient(X, d);
            }
          layout.set_matrix(p, layout.deformation_gradient, F);
          particle.set_location(x);
          Tensor<2, 3> F3;
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              F3[i][j] = (i < dim && j < dim) ? F[i][j] : (i == j ? 1. : 0.);
          SymmetricTensor<2, 3>    sigma  = layout.get_stress(p, layout.stress);
          double                   stored = 0, driver = 0;
          double                  *state = p + layout.state;
          materials::MaterialBatch batch;
          batch.n             = 1;
          batch.dt            = 1.;
          batch.delta_F       = &F3;
          batch.F             = &F3;
          batch.state         = &state;
          batch.stress        = &sigma;
          batch.stored_energy = &stored;
          // Elastic: the displacement is the state, not a load path.
          batch.inelastic.plasticity = false;
          batch.inelastic.damage     = false;
          if (materials[body.material]->has_damage())
            batch.damage_driver = &driver;
          materials[body.material]->update(batch);
          layout.set_stress(p, layout.stress, sigma);
        }
      particles.sort_particles_into_subdomains_and_cells();
      particles.update_cached_numbers();
    }


    // Instantiations (the other members are in the other
    // simulation_*.cc files).
    template void
    Simulation<2>::setup();
    template void
    Simulation<3>::setup();
    template bool
    Simulation<2>::points_out_of_balance() const;
    template bool
    Simulation<3>::points_out_of_balance() const;
    template void
    Simulation<2>::rebalance_if_needed();
    template void
    Simulation<3>::rebalance_if_needed();
    template void
    Simulation<2>::balance_load();
    template void
    Simulation<3>::balance_load();
    template void
    Simulation<2>::start_loop_state();
    template void
    Simulation<3>::start_loop_state();
    template void
    Simulation<2>::seed_bodies();
    template void
    Simulation<3>::seed_bodies();
    template void
    Simulation<2>::apply_initial_displacement();
    template void
    Simulation<3>::apply_initial_displacement();
  } // namespace simulation
} // namespace scarp
