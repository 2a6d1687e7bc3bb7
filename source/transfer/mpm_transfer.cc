// MpmTransfer: set-up, the ghost exchange through the hanging-node
// constraints, the step in its parts, and the sort of the points. The parts
// are in mpm_transfer_cells.cc, mpm_transfer_p2g.cc,
// mpm_transfer_grid_update.cc and mpm_transfer_g2p.cc.
#include <deal.II/base/mpi.h>

#include <scarp/base/exceptions.h>
#include <scarp/transfer/mpm_transfer.h>
#include <scarp/transfer/mpm_transfer_internal.h>

#include <chrono>
#include <cmath>

namespace scarp
{
  namespace transfer
  {
    using namespace internal;


    template <int dim>
    MpmTransfer<dim>::MpmTransfer(
      const grid::BackgroundGrid<dim>                &grid,
      Particles::ParticleHandler<dim>                &particles,
      const particles::PropertyLayout<dim>           &layout,
      const std::vector<const materials::Material *> &materials,
      const TransferParameters                       &parameters)
      : grid(grid)
      , particle_handler(particles)
      , layout(layout)
      , materials(materials)
      , parameters(parameters)
    {
    }


    template <int dim>
    void
    MpmTransfer<dim>::setup()
    {
      const MPI_Comm comm = grid.dof_handler().get_communicator();
      mass.reinit(grid.locally_owned_dofs(),
                  grid.locally_relevant_dofs(),
                  comm);
      for (unsigned int d = 0; d < dim; ++d)
        for (Vector *v : {&momentum[d],
                          &force[d],
                          &body_force_nodal[d],
                          &velocity_old[d],
                          &velocity_new[d],
                          &velocity_remapped[d]})
          v->reinit(mass);
      patches.reinit(grid.dof_handler(),
                     grid.constraints(),
                     *mass.get_partitioner());
      occupied_cells.clear();
      node_arrays_valid      = false;
      occupied_cells_current = false;
      candidate_cells_valid  = false;
      compute_node_cutoffs();
      setup_constraints();
    }


    template <int dim>
    void
    MpmTransfer<dim>::setup_constraints()
    {
      constraint_local.clear();
      constraint_begin.assign(1, 0);
      constraint_entries.clear();
      const Utilities::MPI::Partitioner &partitioner = *mass.get_partitioner();
      for (const auto &line : grid.constraints().get_lines())
        {
          if (!partitioner.in_local_range(line.index))
            continue;
          // Hanging-node constraints are homogeneous; close() resolved
          // chains, so every source is an unconstrained node.
          AssertThrow(line.inhomogeneity == 0.,
                      ExcInternalError("an inhomogeneous grid constraint"));
          constraint_local.push_back(partitioner.global_to_local(line.index));
          for (const auto &entry : line.entries)
            {
              AssertThrow(partitioner.in_local_range(entry.first) ||
                            partitioner.is_ghost_entry(entry.first),
                          ExcInternalError(
                            "a hanging node whose source is not a ghost"));
              constraint_entries.emplace_back(
                partitioner.global_to_local(entry.first), entry.second);
            }
          constraint_begin.push_back(constraint_entries.size());
        }
      const MPI_Comm     comm = grid.dof_handler().get_communicator();
      const unsigned int mine = constraint_local.empty() ? 0 : 1;
      any_constraints         = Utilities::MPI::max(mine, comm) > 0;
    }


    template <int dim>
    void
    MpmTransfer<dim>::distribute_and_update_ghosts(
      const std::vector<Vector *> &vectors,
      const std::vector<Vector *> &unconstrained)
    {
      std::vector<Vector *> all = vectors;
      all.insert(all.end(), unconstrained.begin(), unconstrained.end());
      if (!any_constraints)
        {
          update_ghosts(all, times.exchange);
          return;
        }
      // The sources first (ghost entries), then the owned hanging nodes in
      // the order and arithmetic of AffineConstraints::distribute() (the
      // same numbers to the bit), then the ghosts of those.
      update_ghosts(vectors, times.exchange);
      for (Vector *v : vectors)
        for (unsigned int c = 0; c < constraint_local.size(); ++c)
          {
            double value = 0.;
            for (unsigned int e = constraint_begin[c];
                 e < constraint_begin[c + 1];
                 ++e)
              value += v->local_element(constraint_entries[e].first) *
                       constraint_entries[e].second;
            v->local_element(constraint_local[c]) = value;
          }
      update_ghosts(all, times.exchange);
    }


    template <int dim>
    void
    MpmTransfer<dim>::compute_node_cutoffs()
    {
      // The cutoff of a node scales with the volume of the smallest cell
      // at it: a node of a refined region gets 1/2^dim of the mass per
      // level, and a global cutoff of the coarse (fine) size would empty
      // (keep) its nodes wrongly.
      const IndexSet &owned = grid.locally_owned_dofs();
      node_cutoff.assign(owned.n_elements(),
                         std::numeric_limits<double>::max());
      for (const auto &cell : grid.dof_handler().active_cell_iterators())
        if (!cell->is_artificial())
          {
            const double h      = cell->vertex(1)[0] - cell->vertex(0)[0];
            const double cutoff = mass_cutoff_density * std::pow(h, dim);
            for (const unsigned int v : cell->vertex_indices())
              {
                const types::global_dof_index dof =
                  cell->vertex_dof_index(v, 0);
                if (owned.is_element(dof))
                  {
                    double &c = node_cutoff[owned.index_within_set(dof)];
                    c         = std::min(c, cutoff);
                  }
              }
          }
    }


    template <int dim>
    void
    MpmTransfer<dim>::update_reference_locations()
    {
      auto &pool = particle_handler.get_property_pool();
      for (const OccupiedCell &occupied : occupied_cells)
        {
          const Point<dim> &x0 = occupied.x0;
          const double      h  = occupied.h;
          for (unsigned int q = occupied.point_begin; q < occupied.point_end;
               ++q)
            {
              const unsigned int handle = point_handle[q];
              const Point<dim>  &x      = pool.get_location(handle);
              Point<dim>         xi;
              for (unsigned int d = 0; d < dim; ++d)
                xi[d] = (x[d] - x0[d]) / h;
              pool.set_reference_location(handle, xi);
            }
        }
    }


    template <int dim>
    void
    MpmTransfer<dim>::sort_points(const MPI_Comm communicator)
    {
      occupied_cells_current = false;
      occupied_points.clear();
      for (const OccupiedCell &occupied : occupied_cells)
        occupied_points.push_back(
          {occupied.cell, occupied.point_begin, occupied.point_end});
      candidate_cells_valid = point_mover.sort(particle_handler,
                                               grid.triangulation(),
                                               occupied_points,
                                               point_handle,
                                               communicator);
      if (!candidate_cells_valid)
        return;
      // The mover left every point in a cell that held points before or in
      // one it put points into: only these can hold points now. Sorted by
      // active cell index, the order of the active cell iteration.
      // The occupied cells are in that order already: only the few gained
      // cells are sorted, then merged in (sorting the whole list took 2 %
      // of the step of the rank holding a debris front).
      candidate_cells.clear();
      for (const OccupiedCell &occupied : occupied_cells)
        candidate_cells.push_back(occupied.cell);
      const std::size_t n_held = candidate_cells.size();
      for (const auto &cell : point_mover.cells_gained())
        candidate_cells.emplace_back(&grid.triangulation(),
                                     cell->level(),
                                     cell->index(),
                                     &grid.dof_handler());
      const auto by_index = [](const auto &a, const auto &b) {
        return a->active_cell_index() < b->active_cell_index();
      };
      std::sort(candidate_cells.begin() + n_held,
                candidate_cells.end(),
                by_index);
      std::inplace_merge(candidate_cells.begin(),
                         candidate_cells.begin() + n_held,
                         candidate_cells.end(),
                         by_index);
      candidate_cells.erase(std::unique(candidate_cells.begin(),
                                        candidate_cells.end()),
                            candidate_cells.end());
      // The cells whose points changed: the others hold the points of the
      // list made before this sort, in its order.
      changed_cells.clear();
      for (const auto &cell : point_mover.cells_gained())
        changed_cells.push_back(cell->active_cell_index());
      for (const auto &cell : point_mover.cells_lost())
        changed_cells.push_back(cell->active_cell_index());
      std::sort(changed_cells.begin(), changed_cells.end());
    }


    template <int dim>
    StepReport
    MpmTransfer<dim>::step(const double                        dt,
                           const Tensor<1, dim>               &gravity,
                           const Damping                      &damping,
                           const materials::InelasticSwitches &inelastic,
                           DamagePoints<dim>                  *damage_points)
    {
      StepReport report;
      last_gravity            = gravity;
      gravity_for_empty_nodes = gravity;
      if (damage_points)
        damage_points->clear();
      auto start = Clock::now();
      find_occupied_cells();
      compute_shapes();
      times.shape_functions += seconds_since(start);
      start = Clock::now();
      particles_to_grid(gravity);
      times.p2g += seconds_since(start);
      start = Clock::now();
      solve_grid(dt, damping, report);
      times.grid_update += seconds_since(start);
      // G2P: its time less that of the constitutive updates it makes.
      const auto g2p = [&](const bool                     kinematics,
                           const bool                     stress,
                           const std::array<Vector, dim> &stress_velocity,
                           DamagePoints<dim>             *points,
                           const bool gather_momentum = false) {
        const double constitutive = times.constitutive_update;
        const auto   g2p_start    = Clock::now();
        grid_to_particles(dt,
                          kinematics,
                          stress,
                          inelastic,
                          stress_velocity,
                          report,
                          points,
                          gravity,
                          gather_momentum);
        times.g2p +=
          seconds_since(g2p_start) - (times.constitutive_update - constitutive);
      };
      if (parameters.scheme == UpdateScheme::usl)
        g2p(true, true, velocity_new, damage_points);
      else
        {
          g2p(true, false, velocity_new, nullptr, true);
          remap_momentum();
          g2p(false, true, velocity_remapped, damage_points);
        }
      if (!removal_ids.empty())
        move_removed_points_out();
      return report;
    }


    template <int dim>
    void
    MpmTransfer<dim>::move_removed_points_out()
    {
      // Beyond the mesh's upper corner by its size: the next sort drops
      // them, as it drops points that left the mesh. A rare event, so one
      // pass over the points is cheap.
      const BoundingBox<dim> &domain = grid.domain();
      Point<dim>              outside;
      for (unsigned int d = 0; d < dim; ++d)
        outside[d] =
          domain.get_boundary_points().second[d] + domain.side_length(d);
      std::sort(removal_ids.begin(), removal_ids.end());
      for (auto &particle : particle_handler)
        if (std::binary_search(removal_ids.begin(),
                               removal_ids.end(),
                               particle.get_id()))
          particle.set_location(outside);
      removal_ids.clear();
    }


    template <int dim>
    StepReport
    MpmTransfer<dim>::measure(const Tensor<1, dim> &gravity) const
    {
      StepReport report;
      for (const auto &particle : particle_handler)
        {
          const double *p = particle.get_properties().data();
          add_point_measures(p, particle.get_location(), gravity, report);
        }
      return report;
    }


    template class MpmTransfer<2>;
    template class MpmTransfer<3>;
  } // namespace transfer
} // namespace scarp
