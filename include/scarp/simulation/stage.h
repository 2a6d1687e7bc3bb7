#ifndef scarp_simulation_stage_h
#define scarp_simulation_stage_h

#include <deal.II/base/parameter_handler.h>

#include <scarp/transfer/mpm_transfer.h>

#include <string>

namespace scarp
{
  namespace simulation
  {
    using namespace dealii;

    /**
     * @brief A phase of a run with its own end criterion, damping and
     * physics switches (for instance: load gravity elastically with damping
     * until the kinetic energy has decayed, then let the cliff fail).
     */
    struct Stage
    {
      std::string name;
      double      end_time      = 1.;
      bool        settle        = false;
      double      kinetic_ratio = 1e-4;
      double      settle_time   = 0.;
      /// End once the cliff's deposit has stopped changing (see
      /// Simulation::deposit_settled()).
      bool              deposit_rest            = false;
      double            deposit_check_interval  = 0.1;
      double            deposit_settle_time     = 1.;
      double            deposit_shift_tolerance = 0.05;
      double            deposit_area_tolerance  = 0.01;
      transfer::Damping damping;
      bool              plasticity         = true;
      bool              damage             = true;
      bool              reset_displacement = false;
      /// Inertia multiplied by this factor (mass scaling; 1: none).
      double mass_scaling = 1.;
      /// Mass scaling ends for the rest of the stage once a point moves
      /// faster than this [m/s] (0: never).
      double mass_scaling_end_speed = 0.;
      /// ... and the points faster than that hold more than this volume.
      double mass_scaling_end_volume = 0.;

      /// The stage's switches as the materials get them in their batches.
      materials::InelasticSwitches
      inelastic_switches() const
      {
        materials::InelasticSwitches switches;
        switches.plasticity = plasticity;
        switches.damage     = damage;
        return switches;
      }

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };
  } // namespace simulation
} // namespace scarp

#endif
