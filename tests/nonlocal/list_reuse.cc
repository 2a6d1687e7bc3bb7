// Reuse of the neighbour lists (doc/nonlocal.md, "Reuse"): moves below half
// the skin reuse the lists and give the same averages as a fresh build, also
// when a pair that was beyond the cut-off at the build has come within it;
// the same points in another order reuse them through a reordering; a
// removed point patches them (as a point that left for another rank);
// larger moves, a new receiver, other boxes, invalidate_neighbour_lists()
// and reinit() rebuild.

#include <deal.II/base/mpi.h>

#include "test_tools.h"

using namespace scarp_test;

template <int dim>
class Checker
{
public:
  Checker(const WeightType type)
    : type(type)
    , averager(MPI_COMM_SELF)
  {
    averager.reinit(type, l_c, 0.1);
  }

  /// Average @p points with the persistent averager, compare with a fresh
  /// one, and check that the persistent one rebuilt iff @p expect_rebuild
  /// (else reused, or patched if @p expect_patch).
  std::vector<double>
  step(const PointSet<dim>                 &points,
       const bool                           expect_rebuild,
       const std::string                   &what,
       const std::vector<BoundingBox<dim>> &boxes        = cube<dim>(-1., 4.),
       const bool                           expect_patch = false)
  {
    const unsigned int rebuilds = averager.n_rebuilds();
    const unsigned int reuses   = averager.n_reuses();
    const unsigned int patches  = averager.n_patches();
    const auto         ybar     = points.average(averager, boxes);

    NonlocalAverager<dim> fresh(MPI_COMM_SELF);
    fresh.reinit(type, l_c, 0.1);
    const auto reference = points.average(fresh, boxes);

    // Reused lists only add pairs of weight exactly 0 and sum in the same
    // (id) order, so the results should be bit-identical; 1e-14 relative
    // still allows for a compiler contracting differently.
    double max_difference = 0.;
    for (std::size_t i = 0; i < ybar.size(); ++i)
      max_difference = std::max(max_difference,
                                std::abs(ybar[i] - reference[i]) /
                                  std::max(1., std::abs(reference[i])));
    const bool rebuilt = averager.n_rebuilds() == rebuilds + 1 &&
                         averager.n_reuses() == reuses &&
                         averager.n_patches() == patches;
    const bool reused = averager.n_rebuilds() == rebuilds &&
                        averager.n_reuses() == reuses + 1 &&
                        averager.n_patches() == patches;
    const bool patched = averager.n_rebuilds() == rebuilds &&
                         averager.n_reuses() == reuses &&
                         averager.n_patches() == patches + 1;
    const std::string name =
      std::to_string(dim) + "D " + to_string(type) + ", " + what;
    std::cout << name << ": "
              << (rebuilt   ? "rebuilt"
                  : patched ? "patched"
                  : reused  ? "reused"
                            : "?")
              << ", difference to a fresh build " << max_difference
              << std::endl;
    check(expect_rebuild ? rebuilt
          : expect_patch ? patched
                         : reused,
          name + ": rebuild, patch or reuse");
    check(max_difference <= 1e-14, name + ": same as a fresh build");
    return ybar;
  }

  double
  skin() const
  {
    return averager.skin_distance();
  }

  double
  cutoff() const
  {
    return averager.cutoff_radius();
  }

  const double          l_c = 0.1;
  const WeightType      type;
  NonlocalAverager<dim> averager;
};

template <int dim>
void
run(const WeightType type)
{
  Checker<dim>  checker(type);
  const double  skin   = checker.skin();
  PointSet<dim> points = make_lattice<dim>(dim == 2 ? 30 : 10, 0.1);
  for (std::size_t i = 0; i < points.size(); ++i)
    points.values[i] = std::sin(0.3 * i) + 0.1 * i;

  // A pair beyond the cut-off, within the skin: R + 0.8 skin apart, placed
  // away from the lattice. Each moves 0.45 skin towards the other below.
  const types::particle_index pair_id = points.size();
  Point<dim>                  a, b;
  a[0] = -0.6;
  b[0] = a[0];
  b[1] = checker.cutoff() + 0.8 * skin;
  points.push_back(a, 1e-3, 1., true, pair_id);
  points.push_back(b, 1e-3, 2., true, pair_id + 1);

  points.receivers[5] = false;
  checker.step(points, true, "first call");
  checker.step(points, false, "same points");

  // Moves just below skin/2 in random directions; the pair moves together.
  for (std::size_t i = 0; i < points.size(); ++i)
    {
      Tensor<1, dim> direction;
      for (unsigned int d = 0; d < dim; ++d)
        direction[d] = std::sin(2.3 * i + 1.7 * d + 0.1);
      points.positions[i] += 0.49 * skin * direction / direction.norm();
      points.values[i] += 0.5;
    }
  points.positions[pair_id]     = a;
  points.positions[pair_id + 1] = b;
  points.positions[pair_id][1] += 0.45 * skin;
  points.positions[pair_id + 1][1] -= 0.45 * skin;
  const auto ybar = checker.step(points, false, "moves < skin/2");
  // The pair is now 0.1 skin inside the cut-off: it must interact.
  check(ybar[pair_id] > points.values[pair_id] + 1e-6 &&
          ybar[pair_id + 1] < points.values[pair_id + 1] - 1e-6,
        "a pair that came within the cut-off interacts");

  // Receivers dropping out keep the lists; a new receiver (point 5 was
  // none at the build) needs one.
  points.receivers[6] = false;
  checker.step(points, false, "a receiver less");
  points.receivers[5] = true;
  checker.step(points, true, "a new receiver");

  // One point moves a bit more than skin/2 (from the last build).
  points.positions[7][0] += 0.51 * skin;
  checker.step(points, true, "one move > skin/2");

  // Other ids: a point removed; then the same points in another order.
  PointSet<dim> fewer;
  for (std::size_t i = 1; i < points.size(); ++i)
    fewer.push_back(points.positions[i],
                    points.volumes[i],
                    points.values[i],
                    points.receivers[i],
                    points.ids[i]);
  checker.step(fewer, false, "a point removed", cube<dim>(-1., 4.), true);
  checker.step(fewer, false, "unchanged again");
  std::swap(fewer.positions[0], fewer.positions[1]);
  std::swap(fewer.volumes[0], fewer.volumes[1]);
  std::swap(fewer.values[0], fewer.values[1]);
  std::swap(fewer.ids[0], fewer.ids[1]);
  // The same points in another order (points that changed cells) reuse the
  // lists through a reordering, unless one also moved more than skin/2.
  const unsigned int reorders = checker.averager.n_reorders();
  checker.step(fewer, false, "points reordered");
  check(checker.averager.n_reorders() == reorders + 1,
        "the reordered call went through the reordering");
  std::swap(fewer.positions[2], fewer.positions[3]);
  std::swap(fewer.volumes[2], fewer.volumes[3]);
  std::swap(fewer.values[2], fewer.values[3]);
  std::swap(fewer.ids[2], fewer.ids[3]);
  fewer.positions[2][0] += 0.51 * skin;
  checker.step(fewer, true, "reordered, one move > skin/2");

  checker.step(fewer, true, "other boxes", cube<dim>(-1., 5.));
  checker.averager.invalidate_neighbour_lists();
  checker.step(fewer, true, "invalidated", cube<dim>(-1., 5.));
  checker.averager.reinit(type, checker.l_c, 0.1);
  checker.step(fewer, true, "after reinit", cube<dim>(-1., 5.));
  // A point the last build never saw (a split point) rebuilds.
  fewer.push_back(fewer.positions[3], 1e-3, 0.5, true, pair_id + 2);
  checker.step(fewer, true, "a new point", cube<dim>(-1., 5.));
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  run<2>(WeightType::bell);
  run<2>(WeightType::gaussian);
  run<3>(WeightType::bell);
  run<3>(WeightType::gaussian);
  return n_failures == 0 ? 0 : 1;
}
