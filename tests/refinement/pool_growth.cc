// The growth of the particle pool in steps of 1/16 (particles/pool_growth.h).
//
// deal.II's PropertyPool takes each new slot with a resize by one, so its
// arrays double when full; PoolGrowth::reserve(), called before a batch of
// insertions, makes room for the whole batch on a ladder of sizes 1/16
// apart. Checked here:
// - the ladder: rung(n) >= n, at most 1/16 (plus one for the integer
//   division) above n beyond its first rung of 1024, and rung(rung(n)) =
//   rung(n), so that a capacity reserved before is not reallocated by a
//   later request for a little more;
// - a batch reserved for inserts without moving the pool's storage: the
//   properties of the first point keep their address through the batch
//   (without the reserve the pool, full at the start, would reallocate on
//   the first insert: checked too, so the test can tell the two apart);
// - the reserve takes the pool's free slots into account: a batch that
//   fits into them reserves nothing;
// - (1 and 2 ranks) after the set-up's load balance the pool holds each
//   rank's points in the order of the walk over its cells.
#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/particles/particle_handler.h>

#include <scarp/particles/pool_growth.h>

#include "../core/core_tools.h"

#include <vector>

namespace
{
  using namespace scarp_test;
  using scarp::particles::PoolGrowth;

  void
  ladder()
  {
    bool        bounded = true, idempotent = true, monotone = true;
    std::size_t previous = 0;
    for (std::size_t n = 0; n < 3000000; n += 997)
      {
        const std::size_t r = PoolGrowth::rung(n);
        // The ladder's step is size/16, rounded down: the rung above n
        // exceeds it by at most n/16 + 1.
        bounded =
          bounded && r >= n && r <= std::max<std::size_t>(1024, n + n / 16 + 1);
        idempotent = idempotent && PoolGrowth::rung(r) == r;
        monotone   = monotone && r >= previous;
        previous   = r;
      }
    check(bounded, "rung(n) >= n and at most n + n/16 + 1 (or 1024)");
    check(idempotent, "rung(rung(n)) = rung(n)");
    check(monotone, "rung is monotone");
  }

  void
  batch()
  {
    parallel::distributed::Triangulation<2> tria(MPI_COMM_WORLD);
    GridGenerator::hyper_cube(tria);
    const MappingQ1<2>            mapping;
    Particles::ParticleHandler<2> particles(tria, mapping, 2);
    const auto                    cell       = tria.begin_active();
    std::vector<double>           properties = {1., 2.};
    types::particle_index         id         = 0;
    const auto                    insert     = [&](const unsigned int n) {
      for (unsigned int k = 0; k < n; ++k, ++id)
        particles.insert_particle(Point<2>(0.5, 0.5),
                                  Point<2>(0.5, 0.5),
                                  id,
                                  cell,
                                  make_array_view(properties));
    };
    const auto first_properties = [&]() {
      return particles.begin()->get_properties().data();
    };

    // A pool exactly full (1024 slots, all taken): without a reserve the
    // next insert reallocates.
    particles.reserve(1024);
    insert(1024);
    check(particles.get_property_pool().n_slots() == 1024,
          "1024 points fill a pool of 1024 slots");
    const double *before = first_properties();
    insert(1);
    check(first_properties() != before,
          "without PoolGrowth, an insert into a full pool reallocates");

    // A batch of 3000 reserved first: one reallocation at the reserve,
    // none during the batch.
    PoolGrowth::reserve(particles, 3000);
    const double *reserved = first_properties();
    insert(3000);
    check(first_properties() == reserved,
          "a reserved batch of 3000 inserts without moving the pool");

    // Free slots count: remove points, then insert as many again.
    std::vector<Particles::ParticleIterator<2>> to_remove;
    for (auto p = particles.begin(); p != particles.end(); ++p)
      if (p->get_id() % 2 == 1)
        to_remove.push_back(p);
    const std::size_t n_removed = to_remove.size();
    particles.remove_particles(to_remove);
    const std::size_t slots = particles.get_property_pool().n_slots();
    PoolGrowth::reserve(particles, n_removed);
    const double *kept = first_properties();
    insert(n_removed);
    check(particles.get_property_pool().n_slots() == slots &&
            first_properties() == kept,
          "a batch that fits into the free slots reserves nothing");
  }

  // The pool in the order of the points after the set-up's load balance:
  // on 2 ranks the balance moves cells (a cell weighs its points), and
  // deal.II's unpack leaves the points in the pool's slots out of the
  // order of the cells (1 540 of 1 600 here without the sort that
  // follows it), while the transfers walk the points cell by cell; scattered
  // over the pool they made P2G and G2P wait on memory (a 1e6-point column on 2
  // ranks 1.3 times slower, doc/performance/sort_and_refinement.md). The
  // full sort after the balance puts the pool in the order of the particle
  // handler's walk: the slots must be 0, 1, 2, ... in that order, on every
  // rank.
  void
  order_after_balance()
  {
    // A column filling a box of 10 x 40 cells with one empty layer around
    // it (the empty cells weigh less than the full ones, so the balance
    // moves the cut), 4 points per cell.
    const std::string text =
      scene_header(2) + material_text("linear elastic", 1e6, 0.3, 1000) +
      mesh_text({0, 0}, {1.2, 4.2}, 0.1, {"free", "free", "fixed", "free"}) +
      body_text("body", box_shape({0.1, 0, 1.1, 4}), 2, "0; 0") +
      run_text({0, -9.81}, 0.5, 0.01);
    auto         sim  = make_scene<2>(text, MPI_COMM_WORLD, "pool_order");
    unsigned int slot = 0, out_of_order = 0;
    for (const auto &particle : sim->particle_handler_for_initialisation())
      out_of_order += particle.get_local_index() != slot++;
    const unsigned int total =
      Utilities::MPI::sum(out_of_order, MPI_COMM_WORLD);
    out() << "  points out of the pool's order after the set-up: " << total
          << " of " << Utilities::MPI::sum(slot, MPI_COMM_WORLD) << std::endl;
    check(total == 0,
          "after the load balance the pool holds the points in the order "
          "of the walk over the cells");
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1)
    {
      ladder();
      batch();
    }
  order_after_balance();
  return 0;
}
