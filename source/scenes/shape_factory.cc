#include <deal.II/base/exceptions.h>

#include <scarp/scenes/ball_shape.h>
#include <scarp/scenes/box_shape.h>
#include <scarp/scenes/polygon_shape.h>
#include <scarp/scenes/shape_factory.h>

namespace scarp
{
  namespace scenes
  {
    namespace
    {
      template <int dim>
      Point<dim>
      to_point(const std::vector<double> &values, const unsigned int offset)
      {
        Point<dim> p;
        for (unsigned int d = 0; d < dim; ++d)
          p[d] = values[offset + d];
        return p;
      }


      // Patterns::List has already checked the count and the numbers.
      std::vector<double>
      get_doubles(const ParameterHandler &prm, const std::string &entry)
      {
        return Utilities::string_to_double(
          Utilities::split_string_list(prm.get(entry), ','));
      }


      template <int dim>
      void
      require_2d(const std::string &shape)
      {
        AssertThrow(dim == 2,
                    ExcMessage("Shape = " + shape +
                               " is only available in 2D (plane strain); "
                               "this is a " +
                               std::to_string(dim) +
                               "D scene. Use box or ball."));
      }
    } // namespace


    template <int dim>
    void
    ShapeFactory<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Shape",
                        "box",
                        Patterns::Selection("box|ball|polygon|cliff"),
                        "Geometry of the region: box (Box corners), ball "
                        "(Centre, Radius), polygon (Vertices, 2D only) or "
                        "cliff (subsection Cliff, 2D only).");
      prm.declare_entry("Box corners",
                        dim == 2 ? "0, 0, 1, 1" : "0, 0, 0, 1, 1, 1",
                        Patterns::List(Patterns::Double(), 2 * dim, 2 * dim),
                        "Two opposite corners of the box, "
                        "x0,y0[,z0],x1,y1[,z1]. The box is half open: "
                        "[lower, upper) in every direction.");
      prm.declare_entry("Centre",
                        dim == 2 ? "0, 0" : "0, 0, 0",
                        Patterns::List(Patterns::Double(), dim, dim),
                        "Centre of the ball (disk in 2D).");
      prm.declare_entry("Radius",
                        "1",
                        Patterns::Double(0.),
                        "Radius of the ball (disk in 2D); must be positive.");
      prm.declare_entry(
        "Vertices",
        "0, 0; 1, 0; 0, 1",
        Patterns::Anything(),
        "Polygon vertices in order (either orientation), \"x0,y0; x1,y1; "
        "...\": at least 3, a simple polygon (no crossing edges) of non-zero "
        "area. 2D only.");
      CliffProfile::declare_parameters(prm);
    }


    template <int dim>
    std::unique_ptr<Shape<dim>>
    ShapeFactory<dim>::create(ParameterHandler &prm)
    {
      const std::string shape = prm.get("Shape");
      if (shape == "box")
        {
          const auto corners = get_doubles(prm, "Box corners");
          return std::make_unique<BoxShape<dim>>(to_point<dim>(corners, 0),
                                                 to_point<dim>(corners, dim));
        }
      if (shape == "ball")
        return std::make_unique<BallShape<dim>>(
          to_point<dim>(get_doubles(prm, "Centre"), 0),
          prm.get_double("Radius"));
      if (shape == "polygon")
        {
          require_2d<dim>(shape);
          if constexpr (dim == 2)
            return std::make_unique<PolygonShape>(
              PolygonShape::parse_vertices(prm.get("Vertices")));
        }
      if (shape == "cliff")
        {
          require_2d<dim>(shape);
          if constexpr (dim == 2)
            return std::make_unique<PolygonShape>(
              create_cliff_profile(prm)->body());
        }
      AssertThrow(false, ExcMessage("Shape: unknown shape '" + shape + "'."));
      return nullptr;
    }


    template <int dim>
    std::unique_ptr<CliffProfile>
    ShapeFactory<dim>::create_cliff_profile(ParameterHandler &prm)
    {
      if (prm.get("Shape") != "cliff")
        return nullptr;
      require_2d<dim>("cliff");
      auto profile = std::make_unique<CliffProfile>();
      profile->parse_parameters(prm);
      return profile;
    }


    template class ShapeFactory<2>;
    template class ShapeFactory<3>;
  } // namespace scenes
} // namespace scarp
