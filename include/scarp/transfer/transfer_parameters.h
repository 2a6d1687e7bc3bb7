#ifndef scarp_transfer_transfer_parameters_h
#define scarp_transfer_transfer_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <cmath>

namespace scarp
{
  namespace transfer
  {
    using namespace dealii;

    /// How grid velocities return to the particles.
    enum class VelocityTransfer
    {
      flip, ///< blend of FLIP (increment) and PIC (value) by FLIP fraction
      apic, ///< affine particle-in-cell: carries the velocity gradient
    };

    /// When the stress is updated relative to the grid solve.
    enum class UpdateScheme
    {
      usl,  ///< update stress last, with the grid velocity of the solve
      musl, ///< modified USL: remap particle momentum first, then update
    };

    /// Shape functions of the transfers.
    enum class ShapeFunctions
    {
      q1,   ///< FE_Q(1) of the cell that holds the point
      gimp, ///< GIMP on any mesh (transfer/gimp_patches.h)
    };

    /// How the volume change of the points' deformation increments is
    /// treated (volumetric locking).
    enum class VolumetricAveraging
    {
      none,  ///< each point keeps its own increment
      f_bar, ///< the volume change is the mean of the cell's points
    };

    /**
     * @brief Choices of the explicit MPM step: velocity transfer, update
     * scheme, shape functions, volumetric averaging (F-bar) and the
     * small-mass cutoff of the grid solve.
     */
    struct TransferParameters
    {
      /// The FLIP weight of a step of length @p dt: <FLIP fraction>, or
      /// exp(-dt / <PIC time scale>) when that is set (a PIC share per unit
      /// of time, whatever the time step).
      double
      flip_weight(const double dt) const
      {
        return pic_time_scale > 0 ? std::exp(-dt / pic_time_scale)
                                  : flip_fraction;
      }

      /// The default of <FLIP fraction> (its declaration writes the same).
      static constexpr double default_flip_fraction = 0.99;

      VelocityTransfer velocity_transfer = VelocityTransfer::flip;
      double           flip_fraction     = default_flip_fraction;
      /// With FLIP and > 0: the PIC share of a step of length dt is
      /// 1 - exp(-dt / pic_time_scale) instead of 1 - flip_fraction.
      double              pic_time_scale       = 0;
      UpdateScheme        scheme               = UpdateScheme::musl;
      double              mass_cutoff          = 1e-5;
      ShapeFunctions      shape_functions      = ShapeFunctions::q1;
      VolumetricAveraging volumetric_averaging = VolumetricAveraging::none;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };
  } // namespace transfer
} // namespace scarp

#endif
