#include <deal.II/base/mpi.h>
#include <deal.II/lac/vector.h>

#include <scarp/base/exceptions.h>
#include <scarp/transfer/f_bar.h>
#include <scarp/transfer/mpm_transfer.h>
#include <scarp/transfer/q1_shape.h>

#include <chrono>
#include <cmath>
#include <map>
#include <type_traits>

namespace scarp
{
  namespace transfer
  {
    namespace
    {
      using Clock = std::chrono::steady_clock;

      /// How many points ahead the sweeps prefetch a point's properties.
      constexpr std::size_t prefetch_distance = 4;

      /// Seconds since @p start.
      inline double
      seconds_since(const Clock::time_point &start)
      {
        return std::chrono::duration<double>(Clock::now() - start).count();
      }

      /// Write the 3x3 embedding of a dim x dim tensor into @p b (plane
      /// strain: zz = 1), entry by entry: a temporary returned by value was
      /// built on the stack in overlapping pieces and read back whole, a
      /// failed store-to-load forwarding per tensor (perf: a tenth of the
      /// samples of grid_to_particles in the main job).
      template <int dim>
      void
      embed_into(Tensor<2, 3> &b, const Tensor<2, dim> &a, const double zz)
      {
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            b[i][j] = (i < dim && j < dim) ? a[i % dim][j % dim]
                      : (i == j)           ? zz
                                           : 0.;
      }

      /// Ask for the property record of the point @p ahead places on in
      /// the sweep's order while this one is worked on: a record spans
      /// three cache lines, and the sweeps read every point's from memory.
      inline void
      prefetch_record(const std::vector<double *> &records,
                      const std::size_t            ahead,
                      const unsigned int           n_doubles)
      {
        if (ahead < records.size())
          for (unsigned int i = 0; i < n_doubles; i += 8)
            __builtin_prefetch(records[ahead] + i, 1, 3);
      }

      /// sigma : e for e with zero entries out of the dim x dim block: the
      /// sum of scalar_product() of the embedded e, in its order, without
      /// its zero terms (the same number).
      template <int dim>
      double
      stress_power(const SymmetricTensor<2, 3> &sigma, const Tensor<2, dim> &e)
      {
        double s = 0.;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            s += sigma[i][j] * e[i][j];
        return s;
      }

      template <int dim>
      Tensor<1, dim>
      stress_times(const SymmetricTensor<2, 3> &s, const Tensor<1, dim> &g)
      {
        Tensor<1, dim> r;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            r[i] += s[i][j] * g[j];
        return r;
      }

      /// GIMP: half-widths of a point's domain from its reference volume,
      /// V0 = (2 l)^dim (the seeding lattice gives l = h / (2 n)), at most
      /// h/2 (the patch holds nodes up to h + l <= 3h/2 away), and clipped
      /// to the mesh box: a domain never reaches past the boundary, so
      /// that at the boundary the weights become those of Q1 and a point
      /// next to a fixed face does not keep moving through it.
      template <int dim>
      void
      gimp_half_width(const double            V0,
                      const double            h,
                      const Point<dim>       &x,
                      const BoundingBox<dim> &box,
                      double (&l)[dim])
      {
        const double side = dim == 2 ? std::sqrt(V0) : std::cbrt(V0);
        const double l0   = std::min(0.5 * side, 0.5 * h);
        for (unsigned int d = 0; d < dim; ++d)
          l[d] = std::max(0.,
                          std::min({l0,
                                    x[d] - box.lower_bound(d),
                                    box.upper_bound(d) - x[d]}));
      }

      using Vector = LinearAlgebra::distributed::Vector<double>;

      /// compress(add) of several vectors with one round of messages: all
      /// sends start before the first wait (each on its own channel, < 100).
      /// Its wall time, the waits for the other ranks included, is added to
      /// @p seconds.
      void
      compress_add(const std::vector<Vector *> &vectors, double &seconds)
      {
        const auto start = Clock::now();
        for (unsigned int c = 0; c < vectors.size(); ++c)
          vectors[c]->compress_start(c, VectorOperation::add);
        for (Vector *v : vectors)
          v->compress_finish(VectorOperation::add);
        seconds += seconds_since(start);
      }

      /// update_ghost_values() of several vectors with one round of
      /// messages; its wall time is added to @p seconds.
      void
      update_ghosts(const std::vector<Vector *> &vectors, double &seconds)
      {
        const auto start = Clock::now();
        for (unsigned int c = 0; c < vectors.size(); ++c)
          vectors[c]->update_ghost_values_start(c);
        for (Vector *v : vectors)
          v->update_ghost_values_finish();
        seconds += seconds_since(start);
      }
    } // namespace


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
      double plastic = 0, damage = 0;
      material.dissipated_energy(state, plastic, damage);
      report.plastic_dissipation += V0 * plastic;
      report.damage_dissipation += V0 * damage;
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
      // affine matrix.
      const auto gradient_about = [&](const std::vector<Tensor<1, dim>> &v,
                                      const Tensor<1, dim> &v_point,
                                      const unsigned int    e0,
                                      const unsigned int    e1) {
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
                                         const unsigned int e1) {
        Tensor<1, dim> v_point;
        for (unsigned int e = e0; e < e1; ++e)
          v_point += shape_value[e] * v_stress[shape_node[e]];
        return gradient_about(v_stress, v_point, e0, e1);
      };
      // Cayley (midpoint) increment: exactly a rotation when L is a spin,
      // so rigid rotation creates no stress.
      const auto cayley_increment = [dt](const Tensor<2, dim> &L) {
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
              if (!std::isfinite(sigma.norm()))
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
