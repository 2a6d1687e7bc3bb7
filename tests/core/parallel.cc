// Parallel = serial (architecture: "a run on N ranks gives the same physics
// as on one, to round-off"): the two disks of Sulsky et al. through their
// impact, on all ranks of MPI_COMM_WORLD and, on every rank, as a serial
// copy on MPI_COMM_SELF. Each rank compares its own points of the parallel
// run with the serial copy, matched by their reference positions.

#include "core_tools.h"

#include <map>

using namespace scarp_test;

namespace
{
  constexpr int dim = 2;

  /// @p transfer_extra: more Transfer entries (F-bar).
  std::string
  scene(const std::string &transfer_extra = "")
  {
    return scene_header(dim, "run", "a, b") +
           material_text("linear elastic", 1000, 0.3, 1000) +
           mesh_text({-0.23, -0.23},
                     {1.27, 1.27},
                     0.05,
                     {"free", "free", "free", "free"}) +
           body_text("a", ball_shape({0.2, 0.2}, 0.2), 2, "0.1; 0.1") +
           body_text("b", ball_shape({0.8, 0.8}, 0.2), 2, "-0.1; -0.1") +
           run_text(
             {0, -0.05}, 0.5, 2.5, "FLIP", "MUSL", 1e30, "", transfer_extra);
  }

  void
  compare(const std::string &transfer_extra)
  {
    auto parallel = make_scene<dim>(scene(transfer_extra), MPI_COMM_WORLD);
    auto serial   = make_scene<dim>(scene(transfer_extra), MPI_COMM_SELF);
    const unsigned int n_ranks =
      Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
    const auto local = Utilities::MPI::sum(
      double(parallel->particle_handler().n_locally_owned_particles() > 0),
      MPI_COMM_WORLD);
    out() << "  " << n_ranks << " ranks, " << local << " of them own points"
          << std::endl;
    for (const double t : {1.0, 2.5})
      {
        parallel->run_until(t);
        serial->run_until(t);
        const auto &layout = serial->property_layout();
        std::map<std::pair<long, long>, const double *> by_reference;
        std::map<std::pair<long, long>, Point<dim>>     location;
        const auto key = [&](const double *p) {
          return std::make_pair(std::lround(p[layout.reference_position] * 1e6),
                                std::lround(p[layout.reference_position + 1] *
                                            1e6));
        };
        for (const auto &particle : serial->particle_handler())
          {
            by_reference[key(particle.get_properties().data())] =
              particle.get_properties().data();
            location[key(particle.get_properties().data())] =
              particle.get_location();
          }
        double       dx = 0, dv = 0, ds = 0, s_max = 0, v_max = 0;
        unsigned int missing = 0, n = 0;
        for (const auto &particle : parallel->particle_handler())
          {
            const double *p = particle.get_properties().data();
            const auto    k = key(p);
            const auto    q = by_reference.find(k);
            if (q == by_reference.end())
              {
                ++missing;
                continue;
              }
            ++n;
            dx = std::max(dx, particle.get_location().distance(location[k]));
            dv = std::max(dv,
                          (layout.get_vector(p, layout.velocity) -
                           layout.get_vector(q->second, layout.velocity))
                            .norm());
            ds = std::max(ds,
                          (layout.get_stress(p, layout.stress) -
                           layout.get_stress(q->second, layout.stress))
                            .norm());
            s_max =
              std::max(s_max,
                       layout.get_stress(q->second, layout.stress).norm());
            v_max =
              std::max(v_max,
                       layout.get_vector(q->second, layout.velocity).norm());
          }
        dx      = Utilities::MPI::max(dx, MPI_COMM_WORLD);
        dv      = Utilities::MPI::max(dv, MPI_COMM_WORLD);
        ds      = Utilities::MPI::max(ds, MPI_COMM_WORLD);
        s_max   = Utilities::MPI::max(s_max, MPI_COMM_WORLD);
        v_max   = Utilities::MPI::max(v_max, MPI_COMM_WORLD);
        missing = Utilities::MPI::sum(missing, MPI_COMM_WORLD);
        n       = Utilities::MPI::sum(n, MPI_COMM_WORLD);
        out() << "  t = " << t << ": " << n
              << " points matched, max |dx| = " << dx << " m, max |dv| = " << dv
              << " (of " << v_max << "), max |dsigma| = " << ds << " (of "
              << s_max << ")" << std::endl;
        check(missing == 0 && n == serial->measure().n_points,
              "every point of the parallel run has its serial twin");
        // The ranks add the same nodal contributions in another order
        // (compress(add) of partial sums): eps relative per step, carried
        // by a stable elastic evolution over ~150 steps, through the impact.
        check(dx < 1e-12, "positions equal to 1e-12 m");
        check(dv < 1e-12 * v_max, "velocities equal to 1e-12 relative");
        check(ds <= 1e-10 * s_max, "stresses equal to 1e-10 relative");
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  // compare_fbar: the same with F-bar, whose cell averages need all points
  // of a cell on one rank (they are: a cell's points live on its owner).
  return run_cases(argc,
                   argv,
                   {{"compare", [] { compare(""); }},
                    {"compare_fbar",
                     [] { compare("  set Volumetric averaging = F-bar\n"); }}});
}
