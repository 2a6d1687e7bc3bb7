#include <deal.II/lac/la_parallel_vector.h>

#include <scarp/base/exceptions.h>
#include <scarp/grid/boundary_conditions.h>

#include <map>

namespace scarp
{
  namespace grid
  {
    template <int dim>
    std::string
    BoundaryConditions<dim>::face_name(const unsigned int face)
    {
      static const char *names[] = {"Left", "Right", "Bottom", "Top", "Front",
                                    "Back"};
      return names[face];
    }


    template <int dim>
    void
    BoundaryConditions<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Boundary conditions");
      for (unsigned int f = 0; f < 2 * dim; ++f)
        prm.declare_entry(
          face_name(f),
          "fixed",
          Patterns::Selection("free|fixed|slip|friction"),
          "What the face of the background box (" +
            std::string(f % 2 ? "upper" : "lower") + " face in direction " +
            std::to_string(f / 2) +
            ") does to the grid velocity: free, fixed (no velocity), slip "
            "(roller: no normal velocity) or friction (contact with Coulomb "
            "friction; the material may separate from the face).");
      prm.declare_entry("Friction coefficient",
                        "0.5",
                        Patterns::Double(0.),
                        "Coulomb friction coefficient [-] of faces of type "
                        "friction.");
      prm.leave_subsection();
    }


    template <int dim>
    void
    BoundaryConditions<dim>::parse_parameters(ParameterHandler &prm)
    {
      static const std::map<std::string, BoundaryType> by_name = {
        {"free", BoundaryType::free},
        {"fixed", BoundaryType::fixed},
        {"slip", BoundaryType::slip},
        {"friction", BoundaryType::friction}};
      prm.enter_subsection("Boundary conditions");
      for (unsigned int f = 0; f < 2 * dim; ++f)
        types[f] = by_name.at(prm.get(face_name(f)));
      friction_coefficient = prm.get_double("Friction coefficient");
      prm.leave_subsection();
    }


    template <int dim>
    void
    BoundaryConditions<dim>::setup(const DoFHandler<dim> &dof_handler)
    {
      const IndexSet &owned = dof_handler.locally_owned_dofs();
      std::map<types::global_dof_index, unsigned int> faces_of_dof;
      std::vector<types::global_dof_index> face_dofs(
        dof_handler.get_fe().n_dofs_per_face());
      // Ghost cells too: a node owned here may only touch a ghost cell's face.
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial() && cell->at_boundary())
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary())
              {
                const unsigned int id = cell->face(f)->boundary_id();
                if (types[id] == BoundaryType::free)
                  continue;
                cell->face(f)->get_dof_indices(face_dofs);
                for (const auto dof : face_dofs)
                  if (owned.is_element(dof))
                    faces_of_dof[dof] |= (1u << id);
              }
      nodes.clear();
      for (const auto &[dof, faces] : faces_of_dof)
        nodes.push_back({dof, faces});
    }


    template <int dim>
    template <typename VectorType>
    double
    BoundaryConditions<dim>::apply(
      const VectorType                    &mass,
      std::array<VectorType *, dim>        velocity,
      const std::array<VectorType *, dim> *start_velocity) const
    {
      double removed = 0.;
      for (const Node &node : nodes)
        {
          Tensor<1, dim> v;
          for (unsigned int d = 0; d < dim; ++d)
            v[d] = (*velocity[d])(node.dof);
          const Tensor<1, dim> v_free = v;
          for (unsigned int f = 0; f < 2 * dim; ++f)
            if (node.faces & (1u << f))
              {
                const unsigned int axis = f / 2;
                const double       sign = (f % 2) ? 1. : -1.; // outward
                switch (types[f])
                  {
                    case BoundaryType::fixed:
                      v = 0;
                      break;
                    case BoundaryType::slip:
                      v[axis] = 0;
                      break;
                    case BoundaryType::friction:
                      {
                        const double v_normal = sign * v[axis];
                        if (v_normal > 0) // moving into the face
                          {
                            v[axis] = 0;
                            const double v_tangential = v.norm();
                            if (v_tangential > 0)
                              v *= std::max(0.,
                                            1. - friction_coefficient *
                                                   v_normal / v_tangential);
                          }
                        break;
                      }
                    case BoundaryType::free:
                      break;
                  }
              }
          for (unsigned int d = 0; d < dim; ++d)
            (*velocity[d])(node.dof) = v[d];
          if (start_velocity)
            {
              Tensor<1, dim> v_start;
              for (unsigned int d = 0; d < dim; ++d)
                v_start[d] = (*(*start_velocity)[d])(node.dof);
              removed += mass(node.dof) * ((v_free - v) * (v_start + v)) / 2;
            }
        }
      return removed;
    }

    template class BoundaryConditions<2>;
    template class BoundaryConditions<3>;
    using Vector = LinearAlgebra::distributed::Vector<double>;
    template double
    BoundaryConditions<2>::apply(const Vector &,
                                 std::array<Vector *, 2>,
                                 const std::array<Vector *, 2> *) const;
    template double
    BoundaryConditions<3>::apply(const Vector &,
                                 std::array<Vector *, 3>,
                                 const std::array<Vector *, 3> *) const;
  } // namespace grid
} // namespace scarp
