// MpmTransfer: P2G, the points' mass, momentum and forces summed per cell
// and the cells' sums added to the grid.

#include <scarp/transfer/mpm_transfer.h>
#include <scarp/transfer/mpm_transfer_internal.h>

#include <cmath>

namespace scarp
{
  namespace transfer
  {
    using namespace internal;


    template <int dim>
    void
    MpmTransfer<dim>::particles_to_grid(const Tensor<1, dim> &gravity)
    {
      mass = 0;
      for (unsigned int d = 0; d < dim; ++d)
        {
          momentum[d] = 0;
          force[d]    = 0;
          if (body_force)
            body_force_nodal[d] = 0;
        }
      const auto  &pool         = particle_handler.get_property_pool();
      const bool   apic         = layout.has_affine;
      unsigned int k            = 0; // point counter
      const bool   add_directly = cell_sums_add_directly();
      const bool   f_bar =
        parameters.volumetric_averaging == VolumetricAveraging::f_bar;

      for (const OccupiedCell &occupied : occupied_cells)
        {
          const double        h  = occupied.h;
          const Point<dim>   &x0 = occupied.x0;
          const unsigned int  n  = occupied.n_nodes;
          const unsigned int *local_ptr =
            node_local.data() + occupied.node_begin;
          const Point<dim> *node_ptr =
            node_position.data() + occupied.node_begin;
          // Accumulators of the cell: mass, momentum d, force d and, with
          // a body force, its share of the force d (n each): its work is
          // booked on the grid, where it acts.
          const bool with_body = body_force != nullptr;
          local_sums.assign((1 + (with_body ? 3 : 2) * dim) * n, 0.);
          double *const local_mass = local_sums.data();
          double *local_momentum[dim], *local_force[dim], *local_body[dim];
          for (unsigned int d = 0; d < dim; ++d)
            {
              local_momentum[d] = local_mass + (1 + d) * n;
              local_force[d]    = local_mass + (1 + dim + d) * n;
              local_body[d] =
                with_body ? local_mass + (1 + 2 * dim + d) * n : nullptr;
            }
          // F-bar: the stress deforms with the cell's mean volume change,
          // so its mean normal stress (of the dim in-plane components)
          // acts through the cell's volume-weighted mean of the gradients:
          // each point's is replaced by the cell's. The grid forces then do
          // the work the stresses take (sigma : Dbar); with each point's
          // own, dilatant plastic flow (pressures that differ within a
          // cell) fed energy into the motion without bound
          // (doc/examples.md, section 3).
          double mean_normal_stress = 0;
          if (f_bar)
            {
              double sum_v = 0;
              for (unsigned int q = occupied.point_begin;
                   q < occupied.point_end;
                   ++q)
                {
                  const double *p = point_properties[q];
                  const double  volume =
                    p[layout.reference_volume] *
                    determinant(
                      layout.get_matrix(p, layout.deformation_gradient));
                  const SymmetricTensor<2, 3> sigma =
                    layout.get_stress(p, layout.stress);
                  for (unsigned int d = 0; d < dim; ++d)
                    mean_normal_stress += volume * sigma[d][d] / dim;
                  sum_v += volume;
                }
              mean_normal_stress /= sum_v;
            }
          for (unsigned int q = occupied.point_begin; q < occupied.point_end;
               ++q)
            {
              prefetch_record(point_properties,
                              q + prefetch_distance,
                              layout.n_properties());
              const double    *p = point_properties[q];
              const Point<dim> xp =
                x0 + h * pool.get_reference_location(point_handle[q]);
              const unsigned int e0 = shape_begin[k], e1 = shape_begin[k + 1];
              ++k;
              const double         m = p[layout.mass];
              const Tensor<1, dim> v = layout.get_vector(p, layout.velocity);
              Tensor<2, dim>       C;
              if (apic)
                C = layout.get_matrix(p, layout.affine);
              const double J =
                determinant(layout.get_matrix(p, layout.deformation_gradient));
              const double          volume = p[layout.reference_volume] * J;
              SymmetricTensor<2, 3> sigma = layout.get_stress(p, layout.stress);
              if (f_bar)
                {
                  double normal = 0;
                  for (unsigned int d = 0; d < dim; ++d)
                    normal += sigma[d][d] / dim;
                  for (unsigned int d = 0; d < dim; ++d)
                    sigma[d][d] += mean_normal_stress - normal;
                }
              Tensor<1, dim> acceleration = gravity, body;
              if (with_body)
                {
                  const Point<dim> X(
                    layout.get_vector(p, layout.reference_position));
                  for (unsigned int d = 0; d < dim; ++d)
                    body[d] = body_force->value(X, d);
                  acceleration += body;
                }
              for (unsigned int e = e0; e < e1; ++e)
                {
                  const unsigned int i  = shape_node[e];
                  const double       w  = shape_value[e] * m;
                  Tensor<1, dim>     vi = v;
                  if (apic)
                    vi += C * (node_ptr[i] - xp);
                  const Tensor<1, dim> f =
                    -volume * stress_times<dim>(sigma, shape_gradient[e]) +
                    w * acceleration;
                  local_mass[i] += w;
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      local_momentum[d][i] += w * vi[d];
                      local_force[d][i] += f[d];
                    }
                  if (with_body)
                    for (unsigned int d = 0; d < dim; ++d)
                      local_body[d][i] += w * body[d];
                }
            }
          if (add_directly)
            {
              for (unsigned int i = 0; i < n; ++i)
                {
                  mass.local_element(local_ptr[i]) += local_mass[i];
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      momentum[d].local_element(local_ptr[i]) +=
                        local_momentum[d][i];
                      force[d].local_element(local_ptr[i]) += local_force[d][i];
                      if (with_body)
                        body_force_nodal[d].local_element(local_ptr[i]) +=
                          local_body[d][i];
                    }
                }
              continue;
            }
          std::vector<const double *> values  = {local_mass};
          std::vector<Vector *>       globals = {&mass};
          for (unsigned int d = 0; d < dim; ++d)
            {
              values.insert(values.end(), {local_momentum[d], local_force[d]});
              globals.insert(globals.end(), {&momentum[d], &force[d]});
              if (with_body)
                {
                  values.push_back(local_body[d]);
                  globals.push_back(&body_force_nodal[d]);
                }
            }
          distribute_cell_sums(occupied, values, globals);
        }
      std::vector<Vector *> sums = {&mass};
      for (unsigned int d = 0; d < dim; ++d)
        {
          sums.push_back(&momentum[d]);
          sums.push_back(&force[d]);
          if (body_force)
            sums.push_back(&body_force_nodal[d]);
        }
      compress_add(sums, times.exchange);
    }


    template <int dim>
    bool
    MpmTransfer<dim>::cell_sums_add_directly() const
    {
      // GIMP patch nodes are unconstrained (the patch resolved the hanging
      // ones); Q1 cells on a mesh with hanging nodes go through the
      // constraints.
      return parameters.shape_functions == ShapeFunctions::gimp ||
             grid.constraints().n_constraints() == 0;
    }


    template <int dim>
    void
    MpmTransfer<dim>::distribute_cell_sums(
      const OccupiedCell                &occupied,
      const std::vector<const double *> &values,
      const std::vector<Vector *>       &globals) const
    {
      const unsigned int                         n = occupied.n_nodes;
      const std::vector<types::global_dof_index> dofs(
        node_dof.begin() + occupied.node_begin,
        node_dof.begin() + occupied.node_begin + n);
      dealii::Vector<double> local(n);
      for (unsigned int c = 0; c < values.size(); ++c)
        {
          std::copy(values[c], values[c] + n, local.begin());
          grid.constraints().distribute_local_to_global(local,
                                                        dofs,
                                                        *globals[c]);
        }
    }


    // Instantiations (the other members are in the other mpm_transfer*.cc
    // files).
    template void
    MpmTransfer<2>::particles_to_grid(const Tensor<1, 2> &gravity);
    template void
    MpmTransfer<3>::particles_to_grid(const Tensor<1, 3> &gravity);
    template bool
    MpmTransfer<2>::cell_sums_add_directly() const;
    template bool
    MpmTransfer<3>::cell_sums_add_directly() const;
    template void
    MpmTransfer<2>::distribute_cell_sums(
      const OccupiedCell                &occupied,
      const std::vector<const double *> &values,
      const std::vector<Vector *>       &globals) const;
    template void
    MpmTransfer<3>::distribute_cell_sums(
      const OccupiedCell                &occupied,
      const std::vector<const double *> &values,
      const std::vector<Vector *>       &globals) const;
  } // namespace transfer
} // namespace scarp
