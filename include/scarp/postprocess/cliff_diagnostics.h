#ifndef scarp_postprocess_cliff_diagnostics_h
#define scarp_postprocess_cliff_diagnostics_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <scarp/scenes/cliff_profile.h>

#include <limits>
#include <string>
#include <vector>

namespace scarp
{
  namespace postprocess
  {
    using namespace dealii;

    /**
     * @brief Measures a cliff collapse from a gathered list of particles and
     * the initial CliffProfile: free-surface profiles, debris toe, run-out,
     * debris pile angle, failed area and scarp position.
     *
     * All functions are pure: they read the particle list and the settings
     * and return numbers; the caller gathers the particles of all ranks
     * first. The sea is on the +x side (see scenes::CliffProfile).
     *
     * Definitions (h = bin width, tau = surface threshold, g = maximum gap;
     * see doc/scenes.md for the reasoning):
     *  - Surface profile: the x range is cut into bins of width h starting at
     *    the back of the body (or at the most landward particle, if further
     *    back). y_final(bin) is the largest current y of the particles whose
     *    current x lies in the bin, y_initial(bin) the largest initial y of
     *    the particles whose initial x lies in it; an empty bin has the
     *    beach level. Both profiles use the same estimator, so a particle
     *    cloud that has not moved gives y_final == y_initial exactly; both
     *    lie up to one particle spacing below the true surface.
     *  - Toe: walking seaward from the bin of the back of the body, the last
     *    bin whose height exceeds beach level + tau, where the walk stops
     *    after more than g of consecutive bins at or below it. The toe x is
     *    that bin's seaward edge. initial_toe uses y_initial, debris_toe
     *    y_final; run_out = debris_toe - initial_toe (exactly zero without
     *    motion). initial_toe is the most seaward material to within one bin:
     *    the toe T without a notch, the notch top U with one (the notch
     *    removes the tip of the face; 9 cm landward of T for Joss Bay).
     *  - Accumulation zone: bins where y_final > y_initial + tau. Its seaward
     *    end is the first such bin met walking landward from the debris toe;
     *    walking on landward (gaps up to g allowed), its landward end is the
     *    foot of the scarp: where the final surface comes out from under the
     *    initial one. No accumulation bin: has_debris = false.
     *  - Debris angle: the summit is the most seaward bin of largest height
     *    above the beach in the accumulation zone (the pile height). A
     *    least-squares line y = a + b x is fitted through the bin centres and
     *    y_final of the bins from the summit to the seaward end of the zone
     *    whose height above the beach lies in [Fit lower fraction, Fit upper
     *    fraction] times the pile height; angle = atan(|b|) in degrees. It is
     *    the angle of the seaward flank of the pile; the trimming keeps out
     *    the rounded toe and the top where the pile meets the scarp.
     *  - Failed area: sum of the volumes (areas per unit thickness in 2D) of
     *    the particles displaced by more than the displacement threshold;
     *    also the sum of their reference (initial) volumes, the failed
     *    mass over the density, which the dilation of fully damaged
     *    debris does not inflate.
     *  - Where the failed mass lies: the centroid along x of the failed
     *    particles' reference volumes (their mass over the density), and the
     *    smallest x of a failed particle such that the failed particles at
     *    or landward of it hold at least 95 % (99 %) of that volume.
     *    mass_run_out = x(99 %) - initial_toe. Unlike the profile's toe,
     *    these do not follow a few light, much dilated points thrown ahead.
     *  - Scarp position: the smallest initial x of the failed particles that
     *    started within Top band of the top of the cliff, i.e. where the
     *    failure surface reaches the top; scarp_retreat = crest x - scarp
     *    position.
     */
    class CliffDiagnostics
    {
    public:
      /// @brief One material point, as gathered for the diagnostics.
      struct Particle
      {
        Point<2> position;
        Point<2> initial_position;
        /// Current volume (area per unit thickness in 2D) [m^2].
        double volume = 0.;
        /// Volume in the reference (initial) configuration [m^2].
        double reference_volume = 0.;
        /// Damage in [0, 1]; only written to the particle CSV.
        double damage = 0.;
      };

      /// @brief The settings; lengths in metres.
      struct Parameters
      {
        /// 0: one background cell, see set_cell_size().
        double bin_width = 0.;
        /// 0: half a bin.
        double surface_threshold      = 0.;
        double displacement_threshold = 0.5;
        /// 0: four bins.
        double maximum_gap        = 0.;
        double fit_lower_fraction = 0.1;
        double fit_upper_fraction = 0.9;
        /// 0: two bins.
        double top_band = 0.;
        /// Append the diagnostics to cliff_history.csv at every particle
        /// output.
        bool write_history = true;
      };

      /// @brief Free-surface heights on bins of equal width.
      struct Profile
      {
        double beach_level = 0.;
        double x_min       = 0.;
        double bin_width   = 0.;
        /// Bin centres.
        std::vector<double> x;
        std::vector<double> y_initial;
        std::vector<double> y_final;

        unsigned int
        n_bins() const;
        double
        left_edge(const unsigned int bin) const;
        double
        right_edge(const unsigned int bin) const;
        /// The bin that holds @p x, clamped to the range.
        unsigned int
        bin_of(const double x) const;
      };

      /// @brief The measured quantities; x positions in scene coordinates.
      struct Result
      {
        static constexpr double nan = std::numeric_limits<double>::quiet_NaN();

        double initial_toe = nan;
        double debris_toe  = nan;
        double run_out     = nan;

        /// Whether there is an accumulation zone (see the class notes).
        bool   has_debris  = false;
        double scarp_foot  = nan;
        double pile_summit = nan;
        /// Height of the summit above the beach.
        double pile_height = nan;
        /// Debris angle [degrees]; NaN with fewer than two fit points.
        double       debris_angle     = nan;
        double       fit_x_begin      = nan;
        double       fit_x_end        = nan;
        unsigned int n_fit_points     = 0;
        double       fit_rms_residual = nan;

        double failed_area = 0.;
        /// The failed particles' reference volumes: the failed area before
        /// the debris dilated (fully damaged points expand freely).
        double       failed_reference_area = 0.;
        unsigned int n_failed_particles    = 0;

        /// Centroid along x of the failed reference volumes.
        double failed_mass_centroid = nan;
        /// x at or landward of which 95 % of the failed reference volume lies.
        double failed_mass_x95 = nan;
        /// x at or landward of which 99 % of the failed reference volume lies.
        double failed_mass_x99 = nan;
        /// failed_mass_x99 - initial_toe: a run-out of the mass.
        double mass_run_out = nan;

        /// Whether a failed particle started within the top band.
        bool   has_scarp      = false;
        double scarp_position = nan;
        double scarp_retreat  = nan;
      };

      /// Default settings (Bin width 0 needs set_cell_size()).
      CliffDiagnostics();

      explicit CliffDiagnostics(const Parameters &parameters);

      /// Declares the entries in the current subsection.
      static void
      declare_parameters(ParameterHandler &prm);

      /// Reads the entries of the current subsection; throws an ExcMessage
      /// naming the entry on bad input.
      void
      parse_parameters(const ParameterHandler &prm);

      /// Background cell size, used where an entry is 0 ("one cell").
      void
      set_cell_size(const double cell_size);

      /// Effective bin width (throws if it is 0 and no cell size was set).
      double
      bin_width() const;

      /// The surface profiles on bins from the back of the cliff (or the
      /// most landward particle) to the most seaward particle.
      Profile
      surface_profile(const std::vector<Particle> &particles,
                      const scenes::CliffProfile  &cliff) const;

      /// The surface profiles on bins of the range [x_min, x_max); particles
      /// outside it are ignored.
      Profile
      surface_profile(const std::vector<Particle> &particles,
                      const double                 beach_level,
                      const double                 x_min,
                      const double                 x_max) const;

      /// All diagnostics, on the profile of surface_profile(particles,
      /// cliff).
      Result
      analyse(const std::vector<Particle> &particles,
              const scenes::CliffProfile  &cliff) const;

      /// All diagnostics, on a given @p profile.
      Result
      analyse(const Profile               &profile,
              const std::vector<Particle> &particles,
              const scenes::CliffProfile  &cliff) const;

      /// Writes "x,y_initial,y_final" per bin, preceded by "# name = value"
      /// lines with @p result when given (tools/plot_cliff.py reads both).
      static void
      write_profile_csv(const std::string &filename,
                        const Profile     &profile,
                        const Result      *result = nullptr);

      /// Appends one row of @p result at @p time to @p filename (the
      /// history of a run: time, kinetic energy, largest speed, debris
      /// angle, run-out, debris toe, failed area, failed area before it
      /// moved, failed points, scarp position and retreat, then the failed
      /// mass's centroid, 95 and 99 % positions and run-out), with the
      /// header line first when the file is new or empty.
      static void
      append_history_row(const std::string &filename,
                         const double       time,
                         const double       kinetic_energy,
                         const double       max_speed,
                         const Result      &result);

      /// The settings.
      const Parameters &
      get_parameters() const
      {
        return parameters;
      }

      /// Writes "x,y,damage,x0,y0,volume" per particle, for
      /// tools/plot_cliff.py.
      static void
      write_particles_csv(const std::string           &filename,
                          const std::vector<Particle> &particles);

    private:
      double
      surface_threshold() const;
      unsigned int
      maximum_gap_bins() const;
      double
      top_band() const;

      Parameters parameters;
      double     cell_size = 0.;
    };
  } // namespace postprocess
} // namespace scarp

#endif
