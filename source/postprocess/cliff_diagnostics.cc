#include <deal.II/base/exceptions.h>
#include <deal.II/base/numbers.h>

#include <scarp/postprocess/cliff_diagnostics.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <utility>

namespace scarp
{
  namespace postprocess
  {
    namespace
    {
      std::string
      number(const double x)
      {
        std::ostringstream s;
        s << std::setprecision(12) << x;
        return s.str();
      }


      // Walk seaward from bin @p start; return the last bin whose height
      // exceeds @p level before more than @p max_gap consecutive bins do not
      // (-1 if none does).
      int
      walk_to_toe(const std::vector<double> &y,
                  const unsigned int         start,
                  const double               level,
                  const unsigned int         max_gap)
      {
        int          last = -1;
        unsigned int gap  = 0;
        for (unsigned int i = start; i < y.size(); ++i)
          if (y[i] > level)
            {
              last = i;
              gap  = 0;
            }
          else if (last >= 0 && ++gap > max_gap)
            break;
        return last;
      }
    } // namespace


    unsigned int
    CliffDiagnostics::Profile::n_bins() const
    {
      return x.size();
    }


    double
    CliffDiagnostics::Profile::left_edge(const unsigned int bin) const
    {
      return x_min + bin * bin_width;
    }


    double
    CliffDiagnostics::Profile::right_edge(const unsigned int bin) const
    {
      return x_min + (bin + 1) * bin_width;
    }


    unsigned int
    CliffDiagnostics::Profile::bin_of(const double x_value) const
    {
      const double b = std::floor((x_value - x_min) / bin_width);
      if (!(b > 0.))
        return 0;
      return std::min<unsigned int>(static_cast<unsigned int>(b), n_bins() - 1);
    }


    CliffDiagnostics::CliffDiagnostics()
      : CliffDiagnostics(Parameters())
    {
    }


    CliffDiagnostics::CliffDiagnostics(const Parameters &p)
      : parameters(p)
    {
    }


    void
    CliffDiagnostics::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Bin width",
                        "0",
                        Patterns::Double(0.),
                        "Width [m] of the bins of the free-surface profile; "
                        "0 = one background cell.");
      prm.declare_entry("Surface threshold",
                        "0",
                        Patterns::Double(0.),
                        "Height [m] above the beach (for the toe) or above "
                        "the initial surface (for the debris) that counts as "
                        "material; 0 = half a bin.");
      prm.declare_entry("Displacement threshold",
                        "0.5",
                        Patterns::Double(0.),
                        "A particle displaced further than this [m] counts "
                        "as failed (failed area, scarp position).");
      prm.declare_entry("Maximum gap",
                        "0",
                        Patterns::Double(0.),
                        "Longest run [m] of bins without material that the "
                        "debris may have and still count as one pile; "
                        "0 = four bins.");
      prm.declare_entry("Fit lower fraction",
                        "0.1",
                        Patterns::Double(0., 1.),
                        "The debris angle fit uses the bins whose height "
                        "above the beach is at least this fraction of the "
                        "pile height (keeps out the rounded toe).");
      prm.declare_entry("Fit upper fraction",
                        "0.9",
                        Patterns::Double(0., 1.),
                        "... and at most this fraction of the pile height "
                        "(keeps out the top where the pile meets the scarp).");
      prm.declare_entry("Top band",
                        "0",
                        Patterns::Double(0.),
                        "The scarp position is taken over the failed "
                        "particles that started within this distance [m] of "
                        "the cliff top; 0 = two bins.");
      prm.declare_entry("Write history",
                        "true",
                        Patterns::Bool(),
                        "Append the diagnostics (debris angle, run-out, "
                        "failed areas, scarp retreat) with the kinetic "
                        "energy to cliff_history.csv at every particle "
                        "output: when they stop changing, the deposit has "
                        "settled whatever the energy criterion says.");
    }


    void
    CliffDiagnostics::parse_parameters(const ParameterHandler &prm)
    {
      Parameters p;
      p.bin_width              = prm.get_double("Bin width");
      p.surface_threshold      = prm.get_double("Surface threshold");
      p.displacement_threshold = prm.get_double("Displacement threshold");
      p.maximum_gap            = prm.get_double("Maximum gap");
      p.fit_lower_fraction     = prm.get_double("Fit lower fraction");
      p.fit_upper_fraction     = prm.get_double("Fit upper fraction");
      p.top_band               = prm.get_double("Top band");
      p.write_history          = prm.get_bool("Write history");
      AssertThrow(p.fit_lower_fraction < p.fit_upper_fraction,
                  ExcMessage("Fit lower fraction (" +
                             number(p.fit_lower_fraction) +
                             ") must be smaller than Fit upper fraction (" +
                             number(p.fit_upper_fraction) + ")."));
      parameters = p;
    }


    void
    CliffDiagnostics::set_cell_size(const double h)
    {
      AssertThrow(h > 0.,
                  ExcMessage("CliffDiagnostics::set_cell_size: the cell size "
                             "must be positive, got " +
                             number(h) + "."));
      cell_size = h;
    }


    double
    CliffDiagnostics::bin_width() const
    {
      if (parameters.bin_width > 0.)
        return parameters.bin_width;
      AssertThrow(cell_size > 0.,
                  ExcMessage("Bin width is 0 (one background cell) but no "
                             "cell size was given: call "
                             "CliffDiagnostics::set_cell_size() first."));
      return cell_size;
    }


    double
    CliffDiagnostics::surface_threshold() const
    {
      return parameters.surface_threshold > 0. ? parameters.surface_threshold
                                               : 0.5 * bin_width();
    }


    unsigned int
    CliffDiagnostics::maximum_gap_bins() const
    {
      if (parameters.maximum_gap > 0.)
        return static_cast<unsigned int>(
          std::ceil(parameters.maximum_gap / bin_width() - 1e-9));
      return 4;
    }


    double
    CliffDiagnostics::top_band() const
    {
      return parameters.top_band > 0. ? parameters.top_band : 2. * bin_width();
    }


    CliffDiagnostics::Profile
    CliffDiagnostics::surface_profile(const std::vector<Particle> &particles,
                                      const scenes::CliffProfile  &cliff) const
    {
      double x_min = cliff.back_position();
      double x_max = cliff.toe()[0];
      for (const Particle &p : particles)
        {
          x_min = std::min({x_min, p.position[0], p.initial_position[0]});
          x_max = std::max({x_max, p.position[0], p.initial_position[0]});
        }
      // One more bin so that the most seaward particle falls inside [.., ..)
      // and the profile ends on the beach.
      return surface_profile(particles,
                             cliff.get_parameters().beach_level,
                             x_min,
                             x_max + bin_width());
    }


    CliffDiagnostics::Profile
    CliffDiagnostics::surface_profile(const std::vector<Particle> &particles,
                                      const double                 beach_level,
                                      const double                 x_min,
                                      const double                 x_max) const
    {
      const double w = bin_width();
      AssertThrow(x_max > x_min,
                  ExcMessage("CliffDiagnostics::surface_profile: empty x "
                             "range [" +
                             number(x_min) + ", " + number(x_max) + ")."));
      // Bins keep the exact width (aligned at x_min); the last one may
      // reach past x_max.
      const unsigned int n = std::max<unsigned int>(
        1, static_cast<unsigned int>(std::ceil((x_max - x_min) / w - 1e-9)));

      Profile profile;
      profile.beach_level = beach_level;
      profile.x_min       = x_min;
      profile.bin_width   = w;
      profile.x.resize(n);
      for (unsigned int i = 0; i < n; ++i)
        profile.x[i] = x_min + (i + 0.5) * w;
      const double lowest = -std::numeric_limits<double>::infinity();
      profile.y_initial.assign(n, lowest);
      profile.y_final.assign(n, lowest);

      const auto add = [&](const Point<2> &p, std::vector<double> &y) {
        if (!(p[0] >= x_min && p[0] < x_min + n * w))
          return;
        const unsigned int bin = profile.bin_of(p[0]);
        y[bin]                 = std::max(y[bin], p[1]);
      };
      for (const Particle &p : particles)
        {
          add(p.initial_position, profile.y_initial);
          add(p.position, profile.y_final);
        }
      // Empty bins show the beach.
      for (unsigned int i = 0; i < n; ++i)
        {
          if (profile.y_initial[i] == lowest)
            profile.y_initial[i] = beach_level;
          if (profile.y_final[i] == lowest)
            profile.y_final[i] = beach_level;
        }
      return profile;
    }


    CliffDiagnostics::Result
    CliffDiagnostics::analyse(const std::vector<Particle> &particles,
                              const scenes::CliffProfile  &cliff) const
    {
      return analyse(surface_profile(particles, cliff), particles, cliff);
    }


    CliffDiagnostics::Result
    CliffDiagnostics::analyse(const Profile               &profile,
                              const std::vector<Particle> &particles,
                              const scenes::CliffProfile  &cliff) const
    {
      Result             r;
      const double       tau     = surface_threshold();
      const unsigned int max_gap = maximum_gap_bins();
      const double       y_b     = profile.beach_level;
      const unsigned int start   = profile.bin_of(cliff.back_position());

      // Toes and run-out, with the same estimator on both profiles.
      const int initial_toe =
        walk_to_toe(profile.y_initial, start, y_b + tau, max_gap);
      const int final_toe =
        walk_to_toe(profile.y_final, start, y_b + tau, max_gap);
      if (initial_toe >= 0)
        r.initial_toe = profile.right_edge(initial_toe);
      if (final_toe >= 0)
        r.debris_toe = profile.right_edge(final_toe);
      r.run_out = r.debris_toe - r.initial_toe;

      // Accumulation zone: most seaward run landward of the debris toe.
      if (final_toe >= 0)
        {
          const auto accumulated = [&](const int i) {
            return profile.y_final[i] > profile.y_initial[i] + tau;
          };
          int end = final_toe;
          while (end >= 0 && !accumulated(end))
            --end;
          if (end >= 0)
            {
              int          foot = end;
              unsigned int gap  = 0;
              for (int i = end - 1; i >= 0; --i)
                if (accumulated(i))
                  {
                    foot = i;
                    gap  = 0;
                  }
                else if (++gap > max_gap)
                  break;

              r.has_debris = true;
              r.scarp_foot = profile.left_edge(foot);

              int summit = foot;
              for (int i = foot; i <= end; ++i)
                if (profile.y_final[i] >= profile.y_final[summit])
                  summit = i;
              r.pile_summit = profile.x[summit];
              r.pile_height = profile.y_final[summit] - y_b;

              // Least squares on the seaward flank, trimmed by height.
              const double lower =
                parameters.fit_lower_fraction * r.pile_height;
              const double upper =
                parameters.fit_upper_fraction * r.pile_height;
              std::vector<unsigned int> fit;
              for (int i = summit; i <= end; ++i)
                {
                  const double h = profile.y_final[i] - y_b;
                  if (h >= lower && h <= upper)
                    fit.push_back(i);
                }
              r.n_fit_points = fit.size();
              if (fit.size() >= 2)
                {
                  double x_mean = 0., y_mean = 0.;
                  for (const unsigned int i : fit)
                    {
                      x_mean += profile.x[i];
                      y_mean += profile.y_final[i];
                    }
                  x_mean /= fit.size();
                  y_mean /= fit.size();
                  double sxx = 0., sxy = 0.;
                  for (const unsigned int i : fit)
                    {
                      sxx += (profile.x[i] - x_mean) * (profile.x[i] - x_mean);
                      sxy +=
                        (profile.x[i] - x_mean) * (profile.y_final[i] - y_mean);
                    }
                  const double slope = sxy / sxx;
                  double       rss   = 0.;
                  for (const unsigned int i : fit)
                    {
                      const double e = profile.y_final[i] - y_mean -
                                       slope * (profile.x[i] - x_mean);
                      rss += e * e;
                    }
                  r.debris_angle =
                    std::atan(std::abs(slope)) * 180. / numbers::PI;
                  r.fit_x_begin      = profile.x[fit.front()];
                  r.fit_x_end        = profile.x[fit.back()];
                  r.fit_rms_residual = std::sqrt(rss / fit.size());
                }
            }
        }

      // Failed material and the scarp.
      const double threshold_2 =
        parameters.displacement_threshold * parameters.displacement_threshold;
      const double band_bottom = cliff.top_level() - top_band();
      // (x, reference volume) of the failed particles, for the mass measures.
      std::vector<std::pair<double, double>> failed_mass;
      double                                 moment = 0.;
      for (const Particle &p : particles)
        if ((p.position - p.initial_position).norm_square() > threshold_2)
          {
            r.failed_area += p.volume;
            r.failed_reference_area += p.reference_volume;
            ++r.n_failed_particles;
            failed_mass.emplace_back(p.position[0], p.reference_volume);
            moment += p.position[0] * p.reference_volume;
            if (p.initial_position[1] >= band_bottom)
              {
                r.scarp_position = r.has_scarp ? std::min(r.scarp_position,
                                                          p.initial_position[0])
                                               : p.initial_position[0];
                r.has_scarp      = true;
              }
          }
      if (r.has_scarp)
        r.scarp_retreat = cliff.crest()[0] - r.scarp_position;

      if (r.failed_reference_area > 0.)
        {
          r.failed_mass_centroid = moment / r.failed_reference_area;
          std::sort(failed_mass.begin(), failed_mass.end());
          // The relative slack keeps a fraction that the sum reaches exactly
          // from being missed by round-off.
          const auto quantile = [&](const double fraction) {
            const double target =
              fraction * r.failed_reference_area * (1. - 1e-12);
            double held = 0.;
            for (const auto &[x, v] : failed_mass)
              {
                held += v;
                if (held >= target)
                  return x;
              }
            return failed_mass.back().first;
          };
          r.failed_mass_x95 = quantile(0.95);
          r.failed_mass_x99 = quantile(0.99);
          r.mass_run_out    = r.failed_mass_x99 - r.initial_toe;
        }
      return r;
    }


    void
    CliffDiagnostics::write_profile_csv(const std::string &filename,
                                        const Profile     &profile,
                                        const Result      *result)
    {
      std::ofstream out(filename);
      AssertThrow(out, ExcMessage("Cannot open " + filename + " to write."));
      out << std::setprecision(10);
      if (result != nullptr)
        {
          const Result &r = *result;
          out << "# initial_toe = " << r.initial_toe << '\n'
              << "# debris_toe = " << r.debris_toe << '\n'
              << "# run_out = " << r.run_out << '\n'
              << "# has_debris = " << r.has_debris << '\n'
              << "# scarp_foot = " << r.scarp_foot << '\n'
              << "# pile_summit = " << r.pile_summit << '\n'
              << "# pile_height = " << r.pile_height << '\n'
              << "# debris_angle = " << r.debris_angle << '\n'
              << "# fit_x_begin = " << r.fit_x_begin << '\n'
              << "# fit_x_end = " << r.fit_x_end << '\n'
              << "# n_fit_points = " << r.n_fit_points << '\n'
              << "# fit_rms_residual = " << r.fit_rms_residual << '\n'
              << "# failed_area = " << r.failed_area << '\n'
              << "# failed_reference_area = " << r.failed_reference_area << '\n'
              << "# n_failed_particles = " << r.n_failed_particles << '\n'
              << "# failed_mass_centroid = " << r.failed_mass_centroid << '\n'
              << "# failed_mass_x95 = " << r.failed_mass_x95 << '\n'
              << "# failed_mass_x99 = " << r.failed_mass_x99 << '\n'
              << "# mass_run_out = " << r.mass_run_out << '\n'
              << "# has_scarp = " << r.has_scarp << '\n'
              << "# scarp_position = " << r.scarp_position << '\n'
              << "# scarp_retreat = " << r.scarp_retreat << '\n';
        }
      out << "x,y_initial,y_final\n";
      for (unsigned int i = 0; i < profile.n_bins(); ++i)
        out << profile.x[i] << ',' << profile.y_initial[i] << ','
            << profile.y_final[i] << '\n';
      AssertThrow(out, ExcMessage("Writing " + filename + " failed."));
    }


    void
    CliffDiagnostics::append_history_row(const std::string &filename,
                                         const double       time,
                                         const double       kinetic_energy,
                                         const double       max_speed,
                                         const Result      &r)
    {
      const std::vector<std::pair<std::string, double>> columns = {
        {"time", time},
        {"kinetic_energy", kinetic_energy},
        {"max_speed", max_speed},
        {"debris_angle", r.debris_angle},
        {"run_out", r.run_out},
        {"debris_toe", r.debris_toe},
        {"failed_area", r.failed_area},
        {"failed_reference_area", r.failed_reference_area},
        {"n_failed_particles", r.n_failed_particles},
        {"scarp_position", r.scarp_position},
        {"scarp_retreat", r.scarp_retreat},
        {"failed_mass_centroid", r.failed_mass_centroid},
        {"failed_mass_x95", r.failed_mass_x95},
        {"failed_mass_x99", r.failed_mass_x99},
        {"mass_run_out", r.mass_run_out}};

      // A run continued from a checkpoint may append to a history that an
      // earlier version began: the row follows the header the file has (a
      // column unknown here gets nan), so the file stays one table.
      std::vector<std::string> header;
      if (std::filesystem::exists(filename) &&
          std::filesystem::file_size(filename) > 0)
        {
          std::ifstream in(filename);
          std::string   line, name;
          std::getline(in, line);
          std::istringstream names(line);
          while (std::getline(names, name, ','))
            header.push_back(name);
        }
      const bool new_file = header.empty();

      std::ofstream out(filename, std::ios::app);
      AssertThrow(out, ExcMessage("Cannot open " + filename + " to write."));
      out << std::setprecision(10);
      if (new_file)
        for (unsigned int i = 0; i < columns.size(); ++i)
          {
            header.push_back(columns[i].first);
            out << columns[i].first << (i + 1 < columns.size() ? ',' : '\n');
          }
      for (unsigned int i = 0; i < header.size(); ++i)
        {
          const auto column =
            std::find_if(columns.begin(), columns.end(), [&](const auto &c) {
              return c.first == header[i];
            });
          if (column == columns.end())
            out << "nan";
          else
            out << column->second;
          out << (i + 1 < header.size() ? ',' : '\n');
        }
      AssertThrow(out, ExcMessage("Writing " + filename + " failed."));
    }


    void
    CliffDiagnostics::write_particles_csv(
      const std::string           &filename,
      const std::vector<Particle> &particles)
    {
      std::ofstream out(filename);
      AssertThrow(out, ExcMessage("Cannot open " + filename + " to write."));
      out << std::setprecision(10) << "x,y,damage,x0,y0,volume\n";
      for (const Particle &p : particles)
        out << p.position[0] << ',' << p.position[1] << ',' << p.damage << ','
            << p.initial_position[0] << ',' << p.initial_position[1] << ','
            << p.volume << '\n';
      AssertThrow(out, ExcMessage("Writing " + filename + " failed."));
    }
  } // namespace postprocess
} // namespace scarp
