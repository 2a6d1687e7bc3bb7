#include <scarp/base/exceptions.h>
#include <scarp/simulation/stage.h>

namespace scarp
{
  namespace simulation
  {
    void
    Stage::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("End time",
                        "1",
                        Patterns::Double(0.),
                        "Simulated time [s] (counted from the start of the "
                        "run) at which the stage ends at the latest.");
      prm.declare_entry("End on kinetic energy",
                        "false",
                        Patterns::Bool(),
                        "End the stage earlier, once the kinetic energy has "
                        "stayed below <Kinetic energy ratio> times its "
                        "largest value in this stage for <Settle time>.");
      prm.declare_entry("Kinetic energy ratio",
                        "1e-4",
                        Patterns::Double(0., 1.),
                        "See <End on kinetic energy>.");
      prm.declare_entry("Settle time",
                        "0",
                        Patterns::Double(0.),
                        "See <End on kinetic energy> [s].");
      prm.declare_entry(
        "End on deposit at rest",
        "false",
        Patterns::Bool(),
        "End the stage earlier, once the deposit of a cliff has stopped "
        "changing: after the failure onset, the debris toe and the scarp "
        "(cliff diagnostics) have each stayed within <Deposit shift "
        "tolerance> of where they were, and the failed area and the failed "
        "area before it moved within <Deposit area tolerance> (relative), "
        "for <Deposit settle time>. For collapses whose kinetic energy "
        "hovers about its criterion (a few points jostling on the pile) "
        "while nothing changes, and conversely to keep going while the "
        "scarp still creeps back at low energy. Either criterion ends the "
        "stage when both are on. Scenes with a cliff body (2D) only.");
      prm.declare_entry("Deposit check interval",
                        "0.1",
                        Patterns::Double(0.),
                        "See <End on deposit at rest>: the deposit is "
                        "measured every this much simulated time [s].");
      prm.declare_entry("Deposit settle time",
                        "1",
                        Patterns::Double(0.),
                        "See <End on deposit at rest> [s].");
      prm.declare_entry("Deposit shift tolerance",
                        "0.05",
                        Patterns::Double(0.),
                        "See <End on deposit at rest> [m]. The toe moves "
                        "by whole bins of the cliff profile, so that any "
                        "tolerance below the bin width means the toe has "
                        "not moved at all.");
      prm.declare_entry("Deposit area tolerance",
                        "0.01",
                        Patterns::Double(0.),
                        "See <End on deposit at rest>: relative change of "
                        "the failed areas.");
      prm.declare_entry("Damping type",
                        "none",
                        Patterns::Selection("none|viscous|local"),
                        "Damping of the grid forces: viscous (f -= c m v, "
                        "<Damping> is c in 1/s) or local (Cundall: f -= "
                        "alpha |f| sign(v), <Damping> is alpha in [0,1)).");
      prm.declare_entry("Damping",
                        "0",
                        Patterns::Double(0.),
                        "Damping coefficient, see <Damping type>.");
      prm.declare_entry("Plasticity",
                        "true",
                        Patterns::Bool(),
                        "Plastic returns on (false: elastic, e.g. while "
                        "loading gravity).");
      prm.declare_entry("Damage",
                        "true",
                        Patterns::Bool(),
                        "Damage evolution on (false: damage frozen).");
      prm.declare_entry("Reset displacement",
                        "false",
                        Patterns::Bool(),
                        "At the end of the stage, take the current positions "
                        "as the reference for displacements (after gravity "
                        "loading).");
      prm.declare_entry(
        "Mass scaling",
        "1",
        Patterns::Double(1.),
        "Multiply the inertia (the nodal masses of the momentum balance, "
        "not the weight) by this factor: the stable time step grows by its "
        "square root. For quasi-static phases only (the paper's authors "
        "loaded gravity and let damage creep with it, then switched to real "
        "time at the failure); see <Mass scaling until speed> and "
        "doc/user_guide.md. 1: none.");
      prm.declare_entry(
        "Mass scaling until speed",
        "0",
        Patterns::Double(0.),
        "With <Mass scaling> > 1: once a material point moves faster than "
        "this [m/s], the stage continues in real time (no mass scaling) to "
        "its end, with the velocities it has; the kinetic energy of the "
        "extra inertia is booked as dissipated at the switch. Set it well "
        "above the speeds of the quasi-static phase and below those of the "
        "failure (the cliff diagnostics' onset speed is 0.1 m/s). 0: mass "
        "scaling for the whole stage.");
      prm.declare_entry(
        "Mass scaling until volume",
        "0",
        Patterns::Double(0.),
        "With <Mass scaling until speed>: the points faster than that speed "
        "must hold more than this reference volume [m^2 in 2D, m^3 in 3D] "
        "for the mass scaling to end (a flake of a few points at a notch "
        "does not end it). 0: one point is enough.");
    }


    void
    Stage::parse_parameters(ParameterHandler &prm)
    {
      end_time                = prm.get_double("End time");
      settle                  = prm.get_bool("End on kinetic energy");
      kinetic_ratio           = prm.get_double("Kinetic energy ratio");
      settle_time             = prm.get_double("Settle time");
      deposit_rest            = prm.get_bool("End on deposit at rest");
      deposit_check_interval  = prm.get_double("Deposit check interval");
      deposit_settle_time     = prm.get_double("Deposit settle time");
      deposit_shift_tolerance = prm.get_double("Deposit shift tolerance");
      deposit_area_tolerance  = prm.get_double("Deposit area tolerance");
      if (deposit_rest && deposit_check_interval <= 0.)
        throw ScarpError("Stage " + name +
                         ": <Deposit check interval> must be positive with "
                         "<End on deposit at rest>.");
      const std::string type = prm.get("Damping type");
      damping.type        = type == "viscous" ? transfer::Damping::Type::viscous
                            : type == "local" ? transfer::Damping::Type::local
                                              : transfer::Damping::Type::none;
      damping.coefficient = prm.get_double("Damping");
      if (damping.type == transfer::Damping::Type::local &&
          damping.coefficient >= 1.)
        throw ScarpError("Stage " + name +
                         ": local <Damping> must be below 1.");
      plasticity              = prm.get_bool("Plasticity");
      damage                  = prm.get_bool("Damage");
      reset_displacement      = prm.get_bool("Reset displacement");
      mass_scaling            = prm.get_double("Mass scaling");
      mass_scaling_end_speed  = prm.get_double("Mass scaling until speed");
      mass_scaling_end_volume = prm.get_double("Mass scaling until volume");
      if (mass_scaling_end_speed > 0 && mass_scaling == 1.)
        throw ScarpError("Stage " + name +
                         ": <Mass scaling until speed> is set but <Mass "
                         "scaling> is 1 (no mass scaling to end).");
    }
  } // namespace simulation
} // namespace scarp
