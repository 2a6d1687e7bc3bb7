// BoxShape and BallShape in 2D and 3D: contains() on known points, the
// boundary conventions, bounding boxes and the errors.

#include <scarp/scenes/ball_shape.h>
#include <scarp/scenes/box_shape.h>

#include "check.h"

using namespace scarp::scenes;

int
main()
{
  {
    // Corners in any order; half open [lower, upper).
    const BoxShape<2> box(Point<2>(2., 1.), Point<2>(-1., 0.));
    CHECK(box.contains(Point<2>(0.5, 0.5)));
    CHECK(box.contains(Point<2>(-1., 0.)));
    CHECK(!box.contains(Point<2>(2., 0.5)));
    CHECK(!box.contains(Point<2>(0.5, 1.)));
    CHECK(!box.contains(Point<2>(-1.01, 0.5)));
    CHECK(!box.contains(Point<2>(0.5, -1e-12)));
    CHECK_CLOSE(box.measure(), 3., 1e-14);
    const auto bb = box.bounding_box().get_boundary_points();
    CHECK(bb.first == Point<2>(-1., 0.));
    CHECK(bb.second == Point<2>(2., 1.));

    // Two boxes that tile [0, 2) x [0, 1) claim every lattice point once.
    const BoxShape<2> left(Point<2>(0., 0.), Point<2>(1., 1.));
    const BoxShape<2> right(Point<2>(1., 0.), Point<2>(2., 1.));
    unsigned int      claims = 0, points = 0;
    for (unsigned int i = 0; i < 20; ++i)
      for (unsigned int j = 0; j < 10; ++j, ++points)
        {
          const Point<2> p(0.1 * i, 0.1 * j);
          claims += left.contains(p) + right.contains(p);
        }
    CHECK(claims == points);

    CHECK_THROWS_WITH(BoxShape<2>(Point<2>(0., 0.), Point<2>(1., 0.)),
                      "Box corners");
  }
  {
    const BoxShape<3> box(Point<3>(0., 0., 0.), Point<3>(1., 2., 3.));
    CHECK(box.contains(Point<3>(0.5, 1.5, 2.5)));
    CHECK(!box.contains(Point<3>(0.5, 1.5, 3.5)));
    CHECK(!box.contains(Point<3>(0.5, 2., 1.)));
    CHECK_CLOSE(box.measure(), 6., 1e-14);
    CHECK_THROWS_WITH(BoxShape<3>(Point<3>(0., 0., 1.), Point<3>(1., 1., 1.)),
                      "zero extent in direction 2");
  }
  {
    // Closed disk.
    const BallShape<2> disk(Point<2>(1., 2.), 0.5);
    CHECK(disk.contains(Point<2>(1., 2.)));
    CHECK(disk.contains(Point<2>(1.5, 2.)));
    CHECK(disk.contains(Point<2>(1. + 0.35, 2. + 0.35)));
    CHECK(!disk.contains(Point<2>(1. + 0.36, 2. + 0.36)));
    CHECK(!disk.contains(Point<2>(0., 0.)));
    const auto bb = disk.bounding_box().get_boundary_points();
    CHECK(bb.first == Point<2>(0.5, 1.5));
    CHECK(bb.second == Point<2>(1.5, 2.5));
    CHECK_THROWS_WITH(BallShape<2>(Point<2>(), 0.), "Radius");
    CHECK_THROWS_WITH(BallShape<3>(Point<3>(), -1.), "Radius");

    const BallShape<3> ball(Point<3>(0., 0., 0.), 2.);
    CHECK(ball.contains(Point<3>(1., 1., 1.)));
    CHECK(!ball.contains(Point<3>(1.2, 1.2, 1.2)));
    CHECK(ball.contains(Point<3>(0., 0., -2.)));

    // Lattice volume of the ball: 4/3 pi r^3 to within the lattice error.
    const double h     = 0.05;
    double       count = 0;
    for (double x = -2. + h / 2; x < 2.; x += h)
      for (double y = -2. + h / 2; y < 2.; y += h)
        for (double z = -2. + h / 2; z < 2.; z += h)
          count += ball.contains(Point<3>(x, y, z));
    // Boundary layer of thickness h/2 on the sphere bounds the error.
    CHECK_CLOSE(count * h * h * h,
                4. / 3. * M_PI * 8.,
                4. * M_PI * 4. * h / 2.);
  }
  return scenes_test::finish();
}
