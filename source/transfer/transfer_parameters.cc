#include <scarp/base/exceptions.h>
#include <scarp/transfer/transfer_parameters.h>

namespace scarp
{
  namespace transfer
  {
    void
    TransferParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Transfer");
      prm.declare_entry("Velocity transfer",
                        "FLIP",
                        Patterns::Selection("PIC|FLIP|APIC"),
                        "Grid-to-particle velocity transfer: PIC (the grid "
                        "velocity; dissipative), FLIP (blend of the grid "
                        "velocity increment and PIC, see FLIP fraction) or "
                        "APIC (affine PIC: carries the velocity gradient; "
                        "conserves angular momentum; elastic materials only: "
                        "refused with plasticity or damage, where it creates "
                        "energy, doc/stability.md).");
      // The string of default_flip_fraction.
      prm.declare_entry("FLIP fraction",
                        "0.99",
                        Patterns::Double(0., 1.),
                        "With FLIP: weight of the FLIP increment; the rest is "
                        "PIC (1 = pure FLIP, 0 = PIC). It is the share of "
                        "every step, so the PIC share per second, and with it "
                        "the transfer's dissipation, grows as 1/dt: a smaller "
                        "<CFL number> or finer cells damp more "
                        "(doc/user_guide.md, \"The PIC share per unit of "
                        "time\").");
      prm.declare_entry(
        "PIC time scale",
        "0",
        Patterns::Double(0.),
        "With FLIP and a value T > 0 [s]: the PIC share of a step of length "
        "dt is 1 - exp(-dt/T) instead of 1 - <FLIP fraction>, so that the "
        "points' velocities relax towards the grid's at the rate 1/T of "
        "simulated time whatever the time step (the FLIP fraction is then "
        "not used and must be left at its default). 0: off. Refused with "
        "PIC and APIC.");
      prm.declare_entry("Update scheme",
                        "MUSL",
                        Patterns::Selection("USL|MUSL"),
                        "USL: stress update with the grid velocity of the "
                        "solve. MUSL: particle momentum is mapped to the grid "
                        "again and the stress updated with that velocity "
                        "(robust for tiny nodal masses).");
      prm.declare_entry("Small mass cutoff",
                        "1e-5",
                        Patterns::Double(0., 1.),
                        "Nodes whose mass is below this fraction of the mass "
                        "of a full cell of the densest material get zero "
                        "velocity.");
      prm.declare_entry(
        "Shape functions",
        "Q1",
        Patterns::Selection("Q1|GIMP"),
        "Q1: the bilinear (trilinear) FE_Q(1) functions of the cell that "
        "holds the point. GIMP: generalized interpolation MPM, the mean of "
        "the (hanging-node constrained) Q1 basis over the point's domain, a "
        "box of half-width min(h/(2 n), h_K/2) for n <Particles per cell> "
        "(taken from the reference volume) and h_K the edge of the point's "
        "cell: smooth gradients, no cell-crossing noise, 3^dim instead of "
        "2^dim nodes per point. Works on uniform and refined meshes (across "
        "coarse-fine interfaces); doc/refinement.md.");
      prm.declare_entry(
        "Volumetric averaging",
        "none",
        Patterns::Selection("none|F-bar"),
        "none: every point deforms with its own increment dF = dF(grad v). "
        "F-bar: against volumetric locking of nearly incompressible or "
        "isochoric plastic flow: the volume change det(dF) of each point is "
        "replaced by the mean over the points of its cell (weighted by their "
        "volumes at the start of the step), the isochoric part of dF is kept, "
        "dFbar = (dJbar/dJ)^(1/dim) dF; the stress, F and the point volume "
        "follow dFbar, and the grid forces use the cell's volume-weighted "
        "mean normal stress in place of each point's (they then do the work "
        "sigma : Dbar that the stresses take). The cell is the active cell "
        "that holds the point (any level of a refined mesh; with Q1 or "
        "GIMP); a cell's points are on the rank that owns it, so runs on any "
        "number of ranks agree. "
        "doc/examples.md (Prandtl's footing), doc/stability.md.");
      prm.leave_subsection();
    }


    void
    TransferParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Transfer");
      const std::string transfer = prm.get("Velocity transfer");
      velocity_transfer =
        transfer == "APIC" ? VelocityTransfer::apic : VelocityTransfer::flip;
      flip_fraction  = transfer == "PIC" ? 0. : prm.get_double("FLIP fraction");
      pic_time_scale = prm.get_double("PIC time scale");
      if (pic_time_scale > 0 && transfer != "FLIP")
        throw ScarpError("Transfer: <PIC time scale> sets the PIC share of "
                         "the FLIP transfer; it cannot be used with "
                         "<Velocity transfer> = " +
                         transfer + ".");
      if (pic_time_scale > 0 &&
          prm.get_double("FLIP fraction") != default_flip_fraction)
        throw ScarpError("Transfer: set either <FLIP fraction> (a PIC share "
                         "per step) or <PIC time scale> (a PIC share per "
                         "unit of time), not both.");
      scheme          = prm.get("Update scheme") == "USL" ? UpdateScheme::usl
                                                          : UpdateScheme::musl;
      mass_cutoff     = prm.get_double("Small mass cutoff");
      shape_functions = prm.get("Shape functions") == "GIMP"
                          ? ShapeFunctions::gimp
                          : ShapeFunctions::q1;
      volumetric_averaging = prm.get("Volumetric averaging") == "F-bar"
                               ? VolumetricAveraging::f_bar
                               : VolumetricAveraging::none;
      prm.leave_subsection();
    }
  } // namespace transfer
} // namespace scarp
