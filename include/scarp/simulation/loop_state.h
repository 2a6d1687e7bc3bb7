#ifndef scarp_simulation_loop_state_h
#define scarp_simulation_loop_state_h

#include <deal.II/base/types.h>

#include <boost/serialization/version.hpp>

namespace scarp
{
  namespace simulation
  {
    /**
     * @brief The terms of the energy balance that are sums over the steps,
     * and the balance itself after the last step:
     * E_kin + E_grav + W_int + D_damping + D_boundary + D_mass_scaling +
     * D_transfer + E_removed - W_body - E_0 = residual.
     */
    struct EnergyLedger
    {
      /// E_0: kinetic plus gravitational energy at the start [J].
      double initial              = 0;
      double internal_work        = 0;
      double damping_dissipation  = 0;
      double boundary_dissipation = 0;
      /// Kinetic energy the transfers removed (PIC share of FLIP, APIC).
      double transfer_dissipation = 0;
      double body_force_work      = 0;
      /// Kinetic energy of the scaled inertia booked as dissipated when
      /// mass scaling ends.
      double mass_scaling_dissipation = 0;
      /// Kinetic (of the scaled inertia) plus gravitational energy of the
      /// points removed when they left the mesh.
      double removed_energy = 0;
      /// The largest energy of the run, the scale of the growth check.
      double scale = 0;
      /// The balance residual after the last step.
      double residual = 0;

      /// Version 1 added removed_energy; checkpoints of version 0 load
      /// with none.
      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int version)
      {
        ar &initial &internal_work &damping_dissipation &boundary_dissipation
          &transfer_dissipation &body_force_work &mass_scaling_dissipation
            &scale &residual;
        if (version >= 1)
          ar &removed_energy;
      }
    };

    /**
     * @brief Where the stage loop is inside the current stage: its start
     * and the state of its settling criterion.
     */
    struct StageProgress
    {
      /// Index of the current stage in the scene's list.
      unsigned int index = 0;
      /// The stage has begun (it has a start time and step); false between
      /// stages, so that a checkpoint at a stage's end resumes the next.
      bool         in_progress = false;
      double       start_time  = 0;
      unsigned int start_step  = 0;
      /// Largest kinetic energy of the stage, and since when it has stayed
      /// below Stage::kinetic_ratio of it (-1: not quiet).
      double peak_kinetic  = 0;
      double settled_since = -1;

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &index &in_progress &start_time &start_step &peak_kinetic
          &settled_since;
      }
    };

    /**
     * @brief Mass scaling of the current stage: the factor the step uses
     * (Stage::mass_scaling while it lasts, else 1), and whether and when it
     * ended in this stage.
     */
    struct MassScalingState
    {
      double inertia_scale = 1;
      bool   ended         = false;
      double end_time      = -1;

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &inertia_scale &ended &end_time;
      }
    };

    /**
     * @brief The deposit rest criterion of the current stage
     * (Stage::deposit_rest): when the deposit is measured next, and the
     * measurement that opened the current quiet period (since < 0: none).
     */
    struct DepositRestState
    {
      double next_check  = -1;
      double since       = -1;
      double toe         = 0;
      double scarp       = 0;
      double area        = 0;
      double area_before = 0;

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &next_check &since &toe &scarp &area &area_before;
      }
    };

    /**
     * @brief Times of damage and failure (cliff scenes), -1 until they
     * happen.
     */
    struct FailureTracking
    {
      /// First time the largest damage exceeded 0.5.
      double first_damage_time = -1;
      /// Start of the first stage with damage (the clock of the onset).
      double damage_stage_start = -1;
      /// Onset of the failure (fast points of enough volume).
      double onset_time = -1;
      /// The snapshot "after_failure" has been written.
      bool after_failure_taken = false;

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &first_damage_time &damage_stage_start &onset_time
          &after_failure_taken;
      }
    };

    /**
     * @brief What the run has counted for summary.json: refinement, load
     * balance, removed points, set-up passes.
     */
    struct RunCounters
    {
      unsigned int                  refinement_checks = 0;
      unsigned int                  refinement_passes = 0;
      dealii::types::particle_index points_split      = 0;
      unsigned int                  rebalances        = 0;
      /// Points that left the mesh and were removed (a double: summed from
      /// the reduced StepReport).
      double points_removed = 0;
      /// Runs of the first stage before the run proper that refined the
      /// mesh and reseeded the bodies (Mesh/Refinement/Set-up passes), and
      /// their steps.
      unsigned int setup_passes = 0;
      unsigned int setup_steps  = 0;

      /// Version 1 added the set-up passes; checkpoints of version 0
      /// (before them) are read with none.
      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int version)
      {
        ar &refinement_checks &refinement_passes &points_split &rebalances
          &points_removed;
        if (version >= 1)
          ar &setup_passes &setup_steps;
      }
    };

    /**
     * @brief The error against a <Reference solution> as the statistics
     * rows measure it: the last and the largest, and the largest norm of
     * the reference displacement (-1 / 0 without one).
     */
    struct ReferenceErrorTracking
    {
      double last     = -1;
      double max      = 0;
      double norm_max = 0;

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &last &max &norm_max;
      }
    };

    /**
     * @brief Everything the time loop of a Simulation carries from one step
     * to the next, apart from the particles and the mesh: what a checkpoint
     * must save so that a resumed run continues as if never stopped.
     *
     * Parameters of the scene are not part of it (they are read again from
     * the scene file on resume).
     */
    struct LoopState
    {
      double time = 0;
      /// The time step of the last step.
      double       dt   = 0;
      unsigned int step = 0;
      /// Number of the next VTU output, and the time it is due.
      unsigned int output_index = 0;
      double       next_output  = 0;

      StageProgress          stage;
      EnergyLedger           energy;
      MassScalingState       mass_scaling;
      FailureTracking        failure;
      RunCounters            counters;
      ReferenceErrorTracking reference_error;
      DepositRestState       deposit;

      /// Version 1 added the deposit rest criterion; checkpoints of version
      /// 0 load without a quiet period.
      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int version)
      {
        ar &time &dt &step &output_index                   &next_output;
        ar &stage &energy &mass_scaling &failure &counters &reference_error;
        if (version >= 1)
          ar &deposit;
      }
    };
  } // namespace simulation
} // namespace scarp

BOOST_CLASS_VERSION(scarp::simulation::RunCounters, 1)
BOOST_CLASS_VERSION(scarp::simulation::EnergyLedger, 1)
BOOST_CLASS_VERSION(scarp::simulation::LoopState, 1)

#endif
