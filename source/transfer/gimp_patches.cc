#include <scarp/base/exceptions.h>
#include <scarp/transfer/gimp_patches.h>

#include <algorithm>

namespace scarp
{
  namespace transfer
  {
    template <int dim>
    void
    GimpPatches<dim>::reinit(
      const DoFHandler<dim>             &dof_handler,
      const AffineConstraints<double>   &constraint_set,
      const Utilities::MPI::Partitioner &vector_partitioner)
    {
      partitioner      = &vector_partitioner;
      dofs             = &dof_handler;
      constraints      = &constraint_set;
      const auto &tria = dof_handler.get_triangulation();
      vertex_cells.assign(tria.n_vertices(), {});
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          for (const unsigned int v : cell->vertex_indices())
            vertex_cells[cell->vertex_index(v)].push_back(cell);
      patch_index.assign(tria.n_active_cells(), -1);
      patches.clear();
    }


    template <int dim>
    const typename GimpPatches<dim>::Patch &
    GimpPatches<dim>::patch(
      const typename DoFHandler<dim>::active_cell_iterator &cell)
    {
      int &index = patch_index[cell->active_cell_index()];
      if (index >= 0)
        return patches[index];

      // The active cells that touch the cell, in a fixed order (by
      // level and index, not by the order of the vertex lists), so that
      // the sums of a node come out the same on any partition.
      std::vector<typename DoFHandler<dim>::active_cell_iterator> cells;
      for (const unsigned int v : cell->vertex_indices())
        for (const auto &c : vertex_cells[cell->vertex_index(v)])
          cells.push_back(c);
      std::sort(cells.begin(), cells.end(), [](const auto &a, const auto &b) {
        return a->id() < b->id();
      });
      cells.erase(std::unique(cells.begin(), cells.end()), cells.end());

      Patch                                p;
      constexpr unsigned int               n_v = 1u << dim;
      std::vector<types::global_dof_index> cell_dofs(n_v);
      const auto node_of = [&](const types::global_dof_index dof,
                               const Point<dim>             &position) {
        for (unsigned int k = 0; k < p.node_dofs.size(); ++k)
          if (p.node_dofs[k] == dof)
            return k;
        p.node_dofs.push_back(dof);
        p.node_positions.push_back(position);
        return static_cast<unsigned int>(p.node_dofs.size() - 1);
      };
      // Positions of the masters of hanging vertices: vertices of the
      // patch cells or of cells touching them.
      const auto position_of =
        [&](const types::global_dof_index                         dof,
            const typename DoFHandler<dim>::active_cell_iterator &near) {
          for (const unsigned int v : near->vertex_indices())
            for (const auto &c : vertex_cells[near->vertex_index(v)])
              for (const unsigned int w : c->vertex_indices())
                if (c->vertex_dof_index(w, 0) == dof)
                  return c->vertex(w);
          throw ScarpError("GIMP: the master of a hanging node is not on a "
                           "cell next to the point's cell (mesh not balanced "
                           "at vertices).");
        };
      p.entry_begin.push_back(0);
      for (const auto &c : cells)
        {
          const Point<dim> lower = c->vertex(0);
          p.cell_lower.push_back(lower);
          p.cell_size.push_back(c->vertex(1)[0] - lower[0]);
          c->get_dof_indices(cell_dofs);
          for (unsigned int i = 0; i < n_v; ++i)
            {
              const types::global_dof_index dof = cell_dofs[i];
              if (constraints->is_constrained(dof))
                {
                  const auto *entries =
                    constraints->get_constraint_entries(dof);
                  for (const auto &[master, weight] : *entries)
                    {
                      p.entry_node.push_back(
                        node_of(master, position_of(master, c)));
                      p.entry_weight.push_back(weight);
                    }
                }
              else
                {
                  p.entry_node.push_back(node_of(dof, c->vertex(i)));
                  p.entry_weight.push_back(1.);
                }
              p.entry_begin.push_back(p.entry_node.size());
            }
        }
      for (const types::global_dof_index dof : p.node_dofs)
        p.node_local.push_back(partitioner->global_to_local(dof));
      for (unsigned int c = 0; c < p.cell_size.size(); ++c)
        {
          typename Patch::Cell cell;
          cell.lower = p.cell_lower[c];
          for (unsigned int d = 0; d < dim; ++d)
            cell.upper[d] = p.cell_lower[c][d] + p.cell_size[c];
          cell.h     = p.cell_size[c];
          cell.inv_h = 1. / p.cell_size[c];
          for (unsigned int i = 0; i <= n_v; ++i)
            cell.entry_begin[i] = p.entry_begin[c * n_v + i];
          p.cells.push_back(cell);
        }
      for (unsigned int e = 0; e < p.entry_node.size(); ++e)
        p.entries.emplace_back(p.entry_node[e], p.entry_weight[e]);
      index = patches.size();
      patches.push_back(std::move(p));
      return patches.back();
    }


    template <int dim>
    void
    GimpPatches<dim>::evaluate(const Patch      &patch,
                               const Point<dim> &x,
                               const double (&l)[dim],
                               std::vector<double>         &value,
                               std::vector<Tensor<1, dim>> &gradient)
    {
      const unsigned int n = patch.n_nodes();
      value.assign(n, 0.);
      gradient.assign(n, Tensor<1, dim>());
      constexpr unsigned int n_v = 1u << dim;
      for (const typename Patch::Cell &cell : patch.cells)
        {
          const double h        = cell.h;
          double       fraction = 1.;
          double       xi[dim];
          bool         overlaps = true;
          for (unsigned int d = 0; d < dim && overlaps; ++d)
            {
              const double a = cell.lower[d], b = cell.upper[d];
              if (l[d] > 0)
                {
                  const double lo = std::max(x[d] - l[d], a);
                  const double hi = std::min(x[d] + l[d], b);
                  if (!(hi > lo))
                    overlaps = false;
                  else
                    {
                      fraction *= (hi - lo) / (2. * l[d]);
                      xi[d] = (0.5 * (lo + hi) - a) / h;
                    }
                }
              else
                {
                  // A point domain without extent in d: only on the mesh
                  // boundary, where one cell holds it in that direction.
                  if (!(x[d] >= a && x[d] <= b))
                    overlaps = false;
                  else
                    xi[d] = (x[d] - a) / h;
                }
            }
          if (!overlaps)
            continue;
          const double inv_h = cell.inv_h;
          for (unsigned int i = 0; i < n_v; ++i)
            {
              double f[dim], df[dim];
              for (unsigned int d = 0; d < dim; ++d)
                {
                  const bool upper = (i >> d) & 1u;
                  f[d]             = upper ? xi[d] : 1. - xi[d];
                  df[d]            = upper ? inv_h : -inv_h;
                }
              double         phi = fraction;
              Tensor<1, dim> grad;
              for (unsigned int d = 0; d < dim; ++d)
                phi *= f[d];
              for (unsigned int d = 0; d < dim; ++d)
                {
                  double g = fraction * df[d];
                  for (unsigned int e = 0; e < dim; ++e)
                    if (e != d)
                      g *= f[e];
                  grad[d] = g;
                }
              for (unsigned int e = cell.entry_begin[i];
                   e < cell.entry_begin[i + 1];
                   ++e)
                {
                  const auto &[node, w] = patch.entries[e];
                  value[node] += w * phi;
                  gradient[node] += w * grad;
                }
            }
        }
    }

    template class GimpPatches<2>;
    template class GimpPatches<3>;
  } // namespace transfer
} // namespace scarp
