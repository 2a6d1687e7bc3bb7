#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/grid/grid_generator.h>

#include <scarp/base/exceptions.h>
#include <scarp/base/parameter_tools.h>
#include <scarp/grid/background_grid.h>

#include <cmath>

namespace scarp
{
  namespace grid
  {
    template <int dim>
    BackgroundGrid<dim>::BackgroundGrid(MPI_Comm communicator)
      : communicator(communicator)
      , tria(communicator,
             // At most one level between cells that share a vertex: the
             // GIMP patch of a cell is then the cells at its vertices.
             Triangulation<dim>::limit_level_difference_at_vertices,
             parallel::distributed::Triangulation<dim>::default_setting)
      , fe_q(1)
      , dofs(tria)
    {
    }


    template <int dim>
    void
    BackgroundGrid<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Mesh");
      prm.declare_entry("Lower corner",
                        dim == 2 ? "0, 0" : "0, 0, 0",
                        *ParameterTools::double_list(dim),
                        "Lower corner of the axis-aligned background box [m].");
      prm.declare_entry("Upper corner",
                        dim == 2 ? "1, 1" : "1, 1, 1",
                        *ParameterTools::double_list(dim),
                        "Upper corner of the axis-aligned background box [m]. "
                        "Every side must be a whole number of cells.");
      prm.declare_entry("Cell size",
                        "0.1",
                        Patterns::Double(0.),
                        "Edge length of the square (cubic) coarse cells [m].");
      BoundaryConditions<dim>::declare_parameters(prm);
      prm.enter_subsection("Refinement");
      prm.declare_entry(
        "Adaptive refinement",
        "false",
        Patterns::Bool(),
        "Refine the mesh ahead of and around the failure (needs a material "
        "with damage): cells with a point whose damage exceeds <Damage "
        "limit>, or whose non-local driver exceeds <Driver fraction> of its "
        "damage threshold, and every cell within <Buffer> non-local radii of "
        "them, are refined up to <Maximum level>; points of a refined cell "
        "are split into 2^dim. Cells are never coarsened (points are not "
        "merged), so the refined region only grows.");
      prm.declare_entry("Minimum level",
                        "0",
                        Patterns::Integer(0, 6),
                        "Every cell is refined to this level at set-up, "
                        "before the bodies are seeded.");
      prm.declare_entry("Maximum level",
                        "1",
                        Patterns::Integer(0, 6),
                        "Refinement levels above the coarse cells.");
      prm.declare_entry("Damage limit",
                        "0.01",
                        Patterns::Double(0., 1.),
                        "Cells holding a point whose damage exceeds this are "
                        "refined.");
      prm.declare_entry(
        "Driver fraction",
        "0.5",
        Patterns::Double(0.),
        "Cells holding a point whose non-local driver Ybar exceeds this "
        "fraction of its damage threshold max(sigma_f, kappa) are refined, "
        "so that cells refine before damage starts. 0 switches the "
        "criterion off.");
      prm.declare_entry("Buffer",
                        "1",
                        Patterns::Double(0.),
                        "Cells within this many non-local cut-off radii of a "
                        "flagged cell are refined too (at least 1: the "
                        "average reaches that far).");
      prm.declare_entry("Initial levels",
                        "0",
                        Patterns::Integer(0, 6),
                        "Cells whose centre is inside <Initial region> are "
                        "refined to this level at set-up, before the bodies "
                        "are seeded (a-priori region).");
      prm.declare_entry("Initial region",
                        dim == 2 ? "0, 0, 0, 0" : "0, 0, 0, 0, 0, 0",
                        *ParameterTools::double_list(2 * dim),
                        "Box (lower corner, then upper corner) refined at "
                        "set-up, see <Initial levels>.");
      prm.declare_entry("Interval",
                        "20",
                        Patterns::Integer(1),
                        "Steps between refinement passes.");
      prm.declare_entry(
        "Split stretched points",
        "false",
        Patterns::Bool(),
        "At every refinement pass, also split each point whose current "
        "volume V0 det F has grown past 2^(dim/2) times its cell's share "
        "(h/n)^dim (twice in 2D), n its body's points per cell direction, "
        "into 2^dim children inside the parallelogram it has become (at F "
        "times +-V0^(1/dim)/4), whether or not a cell is refined; only "
        "while V0 is at least half the share, so at most once below it. "
        "Keeps a dilating layer (fully damaged chalk without tensile "
        "stiffness) at the points per cell of the set-up instead of one "
        "point standing for several cells. Not in the paper nor its "
        "authors' code (they delete such points: <Remove points stretched "
        "beyond> of the material). Needs <Adaptive refinement>. "
        "Experimental (doc/refinement.md).");
      prm.declare_entry(
        "Set-up passes",
        "0",
        Patterns::Integer(0, 6),
        "Before the run, the first stage (a loading stage without damage) "
        "runs up to this many times without output: after a pass that "
        "refined the mesh, the points are discarded and the bodies seeded "
        "anew on the refined mesh, so that refined cells hold points seeded "
        "at their own level (the geometry and the initial damage sampled "
        "there) instead of split ones. The passes stop early once one "
        "refines nothing; the run proper then starts on the last mesh. An "
        "<Initial region> found from the loading itself.");
      prm.leave_subsection();
      prm.leave_subsection();
    }


    template <int dim>
    void
    BackgroundGrid<dim>::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Mesh");
      const Point<dim> lower =
        ParameterTools::get_point<dim>(prm, "Lower corner");
      const Point<dim> upper =
        ParameterTools::get_point<dim>(prm, "Upper corner");
      cell_size = prm.get_double("Cell size");
      if (!(cell_size > 0))
        throw ScarpError("Mesh: <Cell size> must be positive.");
      for (unsigned int d = 0; d < dim; ++d)
        {
          if (!(upper[d] > lower[d]))
            throw ScarpError("Mesh: <Upper corner> must be above <Lower "
                             "corner> in every direction (direction " +
                             std::to_string(d) + ").");
          const double n = (upper[d] - lower[d]) / cell_size;
          if (std::abs(n - std::round(n)) > 1e-6 * n)
            throw ScarpError("Mesh: the box side in direction " +
                             std::to_string(d) + " (" +
                             std::to_string(upper[d] - lower[d]) +
                             " m) is not a whole number of cells of <Cell "
                             "size> = " +
                             std::to_string(cell_size) + " m.");
        }
      box = BoundingBox<dim>(std::make_pair(lower, upper));
      boundary.parse_parameters(prm);
      prm.enter_subsection("Refinement");
      adaptive_refinement        = prm.get_bool("Adaptive refinement");
      min_refinement_level       = prm.get_integer("Minimum level");
      max_refinement_level       = prm.get_integer("Maximum level");
      refinement_damage_limit    = prm.get_double("Damage limit");
      refinement_driver_fraction = prm.get_double("Driver fraction");
      refinement_buffer          = prm.get_double("Buffer");
      refinement_interval        = prm.get_integer("Interval");
      split_stretched_points     = prm.get_bool("Split stretched points");
      setup_passes               = prm.get_integer("Set-up passes");
      initial_levels             = prm.get_integer("Initial levels");
      {
        const auto c =
          ParameterTools::get_doubles(prm, "Initial region", 2 * dim);
        Point<dim> a, b;
        for (unsigned int d = 0; d < dim; ++d)
          {
            a[d] = c[d];
            b[d] = c[dim + d];
          }
        initial_region = BoundingBox<dim>(std::make_pair(a, b));
      }
      if (split_stretched_points && !adaptive_refinement)
        throw ScarpError("Mesh/Refinement: <Split stretched points> acts at "
                         "the refinement passes, and there are none without "
                         "<Adaptive refinement> = true.");
      if (adaptive_refinement)
        {
          if (initial_levels > max_refinement_level)
            throw ScarpError("Mesh/Refinement: <Initial levels> (" +
                             std::to_string(initial_levels) +
                             ") exceeds <Maximum level> (" +
                             std::to_string(max_refinement_level) + ").");
          if (min_refinement_level > max_refinement_level)
            throw ScarpError("Mesh/Refinement: <Minimum level> (" +
                             std::to_string(min_refinement_level) +
                             ") exceeds <Maximum level> (" +
                             std::to_string(max_refinement_level) + ").");
          if (refinement_buffer < 1)
            throw ScarpError("Mesh/Refinement: <Buffer> = " +
                             std::to_string(refinement_buffer) +
                             " is below 1: the non-local average of a "
                             "flagged point reaches one cut-off radius.");
        }
      prm.leave_subsection();
      prm.leave_subsection();
    }


    template <int dim>
    void
    BackgroundGrid<dim>::create_mesh()
    {
      create_coarse_mesh();
      if (min_refinement_level > 0)
        tria.refine_global(min_refinement_level);
      for (unsigned int level = min_refinement_level; level < initial_levels;
           ++level)
        {
          for (const auto &cell : tria.active_cell_iterators())
            if (cell->is_locally_owned() &&
                static_cast<unsigned int>(cell->level()) < initial_levels &&
                initial_region.point_inside(cell->center()))
              cell->set_refine_flag();
          tria.execute_coarsening_and_refinement();
        }
    }


    template <int dim>
    void
    BackgroundGrid<dim>::create_coarse_mesh()
    {
      std::vector<unsigned int> repetitions(dim);
      for (unsigned int d = 0; d < dim; ++d)
        repetitions[d] =
          static_cast<unsigned int>(std::round(box.side_length(d) / cell_size));
      GridGenerator::subdivided_hyper_rectangle(
        tria,
        repetitions,
        box.get_boundary_points().first,
        box.get_boundary_points().second,
        /*colorize=*/true);
    }


    template <int dim>
    void
    BackgroundGrid<dim>::setup_dofs()
    {
      dofs.distribute_dofs(fe_q);
      owned_dofs = dofs.locally_owned_dofs();
      DoFTools::extract_locally_relevant_dofs(dofs, relevant_dofs);
      hanging_node_constraints.clear();
      hanging_node_constraints.reinit(relevant_dofs);
      DoFTools::make_hanging_node_constraints(dofs, hanging_node_constraints);
      hanging_node_constraints.close();
      boundary.setup(dofs, box);
    }


    template <int dim>
    double
    BackgroundGrid<dim>::minimum_cell_size() const
    {
      return cell_size_on_level(tria.n_global_levels() - 1);
    }

    template class BackgroundGrid<2>;
    template class BackgroundGrid<3>;
  } // namespace grid
} // namespace scarp
