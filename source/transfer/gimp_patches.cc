#include <scarp/base/exceptions.h>
#include <scarp/transfer/gimp_patches.h>

#include <algorithm>
#include <cmath>
#include <iterator>

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
      auto &cells = scratch_cells;
      cells.clear();
      for (const unsigned int v : cell->vertex_indices())
        for (const auto &c : vertex_cells[cell->vertex_index(v)])
          cells.push_back(c);
      std::sort(cells.begin(), cells.end(), [](const auto &a, const auto &b) {
        return a->id() < b->id();
      });
      cells.erase(std::unique(cells.begin(), cells.end()), cells.end());

      Patch &p = scratch;
      p.cells.clear();
      p.entries.clear();
      p.node_dofs.clear();
      p.node_positions.clear();
      p.node_local.clear();
      p.regular                        = false;
      p.lattice_h                      = 0;
      p.lattice_inv_h                  = 0;
      constexpr unsigned int n_v       = 1u << dim;
      auto                  &cell_dofs = scratch_dofs;
      cell_dofs.resize(n_v);
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
      for (const auto &c : cells)
        {
          typename Patch::Cell patch_cell;
          patch_cell.lower  = c->vertex(0);
          const double size = c->vertex(1)[0] - patch_cell.lower[0];
          for (unsigned int d = 0; d < dim; ++d)
            patch_cell.upper[d] = patch_cell.lower[d] + size;
          patch_cell.h              = size;
          patch_cell.inv_h          = 1. / size;
          patch_cell.entry_begin[0] = p.entries.size();
          c->get_dof_indices(cell_dofs);
          for (unsigned int i = 0; i < n_v; ++i)
            {
              const types::global_dof_index dof = cell_dofs[i];
              if (constraints->is_constrained(dof))
                {
                  const auto *entries =
                    constraints->get_constraint_entries(dof);
                  for (const auto &[master, weight] : *entries)
                    p.entries.emplace_back(node_of(master,
                                                   position_of(master, c)),
                                           weight);
                }
              else
                p.entries.emplace_back(node_of(dof, c->vertex(i)), 1.);
              patch_cell.entry_begin[i + 1] = p.entries.size();
            }
          p.cells.push_back(patch_cell);
        }
      for (const types::global_dof_index dof : p.node_dofs)
        p.node_local.push_back(partitioner->global_to_local(dof));
      detect_regular(p,
                     cell->vertex(0),
                     cell->vertex(1)[0] - cell->vertex(0)[0]);
      // A copy: its arrays take their exact size (a patch lives until the
      // mesh changes), the scratch keeps its room for the next patch.
      index = patches.size();
      patches.push_back(p);
      return patches.back();
    }


    namespace
    {
      constexpr unsigned int
      lattice_size(const int dim)
      {
        return dim == 2 ? 16u : 64u;
      }

      /// 1D GIMP weights w[a] and derivatives g[a] of the 4 lattice nodes
      /// X[0..3] for a domain [x - l, x + l] (l > 0) inside [X[0], X[3]]:
      /// the same sum over the cells the domain overlaps as the general
      /// path, one direction at a time.
      inline void
      weights_1d(const double (&X)[4],
                 const double inv_h,
                 const double x,
                 const double l,
                 double (&w)[4],
                 double (&g)[4])
      {
        for (unsigned int a = 0; a < 4; ++a)
          w[a] = g[a] = 0.;
        const double inv_2l = 0.5 / l;
        for (unsigned int c = 0; c < 3; ++c)
          {
            const double lo = std::max(x - l, X[c]);
            const double hi = std::min(x + l, X[c + 1]);
            if (!(hi > lo))
              continue;
            const double fraction = (hi - lo) * inv_2l;
            const double xi       = (0.5 * (lo + hi) - X[c]) * inv_h;
            w[c] += fraction * (1. - xi);
            w[c + 1] += fraction * xi;
            g[c] -= fraction * inv_h;
            g[c + 1] += fraction * inv_h;
          }
      }

      /// Whether the regular path applies to a point: every half-width is
      /// positive (l_d = 0 only on the mesh boundary, where no patch is
      /// regular; checked all the same).
      template <int dim>
      inline bool
      all_positive(const double (&l)[dim])
      {
        for (unsigned int d = 0; d < dim; ++d)
          if (!(l[d] > 0.))
            return false;
        return true;
      }
    } // namespace


    template <int dim>
    void
    GimpPatches<dim>::detect_regular(Patch            &p,
                                     const Point<dim> &cell_lower,
                                     const double      h)
    {
      constexpr unsigned int n_v = 1u << dim;
      constexpr unsigned int n_l = lattice_size(dim);
      p.regular                  = false;
      if (p.cells.size() != (dim == 2 ? 9u : 27u) || p.n_nodes() != n_l ||
          p.entries.size() != p.cells.size() * n_v)
        return;
      // Every vertex its own node with weight 1 (no hanging vertex), and
      // every cell of the point cell's size (to round-off: the edges of
      // one level are the same number).
      for (const auto &[node, weight] : p.entries)
        if (weight != 1.)
          return;
      for (const auto &c : p.cells)
        if (std::abs(c.h - h) > 1e-12 * h)
          return;
      // The lattice: the nodes at lower + (a - 1) h, a = 0..3.
      std::vector<unsigned int> lattice_index(p.n_nodes());
      std::vector<bool>         taken(n_l, false);
      for (unsigned int j = 0; j < p.n_nodes(); ++j)
        {
          unsigned int index = 0, stride = 1;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double t =
                (p.node_positions[j][d] - cell_lower[d]) / h + 1.;
              const long a = std::lround(t);
              if (a < 0 || a > 3 || std::abs(t - a) > 1e-8)
                return;
              p.lattice[d][a] = p.node_positions[j][d];
              index += a * stride;
              stride *= 4;
            }
          if (taken[index])
            return;
          taken[index]     = true;
          lattice_index[j] = index;
        }
      // Nodes in lattice order, so that the lattice index is the node.
      const auto permute = [&](auto &values) {
        auto old = values;
        for (unsigned int j = 0; j < lattice_index.size(); ++j)
          values[lattice_index[j]] = old[j];
      };
      permute(p.node_dofs);
      permute(p.node_positions);
      permute(p.node_local);
      for (auto &entry : p.entries)
        entry.first = lattice_index[entry.first];
      p.lattice_h     = h;
      p.lattice_inv_h = 1. / h;
      p.regular       = true;
    }


    template <int dim>
    void
    GimpPatches<dim>::evaluate(const Patch      &patch,
                               const Point<dim> &x,
                               const double (&l)[dim],
                               std::vector<double>         &value,
                               std::vector<Tensor<1, dim>> &gradient)
    {
      if (!patch.regular || !all_positive<dim>(l))
        {
          evaluate_general(patch, x, l, value, gradient);
          return;
        }
      // The non-zero entries of the regular path, the others zero.
      value.assign(patch.n_nodes(), 0.);
      gradient.assign(patch.n_nodes(), Tensor<1, dim>());
      constexpr unsigned int n_max = dim == 2 ? 9 : 27;
      unsigned int           node[n_max];
      double                 v[n_max];
      Tensor<1, dim>         g[n_max];
      const unsigned int     n =
        regular_nonzero(patch.lattice, patch.lattice_inv_h, x, l, node, v, g);
      for (unsigned int k = 0; k < n; ++k)
        {
          value[node[k]]    = v[k];
          gradient[node[k]] = g[k];
        }
    }


    template <int dim>
    unsigned int
    GimpPatches<dim>::regular_nonzero(const double (&lattice)[dim][4],
                                      const double      inv_h,
                                      const Point<dim> &x,
                                      const double (&l)[dim],
                                      unsigned int   *node,
                                      double         *value,
                                      Tensor<1, dim> *gradient)
    {
      // The 1D weights vanish outside a range of at most 3 nodes per
      // direction: only the products inside it can be non-zero.
      double       w[dim][4], g[dim][4];
      unsigned int first[dim], last[dim];
      for (unsigned int d = 0; d < dim; ++d)
        {
          weights_1d(lattice[d], inv_h, x[d], l[d], w[d], g[d]);
          first[d] = 4;
          last[d]  = 0;
          for (unsigned int a = 0; a < 4; ++a)
            if (w[d][a] != 0. || g[d][a] != 0.)
              {
                first[d] = std::min(first[d], a);
                last[d]  = a;
              }
          if (first[d] > last[d])
            return 0;
          // l <= h/2 keeps the domain within 2 cells per direction: 3
          // nodes at most (the caller has room for 3^dim entries).
          if (last[d] - first[d] > 2)
            throw ScarpError("GIMP: a point domain reaches more than 2 "
                             "cells in one direction (l > h/2).");
        }
      unsigned int n      = 0;
      const auto   append = [&](const unsigned int(&a)[dim]) {
        double v = 1.;
        for (unsigned int d = 0; d < dim; ++d)
          v *= w[d][a[d]];
        Tensor<1, dim> grad;
        for (unsigned int d = 0; d < dim; ++d)
          {
            double gd = g[d][a[d]];
            for (unsigned int e = 0; e < dim; ++e)
              if (e != d)
                gd *= w[e][a[e]];
            grad[d] = gd;
          }
        if (v != 0. || grad.norm_square() != 0.)
          {
            unsigned int index = 0, stride = 1;
            for (unsigned int d = 0; d < dim; ++d)
              {
                index += a[d] * stride;
                stride *= 4;
              }
            node[n]     = index;
            value[n]    = v;
            gradient[n] = grad;
            ++n;
          }
      };
      unsigned int a[dim];
      if constexpr (dim == 2)
        {
          for (a[1] = first[1]; a[1] <= last[1]; ++a[1])
            for (a[0] = first[0]; a[0] <= last[0]; ++a[0])
              append(a);
        }
      else
        {
          for (a[2] = first[2]; a[2] <= last[2]; ++a[2])
            for (a[1] = first[1]; a[1] <= last[1]; ++a[1])
              for (a[0] = first[0]; a[0] <= last[0]; ++a[0])
                append(a);
        }
      return n;
    }


    template <int dim>
    void
    GimpPatches<dim>::evaluate_general(const Patch      &patch,
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
