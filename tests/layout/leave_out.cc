// "Leave out what a scene does not need": the per-point storage and the
// non-local machinery follow the physics a scene switches on.
#include <common/scene_runner.h>

#include <algorithm>

using namespace scarp_test;

namespace
{
  std::string
  scene(const std::string &model, const std::string &transfer)
  {
    return R"(
set Materials = m
set Bodies    = b
set Stages    = s
subsection Mesh
  set Upper corner = 1, 1
  set Cell size = 0.25
end
subsection Material m
  set Model = )" +
           model + R"(
  set Density = 1000
  subsection Elasticity
    set Young's modulus = 1e6
    set Poisson's ratio = 0.3
  end
end
subsection Body b
  set Material = m
  set Box corners = 0.25, 0.25, 0.75, 0.75
end
subsection Transfer
  set Velocity transfer = )" +
           transfer + R"(
end
)";
  }

  bool
  has_name(const scarp::particles::PropertyLayout<2> &layout,
           const std::string                         &name)
  {
    const auto names = layout.names();
    return std::find(names.begin(), names.end(), name) != names.end();
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const auto elastic = make_scene<2>(scene("linear elastic", "FLIP"));
  const auto apic    = make_scene<2>(scene("linear elastic", "APIC"));
  const auto chalk   = make_scene<2>(scene("chalk", "FLIP"));
  const auto &le = elastic->property_layout(), &la = apic->property_layout(),
             &lc = chalk->property_layout();
  out() << "  properties per point: elastic FLIP " << le.n_properties()
        << ", elastic APIC " << la.n_properties() << ", chalk FLIP "
        << lc.n_properties() << std::endl;
  check(!le.has_affine && la.has_affine,
        "the affine matrix is stored only with APIC");
  check(la.n_properties() == le.n_properties() + 4,
        "APIC adds exactly the 2x2 affine matrix");
  check(!has_name(le, "damage") && !has_name(le, "kappa") &&
          !has_name(le, "plastic_strain"),
        "an elastic scene carries no damage or plastic history");
  check(has_name(lc, "damage") && has_name(lc, "kappa"),
        "a chalk scene carries damage and its history");
  check(!elastic->has_nonlocal_average() && !apic->has_nonlocal_average() &&
          chalk->has_nonlocal_average(),
        "the non-local average exists only in the scene with damage");
  return 0;
}
