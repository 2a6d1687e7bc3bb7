// CliffDiagnostics on synthetic particle clouds of known geometry:
//  - a vertical cliff that slumped into a triangular pile of 30 and 44
//    degrees (regular and jittered lattices): debris angle, run-out, foot of
//    the scarp, against tolerances derived from the particle spacing;
//  - a rigid block displaced by a known vector: failed area (current and
//    reference, also with the block dilated), scarp position, run-out,
//    and the gap rule;
//  - no motion: no debris, zero run-out and failed area;
//  - the Joss Bay profile seeded on a lattice: profile vs the geometry;
//  - the CSV files and the parameters.

#include <deal.II/base/parameter_handler.h>

#include <scarp/postprocess/cliff_diagnostics.h>

#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <vector>

#include "../scenes/check.h"

using namespace dealii;
using namespace scarp;
using Diagnostics = postprocess::CliffDiagnostics;

namespace
{
  constexpr double s = 0.05; // particle spacing
  constexpr double w = 0.1;  // bin width (two particle columns per bin)
  const Point<2>   nowhere(-1e9, -1e9);

  // Vertical cliff: x in [0, 20), y in [0, 15.5), no notch, no crack.
  scenes::CliffProfile
  block_cliff()
  {
    scenes::CliffProfile::Parameters p;
    p.toe_position     = 20.;
    p.height           = 15.5;
    p.lower_face_angle = 90.;
    p.back_length      = 20.;
    p.notch_depth      = 0.;
    p.crack_depth      = 0.;
    return scenes::CliffProfile(p);
  }


  // The lattice points (i + 1/2) s, (j + 1/2) s of [x0, x1) x [0, 15.5).
  template <typename F>
  void
  for_block_lattice(const double x0, const double x1, const F &f)
  {
    for (int i = 0; (i + 0.5) * s < x1; ++i)
      for (int j = 0; (j + 0.5) * s < 15.5; ++j)
        if ((i + 0.5) * s >= x0)
          f(Point<2>((i + 0.5) * s, (j + 0.5) * s));
  }


  Diagnostics::Particle
  particle(const Point<2> &position, const Point<2> &initial)
  {
    Diagnostics::Particle p;
    p.position         = position;
    p.initial_position = initial;
    p.volume           = s * s;
    p.reference_volume = s * s;
    return p;
  }


  // The block's material beyond x = 17 has gone; a pile with a plane
  // surface y = (x_toe - x) tan(angle) lies against the remaining cliff from
  // x = 17 to x_toe. The removed and the added particles are unpaired
  // (their other position lies outside the profile range), which is all
  // the profile needs.
  void
  check_pile(const double angle, const double x_toe, const double jitter)
  {
    const double                       slope = std::tan(angle * M_PI / 180.);
    std::vector<Diagnostics::Particle> particles;
    for_block_lattice(0., 20., [&](const Point<2> &X) {
      particles.push_back(particle(X[0] < 17. ? X : nowhere, X));
    });
    std::mt19937                           random(42);
    std::uniform_real_distribution<double> shift(-jitter * s, jitter * s);
    for (int i = 0; (i + 0.5) * s < x_toe; ++i)
      for (int j = 0; (j + 0.5) * s < 20.; ++j)
        {
          Point<2> x((i + 0.5) * s, (j + 0.5) * s);
          if (jitter > 0.)
            x += Tensor<1, 2>({shift(random), shift(random)});
          if (x[0] >= 17. && x[1] > 0. && x[1] < (x_toe - x[0]) * slope)
            particles.push_back(particle(x, nowhere));
        }

    Diagnostics::Parameters parameters;
    parameters.bin_width = w;
    const Diagnostics          diagnostics(parameters);
    const scenes::CliffProfile cliff = block_cliff();
    const auto                 profile =
      diagnostics.surface_profile(particles, 0., 0., x_toe + 5.);
    const auto r = diagnostics.analyse(profile, particles, cliff);

    // The initial toe is exact: the last lattice column, 19.975, lies in the
    // bin [19.9, 20).
    CHECK_CLOSE(r.initial_toe, 20., 1e-9);
    // The toe is where the surface exceeds tau = w/2; the highest particle
    // of a column lies up to (1 + jitter) s below the plane, so the toe lies
    // up to (tau + (1 + 2 jitter) s) / slope + w before x_toe, never after.
    const double toe_tolerance = (0.5 * w + (1. + 2. * jitter) * s) / slope + w;
    CHECK(r.debris_toe <= x_toe + 1e-9);
    CHECK(r.debris_toe >= x_toe - toe_tolerance);
    CHECK_CLOSE(r.run_out, x_toe - 20., toe_tolerance);

    // The pile comes out from under the initial surface at the old face.
    CHECK(r.has_debris);
    CHECK_CLOSE(r.scarp_foot, 20., 1e-9);
    CHECK_CLOSE(r.pile_height, (x_toe - 20.) * slope, (1. + 2. * jitter) * s);

    // Angle: the fit residuals r_i (highest particle of the left column of
    // each bin vs the plane at that column) lie in an interval of width
    // d = (1 + 2 jitter) s (+ jitter s in x times the slope). For a
    // least-squares line through n equally spaced points over a length L
    // the slope error is at most (d/2) sum|x_i - mean| / sum (x_i - mean)^2
    // ~ (d/2) (3/L); the angle error is cos^2(angle) times that.
    const double d      = (1. + 2. * jitter) * s + 2. * jitter * s * slope;
    const double length = r.fit_x_end - r.fit_x_begin;
    const double cos_2  = std::pow(std::cos(angle * M_PI / 180.), 2);
    const double angle_tolerance = cos_2 * 1.5 * d / length * 180. / M_PI;
    // For a look with tools/plot_cliff.py.
    Diagnostics::write_profile_csv("pile_" + std::to_string(int(angle)) +
                                     (jitter > 0. ? "_jitter" : "") + ".csv",
                                   profile,
                                   &r);
    CHECK(length > 5.);
    CHECK(r.n_fit_points > 50);
    CHECK_CLOSE(r.debris_angle, angle, angle_tolerance);
    std::cout << "pile " << angle << " deg, jitter " << jitter
              << ": angle = " << r.debris_angle << " (tolerance "
              << angle_tolerance << "), run-out = " << r.run_out
              << " (expected " << x_toe - 20. << " within " << toe_tolerance
              << "), fit over [" << r.fit_x_begin << ", " << r.fit_x_end
              << "], rms " << r.fit_rms_residual << std::endl;
  }
} // namespace


int
main()
{
  check_pile(30., 35., 0.);
  check_pile(44., 30., 0.);
  check_pile(30., 35., 0.25);
  check_pile(44., 30., 0.25);
  check_pile(15., 45., 0.); // the paper's low-residual-strength pile

  const scenes::CliffProfile cliff = block_cliff();

  // No motion: no debris, nothing failed, run-out exactly zero.
  {
    std::vector<Diagnostics::Particle> particles;
    for_block_lattice(0., 20., [&](const Point<2> &X) {
      particles.push_back(particle(X, X));
    });
    Diagnostics diagnostics;
    diagnostics.set_cell_size(w);
    const auto r = diagnostics.analyse(particles, cliff);
    CHECK(!r.has_debris);
    CHECK(r.run_out == 0.);
    CHECK(r.failed_area == 0.);
    CHECK(r.failed_reference_area == 0.);
    CHECK(r.n_failed_particles == 0);
    CHECK(!r.has_scarp);
    CHECK(std::isnan(r.debris_angle));
    CHECK(std::isnan(r.scarp_position));
    CHECK(std::isnan(r.failed_mass_centroid) && std::isnan(r.mass_run_out));
  }

  // Rigid block [17, 20) x [5, 15.5) displaced by (4, -5) onto the beach
  // at [21, 24); a strip [16, 17) moved by 0.4 < 0.5 does not count.
  {
    std::vector<Diagnostics::Particle> particles;
    for_block_lattice(0., 20., [&](const Point<2> &X) {
      Point<2> x = X;
      if (X[0] >= 17. && X[1] >= 5.)
        x += Tensor<1, 2>({4., -5.});
      else if (X[0] >= 16. && X[0] < 17.)
        x += Tensor<1, 2>({0.4, 0.});
      particles.push_back(particle(x, X));
    });
    Diagnostics::Parameters parameters;
    parameters.bin_width   = w;
    parameters.maximum_gap = 1.5; // bridges the 1 m gap to the block
    const auto r           = Diagnostics(parameters).analyse(particles, cliff);
    // 60 columns x 210 rows of particles, 0.0025 m^2 each.
    CHECK(r.n_failed_particles == 60 * 210);
    CHECK_CLOSE(r.failed_area, 3. * 10.5, 1e-9);
    // Scarp: most landward failed particle that started within 2 bins of
    // the top; the first column of the block, half a spacing from 17.
    CHECK(r.has_scarp);
    CHECK_CLOSE(r.scarp_position, 17. + s / 2, 1e-9);
    CHECK_CLOSE(r.scarp_retreat, 3. - s / 2, 1e-9);
    // The block's seaward column moved from 19.975 to 23.975.
    CHECK_CLOSE(r.debris_toe, 24., 1e-9);
    CHECK_CLOSE(r.run_out, 4., 1e-9);
    CHECK(r.has_debris);
    CHECK_CLOSE(r.scarp_foot, 21., 1e-9);
    CHECK_CLOSE(r.pile_height, 10.5 - s / 2, 1e-9);
    // Flat top, vertical sides: no flank to fit.
    CHECK(r.n_fit_points < 2);
    CHECK(std::isnan(r.debris_angle));
    // Where the failed mass lies: 60 columns of equal mass from 21 + s/2
    // to 24 - s/2, centroid 22.5; 95 % of it in the first 57 columns, 99 %
    // (59.4 columns) needs the 60th. Tolerance: the sums' round-off.
    CHECK_CLOSE(r.failed_mass_centroid, 22.5, 1e-9);
    CHECK_CLOSE(r.failed_mass_x95, 21. + s / 2 + 56 * s, 1e-9);
    CHECK_CLOSE(r.failed_mass_x99, 24. - s / 2, 1e-9);
    CHECK_CLOSE(r.mass_run_out, 4. - s / 2, 1e-9);

    // With the default gap (4 bins) the block is not part of the pile: the
    // toe stays at the remaining cliff.
    parameters.maximum_gap = 0.;
    const auto r_default   = Diagnostics(parameters).analyse(particles, cliff);
    CHECK_CLOSE(r_default.debris_toe, 20., 1e-9);
    CHECK_CLOSE(r_default.run_out, 0., 1e-9);
    CHECK_CLOSE(r_default.failed_area, 3. * 10.5, 1e-9);
    CHECK_CLOSE(r_default.failed_reference_area, 3. * 10.5, 1e-9);

    // The block dilated to twice its volume (as fully damaged debris
    // does): the failed area doubles, the reference area does not; the
    // points left behind count in neither.
    for (auto &p : particles)
      if ((p.position - p.initial_position).norm() > 0.5)
        p.volume *= 2.;
    const auto r_dilated = Diagnostics(parameters).analyse(particles, cliff);
    CHECK_CLOSE(r_dilated.failed_area, 2. * 3. * 10.5, 1e-9);
    CHECK_CLOSE(r_dilated.failed_reference_area, 3. * 10.5, 1e-9);
    // The mass measures rest on the reference volumes: dilation leaves
    // them as they were (bit for bit).
    CHECK(r_dilated.failed_mass_centroid == r_default.failed_mass_centroid);
    CHECK(r_dilated.failed_mass_x99 == r_default.failed_mass_x99);

    // One light point thrown 10 m ahead moves the profile's toe, not the
    // mass's: 1e-6 of the block's mass 11.55 m beyond its centroid shifts
    // the centroid by 11.55e-6 m (to 1e-11).
    Diagnostics::Particle thrown = particles.front();
    thrown.initial_position      = Point<2>(19.975, 15.475);
    thrown.position              = Point<2>(34.05, 0.5);
    thrown.reference_volume      = 1e-6 * 3. * 10.5;
    particles.push_back(thrown);
    parameters.maximum_gap = 20.;
    const auto r_thrown    = Diagnostics(parameters).analyse(particles, cliff);
    CHECK_CLOSE(r_thrown.run_out, 14.1, 1e-9); // the bin [34, 34.1)
    CHECK_CLOSE(r_thrown.failed_mass_x99, 24. - s / 2, 1e-9);
    CHECK_CLOSE(r_thrown.failed_mass_centroid, 22.5 + 11.55e-6, 1e-9);
  }

  // The Joss Bay profile on a lattice of 2 x 2 particles per 0.045 m cell.
  {
    const scenes::CliffProfile         joss_bay;
    const double                       h = 0.045, spacing = h / 2;
    std::vector<Diagnostics::Particle> particles;
    const auto bb = joss_bay.body().bounding_box().get_boundary_points();
    for (double x = bb.first[0] + spacing / 2; x < bb.second[0]; x += spacing)
      for (double y = spacing / 2; y < bb.second[1]; y += spacing)
        if (joss_bay.body().contains(Point<2>(x, y)))
          particles.push_back(particle(Point<2>(x, y), Point<2>(x, y)));
    Diagnostics diagnostics;
    diagnostics.set_cell_size(h);
    const auto profile = diagnostics.surface_profile(particles, joss_bay);
    const auto r       = diagnostics.analyse(profile, particles, joss_bay);
    CHECK(!r.has_debris);
    CHECK(r.run_out == 0.);
    // The particle toe is the most seaward material, the top of the notch,
    // to within one bin.
    CHECK_CLOSE(r.initial_toe, joss_bay.notch_top()[0], h);
    // Profile vs geometry: the highest particle of a bin lies below the
    // surface at the bin's landward edge by less than one spacing, and the
    // face rises by h tan(78) across a bin.
    const double face_rise = h * std::tan(78. * M_PI / 180.);
    unsigned int n_checked = 0;
    for (unsigned int i = 0; i < profile.n_bins(); ++i)
      {
        const double x_left = profile.left_edge(i);
        // Seaward of the notch top there is no material under the face.
        if (x_left < joss_bay.back_position() ||
            x_left > joss_bay.notch_top()[0])
          continue;
        const double expected = joss_bay.surface_height(x_left);
        CHECK(profile.y_initial[i] <= expected + 1e-9);
        CHECK(profile.y_initial[i] >= expected - spacing - face_rise);
        ++n_checked;
      }
    CHECK(n_checked > 680);
    // Behind the crest, the top row of particles.
    CHECK_CLOSE(profile.y_initial[profile.bin_of(10.)],
                15.5 - spacing / 2,
                spacing / 2);

    // CSV files: header, one line per bin, the result as comments.
    Diagnostics::write_profile_csv("joss_bay_profile.csv", profile, &r);
    std::ifstream in("joss_bay_profile.csv");
    std::string   line;
    unsigned int  n_comments = 0, n_lines = 0;
    bool          header = false;
    while (std::getline(in, line))
      if (line.rfind("#", 0) == 0)
        ++n_comments;
      else if (line == "x,y_initial,y_final")
        header = true;
      else
        ++n_lines;
    CHECK(header);
    CHECK(n_comments == 22);
    CHECK(n_lines == profile.n_bins());
    Diagnostics::write_particles_csv("joss_bay_particles.csv", particles);
    std::ifstream particles_in("joss_bay_particles.csv");
    std::getline(particles_in, line);
    CHECK(line == "x,y,damage,x0,y0,volume");

    // The history: a header once, then one row per call; numbers exact in
    // binary read back exactly, and a quantity without a value (no debris
    // angle before the cliff fails) as nan.
    std::remove("history.csv");
    Diagnostics::Result settled;
    settled.debris_angle          = 33.25;
    settled.run_out               = 4.5;
    settled.debris_toe            = 30.125;
    settled.failed_area           = 58.375;
    settled.failed_reference_area = 46.8125;
    settled.n_failed_particles    = 1234;
    settled.scarp_position        = 21.5;
    settled.scarp_retreat         = 4.25;
    settled.failed_mass_centroid  = 27.5;
    settled.failed_mass_x95       = 29.75;
    settled.failed_mass_x99       = 30.;
    settled.mass_run_out          = 4.375;
    Diagnostics::append_history_row("history.csv", 1.5, 20., 3., r);
    Diagnostics::append_history_row("history.csv", 2.5, 10., 2., settled);
    std::ifstream history("history.csv");
    std::getline(history, line);
    CHECK(line == "time,kinetic_energy,max_speed,debris_angle,run_out,"
                  "debris_toe,failed_area,failed_reference_area,"
                  "n_failed_particles,scarp_position,scarp_retreat,"
                  "failed_mass_centroid,failed_mass_x95,failed_mass_x99,"
                  "mass_run_out");
    std::vector<std::vector<double>> rows;
    while (std::getline(history, line))
      {
        std::vector<double> row;
        std::istringstream  fields(line);
        std::string         field;
        while (std::getline(fields, field, ','))
          row.push_back(std::stod(field));
        rows.push_back(row);
      }
    CHECK(rows.size() == 2);
    CHECK(rows[0].size() == 15 && rows[1].size() == 15);
    CHECK(std::isnan(rows[0][3]));
    CHECK(rows[0][6] == 0.);
    const std::vector<double> expected = {2.5,
                                          10.,
                                          2.,
                                          33.25,
                                          4.5,
                                          30.125,
                                          58.375,
                                          46.8125,
                                          1234.,
                                          21.5,
                                          4.25,
                                          27.5,
                                          29.75,
                                          30.,
                                          4.375};
    for (unsigned int k = 0; k < expected.size(); ++k)
      CHECK(rows[1][k] == expected[k]);

    // A history begun by a version with other columns (a run continued
    // from an older checkpoint): rows follow the file's header, a column
    // unknown here is nan.
    {
      std::ofstream older("history_older.csv");
      older << "time,run_out,no_such_column,scarp_retreat\n1,2,3,4\n";
    }
    Diagnostics::append_history_row("history_older.csv", 2.5, 10., 2., settled);
    std::ifstream            older("history_older.csv");
    std::vector<std::string> older_lines;
    while (std::getline(older, line))
      older_lines.push_back(line);
    CHECK(older_lines.size() == 3);
    CHECK(older_lines[0] == "time,run_out,no_such_column,scarp_retreat");
    CHECK(older_lines[2] == "2.5,4.5,nan,4.25");
  }

  // Parameters.
  {
    ParameterHandler prm;
    prm.enter_subsection("Cliff diagnostics");
    Diagnostics::declare_parameters(prm);
    prm.leave_subsection();
    prm.parse_input_from_string("subsection Cliff diagnostics\n"
                                "  set Bin width = 0.2\n"
                                "  set Fit upper fraction = 0.8\n"
                                "end\n");
    prm.enter_subsection("Cliff diagnostics");
    Diagnostics diagnostics;
    diagnostics.parse_parameters(prm);
    CHECK_CLOSE(diagnostics.bin_width(), 0.2, 1e-14);
    prm.set("Bin width", "0");
    diagnostics.parse_parameters(prm);
    CHECK_THROWS_WITH(diagnostics.bin_width(), "set_cell_size");
    prm.set("Fit lower fraction", "0.85");
    CHECK_THROWS_WITH(diagnostics.parse_parameters(prm),
                      "Fit lower fraction (0.85) must be smaller");
    prm.leave_subsection();
  }

  return scenes_test::finish();
}
