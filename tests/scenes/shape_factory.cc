// ShapeFactory: shapes read from scene-file text inside the caller's
// subsection, in 2D and 3D, and the errors for 2D-only shapes in 3D and for
// malformed entries.

#include <deal.II/base/parameter_handler.h>

#include <scarp/scenes/shape_factory.h>

#include "check.h"

using namespace scarp::scenes;

namespace
{
  // Declares a "Body rock" subsection, reads @p text into it and returns
  // the shape (as the simulation layer would).
  template <int dim>
  std::unique_ptr<Shape<dim>>
  shape_from(const std::string &text)
  {
    ParameterHandler prm;
    prm.enter_subsection("Body rock");
    ShapeFactory<dim>::declare_parameters(prm);
    prm.leave_subsection();
    prm.parse_input_from_string("subsection Body rock\n" + text + "\nend\n");
    prm.enter_subsection("Body rock");
    auto shape = ShapeFactory<dim>::create(prm);
    prm.leave_subsection();
    return shape;
  }
} // namespace


int
main()
{
  {
    const auto box = shape_from<2>("set Shape = box\n"
                                   "set Box corners = 2, 1, 0, 0.5");
    CHECK(box->contains(Point<2>(1., 0.75)));
    CHECK(!box->contains(Point<2>(1., 0.25)));
    CHECK(box->bounding_box().get_boundary_points().second == Point<2>(2., 1.));
  }
  {
    const auto ball = shape_from<2>("set Shape = ball\n"
                                    "set Centre = 1, 1\n"
                                    "set Radius = 0.5");
    CHECK(ball->contains(Point<2>(1.4, 1.)));
    CHECK(!ball->contains(Point<2>(1.6, 1.)));
  }
  {
    const auto polygon = shape_from<2>("set Shape = polygon\n"
                                       "set Vertices = 0,0; 4,0; 4,1; 1,1; "
                                       "1,3; 0,3");
    CHECK(polygon->contains(Point<2>(0.5, 2.5)));
    CHECK(polygon->contains(Point<2>(3.5, 0.5)));
    CHECK(!polygon->contains(Point<2>(2., 2.)));
    CHECK_CLOSE(dynamic_cast<const PolygonShape &>(*polygon).area(),
                4. + 2.,
                1e-14);
  }
  {
    const std::string cliff_text = "set Shape = cliff\n"
                                   "subsection Cliff\n"
                                   "  set Height = 10\n"
                                   "  set Notch depth = 0\n"
                                   "  set Back length = 20\n"
                                   "end";
    const auto        cliff      = shape_from<2>(cliff_text);
    const auto        cot        = 1. / std::tan(78. * M_PI / 180.);
    CHECK_CLOSE(dynamic_cast<const PolygonShape &>(*cliff).area(),
                10. * 20. + 0.5 * 100. * cot,
                1e-10);

    // The profile itself, for the crack and the diagnostics.
    ParameterHandler prm;
    ShapeFactory<2>::declare_parameters(prm);
    prm.parse_input_from_string(cliff_text);
    const auto profile = ShapeFactory<2>::create_cliff_profile(prm);
    CHECK(profile != nullptr);
    CHECK_CLOSE(profile->top_level(), 10., 1e-14);
    prm.set("Shape", "box");
    CHECK(ShapeFactory<2>::create_cliff_profile(prm) == nullptr);
  }
  {
    // Errors from the entries.
    CHECK_THROWS_WITH(shape_from<2>("set Shape = polygon\n"
                                    "set Vertices = 0,0; 1;0; 0,1"),
                      "Vertices: item 1");
    CHECK_THROWS_WITH(shape_from<2>("set Shape = polygon\n"
                                    "set Vertices = 0,0; 1,1; 1,0; 0,1"),
                      "self-intersecting");
    CHECK_THROWS_WITH(shape_from<2>("set Shape = ball\nset Radius = 0"),
                      "Radius must be positive");
    CHECK_THROWS_WITH(shape_from<2>("set Shape = box\n"
                                    "set Box corners = 0, 0, 1, 0"),
                      "Box corners");
    CHECK_THROWS_WITH(shape_from<2>("set Shape = cliff\n"
                                    "subsection Cliff\n"
                                    "  set Crack depth = 20\n"
                                    "end"),
                      "Cliff/Crack depth");
    // Wrong number of corners: the pattern rejects it on reading.
    CHECK(scenes_test::message_of(
            []() { shape_from<2>("set Box corners = 0, 0, 1"); }) != "");
  }
  {
    const auto box = shape_from<3>("set Shape = box\n"
                                   "set Box corners = 0, 0, 0, 1, 2, 3");
    CHECK(box->contains(Point<3>(0.5, 1.5, 2.5)));
    CHECK(!box->contains(Point<3>(0.5, 2.5, 2.5)));
    const auto ball = shape_from<3>("set Shape = ball\n"
                                    "set Centre = 0, 0, 1\n"
                                    "set Radius = 1");
    CHECK(ball->contains(Point<3>(0., 0., 1.9)));
    CHECK(!ball->contains(Point<3>(0., 0., -0.1)));
    CHECK_THROWS_WITH(shape_from<3>("set Shape = polygon"),
                      "Shape = polygon is only available in 2D");
    CHECK_THROWS_WITH(shape_from<3>("set Shape = cliff"),
                      "Shape = cliff is only available in 2D");
  }
  return scenes_test::finish();
}
