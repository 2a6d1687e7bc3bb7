#ifndef scarp_grid_background_grid_h
#define scarp_grid_background_grid_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_cartesian.h>
#include <deal.II/lac/affine_constraints.h>

#include <scarp/grid/boundary_conditions.h>

namespace scarp
{
  namespace grid
  {
    using namespace dealii;

    /**
     * @brief The background mesh: an axis-aligned box of square cells on a
     * distributed (p4est) triangulation, with Q1 shape functions, the
     * hanging-node constraints that adaptive refinement brings, and the
     * boundary conditions of its faces.
     */
    template <int dim>
    class BackgroundGrid
    {
    public:
      explicit BackgroundGrid(MPI_Comm communicator);

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);

      /// Build the coarse mesh (cells of the requested size) and refine
      /// it to <Minimum level> and <Initial levels>.
      void
      create_mesh();

      /// Only the coarse mesh, without any refinement: what
      /// parallel::distributed::Triangulation::load() of a checkpoint needs.
      void
      create_coarse_mesh();

      /// Distribute dofs, build constraints and boundary node lists; call
      /// after every change of the mesh.
      void
      setup_dofs();

      parallel::distributed::Triangulation<dim> &
      triangulation()
      {
        return tria;
      }
      const parallel::distributed::Triangulation<dim> &
      triangulation() const
      {
        return tria;
      }
      const DoFHandler<dim> &
      dof_handler() const
      {
        return dofs;
      }
      const Mapping<dim> &
      mapping() const
      {
        return cartesian_mapping;
      }
      const FE_Q<dim> &
      fe() const
      {
        return fe_q;
      }
      const AffineConstraints<double> &
      constraints() const
      {
        return hanging_node_constraints;
      }
      const IndexSet &
      locally_owned_dofs() const
      {
        return owned_dofs;
      }
      const IndexSet &
      locally_relevant_dofs() const
      {
        return relevant_dofs;
      }
      const BoundaryConditions<dim> &
      boundary_conditions() const
      {
        return boundary;
      }
      /// The box of the mesh.
      const BoundingBox<dim> &
      domain() const
      {
        return box;
      }
      /// Edge length of a coarse cell [m].
      double
      coarse_cell_size() const
      {
        return cell_size;
      }
      /// Edge length of the finest active cell anywhere [m] (collective).
      double
      minimum_cell_size() const;
      /// Edge length of cells on refinement level @p level.
      double
      cell_size_on_level(const unsigned int level) const
      {
        return cell_size / (1u << level);
      }

      /// Refinement levels applied at set-up inside a box (a priori
      /// refinement, e.g. around a tension crack).
      unsigned int     initial_levels = 0;
      BoundingBox<dim> initial_region;

      /// Level every cell has at set-up.
      unsigned int min_refinement_level = 0;

      /// Adaptive refinement settings (see the entries of Mesh/Refinement).
      bool         adaptive_refinement        = false;
      unsigned int max_refinement_level       = 0;
      unsigned int refinement_interval        = 10;
      double       refinement_damage_limit    = 0.;
      double       refinement_driver_fraction = 0.5;
      /// In cut-off radii of the non-local average.
      double refinement_buffer = 1.;
      /// Split points by their current volume at every pass too.
      bool split_stretched_points = false;
      /// Runs of the first stage that refine the mesh and reseed the bodies
      /// before the run proper (0: none).
      unsigned int setup_passes = 0;

    private:
      MPI_Comm                                  communicator;
      parallel::distributed::Triangulation<dim> tria;
      FE_Q<dim>                                 fe_q;
      DoFHandler<dim>                           dofs;
      MappingCartesian<dim>                     cartesian_mapping;
      AffineConstraints<double>                 hanging_node_constraints;
      IndexSet                                  owned_dofs;
      IndexSet                                  relevant_dofs;
      BoundaryConditions<dim>                   boundary;
      BoundingBox<dim>                          box;
      double                                    cell_size = 0;
    };
  } // namespace grid
} // namespace scarp

#endif
