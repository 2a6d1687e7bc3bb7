// PolygonShape: even-odd contains() on convex and non-convex polygons,
// rays through vertices, either orientation, lattice area against the
// shoelace area, validation errors and the vertex-list parser.

#include <scarp/scenes/polygon_shape.h>

#include <algorithm>

#include "check.h"

using namespace scarp::scenes;

namespace
{
  std::vector<Point<2>>
  points(const std::vector<std::pair<double, double>> &xy)
  {
    std::vector<Point<2>> result;
    for (const auto &p : xy)
      result.emplace_back(p.first, p.second);
    return result;
  }


  // Area by counting the points of a lattice of spacing h: error at most
  // (perimeter * h) by the half-cell boundary layer.
  double
  lattice_area(const PolygonShape &polygon, const double h)
  {
    const auto bb    = polygon.bounding_box().get_boundary_points();
    double     count = 0;
    for (double x = bb.first[0] + h / 2; x < bb.second[0]; x += h)
      for (double y = bb.first[1] + h / 2; y < bb.second[1]; y += h)
        count += polygon.contains(Point<2>(x, y));
    return count * h * h;
  }
} // namespace


int
main()
{
  {
    // Diamond: rays from these points pass exactly through vertices.
    const PolygonShape diamond(
      points({{1., 0.}, {2., 1.}, {1., 2.}, {0., 1.}}));
    CHECK(diamond.contains(Point<2>(0.5, 1.))); // ray through (2, 1)
    CHECK(diamond.contains(Point<2>(1., 1.)));
    CHECK(!diamond.contains(Point<2>(-0.5, 1.))); // through (0, 1) and (2, 1)
    CHECK(!diamond.contains(Point<2>(2.5, 1.)));
    CHECK(!diamond.contains(Point<2>(0.2, 0.2)));
    CHECK(diamond.contains(Point<2>(1., 1.9)));
    CHECK(!diamond.contains(Point<2>(-1., 2.))); // through (1, 2)
    CHECK_CLOSE(diamond.area(), 2., 1e-14);
  }
  {
    // Non-convex comb, given clockwise: teeth at x in [0,1], [2,3], [4,5].
    auto               comb = points({{0., 0.},
                                      {0., 2.},
                                      {1., 2.},
                                      {1., 1.},
                                      {2., 1.},
                                      {2., 2.},
                                      {3., 2.},
                                      {3., 1.},
                                      {4., 1.},
                                      {4., 2.},
                                      {5., 2.},
                                      {5., 0.}});
    const PolygonShape clockwise(comb);
    std::reverse(comb.begin(), comb.end());
    const PolygonShape counter_clockwise(comb);
    for (const PolygonShape *polygon : {&clockwise, &counter_clockwise})
      {
        CHECK(polygon->contains(Point<2>(0.5, 1.5)));
        CHECK(!polygon->contains(Point<2>(1.5, 1.5))); // between teeth
        CHECK(polygon->contains(Point<2>(2.5, 1.5)));
        CHECK(!polygon->contains(Point<2>(3.5, 1.5)));
        CHECK(polygon->contains(Point<2>(4.5, 1.5)));
        CHECK(polygon->contains(Point<2>(1.5, 0.5)));
        CHECK(polygon->contains(Point<2>(1.5, 1. - 1e-9))); // ray along y=1
        CHECK(!polygon->contains(Point<2>(5.5, 0.5)));
        CHECK_CLOSE(polygon->area(), 5. + 3., 1e-13);
        const double perimeter = 2. * 5. + 2. * 2. + 4. * 1.;
        CHECK_CLOSE(lattice_area(*polygon, 0.01), 8., perimeter * 0.01);
      }
    // A closing vertex equal to the first one is dropped.
    comb.push_back(comb.front());
    CHECK(PolygonShape(comb).vertices().size() == 12);
  }
  {
    // A triangle with irrational edges: lattice area vs shoelace.
    const PolygonShape triangle(points({{0.1, 0.2}, {3.7, 0.9}, {1.3, 2.9}}));
    const double       area =
      0.5 * std::abs((3.7 - 0.1) * (2.9 - 0.2) - (1.3 - 0.1) * (0.9 - 0.2));
    CHECK_CLOSE(triangle.area(), area, 1e-13);
    CHECK_CLOSE(lattice_area(triangle, 0.005), area, 10. * 0.005);
  }

  // Validation: each error names the problem.
  CHECK_THROWS_WITH(PolygonShape(points({{0., 0.}, {1., 0.}})),
                    "at least 3 vertices");
  CHECK_THROWS_WITH(PolygonShape(points({{0., 0.}, {1., 1.}, {2., 2.}})),
                    "zero area");
  CHECK_THROWS_WITH(PolygonShape(
                      points({{0., 0.}, {1., 0.}, {1., 0.}, {0., 1.}})),
                    "zero-length edge");
  CHECK_THROWS_WITH(PolygonShape(
                      points({{0., 0.}, {1., 1.}, {1., 0.}, {0., 1.}})),
                    "self-intersecting"); // bow tie
  CHECK_THROWS_WITH(PolygonShape(
                      points({{0., 0.}, {2., 0.}, {2., 2.}, {1., 0.}})),
                    "self-intersecting"); // vertex on an edge
  CHECK_THROWS_WITH(PolygonShape(
                      points({{0., 0.}, {2., 0.}, {1., 0.}, {1., 1.}})),
                    "fold back"); // spike back along the first edge
  CHECK_THROWS_WITH(PolygonShape(points(
                      {{0., 0.}, {4., 0.}, {4., 4.}, {2., -1.}, {0., 4.}})),
                    "cross or touch");

  // Parser.
  {
    const auto v = PolygonShape::parse_vertices(" 0,0; 1.5 , 0 ;0,1e1; ");
    CHECK(v.size() == 3);
    CHECK(v[1] == Point<2>(1.5, 0.));
    CHECK(v[2] == Point<2>(0., 10.));
  }
  CHECK_THROWS_WITH(PolygonShape::parse_vertices("0,0; 1 0; 0,1"),
                    "Vertices: item 1 ('1 0')");
  CHECK_THROWS_WITH(PolygonShape::parse_vertices("0,0; 1,x; 0,1"),
                    "Vertices: item 1");
  CHECK_THROWS_WITH(PolygonShape::parse_vertices("0,0,0; 1,0; 0,1"),
                    "Vertices: item 0");
  CHECK_THROWS_WITH(PolygonShape::parse_vertices("0,0;; 0,1"),
                    "Vertices: item 1");
  CHECK_THROWS_WITH(PolygonShape::parse_vertices(""), "Vertices: item 0");

  return scenes_test::finish();
}
