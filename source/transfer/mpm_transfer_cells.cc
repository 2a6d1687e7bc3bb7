// MpmTransfer: the occupied cells (the cells that hold points, with their
// nodes) and the points' shape functions on them.
#include <deal.II/base/mpi.h>

#include <scarp/transfer/mpm_transfer.h>
#include <scarp/transfer/mpm_transfer_internal.h>
#include <scarp/transfer/q1_shape.h>

#include <cmath>

namespace scarp
{
  namespace transfer
  {
    using namespace internal;


    template <int dim>
    void
    MpmTransfer<dim>::compute_shapes()
    {
      // All sweeps of a step evaluate the shape functions at the points'
      // positions of the step's start (the reference locations change only
      // in the sort after the step): evaluate once, keep the non-zero ones.
      // Room for every entry (a patch node of the point's cell, at most
      // 3^dim on a regular patch), written in place: no growth checks in
      // the loop. The arrays only grow; shape_begin says what is valid.
      std::size_t bound = 0;
      for (const OccupiedCell &occupied : occupied_cells)
        bound += std::size_t(occupied.point_end - occupied.point_begin) *
                 (occupied.regular ? Utilities::pow(3, dim) : occupied.n_nodes);
      if (shape_node.size() < bound)
        {
          shape_node.resize(bound);
          shape_value.resize(bound);
          shape_gradient.resize(bound);
        }
      shape_begin.resize(point_handle.size() + 1);
      shape_begin[0]                        = 0;
      unsigned int                n_entries = 0;
      const auto                 &pool = particle_handler.get_property_pool();
      std::vector<double>         value;
      std::vector<Tensor<1, dim>> gradient;
      unsigned int                k = 0;
      for (const OccupiedCell &occupied : occupied_cells)
        {
          const double      h  = occupied.h;
          const Point<dim> &x0 = occupied.x0;
          for (unsigned int q = occupied.point_begin; q < occupied.point_end;
               ++q, ++k)
            {
              const double *p    = point_properties[q];
              const auto    xi   = pool.get_reference_location(point_handle[q]);
              const Point<dim> x = x0 + h * xi;
              if (occupied.patch)
                {
                  double l[dim];
                  gimp_half_width<dim>(
                    p[layout.reference_volume], h, x, grid.domain(), l);
                  bool positive = true;
                  for (unsigned int d = 0; d < dim; ++d)
                    positive = positive && l[d] > 0.;
                  if (occupied.regular && positive)
                    n_entries += GimpPatches<dim>::regular_nonzero(
                      occupied.lattice,
                      1. / h,
                      x,
                      l,
                      shape_node.data() + n_entries,
                      shape_value.data() + n_entries,
                      shape_gradient.data() + n_entries);
                  else
                    {
                      GimpPatches<dim>::evaluate_general(
                        *occupied.patch, x, l, value, gradient);
                      n_entries += keep_nonzero(value.data(),
                                                gradient.data(),
                                                value.size(),
                                                n_entries);
                    }
                }
              else
                {
                  // Q1: straight from the evaluation into the cache.
                  Q1Shape<dim> q1;
                  q1.evaluate(xi, h);
                  n_entries += keep_nonzero(q1.value,
                                            q1.gradient,
                                            Q1Shape<dim>::n,
                                            n_entries);
                }
              shape_begin[k + 1] = n_entries;
            }
        }
    }


    template <int dim>
    unsigned int
    MpmTransfer<dim>::keep_nonzero(const double         *value,
                                   const Tensor<1, dim> *gradient,
                                   const unsigned int    n,
                                   const unsigned int    at)
    {
      unsigned int kept = 0;
      for (unsigned int i = 0; i < n; ++i)
        if (value[i] != 0. || gradient[i].norm_square() != 0.)
          {
            shape_node[at + kept]     = i;
            shape_value[at + kept]    = value[i];
            shape_gradient[at + kept] = gradient[i];
            ++kept;
          }
      return kept;
    }


    template <int dim>
    void
    MpmTransfer<dim>::find_occupied_cells()
    {
      // No point changed cells in the last step (no sort_points() since the
      // list was made), nor did the mesh change (no setup()): the same
      // cells hold the same points in the same slots. The count guards
      // against a change of the points that bypassed both.
      if (occupied_cells_current &&
          particle_handler.n_locally_owned_particles() == point_handle.size())
        return;
      // The occupied cells, in order, with their points. The step before's
      // list is kept aside: a cell occupied then keeps its node ranges, and
      // its points if they did not change.
      std::swap(occupied_cells, previous_cells);
      std::swap(point_handle, previous_point_handle);
      occupied_cells.clear();
      point_handle.clear();
      point_properties.clear();
      auto      &pool = particle_handler.get_property_pool();
      const auto add  = [&](const auto &cell) -> OccupiedCell  &{
        OccupiedCell &occupied = occupied_cells.emplace_back();
        occupied.cell          = cell;
        // Cells are axis-aligned squares (cubes): the edge is the
        // distance of the first two vertices.
        occupied.x0          = cell->vertex(0);
        occupied.h           = cell->vertex(1)[0] - occupied.x0[0];
        occupied.point_begin = point_handle.size();
        return occupied;
      };
      const auto visit = [&](const auto &cell) {
        const auto particles = particle_handler.particles_in_cell(cell);
        if (particles.begin() == particles.end())
          return;
        OccupiedCell &occupied = add(cell);
        for (const auto &particle : particles)
          {
            const unsigned int handle = particle.get_local_index();
            point_handle.push_back(handle);
            point_properties.push_back(pool.get_properties(handle).data());
          }
        occupied.point_end = point_handle.size();
      };
      // Walking every active cell costs a few per cent of a step of the
      // flowing debris on a refined mesh mostly of air; after the point
      // mover's sort only the candidate cells can hold points, and only
      // those it put points into or took points out of hold other points
      // than before. The others' handles are copied from the list before
      // (reading them from the particle handler, a list node and a vector
      // per cell scattered over the heap, waited on memory for 3 % of the
      // step of the rank holding a debris front). The pool's storage may
      // have moved, so the property pointers are taken anew.
      // The count guards against a change of the points that bypassed
      // sort_points(); then every cell is visited after all.
      bool found_all = false;
      if (candidate_cells_valid)
        {
          std::size_t j = 0, k = 0;
          for (const auto &cell : candidate_cells)
            {
              const unsigned int index = cell->active_cell_index();
              while (k < changed_cells.size() && changed_cells[k] < index)
                ++k;
              if (!find_previous(cell, j) ||
                  (k < changed_cells.size() && changed_cells[k] == index))
                {
                  visit(cell);
                  continue;
                }
              OccupiedCell &occupied = add(cell);
              for (unsigned int i = previous_cells[j].point_begin;
                   i < previous_cells[j].point_end;
                   ++i)
                {
                  const unsigned int handle = previous_point_handle[i];
                  point_handle.push_back(handle);
                  point_properties.push_back(
                    pool.get_properties(handle).data());
                }
              occupied.point_end = point_handle.size();
            }
          found_all =
            point_handle.size() == particle_handler.n_locally_owned_particles();
          if (!found_all)
            {
              occupied_cells.clear();
              point_handle.clear();
              point_properties.clear();
            }
        }
      if (!found_all)
        for (const auto &cell : grid.dof_handler().active_cell_iterators())
          if (cell->is_locally_owned())
            visit(cell);
      candidate_cells_valid  = false;
      occupied_cells_current = true;

      // Their nodes depend on the cells only. A cell occupied in the step
      // before takes its node ranges over (both lists are in the order of
      // the active cells); a newly occupied one appends its nodes. At the
      // front of a flowing debris cells change in nearly every step, and
      // copying every cell's nodes again then cost 5 % of the front rank's
      // step. The arrays are written anew in order once less than half of
      // them is in use, and after every change of the mesh.
      std::size_t n_live = 0;
      if (node_arrays_valid)
        {
          std::size_t j = 0;
          for (OccupiedCell &occupied : occupied_cells)
            {
              if (find_previous(occupied.cell, j))
                take_nodes(previous_cells[j], occupied);
              else
                append_nodes(occupied);
              n_live += occupied.n_nodes;
            }
        }
      if (!node_arrays_valid || 2 * n_live < node_local.size())
        {
          node_local.clear();
          node_dof.clear();
          node_position.clear();
          for (OccupiedCell &occupied : occupied_cells)
            append_nodes(occupied);
        }
      node_arrays_valid = true;
    }


    template <int dim>
    bool
    MpmTransfer<dim>::find_previous(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      std::size_t                                          &j) const
    {
      const unsigned int index = cell->active_cell_index();
      while (j < previous_cells.size() &&
             previous_cells[j].cell->active_cell_index() < index)
        ++j;
      return j < previous_cells.size() && previous_cells[j].cell == cell;
    }


    template <int dim>
    void
    MpmTransfer<dim>::take_nodes(const OccupiedCell &from, OccupiedCell &to)
    {
      to.patch      = from.patch;
      to.regular    = from.regular;
      to.node_begin = from.node_begin;
      to.n_nodes    = from.n_nodes;
      if (to.regular)
        std::copy(&from.lattice[0][0],
                  &from.lattice[0][0] + 4 * dim,
                  &to.lattice[0][0]);
    }


    template <int dim>
    void
    MpmTransfer<dim>::append_nodes(OccupiedCell &occupied)
    {
      occupied.node_begin = node_local.size();
      if (parameters.shape_functions == ShapeFunctions::gimp)
        {
          const auto &patch = patches.patch(occupied.cell);
          occupied.patch    = &patch;
          // A regular patch's lattice is its cell's (the same numbers:
          // the point cell's vertices are lattice nodes 1 and 2).
          occupied.regular =
            patch.regular &&
            std::abs(patch.lattice_h - occupied.h) <= 1e-12 * occupied.h;
          if (occupied.regular)
            std::copy(&patch.lattice[0][0],
                      &patch.lattice[0][0] + 4 * dim,
                      &occupied.lattice[0][0]);
          node_local.insert(node_local.end(),
                            patch.node_local.begin(),
                            patch.node_local.end());
          node_dof.insert(node_dof.end(),
                          patch.node_dofs.begin(),
                          patch.node_dofs.end());
          node_position.insert(node_position.end(),
                               patch.node_positions.begin(),
                               patch.node_positions.end());
        }
      else
        {
          const Utilities::MPI::Partitioner &partitioner =
            *mass.get_partitioner();
          occupied.patch   = nullptr;
          occupied.regular = false;
          cell_dofs.resize(Q1Shape<dim>::n);
          occupied.cell->get_dof_indices(cell_dofs);
          for (unsigned int i = 0; i < Q1Shape<dim>::n; ++i)
            {
              Point<dim> x;
              for (unsigned int d = 0; d < dim; ++d)
                x[d] = occupied.x0[d] + occupied.h * Q1Shape<dim>::offset(i, d);
              node_local.push_back(partitioner.global_to_local(cell_dofs[i]));
              node_dof.push_back(cell_dofs[i]);
              node_position.push_back(x);
            }
        }
      occupied.n_nodes = node_local.size() - occupied.node_begin;
    }


    // Instantiations (the other members are in the other mpm_transfer*.cc
    // files).
    template void
    MpmTransfer<2>::compute_shapes();
    template void
    MpmTransfer<3>::compute_shapes();
    template unsigned int
    MpmTransfer<2>::keep_nonzero(const double       *value,
                                 const Tensor<1, 2> *gradient,
                                 const unsigned int  n,
                                 const unsigned int  at);
    template unsigned int
    MpmTransfer<3>::keep_nonzero(const double       *value,
                                 const Tensor<1, 3> *gradient,
                                 const unsigned int  n,
                                 const unsigned int  at);
    template void
    MpmTransfer<2>::find_occupied_cells();
    template void
    MpmTransfer<3>::find_occupied_cells();
    template bool
    MpmTransfer<2>::find_previous(
      const typename DoFHandler<2>::active_cell_iterator &cell,
      std::size_t                                        &j) const;
    template bool
    MpmTransfer<3>::find_previous(
      const typename DoFHandler<3>::active_cell_iterator &cell,
      std::size_t                                        &j) const;
    template void
    MpmTransfer<2>::take_nodes(const OccupiedCell &from, OccupiedCell &to);
    template void
    MpmTransfer<3>::take_nodes(const OccupiedCell &from, OccupiedCell &to);
    template void
    MpmTransfer<2>::append_nodes(OccupiedCell &occupied);
    template void
    MpmTransfer<3>::append_nodes(OccupiedCell &occupied);
  } // namespace transfer
} // namespace scarp
