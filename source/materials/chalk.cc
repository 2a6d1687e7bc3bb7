#include <deal.II/base/numbers.h>

#include <scarp/materials/chalk.h>
#include <scarp/materials/hencky_strain.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace scarp
{
  namespace materials
  {
    namespace
    {
      /// Driver Y from principal effective Cauchy stresses.
      inline double
      driver_from_principal(const std::array<double, 3> &s,
                            const double                 scale,
                            const double                 friction)
      {
        const double I1 = s[0] + s[1] + s[2];
        const double p  = I1 / 3.;
        const double s2 = (s[0] - p) * (s[0] - p) + (s[1] - p) * (s[1] - p) +
                          (s[2] - p) * (s[2] - p);
        // sqrt(3 J2) = sqrt(3/2 s:s).
        return std::max(0., scale * (std::sqrt(1.5 * s2) + I1 * friction));
      }
    } // namespace


    void
    Chalk::DamageParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Damage angle",
                        "60",
                        Patterns::Double(0., 90.),
                        "Damage (friction) angle theta of the driving stress "
                        "Y = 3/(3 + tan theta) (sqrt(3 J2) + I1 tan theta / "
                        "3) [deg], in [0, 90). Joss Bay chalk: 60.");
      prm.declare_entry("Initiation stress",
                        "20e3",
                        Patterns::Double(0.),
                        "Damage initiation stress sigma_f [Pa], > 0: damage "
                        "starts when the history kappa exceeds it. Joss Bay "
                        "chalk: 20e3.");
      prm.declare_entry("Ductility",
                        "5",
                        Patterns::Double(1.),
                        "Ductility eta [-], > 1: the energy dissipated per "
                        "volume in uniaxial tension is eta sigma_f^2 / (2 E). "
                        "Joss Bay chalk: 5.");
      prm.declare_entry("Characteristic time",
                        "1",
                        Patterns::Double(0.),
                        "Characteristic time tau of the delayed history "
                        "kappa_dot = <Ybar - kappa> / tau [s], >= 0 (0: no "
                        "delay). Joss Bay chalk: 1.");
      prm.declare_entry("Length scale",
                        "0.18",
                        Patterns::Double(0.),
                        "Length scale l_c of the non-local average [m], > 0 "
                        "(standard deviation of the weight; bell support "
                        "radius sqrt(7) l_c, Gaussian cut at 3 l_c). Joss "
                        "Bay chalk: 0.18.");
      prm.declare_entry("Nonlocal weight",
                        "bell",
                        Patterns::Selection("bell|gaussian|local"),
                        "Weight of the non-local average of the damage "
                        "driver: bell (1 - r^2/R^2)^2 with R = sqrt(7) l_c, "
                        "gaussian exp(-r^2/(2 l_c^2)) cut at 3 l_c, or local "
                        "(no average, mesh-dependent).");
      prm.declare_entry("Residual tensile ratio",
                        "1e-9",
                        Patterns::Double(0., 1.),
                        "Residual ratio r_t of the bulk stiffness in tension "
                        "(mean stress > 0) at d = 1 [-], in [0, 1]. Joss Bay "
                        "chalk: 1e-9.");
      prm.declare_entry("Residual compressive ratio",
                        "1e-2",
                        Patterns::Double(0., 1.),
                        "Residual ratio r_c of the bulk stiffness in "
                        "compression at d = 1 [-], in [0, 1]. Joss Bay "
                        "chalk: 1e-2.");
      prm.declare_entry("Residual shear ratio",
                        "5e-3",
                        Patterns::Double(0., 1.),
                        "Residual ratio r_g of the shear stiffness at d = 1 "
                        "[-], in [0, 1]. Joss Bay chalk: 5e-3 or 1e-2 (the "
                        "two runs of the paper).");
      prm.declare_entry("Driving stress",
                        "plastically corrected",
                        Patterns::Selection(
                          "plastically corrected|elastic trial"),
                        "Effective (undamaged) stress the local driver Y is "
                        "computed from: plastically corrected (after the "
                        "Mohr-Coulomb return) or elastic trial (the "
                        "predictor before the return, as the design note "
                        "pins it). They differ only where the point yields.");
      prm.declare_entry("Nonlocal exclude fully damaged",
                        "false",
                        Patterns::Bool(),
                        "Leave fully damaged points (d = 1) out of both sums "
                        "of the non-local average, as the authors' code "
                        "does. false: they stay in the denominator with "
                        "Y = 0, which dilutes the average next to a crack.");
      prm.declare_entry("Remove points stretched beyond",
                        "0",
                        Patterns::Double(0.),
                        "Remove a point whose damage has reached <Removal "
                        "damage> once its extent along x or y (z) has "
                        "stretched beyond this factor, as the authors' code "
                        "does with 4. The extent follows the normal part of "
                        "each deformation increment (shear leaves it); the "
                        "three stretches are state variables of the point "
                        "(axis_stretch_x, _y, _z). Its mass leaves the scene "
                        "and its energy is booked as removed. 0: never; "
                        "otherwise > 1.");
      prm.declare_entry("Removal damage",
                        "0.9",
                        Patterns::Double(0., 1.),
                        "Damage from which a stretched point is removed "
                        "(<Remove points stretched beyond>); the authors' "
                        "code: 0.9.");
    }


    void
    Chalk::DamageParameters::parse_parameters(ParameterHandler &prm)
    {
      damage_angle               = prm.get_double("Damage angle");
      initiation_stress          = prm.get_double("Initiation stress");
      ductility                  = prm.get_double("Ductility");
      characteristic_time        = prm.get_double("Characteristic time");
      length_scale               = prm.get_double("Length scale");
      const std::string w        = prm.get("Nonlocal weight");
      nonlocal_weight            = (w == "bell")       ? NonlocalWeight::bell
                                   : (w == "gaussian") ? NonlocalWeight::gaussian
                                                       : NonlocalWeight::local;
      residual_tensile_ratio     = prm.get_double("Residual tensile ratio");
      residual_compressive_ratio = prm.get_double("Residual compressive ratio");
      residual_shear_ratio       = prm.get_double("Residual shear ratio");
      driving_stress        = (prm.get("Driving stress") == "elastic trial")
                                ? DrivingStress::trial
                                : DrivingStress::corrected;
      exclude_fully_damaged = prm.get_bool("Nonlocal exclude fully damaged");
      removal_stretch       = prm.get_double("Remove points stretched beyond");
      removal_damage        = prm.get_double("Removal damage");
      check();
    }


    void
    Chalk::DamageParameters::check() const
    {
      AssertThrow(damage_angle >= 0. && damage_angle < 90.,
                  ExcMessage("Material: 'Damage angle' must lie in [0, 90) "
                             "deg, got " +
                             std::to_string(damage_angle) + "."));
      AssertThrow(initiation_stress > 0.,
                  ExcMessage("Material: 'Initiation stress' must be > 0 Pa."));
      AssertThrow(ductility > 1.,
                  ExcMessage("Material: 'Ductility' must be > 1 (the "
                             "softening law needs eta - 1 > 0), got " +
                             std::to_string(ductility) + "."));
      AssertThrow(characteristic_time >= 0.,
                  ExcMessage("Material: 'Characteristic time' must be >= 0 "
                             "s."));
      AssertThrow(length_scale > 0. || nonlocal_weight == NonlocalWeight::local,
                  ExcMessage("Material: 'Length scale' must be > 0 m unless "
                             "'Nonlocal weight' is local."));
      for (const auto &[name, r] :
           {std::make_pair("Residual tensile ratio", residual_tensile_ratio),
            std::make_pair("Residual compressive ratio",
                           residual_compressive_ratio),
            std::make_pair("Residual shear ratio", residual_shear_ratio)})
        AssertThrow(r >= 0. && r <= 1.,
                    ExcMessage(std::string("Material: '") + name +
                               "' must lie in [0, 1]."));
      // A factor in (0, 1] would remove points that have not stretched.
      std::ostringstream factor;
      factor << removal_stretch;
      AssertThrow(removal_stretch == 0. || removal_stretch > 1.,
                  ExcMessage("Material: 'Remove points stretched beyond' "
                             "must be 0 (never) or > 1, got " +
                             factor.str() + "."));
    }


    Chalk::Chalk(const double                         density,
                 const IsotropicElasticity           &elasticity,
                 const MohrCoulombReturn::Parameters &strength,
                 const DamageParameters              &damage_parameters)
      : rho(density)
      , elasticity(elasticity)
      , mohr_coulomb(elasticity, strength)
      , parameters(damage_parameters)
      , driver_scale(3. / (3. + std::tan(damage_parameters.damage_angle *
                                         numbers::PI / 180.)))
      , driver_friction(
          std::tan(damage_parameters.damage_angle * numbers::PI / 180.) / 3.)
    {
      AssertThrow(density > 0.,
                  ExcMessage("Material: 'Density' must be > 0 kg/m^3."));
      parameters.check();
    }


    std::vector<std::string>
    Chalk::state_variable_names() const
    {
      std::vector<std::string> names = {"elastic_strain_xx",
                                        "elastic_strain_yy",
                                        "elastic_strain_zz",
                                        "elastic_strain_xy",
                                        "elastic_strain_yz",
                                        "elastic_strain_xz",
                                        "plastic_strain",
                                        "plastic_dissipation",
                                        "damage",
                                        "kappa",
                                        "damage_dissipation",
                                        "damage_driver",
                                        "nonlocal_driver"};
      if (parameters.removal_stretch > 0)
        for (const char *axis : {"x", "y", "z"})
          names.push_back(std::string("axis_stretch_") + axis);
      return names;
    }


    void
    Chalk::initialize_state(const SymmetricTensor<2, 3> &initial_stress,
                            double                      *state) const
    {
      store_symmetric(elasticity.strain(initial_stress), state);
      for (unsigned int i = plastic_strain; i < n_state; ++i)
        state[i] = 0.;
      if (parameters.removal_stretch > 0)
        for (unsigned int i = 0; i < 3; ++i)
          state[axis_stretch + i] = 1.;
    }


    double
    Chalk::nonlocal_length() const
    {
      return parameters.nonlocal_weight == NonlocalWeight::local
               ? 0.
               : parameters.length_scale;
    }


    bool
    Chalk::damage_can_change(const double *state) const
    {
      return state[damage_variable] < 1.;
    }


    void
    Chalk::set_fully_damaged(double *state) const
    {
      state[damage_variable] = 1.;
    }


    void
    Chalk::set_initial_damage(double *state, const double d) const
    {
      AssertThrow(d >= 0. && d <= 1.,
                  ExcMessage("Chalk: an initial damage must lie in [0, 1], "
                             "got " +
                             std::to_string(d) + "."));
      if (d <= 0.)
        return;
      // The same rounding as update_damage(); the kappa of d = 1 is the
      // smallest history that the rounding turns into d = 1.
      const bool full = d > 1. - 1e-6;
      state[kappa]    = kappa_from_damage(full ? 1. - 1e-6 : d);
      // d(kappa) may exceed d by round-off; taking the larger keeps an
      // unloaded point exactly where it is in update_damage().
      state[damage_variable] =
        full ? 1. : std::max(d, damage_from_kappa(state[kappa]));
    }


    double
    Chalk::kappa_from_damage(const double d) const
    {
      AssertThrow(d >= 0. && d < 1.,
                  ExcMessage("Chalk::kappa_from_damage: d must lie in [0, "
                             "1)."));
      // With x = kappa/sigma_f: g(x) = ln x + 2 (x - 1)/(eta - 1) =
      // -ln(1 - d), increasing from g(1) = 0; ln x >= 0 bounds x from
      // above. Bisection: set-up code, 100 halvings reach round-off.
      const double target = -std::log1p(-d);
      const double c      = 2. / (parameters.ductility - 1.);
      double       lo = 1., hi = 1. + target / c;
      for (unsigned int i = 0; i < 100 && hi - lo > 1e-16 * hi; ++i)
        {
          const double mid = 0.5 * (lo + hi);
          if (std::log(mid) + c * (mid - 1.) < target)
            lo = mid;
          else
            hi = mid;
        }
      return 0.5 * (lo + hi) * parameters.initiation_stress;
    }


    double
    Chalk::local_driver(const SymmetricTensor<2, 3> &effective_stress) const
    {
      const SymmetricTensor<2, 3> s  = deviator(effective_stress);
      const double                I1 = trace(effective_stress);
      return std::max(0.,
                      driver_scale *
                        (std::sqrt(1.5 * (s * s)) + I1 * driver_friction));
    }


    double
    Chalk::damage_from_kappa(const double k) const
    {
      const double sf = parameters.initiation_stress;
      if (k <= sf)
        return 0.;
      return 1. -
             sf / k *
               std::exp(-2. * (k - sf) / ((parameters.ductility - 1.) * sf));
    }


    SymmetricTensor<2, 3>
    Chalk::degrade(const SymmetricTensor<2, 3> &effective_stress,
                   const double                 d) const
    {
      const double p = trace(effective_stress) / 3.;
      const double gp =
        1. - (1. - (p > 0. ? parameters.residual_tensile_ratio
                           : parameters.residual_compressive_ratio)) *
               d;
      const double gs = 1. - (1. - parameters.residual_shear_ratio) * d;
      return gp * p * unit_symmetric_tensor<3>() +
             gs * deviator(effective_stress);
    }


    void
    Chalk::update(const MaterialBatch &batch) const
    {
      const double          rg = parameters.residual_shear_ratio;
      SpectralDecomposition trial[hencky_chunk];
      for (unsigned int q = 0; q < batch.n; ++q)
        {
          double *const          state = batch.state[q];
          const double           d     = state[damage_variable];
          SpectralDecomposition &e     = hencky_trial_strain_by_chunks(
            batch.delta_F, batch.state, batch.n, q, trial);
          // Effective (undamaged) principal Kirchhoff stress.
          std::array<double, 3> tau = elasticity.principal_stress(e.values);
          const std::array<double, 3> tau_trial = tau;
          std::array<double, 3>       dep       = {{0., 0., 0.}};
          if (batch.inelastic.plasticity &&
              mohr_coulomb.return_stress(tau) !=
                MohrCoulombReturn::Region::elastic)
            {
              const std::array<double, 3> eps =
                elasticity.principal_strain(tau);
              double norm2 = 0.;
              for (unsigned int i = 0; i < 3; ++i)
                {
                  dep[i] = e.values[i] - eps[i];
                  norm2 += dep[i] * dep[i];
                  e.values[i] = eps[i];
                }
              state[plastic_strain] += std::sqrt(2. / 3. * norm2);
            }
          store_composed(e.values, e.vectors, state + elastic_strain);

          const double J = determinant(batch.F[q]);
          // Driver from the undamaged Cauchy stress tau / J, after the
          // plastic correction or of the trial; fully damaged points
          // contribute nothing.
          const std::array<double, 3> &tau_y =
            (parameters.driving_stress == DrivingStress::trial) ? tau_trial
                                                                : tau;
          const double Y       = (d >= 1.)
                                   ? 0.
                                   : driver_from_principal(
                                 {{tau_y[0] / J, tau_y[1] / J, tau_y[2] / J}},
                                 driver_scale,
                                 driver_friction);
          state[damage_driver] = Y;
          if (batch.damage_driver != nullptr)
            batch.damage_driver[q] = Y;

          // Degradation with d_n and the tension/compression split.
          const double p = (tau[0] + tau[1] + tau[2]) / 3.;
          const double gp =
            1. - (1. - (p > 0. ? parameters.residual_tensile_ratio
                               : parameters.residual_compressive_ratio)) *
                   d;
          const double          gs = 1. - (1. - rg) * d;
          std::array<double, 3> tau_d;
          for (unsigned int i = 0; i < 3; ++i)
            tau_d[i] = gp * p + gs * (tau[i] - p);
          // Plastic dissipation with the stress that actually acts.
          state[plastic_dissipation] +=
            tau_d[0] * dep[0] + tau_d[1] * dep[1] + tau_d[2] * dep[2];
          compose_scaled_into(tau_d, e.vectors, 1. / J, batch.stress[q]);
          // The extent along each axis follows the normal part of the
          // increment, as the authors' domain lengths follow the grid
          // velocity at the domain's face midpoints.
          if (parameters.removal_stretch > 0)
            for (unsigned int i = 0; i < 3; ++i)
              state[axis_stretch + i] *= batch.delta_F[q][i][i];
          if (batch.stored_energy != nullptr)
            batch.stored_energy[q] =
              0.5 * (tau_d[0] * e.values[0] + tau_d[1] * e.values[1] +
                     tau_d[2] * e.values[2]);
        }
    }


    void
    Chalk::update_damage(const double nonlocal_driver,
                         const double dt,
                         double      *state) const
    {
      const double d_n              = state[damage_variable];
      state[Chalk::nonlocal_driver] = nonlocal_driver;
      if (d_n >= 1.)
        return;
      // Exact integration of kappa_dot = <Ybar - kappa>/tau over the step
      // with Ybar constant: unconditionally stable, rate bounded by 1/tau.
      const double tau    = parameters.characteristic_time;
      const double factor = (tau > 0.) ? -std::expm1(-dt / tau) : 1.;
      double      &k      = state[kappa];
      k += factor * std::max(0., nonlocal_driver - k);

      double d = std::max(d_n, damage_from_kappa(k));
      if (d > 1. - 1e-6)
        d = 1.;
      if (d > d_n)
        {
          // Energy released: -dpsi/dd * (d - d_n) at the current elastic
          // strain (an end-point rule; its error is O(strain increment)).
          const SymmetricTensor<2, 3> eps =
            load_symmetric(state + elastic_strain);
          const double tr      = trace(eps);
          const double psi_vol = 0.5 * elasticity.bulk_modulus() * tr * tr;
          const SymmetricTensor<2, 3> e = deviator(eps);
          const double psi_dev          = elasticity.shear_modulus() * (e * e);
          const double r = (tr > 0.) ? parameters.residual_tensile_ratio
                                     : parameters.residual_compressive_ratio;
          state[damage_dissipation] +=
            (d - d_n) * ((1. - r) * psi_vol +
                         (1. - parameters.residual_shear_ratio) * psi_dev);
          state[damage_variable] = d;
        }
    }
  } // namespace materials
} // namespace scarp
