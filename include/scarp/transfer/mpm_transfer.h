#ifndef scarp_transfer_mpm_transfer_h
#define scarp_transfer_mpm_transfer_h

#include <deal.II/base/function.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/particles/particle_handler.h>

#include <scarp/grid/background_grid.h>
#include <scarp/materials/material.h>
#include <scarp/particles/point_mover.h>
#include <scarp/particles/property_layout.h>
#include <scarp/transfer/gimp_patches.h>
#include <scarp/transfer/step_report.h>
#include <scarp/transfer/transfer_parameters.h>

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace scarp
{
  namespace transfer
  {
    using namespace dealii;

    /// Damping of the grid forces (used to load gravity quasi-statically).
    struct Damping
    {
      enum class Type
      {
        none,
        viscous, ///< f -= c m v, c in 1/s
        local,   ///< Cundall: f_k -= alpha |f_k| sign(v_k), alpha in [0,1)
      };
      Type   type        = Type::none;
      double coefficient = 0;
    };

    /**
     * @brief Points of damage materials gathered during a step, for the
     * non-local average of the damage driver.
     */
    template <int dim>
    struct DamagePoints
    {
      std::vector<Point<dim>> position;
      std::vector<double>     volume;
      std::vector<double>     driver;
      std::vector<bool>       receiver;
      /// Whether the point enters the sums of the average
      /// (Material::is_nonlocal_source()), taken in G2P while the point's
      /// record is in the cache.
      std::vector<bool>                  source;
      std::vector<types::particle_index> id;
      /// Property arrays of the points (valid until particles are sorted).
      std::vector<double *> properties;
      void
      clear()
      {
        properties.clear();
        position.clear();
        volume.clear();
        driver.clear();
        receiver.clear();
        source.clear();
        id.clear();
      }
    };

    /**
     * @brief The explicit MPM step on the background grid: particle to grid
     * (mass, momentum, force), the grid solve with boundary conditions and
     * hanging-node constraints, grid to particle (velocity, position,
     * deformation) and the constitutive update, cell by cell.
     */
    template <int dim>
    class MpmTransfer
    {
    public:
      using Vector = LinearAlgebra::distributed::Vector<double>;

      MpmTransfer(const grid::BackgroundGrid<dim>                &grid,
                  Particles::ParticleHandler<dim>                &particles,
                  const particles::PropertyLayout<dim>           &layout,
                  const std::vector<const materials::Material *> &materials,
                  const TransferParameters                       &parameters);

      /// Size the grid vectors; call after every change of the mesh.
      void
      setup();

      /// An extra body force per unit mass b(X, t), a function of the
      /// reference position X (manufactured solutions); nullptr: none.
      void
      set_body_force(const Function<dim> *function)
      {
        body_force = function;
      }

      /// Nodal mass below which a node is treated as empty, per unit
      /// volume of the smallest cell at the node [kg/m^dim]: the cutoff of
      /// a node follows the local cell size on a refined mesh.
      void
      set_mass_cutoff_density(const double cutoff_density)
      {
        mass_cutoff_density = cutoff_density;
        compute_node_cutoffs();
      }

      /// Mass scaling: the inertia of the momentum balance (not the weight)
      /// is @p scale times the mass. The kinetic energy the step reports is
      /// that of the real masses; the damping and boundary work are those
      /// of the scaled system (the forces that act), so its balance holds
      /// with @p scale times the kinetic energy.
      void
      set_mass_scale(const double scale)
      {
        mass_scale = scale;
      }

      /**
       * One explicit step of length @p dt. Returns this rank's report (not
       * yet reduced). The materials' updates get the switches @p inelastic
       * (the stage's) in their batches. If @p damage_points is given, points
       * of damage materials are gathered into it in the order of the
       * particle iteration, for the non-local step; they are receivers only
       * if damage grows in this step.
       */
      StepReport
      step(const double                        dt,
           const Tensor<1, dim>               &gravity,
           const Damping                      &damping,
           const materials::InelasticSwitches &inelastic,
           DamagePoints<dim>                  *damage_points);

      /// The GIMP patches (for tests and statistics).
      GimpPatches<dim> &
      gimp_patches()
      {
        return patches;
      }

      /// Measure the energies and momenta of the particles as they are.
      StepReport
      measure(const Tensor<1, dim> &gravity) const;

      /// Nodal fields of the last step (for output).
      const Vector &
      nodal_mass() const
      {
        return mass;
      }
      const std::array<Vector, dim> &
      nodal_velocity() const
      {
        return velocity_new;
      }

      /**
       * @brief Wall time of the parts of the steps so far [s], on this
       * rank: the shape functions (occupied cells and the points' weights),
       * P2G (with the momentum P2G of the MUSL remap), the grid update (the
       * nodal solve, boundary conditions, constraints, ghost exchange, the
       * remapped velocities), G2P (velocities, positions, deformation and
       * the bookkeeping of the points) and the constitutive updates;
       * @p exchange is the part of P2G and the grid update spent in the
       * ghost exchanges of nodal vectors (counted in those parts too). On
       * several ranks it holds the waits for the slowest one: the rank
       * with the least exchange time sets the pace.
       */
      struct PartTimes
      {
        double shape_functions = 0, p2g = 0, grid_update = 0, g2p = 0,
               constitutive_update = 0, exchange = 0;

        /// The parts by the names summary.json gives them, in its order.
        std::vector<std::pair<std::string, double>>
        named() const
        {
          return {{"shape functions", shape_functions},
                  {"P2G", p2g},
                  {"grid update", grid_update},
                  {"G2P", g2p},
                  {"constitutive update", constitutive_update},
                  {"exchange", exchange}};
        }

        /// This rank's own work: the parts less its exchange.
        double
        compute() const
        {
          return shape_functions + p2g + grid_update + g2p +
                 constitutive_update - exchange;
        }
      };
      const PartTimes &
      part_times() const
      {
        return times;
      }

      /// After a step in which no point left its cell (StepReport::
      /// n_changed_cell == 0 on every rank): set the reference locations
      /// from the new positions, which is all the particle handler's sort
      /// would do then, at a fraction of its cost.
      void
      update_reference_locations();

      /// After a step in which points left their cells: sort them into
      /// their new cells (particles::PointMover on the occupied cells of the
      /// step, or the particle handler's sort if a point leaves the rank or
      /// the mesh). Collective.
      void
      sort_points(const MPI_Comm communicator);

      /// Put the particle handler's list of cells in order if
      /// sort_points() left it out of order
      /// (particles::PointMover::restore_order()): before anything iterates
      /// over all points in the handler's order. Collective.
      void
      restore_point_order()
      {
        point_mover.restore_order(particle_handler);
      }

    private:
      particles::PointMover<dim> point_mover;
      std::vector<typename particles::PointMover<dim>::CellPoints>
        occupied_points;

      void
      particles_to_grid(const Tensor<1, dim> &gravity);
      /// G2P: the kinematic update and/or the stress update of the points.
      /// With @p gather_momentum the kinematic update also gathers the
      /// momentum of the new point velocities on the grid, the P2G of the
      /// MUSL remap (remap_momentum()).
      void
      grid_to_particles(const double dt,
                        const bool   update_positions_and_velocities,
                        const bool   update_stress,
                        const materials::InelasticSwitches &inelastic,
                        const std::array<Vector, dim>      &stress_velocity,
                        StepReport                         &report,
                        DamagePoints<dim>                  *damage_points,
                        const Tensor<1, dim>               &gravity,
                        const bool                          gather_momentum);
      void
      compute_node_cutoffs();
      /// Fill the shape cache for the points of the occupied cells.
      void
      compute_shapes();
      /// Write the non-zero entries of the @p n values and gradients
      /// (indexed by the cell's nodes) to the shape cache from entry @p at
      /// on; returns their number.
      unsigned int
      keep_nonzero(const double         *value,
                   const Tensor<1, dim> *gradient,
                   const unsigned int    n,
                   const unsigned int    at);
      double
      solve_grid(const double dt, const Damping &damping, StepReport &report);
      /// MUSL: the remapped grid velocity from the momentum that
      /// grid_to_particles() gathered.
      void
      remap_momentum();
      void
      add_point_measures(const double         *p,
                         const Point<dim>     &x,
                         const Tensor<1, dim> &gravity,
                         StepReport           &report) const;

      PartTimes times;

      const grid::BackgroundGrid<dim>         &grid;
      Particles::ParticleHandler<dim>         &particle_handler;
      const particles::PropertyLayout<dim>    &layout;
      std::vector<const materials::Material *> materials;
      const TransferParameters                &parameters;
      double                                   mass_cutoff_density = 0;
      double                                   mass_scale          = 1;
      /// Mass cutoff of each locally owned node (by local index).
      std::vector<double>  node_cutoff;
      const Function<dim> *body_force = nullptr;
      Tensor<1, dim>       last_gravity;
      Tensor<1, dim>       gravity_for_empty_nodes;

      /// A locally owned cell that holds points, with what every sweep of
      /// a step needs of it. Gathered once per step (points change cells
      /// only in the sort after it), so the five P2G/G2P sweeps of a MUSL
      /// step neither visit empty cells, nor ask the particle handler for
      /// each cell's points, nor look up patches and dof indices again: they
      /// read the flat arrays below in order.
      struct OccupiedCell
      {
        typename DoFHandler<dim>::active_cell_iterator cell;
        /// Lowest vertex and edge of the (axis-aligned) cell.
        Point<dim> x0;
        double     h;
        /// GIMP: the cell's patch (GimpPatches keeps it in place until its
        /// next reinit); Q1: nullptr.
        const typename GimpPatches<dim>::Patch *patch = nullptr;
        /// GIMP on a regular patch: its lattice, copied here so that the
        /// shape functions of the cell's points read no patch memory.
        bool   regular         = false;
        double lattice[dim][4] = {};
        /// Its nodes: entries [node_begin, node_begin + n_nodes) of
        /// node_local, node_dof, node_position. Q1: the cell's 2^dim
        /// (constrained if hanging), GIMP: the unconstrained patch nodes.
        unsigned int node_begin, n_nodes;
        /// Its points: entries [point_begin, point_end) of point_handle,
        /// point_properties.
        unsigned int point_begin, point_end;
      };
      /// Whether the nodal sums of a cell go straight into the grid vectors
      /// (GIMP, or no hanging nodes) or through distribute_cell_sums().
      bool
      cell_sums_add_directly() const;
      /// Add the sums @p values of the nodes of @p occupied (n_nodes each)
      /// to @p globals, value c to vector c, through the hanging-node
      /// constraints (Q1 on a refined mesh).
      void
      distribute_cell_sums(const OccupiedCell                &occupied,
                           const std::vector<const double *> &values,
                           const std::vector<Vector *>       &globals) const;
      std::vector<OccupiedCell> occupied_cells;
      /// The list of the step before and its point handles, kept while
      /// the new one is made.
      std::vector<OccupiedCell> previous_cells;
      std::vector<unsigned int> previous_point_handle;
      /// After a sort_points() in which the point mover moved the points:
      /// the active cell indices (sorted, repeats possible) of the cells
      /// whose points changed.
      std::vector<unsigned int> changed_cells;
      /// Scratch for a Q1 cell's dof indices.
      std::vector<types::global_dof_index> cell_dofs;
      /// Whether the node arrays of occupied_cells still hold (until the
      /// next setup()).
      bool node_arrays_valid = false;
      /// Whether occupied_cells and the point arrays are those of the
      /// points as they are now: from find_occupied_cells() until the next
      /// sort_points() or setup() (a step in which no point changed cells
      /// only updates reference locations, and keeps them).
      bool occupied_cells_current = false;
      /// After a sort_points() in which the point mover moved the points:
      /// the cells that may hold points now (those that held them, those
      /// that gained some), by active cell index, so that
      /// find_occupied_cells() visits them instead of every active cell.
      std::vector<typename DoFHandler<dim>::active_cell_iterator>
           candidate_cells;
      bool candidate_cells_valid = false;
      /// Nodes of the occupied cells: index in the local storage of the
      /// grid vectors (local_element()), global dof, position.
      std::vector<unsigned int>            node_local;
      std::vector<types::global_dof_index> node_dof;
      std::vector<Point<dim>>              node_position;
      /// Points of the occupied cells: PropertyPool handle and property
      /// array (the pool does not move its storage within a step).
      std::vector<unsigned int> point_handle;
      std::vector<double *>     point_properties;
      /// Rebuild occupied_cells and the node and point arrays.
      void
      find_occupied_cells();

      /// Advance @p j through previous_cells (in the order of the active
      /// cells) to @p cell; whether the list of the step before holds it
      /// (then at @p j). Calls with cells in that order share one walk.
      bool
      find_previous(const typename DoFHandler<dim>::active_cell_iterator &cell,
                    std::size_t &j) const;

      /// Give @p to the nodes (and patch) of @p from, the same cell's entry
      /// in the list of the step before.
      void
      take_nodes(const OccupiedCell &from, OccupiedCell &to);

      /// Append the nodes of the cell of @p occupied to the node arrays.
      void
      append_nodes(OccupiedCell &occupied);

      /// Scratch of one cell's constitutive update for one material, kept
      /// between calls so that its storage is not allocated again.
      struct MaterialScratch
      {
        /// Points held; the arrays are longer (they only grow, so that the
        /// sweep writes by index without a check per array).
        unsigned int              n = 0;
        std::vector<Tensor<2, 3>> delta_F, F;
        /// dt sym(L) of the dim x dim velocity gradient (for the stress
        /// power only: the out-of-plane entries are zero).
        std::vector<Tensor<2, dim>>        strain_increment;
        std::vector<double *>              state;
        std::vector<SymmetricTensor<2, 3>> stress;
        std::vector<double>                stored_energy, driver;
        std::vector<double *>              properties;
        std::vector<Point<dim>>            position;
        std::vector<types::particle_index> id;
        /// The index of a new point, the arrays grown if full.
        unsigned int
        append()
        {
          if (n == delta_F.size())
            grow();
          return n++;
        }
        void
        grow()
        {
          const std::size_t size = std::max<std::size_t>(2 * n, 512);
          delta_F.resize(size);
          F.resize(size);
          strain_increment.resize(size);
          state.resize(size);
          stress.resize(size);
          stored_energy.resize(size);
          driver.resize(size);
          properties.resize(size);
          position.resize(size);
          id.resize(size);
        }
        void
        clear()
        {
          n = 0;
        }
      };
      std::vector<MaterialScratch> material_scratch;
      /// Points in material_scratch not yet updated, and their material if
      /// they are of one (G2P updates the points of consecutive cells of
      /// one material together, in the order of the cells).
      unsigned int n_pending        = 0;
      int          pending_material = -1;
      /// Update the materials of the points in material_scratch (in the
      /// order of the materials) and book them in @p report.
      void
      update_pending(const double                        dt,
                     const materials::InelasticSwitches &inelastic,
                     StepReport                         &report,
                     DamagePoints<dim>                  *damage_points,
                     const Tensor<1, dim>               &gravity);
      /// Ids of the damaged points that stretched too far in this step
      /// (materials::Material::removal_stretch()), and moving them out of
      /// the mesh at the end of the step, so that the sort after it drops
      /// them as it drops points that left the mesh.
      std::vector<types::particle_index> removal_ids;
      void
      move_removed_points_out();
      /// F-bar scratch of one cell: its points' velocity gradients,
      /// deformation increments and volumes at the start of the step.
      std::vector<Tensor<2, dim>> cell_L, cell_delta_F;
      std::vector<double>         cell_volume;
      /// Per-cell scratch of the sweeps: P2G accumulators (mass, then dim
      /// momentum and dim force components of n nodes each), G2P nodal
      /// velocities and empty-node flags.
      std::vector<double>         local_sums;
      std::vector<Tensor<1, dim>> local_v_new, local_v_old, local_v_stress;
      std::vector<char>           local_empty;

      /// Non-zero shape functions of every point of the occupied cells (in
      /// the order of occupied_cells and their points) for this step:
      /// entries [shape_begin[k], shape_begin[k + 1]) of point k, with the
      /// node's index among the cell's nodes (OccupiedCell::n_nodes).
      std::vector<unsigned int>   shape_begin;
      std::vector<unsigned int>   shape_node;
      std::vector<double>         shape_value;
      std::vector<Tensor<1, dim>> shape_gradient;

      /// GIMP patches of the occupied cells (built as cells fill).
      GimpPatches<dim> patches;

      /**
       * The hanging-node constraints of the locally owned nodes, in the
       * local storage of the grid vectors: node constraint_local[c] takes
       * sum_j weight_j v(source_j) over constraint_entries
       * [constraint_begin[c], constraint_begin[c + 1]). The sources of an
       * owned hanging node are vertices of a locally owned or ghost cell,
       * so ghost entries hold them. With this, the constraints of several
       * vectors take two batched ghost exchanges instead of the
       * AffineConstraints::distribute() of each vector (which builds a
       * ghosted copy, with a new partitioner, and compresses it back).
       */
      std::vector<unsigned int>                    constraint_local;
      std::vector<unsigned int>                    constraint_begin;
      std::vector<std::pair<unsigned int, double>> constraint_entries;
      /// Whether any rank owns a constrained node (the ghost exchanges are
      /// collective: all ranks take the same branch).
      bool any_constraints = false;
      void
      setup_constraints();
      /// Apply the hanging-node constraints to @p vectors (owned values
      /// set) and update their ghost entries, and those of
      /// @p unconstrained with the same messages.
      void
      distribute_and_update_ghosts(const std::vector<Vector *> &vectors,
                                   const std::vector<Vector *> &unconstrained);

      Vector                  mass;
      std::array<Vector, dim> momentum, force, velocity_old, velocity_new,
        velocity_remapped;
      /// The body force's share of the nodal force (only with a body
      /// force), for its work.
      std::array<Vector, dim> body_force_nodal;
    };
  } // namespace transfer
} // namespace scarp

#endif
