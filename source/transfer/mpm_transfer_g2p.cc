// MpmTransfer: G2P, the points' velocities, positions and deformation from
// the grid, and the constitutive updates in batches by material.

#include <scarp/transfer/f_bar.h>
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
    MpmTransfer<dim>::add_point_measures(const double         *p,
                                         const Point<dim>     &x,
                                         const Tensor<1, dim> &gravity,
                                         StepReport           &report) const
    {
      const double         m = p[layout.mass];
      const Tensor<1, dim> v = layout.get_vector(p, layout.velocity);
      report.kinetic_energy += 0.5 * m * v.norm_square();
      report.gravitational_energy -= m * (gravity * x);
      report.mass += m;
      report.n_points += 1;
      for (unsigned int d = 0; d < dim; ++d)
        report.momentum[d] += m * v[d];
      if (dim == 2)
        report.angular_momentum[2] += m * (x[0] * v[1] - x[1] * v[0]);
      else
        {
          const Tensor<1, 3> r({x[0], x[1], x[dim - 1]});
          const Tensor<1, 3> u({v[0], v[1], v[dim - 1]});
          const auto         l = cross_product_3d(r, u);
          for (unsigned int d = 0; d < 3; ++d)
            report.angular_momentum[d] += m * l[d];
        }
      // Squared here; StepReport::reduce takes the root.
      report.max_speed = std::max(report.max_speed, v.norm_square());
      const materials::Material &material =
        *materials[static_cast<unsigned int>(p[layout.material_id])];
      const double *state = p + layout.state;
      const double  d     = material.damage(state);
      report.max_damage   = std::max(report.max_damage, d);
      const double V0     = p[layout.reference_volume];
      report.damaged_volume += d * V0;
      const materials::DissipatedEnergy dissipated =
        material.dissipated_energy(state);
      report.plastic_dissipation += V0 * dissipated.plastic;
      report.damage_dissipation += V0 * dissipated.damage;
    }


    template <int dim>
    void
    MpmTransfer<dim>::grid_to_particles(
      const double                        dt,
      const bool                          update_positions_and_velocities,
      const bool                          update_stress,
      const materials::InelasticSwitches &inelastic,
      const std::array<Vector, dim>      &stress_velocity,
      StepReport                         &report,
      DamagePoints<dim>                  *damage_points,
      const Tensor<1, dim>               &gravity,
      const bool                          gather_momentum)
    {
      auto                   &pool   = particle_handler.get_property_pool();
      unsigned int            k      = 0; // point counter
      const double            alpha  = parameters.flip_weight(dt);
      const bool              apic   = layout.has_affine;
      const BoundingBox<dim> &domain = grid.domain();
      material_scratch.resize(materials.size());
      auto &batches  = material_scratch;
      auto &v_new    = local_v_new;
      auto &v_old    = local_v_old;
      auto &v_stress = local_v_stress;
      auto &empty    = local_empty;

      const bool f_bar =
        parameters.volumetric_averaging == VolumetricAveraging::f_bar;
      // The MUSL remap's P2G of the new point velocities (remap_momentum()),
      // made while each point's velocity and shape functions are at hand:
      // the sums, and their order, of a P2G of m v alone, point by point
      // and cell by cell. Without the affine term also with APIC: C = grad
      // v_grid^{n+1} is unbounded next to a node of tiny mass (grad S_i
      // does not vanish with S_i); mapped here it would make the stress
      // velocity unbounded too, and APIC blew up as soon as points crossed
      // into empty cells (vibrating bar, rotating disk).
      const bool gather = update_positions_and_velocities && gather_momentum;
      if (gather)
        for (unsigned int d = 0; d < dim; ++d)
          momentum[d] = 0;
      const bool gather_directly = cell_sums_add_directly();
      // Empty nodes enter the velocity gradients (stress) and APIC's affine
      // matrix.
      const bool need_empty =
        update_stress || (apic && update_positions_and_velocities);
      // Whether a node of the current cell is empty: nearly never, and then
      // the sums need no test per entry.
      bool cell_has_empty = false;
      // Gradient at a point, from its shape entries [e0, e1), of the nodal
      // velocities v taken relative to the point's own v_point (empty nodes
      // left out): the velocity gradient of the stress sweep and APIC's
      // affine matrix. The lambdas here are inlined: called, their tensors
      // came back through the stack (see cayley_increment below).
      const auto gradient_about = [&](const std::vector<Tensor<1, dim>> &v,
                                      const Tensor<1, dim> &v_point,
                                      const unsigned int    e0,
                                      const unsigned int    e1)
        __attribute__((always_inline))
      {
        Tensor<2, dim> L;
        if (cell_has_empty)
          {
            for (unsigned int e = e0; e < e1; ++e)
              if (!empty[shape_node[e]])
                L +=
                  outer_product(v[shape_node[e]] - v_point, shape_gradient[e]);
          }
        else // the same sums without a test per entry
          for (unsigned int e = e0; e < e1; ++e)
            L += outer_product(v[shape_node[e]] - v_point, shape_gradient[e]);
        return L;
      };
      // Velocity gradient of a point from its shape entries [e0, e1).
      const auto velocity_gradient = [&](const unsigned int e0,
                                         const unsigned int e1)
        __attribute__((always_inline))
      {
        Tensor<1, dim> v_point;
        for (unsigned int e = e0; e < e1; ++e)
          v_point += shape_value[e] * v_stress[shape_node[e]];
        return gradient_about(v_stress, v_point, e0, e1);
      };
      // Cayley (midpoint) increment: exactly a rotation when L is a spin,
      // so rigid rotation creates no stress. Inlined: as a call its result
      // came back through the stack, stored in 8-byte pieces and read in
      // 16-byte ones, a failed store forwarding per point (perf annotate).
      const auto cayley_increment = [dt](const Tensor<2, dim> &L)
        __attribute__((always_inline))
      {
        const Tensor<2, dim> half_step = 0.5 * dt * L;
        return Tensor<2, dim>(invert(unit_symmetric_tensor<dim>() - half_step) *
                              (unit_symmetric_tensor<dim>() + half_step));
      };

      for (const OccupiedCell &occupied : occupied_cells)
        {
          const double        h     = occupied.h;
          const Point<dim>   &x0    = occupied.x0;
          const auto         *patch = occupied.patch;
          const unsigned int  n     = occupied.n_nodes;
          const unsigned int *local_ptr =
            node_local.data() + occupied.node_begin;
          const types::global_dof_index *dof_ptr =
            node_dof.data() + occupied.node_begin;
          v_new.resize(n);
          v_old.resize(n);
          v_stress.resize(n);
          empty.resize(n);
          if (gather)
            local_sums.assign(dim * n, 0.);
          // A node no point gives mass to (a point on a cell edge has zero
          // weight but a non-zero gradient there) knows no velocity; it takes
          // part in gradients with the point's own interpolated velocity,
          // which keeps sum_i grad S_i = 0 and uniform motion strain-free.
          // Each sweep gathers only the nodal values it reads (MUSL: the
          // kinematic sweep the new and old velocities, the stress sweep
          // the remapped ones).
          cell_has_empty = false;
          if (need_empty)
            for (unsigned int i = 0; i < n; ++i)
              {
                empty[i] =
                  mass.local_element(local_ptr[i]) == 0. &&
                  (patch || !grid.constraints().is_constrained(dof_ptr[i]));
                cell_has_empty = cell_has_empty || empty[i];
              }
          if (update_positions_and_velocities)
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int d = 0; d < dim; ++d)
                {
                  v_new[i][d] = velocity_new[d].local_element(local_ptr[i]);
                  v_old[i][d] = velocity_old[d].local_element(local_ptr[i]);
                }
          if (update_stress)
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int d = 0; d < dim; ++d)
                v_stress[i][d] = stress_velocity[d].local_element(local_ptr[i]);
          // The constitutive updates of consecutive cells of one material
          // go together, in the order of the cells (so the points' order
          // of the bookings below and of the non-local step is that of
          // cell-by-cell updates); a cell of several materials is updated
          // on its own, material by material.
          // With one material in the scene there is nothing to read (the
          // read was the first touch of each point's record in this sweep,
          // a wait on memory per point).
          int cell_material = materials.size() == 1 ? 0 : -1;
          if (update_stress)
            {
              for (unsigned int q = occupied.point_begin;
                   q < occupied.point_end && materials.size() > 1;
                   ++q)
                {
                  prefetch_record(point_properties,
                                  q + prefetch_distance,
                                  layout.n_properties());
                  const int m =
                    static_cast<int>(point_properties[q][layout.material_id]);
                  if (cell_material == -1)
                    cell_material = m;
                  else if (m != cell_material)
                    {
                      cell_material = -2; // several
                      break;
                    }
                }
              if (n_pending > 0 &&
                  (cell_material != pending_material || n_pending >= 256))
                update_pending(dt, inelastic, report, damage_points, gravity);
              pending_material = cell_material;
              n_pending += occupied.point_end - occupied.point_begin;
            }
          // F-bar: the increments of all points of the cell first, then
          // their common volume change (transfer/f_bar.h).
          if (update_stress && f_bar)
            {
              const unsigned int first    = occupied.point_begin;
              const unsigned int n_points = occupied.point_end - first;
              cell_L.resize(n_points);
              cell_delta_F.resize(n_points);
              cell_volume.resize(n_points);
              for (unsigned int i = 0; i < n_points; ++i)
                {
                  const double *p = point_properties[first + i];
                  cell_L[i]       = velocity_gradient(shape_begin[first + i],
                                                shape_begin[first + i + 1]);
                  cell_delta_F[i] = cayley_increment(cell_L[i]);
                  cell_volume[i] =
                    p[layout.reference_volume] *
                    determinant(
                      layout.get_matrix(p, layout.deformation_gradient));
                }
              apply_f_bar<dim>(cell_delta_F.data(),
                               cell_volume.data(),
                               n_points);
              // The rate of the stress power: Lbar, whose trace is the
              // cell's mean (the work of the grid forces of P2G).
              double sum_v = 0, mean_trace = 0;
              for (unsigned int i = 0; i < n_points; ++i)
                {
                  mean_trace += cell_volume[i] * trace(cell_L[i]);
                  sum_v += cell_volume[i];
                }
              mean_trace /= sum_v;
              for (unsigned int i = 0; i < n_points; ++i)
                {
                  const double shift = (mean_trace - trace(cell_L[i])) / dim;
                  for (unsigned int d = 0; d < dim; ++d)
                    cell_L[i][d][d] += shift;
                }
            }

          for (unsigned int q = occupied.point_begin; q < occupied.point_end;
               ++q)
            {
              prefetch_record(point_properties,
                              q + prefetch_distance,
                              layout.n_properties());
              const unsigned int handle = point_handle[q];
              double            *p      = point_properties[q];
              const auto        &xi     = pool.get_reference_location(handle);
              const unsigned int e0 = shape_begin[k], e1 = shape_begin[k + 1];
              ++k;
              if (update_positions_and_velocities)
                {
                  Tensor<1, dim> v_grid, dv;
                  for (unsigned int e = e0; e < e1; ++e)
                    {
                      const unsigned int i = shape_node[e];
                      v_grid += shape_value[e] * v_new[i];
                      dv += shape_value[e] * (v_new[i] - v_old[i]);
                    }
                  Tensor<1, dim> v;
                  // The FLIP update, v_p + S (v_new - v_start): the one the
                  // energy balance follows (it passes on the grid's
                  // changes and keeps the rest of the point's velocity).
                  const Tensor<1, dim> v_flip =
                    layout.get_vector(p, layout.velocity) + dv;
                  if (apic)
                    {
                      // The affine matrix: the gradient of the grid
                      // velocity at the point (APIC only).
                      v = v_grid;
                      layout.set_matrix(p,
                                        layout.affine,
                                        gradient_about(v_new, v_grid, e0, e1));
                    }
                  else
                    v = alpha * (layout.get_vector(p, layout.velocity) + dv) +
                        (1. - alpha) * v_grid;
                  layout.set_vector(p, layout.velocity, v);
                  if (gather)
                    {
                      const double m = p[layout.mass];
                      for (unsigned int e = e0; e < e1; ++e)
                        {
                          const unsigned int i = shape_node[e];
                          const double       w = shape_value[e] * m;
                          for (unsigned int d = 0; d < dim; ++d)
                            local_sums[d * n + i] += w * v[d];
                        }
                    }
                  // What the PIC share (APIC: the grid velocity) took from
                  // the FLIP update (doc/user_guide.md, energy balance).
                  report.transfer_dissipation +=
                    mass_scale * 0.5 * p[layout.mass] *
                    (v_flip.norm_square() - v.norm_square());
                  const Point<dim>     x_old = x0 + h * xi;
                  const Tensor<1, dim> dx    = dt * v_grid;
                  const Point<dim>     x_new = pool.get_location(handle) + dx;
                  pool.set_location(handle, x_new);
                  const bool finite = std::isfinite(v.norm_square()) &&
                                      std::isfinite(x_new.norm_square());
                  const bool outside  = finite && !domain.point_inside(x_new);
                  const bool too_fast = finite && dx.norm_square() > h * h;
                  if (!finite)
                    report.n_not_finite += 1;
                  report.n_outside += outside;
                  if (outside)
                    {
                      // The energy the point takes out of the mesh (its
                      // measures of this step still count it).
                      report.removed_kinetic_energy +=
                        0.5 * p[layout.mass] * v.norm_square();
                      report.removed_gravitational_energy -=
                        p[layout.mass] * (gravity * x_new);
                    }
                  report.n_too_fast += too_fast;
                  for (unsigned int d = 0; d < dim; ++d)
                    if (!(x_new[d] >= x0[d] && x_new[d] <= x0[d] + h))
                      {
                        report.n_changed_cell += 1;
                        break;
                      }
                  if ((!finite || outside || too_fast) && !report.has_offender)
                    {
                      report.has_offender = true;
                      for (unsigned int d = 0; d < dim; ++d)
                        report.offender[d] = x_old[d];
                    }
                }
              if (update_stress)
                {
                  // With F-bar, dF is dFbar and L (for the stress power
                  // only) Lbar.
                  const unsigned int   i = q - occupied.point_begin;
                  const Tensor<2, dim> L =
                    f_bar ? cell_L[i] : velocity_gradient(e0, e1);
                  const Tensor<2, dim> dF =
                    f_bar ? cell_delta_F[i] : cayley_increment(L);
                  const Tensor<2, dim> F =
                    dF * layout.get_matrix(p, layout.deformation_gradient);
                  layout.set_matrix(p, layout.deformation_gradient, F);
                  const double J = determinant(F);
                  if (!std::isfinite(J))
                    {
                      // Nothing sensible can be computed from it; the step
                      // is reported and the run stops collectively.
                      report.n_not_finite += 1;
                      if (!report.has_offender)
                        {
                          report.has_offender = true;
                          for (unsigned int d = 0; d < dim; ++d)
                            report.offender[d] = pool.get_location(handle)[d];
                        }
                      continue;
                    }
                  if (!(J > 0))
                    {
                      report.n_inverted += std::isfinite(J) ? 1 : 0;
                      report.n_not_finite += std::isfinite(J) ? 0 : 1;
                      if (!report.has_offender)
                        {
                          report.has_offender = true;
                          for (unsigned int d = 0; d < dim; ++d)
                            report.offender[d] = pool.get_location(handle)[d];
                        }
                    }
                  // Stress power with the old stress; the new half is added
                  // after the update (trapezoidal rule).
                  const SymmetricTensor<2, 3> sigma =
                    layout.get_stress(p, layout.stress);
                  double power = 0;
                  for (unsigned int i = 0; i < dim; ++i)
                    for (unsigned int j = 0; j < dim; ++j)
                      power += sigma[i][j] * 0.5 * (L[i][j] + L[j][i]);
                  const double V = p[layout.reference_volume] * J;
                  report.internal_work += 0.5 * dt * V * power;

                  MaterialScratch &b =
                    batches[static_cast<unsigned int>(p[layout.material_id])];
                  const unsigned int j = b.append();
                  embed_into<dim>(b.delta_F[j], dF, 1.);
                  b.strain_increment[j] = Tensor<2, dim>(dt * symmetrize(L));
                  embed_into<dim>(b.F[j], F, 1.);
                  b.state[j]      = p + layout.state;
                  b.stress[j]     = sigma;
                  b.properties[j] = p;
                  b.position[j]   = pool.get_location(handle);
                  b.id[j]         = pool.get_id(handle);
                }
            }

          if (update_stress && cell_material == -2)
            update_pending(dt, inelastic, report, damage_points, gravity);
          if (gather && gather_directly)
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int d = 0; d < dim; ++d)
                momentum[d].local_element(local_ptr[i]) +=
                  local_sums[d * n + i];
          else if (gather)
            {
              std::vector<const double *> values;
              std::vector<Vector *>       globals;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  values.push_back(local_sums.data() + d * n);
                  globals.push_back(&momentum[d]);
                }
              distribute_cell_sums(occupied, values, globals);
            }
        }
      if (update_stress && n_pending > 0)
        update_pending(dt, inelastic, report, damage_points, gravity);
    }


    template <int dim>
    void
    MpmTransfer<dim>::update_pending(
      const double                        dt,
      const materials::InelasticSwitches &inelastic,
      StepReport                         &report,
      DamagePoints<dim>                  *damage_points,
      const Tensor<1, dim>               &gravity)
    {
      auto &batches = material_scratch;
      for (unsigned int mat = 0; mat < batches.size(); ++mat)
        {
          MaterialScratch &b = batches[mat];
          if (b.n == 0)
            continue;
          const materials::Material &material      = *materials[mat];
          const double             removal_stretch = material.removal_stretch();
          materials::MaterialBatch batch;
          batch.n             = b.n;
          batch.dt            = dt;
          batch.delta_F       = b.delta_F.data();
          batch.F             = b.F.data();
          batch.state         = b.state.data();
          batch.stress        = b.stress.data();
          batch.stored_energy = b.stored_energy.data();
          batch.inelastic     = inelastic;
          if (material.has_damage())
            {
              batch.damage_driver = b.driver.data();
            }
          try
            {
              const auto start = Clock::now();
              material.update(batch);
              times.constitutive_update += seconds_since(start);
            }
          catch (...)
            {
              // A failed constitutive update (e.g. no convergence on a
              // garbage state) is reported like a non-finite stress:
              // the run then stops on every rank with the message.
              report.n_not_finite += batch.n;
              for (unsigned int k = 0; k < b.n; ++k)
                b.stress[k] = SymmetricTensor<2, 3>();
              if (!report.has_offender)
                {
                  report.has_offender = true;
                  for (unsigned int d = 0; d < dim; ++d)
                    report.offender[d] = b.position[0][d];
                }
            }
          for (unsigned int k = 0; k < batch.n; ++k)
            {
              double                      *p     = b.properties[k];
              const SymmetricTensor<2, 3> &sigma = b.stress[k];
              layout.set_stress(p, layout.stress, sigma);
              const double J  = determinant(b.F[k]);
              const double V0 = p[layout.reference_volume];
              // Second half of the trapezoidal stress power.
              report.internal_work +=
                0.5 * V0 * J * stress_power(sigma, b.strain_increment[k]);
              report.stored_energy += V0 * b.stored_energy[k];
              // The squared norm is finite exactly when the norm is; the
              // root kept every point's write-back waiting on it.
              if (!std::isfinite(scalar_product(sigma, sigma)))
                {
                  report.n_not_finite += 1;
                  if (!report.has_offender)
                    {
                      report.has_offender = true;
                      for (unsigned int d = 0; d < dim; ++d)
                        report.offender[d] = b.position[k][d];
                    }
                }
              add_point_measures(p, b.position[k], gravity, report);
              // A damaged point stretched too far (the authors' removal):
              // its energy is booked here, the point leaves the mesh at the
              // end of the step. The damage is that of the step before.
              if (removal_stretch > 0 && material.removable(p + layout.state))
                {
                  const double m = p[layout.mass];
                  report.removed_kinetic_energy +=
                    0.5 * m *
                    layout.get_vector(p, layout.velocity).norm_square();
                  report.removed_gravitational_energy -=
                    m * (gravity * b.position[k]);
                  report.n_removed_stretched += 1;
                  removal_ids.push_back(b.id[k]);
                }
              if (damage_points && material.has_damage())
                {
                  const double *state = p + layout.state;
                  damage_points->position.push_back(b.position[k]);
                  damage_points->volume.push_back(V0 * J);
                  damage_points->driver.push_back(b.driver[k]);
                  damage_points->receiver.push_back(
                    inelastic.damage && material.damage_can_change(state));
                  damage_points->source.push_back(
                    material.is_nonlocal_source(state));
                  damage_points->id.push_back(b.id[k]);
                  damage_points->properties.push_back(p);
                }
            }
        }
      for (auto &b : batches)
        b.clear();
      n_pending        = 0;
      pending_material = -1;
    }


    // Instantiations (the other members are in the other mpm_transfer*.cc
    // files).
    template void
    MpmTransfer<2>::add_point_measures(const double       *p,
                                       const Point<2>     &x,
                                       const Tensor<1, 2> &gravity,
                                       StepReport         &report) const;
    template void
    MpmTransfer<3>::add_point_measures(const double       *p,
                                       const Point<3>     &x,
                                       const Tensor<1, 3> &gravity,
                                       StepReport         &report) const;
    template void
    MpmTransfer<2>::grid_to_particles(
      const double                        dt,
      const bool                          update_positions_and_velocities,
      const bool                          update_stress,
      const materials::InelasticSwitches &inelastic,
      const std::array<Vector, 2>        &stress_velocity,
      StepReport                         &report,
      DamagePoints<2>                    *damage_points,
      const Tensor<1, 2>                 &gravity,
      const bool                          gather_momentum);
    template void
    MpmTransfer<3>::grid_to_particles(
      const double                        dt,
      const bool                          update_positions_and_velocities,
      const bool                          update_stress,
      const materials::InelasticSwitches &inelastic,
      const std::array<Vector, 3>        &stress_velocity,
      StepReport                         &report,
      DamagePoints<3>                    *damage_points,
      const Tensor<1, 3>                 &gravity,
      const bool                          gather_momentum);
    template void
    MpmTransfer<2>::update_pending(
      const double                        dt,
      const materials::InelasticSwitches &inelastic,
      StepReport                         &report,
      DamagePoints<2>                    *damage_points,
      const Tensor<1, 2>                 &gravity);
    template void
    MpmTransfer<3>::update_pending(
      const double                        dt,
      const materials::InelasticSwitches &inelastic,
      StepReport                         &report,
      DamagePoints<3>                    *damage_points,
      const Tensor<1, 3>                 &gravity);
  } // namespace transfer
} // namespace scarp
