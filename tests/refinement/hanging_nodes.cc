// Hanging nodes: a stress-free block falls through a mesh that is refined
// (two levels) in a band it crosses. Uniform motion is in the FE space with
// hanging-node constraints, so the grid reproduces it exactly: the centre of
// mass follows y0 - g t^2/2 - g dt t/2 (the x += dt v^{n+1} update with a
// constant dt) and the velocity is -g t, to round-off; no stress appears.
// A constraint applied wrongly (mass or momentum of a hanging node lost or
// double counted) breaks all three by far more than round-off.
// Argument: Q1 (default) or GIMP; GIMP's patches resolve the hanging nodes
// themselves (transfer/gimp_patches.h) and the domains of the points reach
// across the coarse-fine interfaces.
#include <common/scene_runner.h>

using namespace scarp_test;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const double                     g = 9.81, dt = 5e-4;
  const std::string                shape = argc > 1 ? argv[1] : "Q1";
  out() << "  shape functions: " << shape << std::endl;
  auto sim = make_scene<2>(
    "subsection Transfer\n  set Shape functions = " + shape + "\nend\n" + R"(
set Dimension = 2
set Materials = rubber
set Bodies    = block
set Stages    = fall
subsection Mesh
  set Lower corner = 0, 0
  set Upper corner = 4, 4
  set Cell size    = 0.25
  subsection Boundary conditions
    set Left = free
    set Right = free
    set Bottom = free
    set Top = free
  end
  subsection Refinement
    set Initial levels = 2
    set Initial region = 0, 1.2, 4, 2.3
  end
end
subsection Material rubber
  set Model = linear elastic
  set Density = 1000
  subsection Elasticity
    set Young's modulus = 1e6
    set Poisson's ratio = 0.3
  end
end
subsection Body block
  set Material = rubber
  set Shape = box
  set Box corners = 1.5, 2.5, 2.5, 3.5
end
subsection Physics
  set Gravity = 0, -9.81
end
subsection Time
  set Maximum time step = 5e-4
end
subsection Stage fall
  set End time = 0.6
end
)");
  const auto &layout = sim->property_layout();
  const auto  mass   = [&](const double *p, const Point<2> &) {
    return p[layout.mass];
  };
  const auto y_mass = [&](const double *p, const Point<2> &x) {
    return p[layout.mass] * x[1];
  };
  const double M  = sum_over_points<2>(*sim, mass);
  const double y0 = sum_over_points<2>(*sim, y_mass) / M;
  check(sim->background_grid().triangulation().n_global_levels() == 3,
        "the mesh has two levels of refinement (hanging nodes)");

  // 0.6 s: the block (2.5 to 3.5) falls 1.77 m, through the refined band
  // (dt = 5e-4 stays below the CFL limit of the finest cells, so it is
  // constant).
  sim->run_until(0.6);
  const double t        = sim->time();
  const double y        = sum_over_points<2>(*sim, y_mass) / M;
  const double expected = y0 - g * t * t / 2 - g * dt * t / 2;
  const double v_error =
    max_over_points<2>(*sim, [&](const double *p, const Point<2> &) {
      return std::abs(p[layout.velocity + 1] + g * t) +
             std::abs(p[layout.velocity]);
    });
  const double stress =
    max_over_points<2>(*sim, [&](const double *p, const Point<2> &) {
      return layout.get_stress(p, layout.stress).norm();
    });
  out() << "  t = " << t << " s, centre of mass " << y << " m, exact "
        << expected << " m, velocity error " << v_error
        << " m/s, largest stress " << stress << " Pa" << std::endl;
  // Round-off: 800 steps of sums of O(1) numbers -> ~1e-12 relative.
  check(std::abs(y - expected) < 1e-10 * std::abs(y0),
        "centre of mass exact through the hanging nodes");
  check(v_error < 1e-10 * g * t, "velocity -g t at every point");
  // A spurious strain of 1e-12 would give 1e-6 Pa at E = 1e6.
  check(stress < 1e-4, "no stress from a uniform motion");
  return 0;
}
