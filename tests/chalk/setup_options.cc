// Scene options of the paper's set-up (doc/joss_bay.md, "Set up as the
// paper and its authors did"), in whole scenes:
//
// ybar_output: the non-local driver Ybar is a point property
//   (nonlocal_driver) written to the VTU next to Y and kappa. A block under
//   a uniform uniaxial tension sigma = 10 kPa (< sigma_f, no damage), held
//   by fixed faces, without gravity, is a constant field: Y = sigma at every
//   point (Y of uniaxial tension is the stress), and the renormalised average
//   of a constant is that constant, also at the edges.
// crack_band_base_layer: a small cliff with a pre-damage band and a base
//   layer: every point's initial damage is the closed form exp(-(r/w)^4)
//   (r <= w, else 0) with its history kappa consistent (d(kappa) = d); the
//   points fill the slab under the beach; a layer that does not fit in the
//   mesh is refused with a message naming the entries.
// setup_passes: the band refines (damage criterion) in a loading stage;
//   with Mesh/Refinement/Set-up passes the bodies are seeded anew on the
//   refined mesh: every point carries the lattice volume of its own cell and
//   the closed-form damage at its own position, nothing is split in the run
//   proper. Without them the split points inherit their parent's damage
//   (the check fails by > 0.05). On 2 ranks the same, and the same points
//   and cells as a serial copy.

#include <deal.II/base/mpi.h>

#include "chalk_tools.h"

#include <filesystem>
#include <fstream>
#include <iterator>

using namespace scarp_chalk_test;

namespace
{
  constexpr int dim = 2;

  unsigned int
  state_index(const materials::Material &m, const std::string &name)
  {
    const auto names = m.state_variable_names();
    return std::find(names.begin(), names.end(), name) - names.begin();
  }


  void
  ybar_output()
  {
    const double      sigma = 1e4;
    const std::string text =
      "set Dimension = 2\nset Materials = chalk\nset Bodies = block\n"
      "set Stages = run\nset Output directory = output_ybar\n" +
      mesh_text({0, 0}, {2, 1}, 0.125, {"fixed", "fixed", "fixed", "fixed"}) +
      ChalkText().text("chalk") +
      box_body_text("block", "chalk", {0, 0, 2, 1}, 2) +
      "subsection Body block\n  subsection Initial stress\n"
      "    set Function expression = " +
      num(sigma) + "; 0; 0; 0; 0; 0\n  end\nend\n" + stage_text("run", 3e-4) +
      "subsection Physics\n  set Gravity = 0, 0\nend\n" +
      "subsection Output\n  set Interval = 1e-4\nend\n";
    auto sim = make_scene<dim>(text, MPI_COMM_WORLD, "ybar");
    sim->run();

    const auto        &m    = sim->material(0);
    const unsigned int iY   = state_index(m, "damage_driver");
    const unsigned int iBar = state_index(m, "nonlocal_driver");
    const unsigned int s    = sim->property_layout().state;
    check(iBar < m.n_state_variables(), "chalk has a nonlocal_driver state");
    // The block does not move (uniform stress, fixed faces, no gravity):
    // the interior node forces cancel up to round-off, so Y stays sigma to
    // round-off in the stress. Measured: |Y - sigma| 4.7e-12 sigma,
    // |Ybar - Y| 2.2e-15 sigma; 1e-9 sigma bounds both, far below the
    // 10 kPa a missing Ybar would be off by.
    const double dY = scarp_test::max_over_points<dim>(
      *sim, [&](const double *p, const Point<dim> &) {
        return std::abs(p[s + iY] - sigma);
      });
    const double dBar = scarp_test::max_over_points<dim>(
      *sim, [&](const double *p, const Point<dim> &) {
        return std::abs(p[s + iBar] - p[s + iY]);
      });
    out() << "  max |Y - sigma| = " << dY << " Pa, max |Ybar - Y| = " << dBar
          << " Pa" << std::endl;
    check(dY <= 1e-9 * sigma, "Y = sigma (uniaxial tension)");
    check(dBar <= 1e-9 * sigma, "Ybar = Y in a constant field");

    // The VTU carries the field by name.
    bool found = false;
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      for (const auto &f : std::filesystem::directory_iterator("output_ybar"))
        if (f.path().extension() == ".vtu")
          {
            std::ifstream     in(f.path());
            const std::string content((std::istreambuf_iterator<char>(in)),
                                      std::istreambuf_iterator<char>());
            found =
              found ||
              (content.find("Name=\"nonlocal_driver\"") != std::string::npos &&
               content.find("Name=\"damage_driver\"") != std::string::npos &&
               content.find("Name=\"kappa\"") != std::string::npos);
          }
    check(Utilities::MPI::max(found ? 1 : 0, MPI_COMM_WORLD) == 1,
          "particles VTU has nonlocal_driver next to damage_driver, kappa");
  }


  std::string
  cliff_scene(const double mesh_bottom)
  {
    return "set Dimension = 2\nset Materials = chalk\nset Bodies = cliff\n"
           "set Stages = run\nset Output directory = output_band\n" +
           mesh_text({0, mesh_bottom},
                     {10, 5},
                     0.125,
                     {"slip", "free", "fixed", "free"}) +
           ChalkText().text("chalk") +
           "subsection Body cliff\n  set Material = chalk\n"
           "  set Particles per cell = 2\n  set Shape = cliff\n"
           "  subsection Cliff\n    set Toe position = 6\n"
           "    set Height = 4\n    set Upper face height = 1.5\n"
           "    set Back length = 4\n    set Notch depth = 0\n"
           "    set Crack offset = 1\n    set Crack depth = 2\n"
           "    set Crack band width factor = 2.6457513110645906\n"
           "    set Base layer thickness = 1\n"
           "    set Base layer extent = 3\n  end\nend\n" +
           stage_text("run", 1e-4);
  }


  /// The initial damage of cliff_scene() at @p x in closed form: crest =
  /// knee x = 6 - 2.5 cot 78, crack centre line 1 m behind it from y = 2
  /// to 4, d = exp(-(r/w)^4) within w = sqrt(7) l_c of it; d > 1 - 1e-6 is
  /// rounded to 1 by the model (as update_damage does).
  double
  band_damage(const Point<dim> &x)
  {
    const double x_k = 6. - 2.5 / std::tan(78. * M_PI / 180.) - 1.;
    const double w   = std::sqrt(7.) * 0.18;
    const double y   = std::clamp(x[1], 2., 4.);
    const double r   = std::hypot(x[0] - x_k, x[1] - y);
    const double d   = r > w ? 0. : std::exp(-std::pow(r / w, 4));
    return d > 1. - 1e-6 ? 1. : d;
  }


  void
  crack_band_base_layer()
  {
    auto        sim = make_scene<dim>(cliff_scene(-1), MPI_COMM_WORLD, "band");
    const auto *chalk =
      dynamic_cast<const materials::Chalk *>(&sim->material(0));
    check(chalk != nullptr, "the body is chalk");
    const unsigned int s = sim->property_layout().state;
    const unsigned int v = sim->property_layout().reference_volume;

    // d: the same few flops in another order, round-off 1e-15.
    const double dd = scarp_test::max_over_points<dim>(
      *sim, [&](const double *p, const Point<dim> &x) {
        return std::abs(p[s + materials::Chalk::damage_variable] -
                        band_damage(x));
      });
    // kappa: bisection to round-off; d(kappa) then agrees to ~1e-15 times
    // the slope kappa dd/dkappa (< 10 here): 1e-12 is ample.
    const double dk = scarp_test::max_over_points<dim>(
      *sim, [&](const double *p, const Point<dim> &) {
        const double d = p[s + materials::Chalk::damage_variable];
        if (d == 0.)
          return p[s + materials::Chalk::kappa];
        const double k = p[s + materials::Chalk::kappa];
        return std::abs(chalk->damage_from_kappa(k) - std::min(d, 1. - 1e-6));
      });
    const double n_band = scarp_test::sum_over_points<dim>(
      *sim, [&](const double *p, const Point<dim> &) {
        return p[s + materials::Chalk::damage_variable] > 0. ? 1. : 0.;
      });
    const double d_max = scarp_test::max_over_points<dim>(
      *sim, [&](const double *p, const Point<dim> &) {
        return p[s + materials::Chalk::damage_variable];
      });
    out() << "  band points " << n_band << ", max d " << d_max
          << ", max |d - closed form| " << dd << ", max |d(kappa) - d| " << dk
          << std::endl;
    check(n_band > 100 && d_max > 0.99, "the band is seeded");
    check(dd <= 1e-14, "initial damage = exp(-(r/w)^4), 0 beyond w");
    check(dk <= 1e-12, "kappa consistent with d (0 where d = 0)");

    // Area: the body with its 1 m slab from the back (x = 1.469) to 3 m in
    // front of the toe. Each point carries (h/2)^2 of a lattice of spacing
    // h/2, so the sum misses at most half a spacing along the perimeter.
    const double x_back = 6. - 2.5 / std::tan(78. * M_PI / 180.) - 4.;
    const double area   = 4. * 4. +
                        0.5 * 2.5 * 2.5 / std::tan(78. * M_PI / 180.) +
                        1. * (9. - x_back);
    const double perimeter = 2. * (9. - x_back) + 2. * 5.;
    const double volume    = scarp_test::sum_over_points<dim>(
      *sim, [&](const double *p, const Point<dim> &) { return p[v]; });
    const double y_min = -scarp_test::max_over_points<dim>(
      *sim, [&](const double *, const Point<dim> &x) { return -x[1]; });
    out() << "  volume " << volume << " m^2, closed-form area " << area
          << ", lowest point y = " << y_min << std::endl;
    check(std::abs(volume - area) <= perimeter * 0.125 / 4.,
          "points fill the body with its base layer");
    check(y_min < -1. + 0.125 / 2. && y_min > -1., "points reach y = -1");

    // The same layer in a mesh that starts at the beach level is refused.
    const std::string message =
      refusal_message<dim>(cliff_scene(0), MPI_COMM_WORLD, "band_outside");
    out() << "  message: " << message << std::endl;
    check(message.find("Base layer thickness") != std::string::npos &&
            message.find("Mesh/Lower corner") != std::string::npos,
          "a layer outside the mesh is refused, naming the entries");
  }


  /// @p tag names the output directory; @p serial_copy: a copy on
  /// MPI_COMM_SELF of every rank, whose directory carries the rank.
  std::string
  setup_pass_scene(const unsigned int passes,
                   const std::string &tag,
                   const bool         serial_copy = false)
  {
    const std::string directory =
      "output_" + tag +
      (serial_copy ? "_" + std::to_string(
                             Utilities::MPI::this_mpi_process(MPI_COMM_WORLD))
                   : "");
    std::string text = cliff_scene(-1);
    // Coarse cells 0.25 m, one level: the refined cells are those of
    // crack_band_base_layer. No gravity: nothing moves, so the closed form
    // holds at the points' positions after the stages.
    const auto replace = [&](const std::string &a, const std::string &b) {
      const auto k = text.find(a);
      AssertThrow(k != std::string::npos, ExcMessage("scene text: " + a));
      text.replace(k, a.size(), b);
    };
    replace("set Stages = run", "set Stages = load, hold");
    replace("output_band", directory);
    replace("set Cell size = 0.125", "set Cell size = 0.25");
    replace(stage_text("run", 1e-4),
            stage_text("load", 2e-3, false, false) +
              stage_text("hold", 3e-3, false, false));
    return text +
           "subsection Mesh\n  subsection Refinement\n"
           "    set Adaptive refinement = true\n    set Maximum level = 1\n"
           "    set Interval = 5\n    set Set-up passes = " +
           std::to_string(passes) +
           "\n  end\nend\n"
           "subsection Physics\n  set Gravity = 0, 0\nend\n"
           "subsection Output\n  set Interval = 0\nend\n";
  }


  /// Largest |d - exp(-(r/w)^4)| over the points of the small cliff (its
  /// crack 1 m behind the crest, from y = 2 to 4; w = sqrt(7) l_c), and
  /// largest |V0 - (h_K/2)^2| / (h_K/2)^2 with h_K the point's cell.
  std::pair<double, double>
  seeding_errors(const simulation::Simulation<dim> &sim)
  {
    const unsigned int s  = sim.property_layout().state;
    const unsigned int v  = sim.property_layout().reference_volume;
    double             dd = 0, dv = 0;
    for (const auto &particle : sim.particle_handler())
      {
        const double *p   = particle.get_properties().data();
        dd                = std::max(dd,
                      std::abs(p[s + materials::Chalk::damage_variable] -
                               band_damage(particle.get_location())));
        const auto   cell = particle.get_surrounding_cell();
        const double h    = cell->vertex(1)[0] - cell->vertex(0)[0];
        dv = std::max(dv, std::abs(p[v] - 0.25 * h * h) / (0.25 * h * h));
      }
    const MPI_Comm comm = scarp_test::communicator_of(sim);
    return {Utilities::MPI::max(dd, comm), Utilities::MPI::max(dv, comm)};
  }


  void
  setup_passes()
  {
    auto sim =
      make_scene<dim>(setup_pass_scene(3, "passes"), MPI_COMM_WORLD, "passes");
    sim->run();
    const auto &counters = sim->loop_state().counters;
    const auto [dd, dv]  = seeding_errors(*sim);
    const double n_cells =
      sim->background_grid().triangulation().n_global_active_cells();
    const double n_points = sim->measure().n_points;
    out() << "  set-up passes " << counters.setup_passes << " ("
          << counters.setup_steps
          << " steps), run proper: " << counters.refinement_passes
          << " refinement passes, " << counters.points_split
          << " points split; " << std::setprecision(12) << n_cells << " cells, "
          << n_points << " points; max |d - closed form| " << dd
          << ", max |V0 / (h_K/2)^2 - 1| " << dv << std::endl;
    // Pass 1 refines the band's cells to the maximum level, pass 2 finds
    // nothing more to refine and stops the passes; the run proper repeats
    // pass 2 on the same points, so it refines and splits nothing.
    check(counters.setup_passes == 2 && counters.setup_steps > 0,
          "two set-up passes (the second refines nothing)");
    check(n_cells > 24. * 40., "the mesh refined around the band");
    check(counters.refinement_passes == 0 && counters.points_split == 0,
          "the run proper refines and splits nothing");
    // Lattice volumes are (h/2)^2 exactly in binary for h = 0.25, 0.125;
    // the damage is the same few flops in another order (1e-15).
    check(dv <= 1e-14, "every point carries the lattice volume of its cell");
    check(dd <= 1e-14, "initial damage = exp(-(r/w)^4) at every point");

    // Without the passes the band cells refine in the run proper and the
    // split points keep their parent's damage: the check above fails.
    auto plain =
      make_scene<dim>(setup_pass_scene(0, "plain"), MPI_COMM_WORLD, "plain");
    plain->run();
    const auto [dd0, dv0] = seeding_errors(*plain);
    out() << "  without set-up passes: "
          << plain->loop_state().counters.points_split
          << " points split; max |d - closed form| " << dd0 << std::endl;
    check(plain->loop_state().counters.points_split > 0 && dd0 > 0.05,
          "without the passes split points inherit their parent's damage");

    // On 2 ranks the mesh and the seeding are those of a serial run.
    if (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
      {
        auto serial =
          make_scene<dim>(setup_pass_scene(3, "passes_serial", true),
                          MPI_COMM_SELF,
                          "passes_serial");
        serial->run();
        const double n_cells_1 =
          serial->background_grid().triangulation().n_global_active_cells();
        const double n_points_1 = serial->measure().n_points;
        out() << "  serial copy: " << std::setprecision(12) << n_cells_1
              << " cells, " << n_points_1 << " points" << std::endl;
        check(n_cells_1 == n_cells && n_points_1 == n_points,
              "the same cells and points as a serial run");
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  return scarp_test::run_cases(argc,
                               argv,
                               {{"ybar_output", ybar_output},
                                {"crack_band_base_layer",
                                 crack_band_base_layer},
                                {"setup_passes", setup_passes}});
}
