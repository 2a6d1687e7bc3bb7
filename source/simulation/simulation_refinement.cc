// Simulation: a refinement pass (flags from the criteria, refinement,
// splitting, load balance; doc/refinement.md).
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
#include <scarp/particles/checked_sort.h>
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
    bool
    Simulation<dim>::refinement_due() const
    {
      return grid.adaptive_refinement &&
             loop.step % grid.refinement_interval == 0;
    }


    template <int dim>
    bool
    Simulation<dim>::precursors_due(const unsigned int s) const
    {
      return grid.adaptive_refinement && grid.refinement_driver_fraction > 0 &&
             s % grid.refinement_interval == 0;
    }


    template <int dim>
    void
    Simulation<dim>::refine_mesh()
    {
      TimerOutput::Scope scope(timer, "refinement");
      auto              &tria = grid.triangulation();
      ++loop.counters.refinement_checks;
      // Seeds: cells with a damaged point, or with a point whose non-local
      // driver approaches its damage threshold (gathered in the non-local
      // step). Both are properties of the points, so the seeds do not
      // depend on the partition.
      std::vector<typename Triangulation<dim>::active_cell_iterator> seeds;
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto &particle : particles.particles_in_cell(cell))
            {
              const double *p = particle.get_properties().data();
              const auto   &m =
                *materials[static_cast<unsigned int>(p[layout.material_id])];
              if (m.damage(p + layout.state) > grid.refinement_damage_limit ||
                  std::binary_search(precursor_ids.begin(),
                                     precursor_ids.end(),
                                     particle.get_id()))
                {
                  seeds.push_back(cell);
                  break;
                }
            }
      precursor_ids.clear();
      const double buffer =
        grid.refinement_buffer * (averager ? averager->cutoff_radius() : 0.);
      const bool refines =
        grid::RefinementMarker<dim>::mark(tria,
                                          seeds,
                                          buffer,
                                          grid.max_refinement_level) > 0;
      // Without a cell to refine, only points stretched past their cell's
      // share can split (Split stretched points).
      if (!refines && !grid.split_stretched_points)
        return;
      // The split and the transfer walk the points in the list's order
      // (the check above reads them cell by cell).
      order_points();
      if (refines)
        {
          // Refinement repartitions the mesh as well, weighing each child
          // of a refined cell as its parent (balance_load()'s weight): the
          // points the child holds after the split, if they were spread
          // evenly.
          particles.prepare_for_coarsening_and_refinement();
          tria.execute_coarsening_and_refinement();
          particles.unpack_after_coarsening_and_refinement();
        }
      std::vector<unsigned int> per_direction;
      for (const auto &body : bodies)
        per_direction.push_back(body.per_direction);
      const types::particle_index n_split =
        particles::PointSplitter<dim>::split(particles,
                                             layout,
                                             per_direction,
                                             grid.domain(),
                                             communicator,
                                             grid.split_stretched_points);
      if (!refines && n_split == 0)
        return;
      loop.counters.points_split += n_split;
      particles::CheckedSort<dim>::sort(particles,
                                        tria,
                                        layout.mass,
                                        "after the refinement and the split",
                                        communicator);
      // A second repartition (and particle transfer) only where the split
      // points are spread so unevenly that the ranks are out of balance.
      if (points_out_of_balance())
        balance_load();
      else if (refines)
        grid.setup_dofs();
      mpm->setup();
      local_boxes.clear();
      if (averager)
        averager->invalidate_neighbour_lists();
      if (refines)
        ++loop.counters.refinement_passes;
    }


    // Instantiations (the other members are in the other
    // simulation_*.cc files).
    template bool
    Simulation<2>::refinement_due() const;
    template bool
    Simulation<3>::refinement_due() const;
    template bool
    Simulation<2>::precursors_due(const unsigned int s) const;
    template bool
    Simulation<3>::precursors_due(const unsigned int s) const;
    template void
    Simulation<2>::refine_mesh();
    template void
    Simulation<3>::refine_mesh();
  } // namespace simulation
} // namespace scarp
