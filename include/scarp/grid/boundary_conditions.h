#ifndef scarp_grid_boundary_conditions_h
#define scarp_grid_boundary_conditions_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>

#include <array>
#include <string>
#include <vector>

namespace scarp
{
  namespace grid
  {
    using namespace dealii;

    /// What a face of the background box does to the grid velocity.
    enum class BoundaryType
    {
      free,     ///< nothing
      fixed,    ///< all velocity components zero
      slip,     ///< normal component zero (roller), tangential free
      friction, ///< contact: no penetration, Coulomb friction, may separate
    };

    /**
     * @brief Boundary conditions on the nodal velocities of the axis-aligned
     * background box: one type per face, applied node by node after the grid
     * update.
     *
     * Faces are numbered as deal.II's colorized hyper_rectangle: 2*d is the
     * lower face in direction d, 2*d+1 the upper one.
     *
     * Optionally a part of one face (the nodes of the face inside a box,
     * `subsection Prescribed velocity`) moves with a prescribed constant
     * velocity: all of its components (a rough rigid plate) or only the
     * normal one (a smooth plate). Inside the region this replaces the
     * face's own condition. The force the material exerts on the region
     * (the reaction, e.g. the load on a footing) is accumulated from the
     * constraint impulses m (v_free - v_prescribed) of its nodes and
     * reported averaged over the steps since it was last asked for.
     */
    template <int dim>
    class BoundaryConditions
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);

      /// Record which locally owned degrees of freedom lie on which faces
      /// of the mesh box @p box, and which in the prescribed-velocity
      /// region. Throws a ScarpError (on every rank) when the region does
      /// not lie on its face, holds no node of it, or contradicts the
      /// condition of a face it touches.
      void
      setup(const DoFHandler<dim> &dof_handler, const BoundingBox<dim> &box);

      /**
       * Apply the conditions to the nodal velocity components @p velocity
       * (one vector per direction, indexed by global dof). If
       * @p start_velocity (the velocity of P2G at the start of the step,
       * v_r) is given, the conditions are applied to it too (v_s), and the
       * call returns the energy the boundary removed from the points over
       * the step: the work of the nodal forces over the constrained
       * velocities, m (v_free - v_r) . (v_s + v)/2 (what the stress power
       * at the points sees), less the kinetic energy the points' FLIP
       * update v_p + S (v - v_s) draws from the node, m v_r . dv + m
       * |dv|^2/2 with dv = v - v_s. It is zero where no condition acts, on
       * fixed faces and on slip faces; on friction faces the kinetic
       * energy of the normal velocity the face stops and the friction
       * (<Friction contact> = consistent: the faces the end velocity
       * presses on stay in contact for the step, the call without
       * @p start_velocity, the MUSL remap, keeps their normal velocity at
       * zero, and v_s keeps the normal velocity for the FLIP update, while
       * the work is taken over the start velocity without it, the one the
       * stress sees); on a prescribed velocity
       * (which reaches the stress and the PIC share from the first step)
       * the work of its whole reaction impulse m (v_free - v) against
       * (v_s + v)/2, negative when it drives the material. The call with
       * @p start_velocity also adds the step (of length @p dt) to the
       * reaction on the prescribed region; @p damping_force (the grid
       * damping force included in @p velocity) is taken out of it: damping
       * is a numerical force of the grid, not one the material exerts. With
       * mass scaling the nodes' inertia is @p mass_scale times @p mass (the
       * energy returned is that of @p mass: the caller scales it).
       */
      template <typename VectorType>
      double
      apply(const VectorType                    &mass,
            std::array<VectorType *, dim>        velocity,
            std::array<VectorType *, dim>       *start_velocity = nullptr,
            const double                         dt             = 0,
            const std::array<VectorType *, dim> *damping_force  = nullptr,
            const double                         mass_scale     = 1) const;

      /// Whether a part of a face has a prescribed velocity.
      bool
      has_prescribed_velocity() const
      {
        return prescribed_face != numbers::invalid_unsigned_int;
      }

      /// Names of the statistics columns of the reaction on the prescribed
      /// region (none without one): reaction_x, reaction_y[, reaction_z].
      std::vector<std::string>
      reaction_column_names() const;

      /**
       * The force the material exerted on the prescribed region [N; N/m in
       * 2D plane strain], averaged over the steps applied (with their dt)
       * since the previous call, summed over all ranks; resets the
       * average. Zero when no step was taken since. Collective.
       */
      Tensor<1, dim>
      take_reaction(const MPI_Comm communicator) const;

      BoundaryType
      type(const unsigned int face) const
      {
        return types[face];
      }

      static std::string
      face_name(const unsigned int face);

    private:
      struct Node
      {
        types::global_dof_index dof;
        unsigned int            faces; ///< bit f set: node lies on face f
        /// Bit f set: the last grid update pressed on friction face f.
        mutable unsigned int contact = 0;
      };

      /// Bit of Node::faces that marks a node of the prescribed region.
      static constexpr unsigned int prescribed_bit = 1u << (2 * dim);

      std::array<BoundaryType, 2 * dim> types;
      double                            friction_coefficient    = 0.;
      bool                              legacy_friction_contact = false;
      std::vector<Node>                 nodes;

      /// The prescribed-velocity region: face (invalid: none), box of its
      /// nodes, velocity, whether only the normal component is prescribed.
      unsigned int        prescribed_face = numbers::invalid_unsigned_int;
      std::vector<double> region_corners; ///< empty: the whole face
      Tensor<1, dim>      prescribed_velocity;
      bool                normal_only = false;

      /// Impulse the region gave the material, and the time it was summed
      /// over (apply() is const: the grid update only reads the conditions).
      mutable Tensor<1, dim> reaction_impulse;
      mutable double         reaction_time = 0;
    };
  } // namespace grid
} // namespace scarp

#endif
