#ifndef scarp_grid_boundary_conditions_h
#define scarp_grid_boundary_conditions_h

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
     */
    template <int dim>
    class BoundaryConditions
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);

      /// Record which locally owned degrees of freedom lie on which faces.
      void
      setup(const DoFHandler<dim> &dof_handler);

      /**
       * Apply the conditions to the nodal velocity components @p velocity
       * (one vector per direction, indexed by global dof). If
       * @p start_velocity (the constrained velocity at the start of the
       * step) is given, returns the energy the boundary removed over the
       * step: the work of the reaction impulse m (v_free - v) against the
       * mean velocity (v_start + v)/2; it is zero on fixed and slip faces
       * and the friction loss on friction faces.
       */
      template <typename VectorType>
      double
      apply(const VectorType                    &mass,
            std::array<VectorType *, dim>        velocity,
            const std::array<VectorType *, dim> *start_velocity = nullptr)
        const;

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
      };

      std::array<BoundaryType, 2 * dim> types;
      double                            friction_coefficient = 0.;
      std::vector<Node>                 nodes;
    };
  } // namespace grid
} // namespace scarp

#endif
