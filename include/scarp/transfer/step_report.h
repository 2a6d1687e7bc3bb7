#ifndef scarp_transfer_step_report_h
#define scarp_transfer_step_report_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <array>
#include <cstddef>
#include <string>

namespace scarp
{
  namespace transfer
  {
    using namespace dealii;

    /**
     * @brief What one explicit step measured: energies, momenta, the
     * largest speed, and counts of points that went wrong. Filled per rank,
     * then reduced over all ranks in one call.
     */
    struct StepReport
    {
      // Sums (reduced with MPI_SUM).
      double kinetic_energy       = 0; ///< sum m |v|^2 / 2
      double gravitational_energy = 0; ///< -sum m g.x
      double stored_energy        = 0; ///< sum V0 psi
      double internal_work        = 0; ///< dt sum V sigma : D (this step)
      double damping_dissipation  = 0; ///< energy removed by damping
      double boundary_dissipation = 0; ///< energy removed by the boundaries
      double transfer_dissipation = 0; ///< removed by P2G and G2P (below)
      double body_force_work      = 0; ///< by <Physics/Body force>, on grid
      double mass                 = 0;
      double plastic_dissipation  = 0; ///< cumulative, from material states
      double damage_dissipation   = 0; ///< cumulative, from material states
      double damaged_volume       = 0; ///< sum V d
      double n_points             = 0;
      std::array<double, 3> momentum{{0, 0, 0}};
      std::array<double, 3> angular_momentum{{0, 0, 0}};
      // transfer_dissipation: (points before P2G - grid after P2G) + (grid
      // after its update - points after G2P), kinetic energies of the
      // mass-scaled inertia; negative where a transfer adds energy (APIC's
      // affine part, FLIP points that keep what a boundary took from the
      // start-of-step grid velocity). body_force_work: dt f_b . (v_start +
      // v_free) / 2 summed over the nodes, the body force's exact share of
      // the grid's energy change.

      // Maxima (reduced with MPI_MAX).
      double max_speed  = 0; ///< largest |v| (|v|^2 before reduce())
      double max_damage = 0;
      // Failure counts (summed).
      double n_not_finite = 0; ///< NaN or inf in velocity, F or stress
      double n_inverted   = 0; ///< J <= 0
      double n_outside    = 0; ///< left the mesh
      double n_too_fast   = 0; ///< moved more than a cell in one step
      /// Points that left their cell (not a failure): when no point on any
      /// rank did, the particles need no sorting after the step.
      double n_changed_cell = 0;
      /// Position of one offending point (the first found on this rank).
      std::array<double, 3> offender{{0, 0, 0}};
      bool                  has_offender = false;

      // Added after checkpoint format 4 was fixed: checkpoints hold the
      // report up to here (checkpoint_size), so that older ones load.
      /// Kinetic (unscaled) and gravitational energy of the points that
      /// left the mesh in this step (removed in the sort after it; summed).
      double removed_kinetic_energy       = 0;
      double removed_gravitational_energy = 0;
      /// Damaged points removed because they stretched too far (material
      /// entry <Remove points stretched beyond>; their energies are in the
      /// two above). Not a failure.
      double n_removed_stretched = 0;

      /// The bytes of a report that a checkpoint holds: the members before
      /// removed_kinetic_energy (what the next step needs of the last
      /// report; the removed energies are booked in the step that has
      /// them).
      static constexpr std::size_t
      checkpoint_size();

      /// Sum/max over all ranks; the offender is taken from the lowest rank
      /// that has one.
      void
      reduce(MPI_Comm communicator);

      /// Total failures.
      double
      n_failures() const
      {
        return n_not_finite + n_inverted + n_outside + n_too_fast;
      }

      /// A sentence naming what went wrong (empty if nothing did).
      std::string
      failure_message() const;
    };

    constexpr std::size_t
    StepReport::checkpoint_size()
    {
      return offsetof(StepReport, removed_kinetic_energy);
    }
  } // namespace transfer
} // namespace scarp

#endif
