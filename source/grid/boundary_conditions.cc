#include <deal.II/base/mpi.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <scarp/base/exceptions.h>
#include <scarp/base/parameter_tools.h>
#include <scarp/grid/boundary_conditions.h>

#include <cmath>
#include <map>
#include <sstream>

namespace scarp
{
  namespace grid
  {
    template <int dim>
    std::string
    BoundaryConditions<dim>::face_name(const unsigned int face)
    {
      static const char *names[] = {
        "Left", "Right", "Bottom", "Top", "Front", "Back"};
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
      prm.declare_entry(
        "Friction contact",
        "consistent",
        Patterns::Selection("consistent|legacy"),
        "How a friction face decides contact within a step. consistent: the "
        "faces the end velocity of the grid update presses on are in "
        "contact for the whole step (the MUSL remap keeps their normal "
        "velocity at zero, no second friction), and the FLIP points lose "
        "the normal velocity the face stops and feel its friction. legacy: "
        "the start velocity, the end velocity and the MUSL remap each "
        "decide by their own direction (scarp before 2026-12): a body that "
        "separates from the face gains energy and FLIP points keep a "
        "normal velocity that brakes the grid every step; kept only to "
        "reproduce results obtained with it (doc/user_guide.md, Energy "
        "balance).");
      prm.enter_subsection("Prescribed velocity");
      prm.declare_entry(
        "Face",
        "none",
        Patterns::Selection(dim == 2 ? "none|Left|Right|Bottom|Top"
                                     : "none|Left|Right|Bottom|Top|Front|Back"),
        "Face of the background box on which a region moves with a "
        "prescribed constant velocity (a rigid footing or plate), or none. "
        "Inside the region this replaces the face's own condition; the force "
        "the material exerts on the region is written to statistics.csv "
        "(reaction_x, reaction_y[, reaction_z]).");
      prm.declare_entry(
        "Region",
        "",
        Patterns::Anything(),
        "Two opposite corners x0, y0[, z0], x1, y1[, z1] of a box: the nodes "
        "of <Face> inside it (closed, to 1e-9 of the box size) have the "
        "prescribed velocity. The box must reach the face and hold at least "
        "one node of it. Empty: the whole face.");
      prm.declare_entry("Velocity",
                        dim == 2 ? "0, 0" : "0, 0, 0",
                        *ParameterTools::double_list(dim),
                        "The prescribed velocity [m/s], constant in time.");
      prm.declare_entry(
        "Components",
        "all",
        Patterns::Selection("all|normal"),
        "all: every velocity component of the region's nodes is prescribed "
        "(a rough plate, no slip); normal: only the component normal to "
        "<Face> (a smooth plate, the tangential velocity is free; the "
        "tangential components of <Velocity> must then be zero).");
      prm.leave_subsection();
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
      friction_coefficient    = prm.get_double("Friction coefficient");
      legacy_friction_contact = prm.get("Friction contact") == "legacy";
      prm.enter_subsection("Prescribed velocity");
      const std::string where =
        "Mesh/Boundary conditions/Prescribed velocity: ";
      prescribed_face = numbers::invalid_unsigned_int;
      for (unsigned int f = 0; f < 2 * dim; ++f)
        if (prm.get("Face") == face_name(f))
          prescribed_face = f;
      prescribed_velocity = ParameterTools::get_vector<dim>(prm, "Velocity");
      normal_only         = prm.get("Components") == "normal";
      region_corners.clear();
      {
        std::string text = prm.get("Region");
        for (char &c : text)
          if (c == ',')
            c = ' ';
        std::istringstream in(text);
        double             x;
        while (in >> x)
          region_corners.push_back(x);
        if (!in.eof() ||
            (!region_corners.empty() && region_corners.size() != 2 * dim))
          throw ScarpError(where + "<Region> (" + prm.get("Region") +
                           ") must be empty or " + std::to_string(2 * dim) +
                           " numbers: two opposite corners of a box.");
      }
      if (has_prescribed_velocity() && normal_only)
        for (unsigned int d = 0; d < dim; ++d)
          if (d != prescribed_face / 2 && prescribed_velocity[d] != 0)
            throw ScarpError(
              where +
              "<Components> = normal prescribes only the velocity "
              "normal to the " +
              face_name(prescribed_face) + " face, but <Velocity> has " +
              std::to_string(prescribed_velocity[d]) + " in direction " +
              std::to_string(d) +
              " (tangential); set it to 0 or use <Components> = all.");
      prm.leave_subsection();
      prm.leave_subsection();
    }


    template <int dim>
    std::vector<std::string>
    BoundaryConditions<dim>::reaction_column_names() const
    {
      if (!has_prescribed_velocity())
        return {};
      std::vector<std::string> names{"reaction_x", "reaction_y"};
      if (dim == 3)
        names.push_back("reaction_z");
      return names;
    }


    template <int dim>
    Tensor<1, dim>
    BoundaryConditions<dim>::take_reaction(const MPI_Comm communicator) const
    {
      Tensor<1, dim> impulse;
      for (unsigned int d = 0; d < dim; ++d)
        impulse[d] = Utilities::MPI::sum(reaction_impulse[d], communicator);
      // Every rank takes the same steps: its own time is the time.
      const double time = reaction_time;
      reaction_impulse  = Tensor<1, dim>();
      reaction_time     = 0;
      // The material pushes on the region with minus the impulse the region
      // gave it.
      return time > 0 ? -impulse / time : Tensor<1, dim>();
    }


    template <int dim>
    void
    BoundaryConditions<dim>::setup(const DoFHandler<dim>  &dof_handler,
                                   const BoundingBox<dim> &box)
    {
      const IndexSet &owned = dof_handler.locally_owned_dofs();
      std::map<types::global_dof_index, unsigned int> faces_of_dof;
      std::vector<types::global_dof_index>            face_dofs(
        dof_handler.get_fe().n_dofs_per_face());

      // The prescribed region: a closed box (the whole face when no region
      // is given), checked against the mesh box and the other faces.
      const std::string where =
        "Mesh/Boundary conditions/Prescribed velocity: ";
      Point<dim> region_lower = box.get_boundary_points().first;
      Point<dim> region_upper = box.get_boundary_points().second;
      double     tolerance    = 0;
      for (unsigned int d = 0; d < dim; ++d)
        tolerance = std::max(tolerance, 1e-9 * box.side_length(d));
      if (has_prescribed_velocity())
        {
          const unsigned int axis = prescribed_face / 2;
          const double       face_x =
            prescribed_face % 2 ? region_upper[axis] : region_lower[axis];
          if (!region_corners.empty())
            for (unsigned int d = 0; d < dim; ++d)
              {
                region_lower[d] =
                  std::min(region_corners[d], region_corners[dim + d]);
                region_upper[d] =
                  std::max(region_corners[d], region_corners[dim + d]);
              }
          if (face_x < region_lower[axis] - tolerance ||
              face_x > region_upper[axis] + tolerance)
            {
              std::ostringstream m;
              m << where << "<Region> spans " << region_lower[axis] << " to "
                << region_upper[axis] << " in direction " << axis
                << ", so it does not lie on the " << face_name(prescribed_face)
                << " face (at " << face_x << "); the box must contain it.";
              throw ScarpError(m.str());
            }
          // Faces the region reaches at its edges keep their own condition
          // there, applied first; a prescribed component they forbid is a
          // contradiction.
          for (unsigned int g = 0; g < 2 * dim; ++g)
            {
              if (g / 2 == axis || types[g] == BoundaryType::free)
                continue;
              const unsigned int a = g / 2;
              const double g_x     = g % 2 ? box.get_boundary_points().second[a]
                                           : box.get_boundary_points().first[a];
              if (g_x < region_lower[a] - tolerance ||
                  g_x > region_upper[a] + tolerance)
                continue;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  const bool prescribed = !normal_only || d == axis;
                  const bool forbidden =
                    types[g] == BoundaryType::fixed || d == a;
                  if (prescribed && forbidden && prescribed_velocity[d] != 0)
                    {
                      std::ostringstream m;
                      m << where << "the region reaches the " << face_name(g)
                        << " face, which is "
                        << (types[g] == BoundaryType::fixed
                              ? "fixed (no velocity)"
                              : (types[g] == BoundaryType::slip
                                   ? "slip (no normal velocity)"
                                   : "friction (no normal velocity into it)"))
                        << ", but <Velocity> prescribes "
                        << prescribed_velocity[d] << " in direction " << d
                        << " there; make the region end before that face or "
                           "change its condition.";
                      throw ScarpError(m.str());
                    }
                }
            }
        }
      unsigned int n_region_nodes = 0;
      // Ghost cells too: a node owned here may only touch a ghost cell's face.
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial() && cell->at_boundary())
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary())
              {
                const unsigned int id = cell->face(f)->boundary_id();
                if (id == prescribed_face)
                  {
                    // FE_Q(1): one dof per vertex, in vertex order.
                    const auto face = cell->face(f);
                    for (const unsigned int v : face->vertex_indices())
                      {
                        const auto  dof = face->vertex_dof_index(v, 0);
                        const auto &x   = face->vertex(v);
                        bool        in  = true;
                        for (unsigned int d = 0; d < dim; ++d)
                          in = in && x[d] >= region_lower[d] - tolerance &&
                               x[d] <= region_upper[d] + tolerance;
                        if (in && owned.is_element(dof))
                          faces_of_dof[dof] |= prescribed_bit;
                      }
                  }
                if (types[id] == BoundaryType::free)
                  continue;
                cell->face(f)->get_dof_indices(face_dofs);
                for (const auto dof : face_dofs)
                  if (owned.is_element(dof))
                    faces_of_dof[dof] |= (1u << id);
              }
      for (const auto &[dof, faces] : faces_of_dof)
        if (faces & prescribed_bit)
          ++n_region_nodes;
      if (has_prescribed_velocity() &&
          Utilities::MPI::sum(n_region_nodes, dof_handler.get_communicator()) ==
            0)
        {
          std::ostringstream m;
          m << where << "<Region> holds no node of the "
            << face_name(prescribed_face)
            << " face; make it reach at least one mesh node.";
          throw ScarpError(m.str());
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
      std::array<VectorType *, dim>       *start_velocity,
      const double                         dt,
      const std::array<VectorType *, dim> *damping_force,
      const double                         mass_scale) const
    {
      // The conditions of one node, applied to the velocity v in place.
      // Friction faces by pass: the grid update (end velocity) decides
      // contact by its own direction and records it in node.contact; the
      // start velocity and the MUSL remap (consistent contact) take the
      // normal velocity off the faces in contact only, without friction;
      // the start of the FLIP update (consistent contact) leaves friction
      // faces alone; legacy contact treats every pass like the grid update.
      enum class Pass
      {
        update,
        start,
        flip_start,
        remap
      };
      const auto constrain =
        [&](const Node &node, Tensor<1, dim> &v, const Pass pass) {
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
                        if (pass == Pass::flip_start)
                          break;
                        if (pass != Pass::update && !legacy_friction_contact)
                          {
                            if (node.contact & (1u << f))
                              v[axis] = 0;
                            break;
                          }
                        const double v_normal = sign * v[axis];
                        if (v_normal > 0) // moving into the face
                          {
                            if (pass == Pass::update)
                              node.contact |= (1u << f);
                            v[axis]                   = 0;
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
          if (node.faces & prescribed_bit)
            for (unsigned int d = 0; d < dim; ++d)
              if (!normal_only || d == prescribed_face / 2)
                v[d] = prescribed_velocity[d];
        };

      double removed = 0.;
      for (const Node &node : nodes)
        {
          Tensor<1, dim> v;
          for (unsigned int d = 0; d < dim; ++d)
            v[d] = (*velocity[d])(node.dof);
          const Tensor<1, dim> v_free = v;
          if (start_velocity)
            node.contact = 0;
          constrain(node, v, start_velocity ? Pass::update : Pass::remap);
          for (unsigned int d = 0; d < dim; ++d)
            (*velocity[d])(node.dof) = v[d];
          if (!start_velocity)
            continue;
          if (node.faces & prescribed_bit)
            for (unsigned int d = 0; d < dim; ++d)
              if (!normal_only || d == prescribed_face / 2)
                reaction_impulse[d] +=
                  mass_scale * mass(node.dof) * (v[d] - v_free[d]) +
                  (damping_force ? dt * (*(*damping_force)[d])(node.dof) : 0.);
          Tensor<1, dim> v_raw;
          for (unsigned int d = 0; d < dim; ++d)
            v_raw[d] = (*(*start_velocity)[d])(node.dof);
          // v_work: the start velocity the stress sees (the remap keeps the
          // contact faces' normal velocity at zero). v_start: the one the
          // FLIP update v_p + S (v - v_start) starts from. Fixed and slip
          // faces take the normal velocity off both: FLIP points keep the
          // velocity a wall stops, harmless there since every step removes
          // it again. Consistent friction faces leave v_start as P2G gave
          // it: a normal velocity kept by the points would brake the
          // grid's tangential velocity anew every step, and the friction
          // would not reach them; so they lose what the face stops.
          Tensor<1, dim> v_work = v_raw;
          constrain(node, v_work, Pass::start);
          Tensor<1, dim> v_start = v_raw;
          constrain(node,
                    v_start,
                    legacy_friction_contact || (node.faces & prescribed_bit)
                      ? Pass::start
                      : Pass::flip_start);
          for (unsigned int d = 0; d < dim; ++d)
            (*(*start_velocity)[d])(node.dof) = v_start[d];
          const Tensor<1, dim> dv = v - v_start;
          if (node.faces & prescribed_bit)
            // A prescribed velocity reaches the stress and, through the
            // PIC share, the points from the first step on: the work of its
            // whole reaction impulse against (v_start + v)/2 (a sudden
            // start is an inelastic impact).
            removed += mass(node.dof) * ((v_free - v) * (v_start + v)) / 2;
          else
            // The forces' work over the velocities the stress power at the
            // points sees, (v_work + v)/2, less the kinetic energy the
            // points' FLIP update draws from the node, p . dv + m |dv|^2 / 2
            // with the node's P2G momentum p = m v_raw: zero where no
            // condition acts.
            removed += mass(node.dof) * ((v_free - v_raw) * (v_work + v) / 2 -
                                         v_raw * dv - dv.norm_square() / 2);
        }
      if (start_velocity)
        reaction_time += dt;
      return removed;
    }

    template class BoundaryConditions<2>;
    template class BoundaryConditions<3>;
    using Vector = LinearAlgebra::distributed::Vector<double>;
    template double
    BoundaryConditions<2>::apply(const Vector &,
                                 std::array<Vector *, 2>,
                                 std::array<Vector *, 2> *,
                                 double,
                                 const std::array<Vector *, 2> *,
                                 double) const;
    template double
    BoundaryConditions<3>::apply(const Vector &,
                                 std::array<Vector *, 3>,
                                 std::array<Vector *, 3> *,
                                 double,
                                 const std::array<Vector *, 3> *,
                                 double) const;
  } // namespace grid
} // namespace scarp
