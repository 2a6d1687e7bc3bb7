#ifndef scarp_materials_chalk_h
#define scarp_materials_chalk_h

#include <algorithm>

#include <scarp/materials/isotropic_elasticity.h>
#include <scarp/materials/material.h>
#include <scarp/materials/mohr_coulomb_return.h>

namespace scarp
{
  namespace materials
  {
    /// Weight function of the non-local average of the damage driver.
    enum class NonlocalWeight
    {
      /// w = (1 - r^2/R^2)^2 for r < R = sqrt(7) l_c.
      bell,
      /// w = exp(-r^2 / (2 l_c^2)), cut at r = 3 l_c.
      gaussian,
      /// No averaging: Ybar = Y (mesh-dependent; for calibration only).
      local
    };

    /// Stress the local damage driver Y is computed from.
    enum class DrivingStress
    {
      /// Effective stress after the Mohr-Coulomb return (default).
      corrected,
      /// Elastic trial (undamaged predictor) stress, before the return
      /// (design note, section 3, item 1).
      trial
    };

    /**
     * @brief Chalk damage-plasticity (doc/materials.md, design note
     * chalk-model.md): Hencky elasticity and Mohr-Coulomb plasticity in the
     * undamaged (effective) stress space, scalar damage d from a
     * viscously delayed, non-locally averaged stress history kappa, and a
     * tension/compression split of the degradation.
     *
     * Per step: update() returns the effective stress, writes the local
     * driver Y to batch.damage_driver and degrades with d_n; the caller then
     * averages Y and calls update_damage() with the average.
     */
    class Chalk : public Material
    {
    public:
      /// Layout of the state array of a point.
      enum StateIndex : unsigned int
      {
        elastic_strain      = 0,  ///< 6 values: xx, yy, zz, xy, yz, xz
        plastic_strain      = 6,  ///< sum of sqrt(2/3 d eps_p : d eps_p)
        plastic_dissipation = 7,  ///< [J/m^3]
        damage_variable     = 8,  ///< d in [0, 1]
        kappa               = 9,  ///< stress history [Pa]
        damage_dissipation  = 10, ///< [J/m^3]
        damage_driver       = 11, ///< last local driver Y [Pa] (output)
        nonlocal_driver     = 12, ///< last non-local driver Ybar [Pa] (output)
        n_state             = 13,
        /// 3 values, only with <Remove points stretched beyond>: the
        /// stretch of the point's extent along x, y, z (each step times
        /// the diagonal of its deformation increment, so shear leaves it).
        axis_stretch = 13
      };

      /**
       * @brief Damage parameters (subsection `Damage`).
       */
      struct DamageParameters
      {
        /// Damage (friction) angle theta of the driver Y [deg].
        double damage_angle = 60.;
        /// Initiation stress sigma_f [Pa].
        double initiation_stress = 20.e3;
        /// Ductility eta > 1 [-].
        double ductility = 5.;
        /// Characteristic time tau of the delayed history [s].
        double characteristic_time = 1.;
        /// Length scale l_c of the non-local average [m].
        double length_scale = 0.18;
        /// Weight function of the non-local average.
        NonlocalWeight nonlocal_weight = NonlocalWeight::bell;
        /// Residual ratios r_t, r_c, r_g of tensile bulk, compressive bulk
        /// and shear stiffness at d = 1.
        double residual_tensile_ratio     = 1.e-9;
        double residual_compressive_ratio = 1.e-2;
        double residual_shear_ratio       = 5.e-3;
        /// Stress of the local driver Y: after the return or trial.
        DrivingStress driving_stress = DrivingStress::corrected;
        /// Leave fully damaged points (d = 1) out of both sums of the
        /// non-local average, as the authors' code does; otherwise they stay
        /// in the denominator with Y = 0.
        bool exclude_fully_damaged = false;
        /// Remove points with d >= removal_damage whose extent along x or
        /// y (z) has stretched beyond removal_stretch times its length, as
        /// the authors' code does; 0: never.
        double removal_stretch = 0.;
        double removal_damage  = 0.9;

        /// Declare the entries in the current subsection.
        static void
        declare_parameters(ParameterHandler &prm);

        /// Read and check them (current subsection).
        void
        parse_parameters(ParameterHandler &prm);

        /// Throw ExcMessage naming the entry if a value is impossible.
        void
        check() const;
      };

      Chalk(const double                         density,
            const IsotropicElasticity           &elasticity,
            const MohrCoulombReturn::Parameters &strength,
            const DamageParameters              &damage_parameters);

      double
      density() const override
      {
        return rho;
      }

      double
      p_wave_modulus() const override
      {
        return elasticity.p_wave_modulus();
      }

      unsigned int
      n_state_variables() const override
      {
        return parameters.removal_stretch > 0 ? n_state + 3 : n_state;
      }

      /// elastic_strain_xx..xz, plastic_strain, plastic_dissipation,
      /// damage, kappa, damage_dissipation, damage_driver,
      /// nonlocal_driver.
      std::vector<std::string>
      state_variable_names() const override;

      /// Undamaged point with eps_e = D^-1 : sigma, kappa = 0.
      void
      initialize_state(const SymmetricTensor<2, 3> &initial_stress,
                       double                      *state) const override;

      /// Without batch.inelastic.plasticity no return mapping (gravity
      /// loading). The damage d does not change here whatever the switches
      /// (only update_damage() changes it); it degrades the stress, and Y is
      /// computed and written for output.
      void
      update(const MaterialBatch &batch) const override;

      bool
      has_plasticity() const override
      {
        return true;
      }

      bool
      has_damage() const override
      {
        return true;
      }

      /// l_c, or 0 for NonlocalWeight::local (no averaging needed).
      double
      nonlocal_length() const override;

      /// False once d = 1.
      bool
      damage_can_change(const double *state) const override;

      double
      damage(const double *state) const override
      {
        return state[damage_variable];
      }

      /// max(sigma_f, kappa): damage grows once the history kappa, driven
      /// towards Ybar, passes the initiation stress and its last value.
      double
      damage_threshold(const double *state) const override
      {
        return std::max(parameters.initiation_stress, state[kappa]);
      }

      void
      set_fully_damaged(double *state) const override;

      /// d as given (d > 1 - 1e-6 -> 1, as in update_damage()) and kappa =
      /// the history that gives it, d(kappa) = d (at d = 1: the kappa of
      /// d = 1 - 1e-6); kappa = 0 for d = 0.
      void
      set_initial_damage(double *state, const double d) const override;

      double
      removal_stretch() const override
      {
        return parameters.removal_stretch;
      }

      /// d >= <Removal damage> and an axis stretch beyond <Remove points
      /// stretched beyond> (the authors' criterion, on the point's extent
      /// along the axes, not on F, whose fibres also stretch in shear).
      bool
      removable(const double *state) const override
      {
        return parameters.removal_stretch > 0 &&
               state[damage_variable] >= parameters.removal_damage &&
               std::max({state[axis_stretch],
                         state[axis_stretch + 1],
                         state[axis_stretch + 2]}) > parameters.removal_stretch;
      }

      /// False for d = 1 if Nonlocal exclude fully damaged is set.
      bool
      is_nonlocal_source(const double *state) const override
      {
        return !(parameters.exclude_fully_damaged &&
                 state[damage_variable] >= 1.);
      }

      double
      last_nonlocal_driver(const double *state) const override
      {
        return state[nonlocal_driver];
      }

      /// Inverse of damage_from_kappa() for d in [0, 1): the kappa >= sigma_f
      /// with d(kappa) = d (sigma_f for d = 0).
      double
      kappa_from_damage(const double d) const;

      /// kappa += (1 - exp(-dt/tau)) <Ybar - kappa>, d = max(d_n,
      /// d(kappa)), d > 1 - 1e-6 -> 1; accumulates the released energy.
      /// Ybar is kept in the state (nonlocal_driver) for output.
      void
      update_damage(const double nonlocal_driver,
                    const double dt,
                    double      *state) const override;

      DissipatedEnergy
      dissipated_energy(const double *state) const override
      {
        return {state[plastic_dissipation], state[damage_dissipation]};
      }

      NonlocalWeight
      nonlocal_weight() const
      {
        return parameters.nonlocal_weight;
      }

      /// Local driver Y of an effective Cauchy stress, Y >= 0 [Pa].
      double
      local_driver(const SymmetricTensor<2, 3> &effective_stress) const;

      /// Damage d(kappa) of the exponential softening law (no rounding).
      double
      damage_from_kappa(const double kappa) const;

      /// Degraded stress from an effective stress at damage d.
      SymmetricTensor<2, 3>
      degrade(const SymmetricTensor<2, 3> &effective_stress,
              const double                 d) const;

      const DamageParameters &
      get_damage_parameters() const
      {
        return parameters;
      }

      const IsotropicElasticity &
      get_elasticity() const
      {
        return elasticity;
      }

      const MohrCoulombReturn &
      get_return_mapping() const
      {
        return mohr_coulomb;
      }

    private:
      const double              rho;
      const IsotropicElasticity elasticity;
      const MohrCoulombReturn   mohr_coulomb;
      const DamageParameters    parameters;
      /// 3 / (3 + tan theta) and tan theta / 3 of the driver.
      const double driver_scale;
      const double driver_friction;
    };
  } // namespace materials
} // namespace scarp

#endif
