#include <deal.II/base/exceptions.h>

#include <scarp/materials/point_driver.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>

namespace scarp
{
  namespace materials
  {
    void
    PointDriver::Parameters::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Type",
                        "uniaxial tension",
                        Patterns::Selection("uniaxial tension|uniaxial "
                                            "compression|plane-strain "
                                            "compression|simple shear"),
                        "Deformation path: uniaxial tension or compression "
                        "(axial x, lateral stresses = -Confining stress), "
                        "plane-strain compression (axial y, F_zz = 1, "
                        "sigma_xx = -Confining stress) or simple shear "
                        "(F_xy = gamma).");
      prm.declare_entry("Max strain",
                        "1e-3",
                        Patterns::Double(0.),
                        "Final axial logarithmic strain magnitude, or final "
                        "shear gamma for simple shear [-], > 0.");
      prm.declare_entry("Steps",
                        "1000",
                        Patterns::Integer(1),
                        "Number of equal strain increments, >= 1.");
      prm.declare_entry("Confining stress",
                        "0",
                        Patterns::Double(0.),
                        "Confining pressure p >= 0 [Pa]: the point starts "
                        "from the stress -p I and the lateral "
                        "stress-controlled components are held at -p.");
      prm.declare_entry("Duration",
                        "1e4",
                        Patterns::Double(0.),
                        "Physical time of the whole path [s], > 0 (sets dt "
                        "for the delayed damage history: dt = Duration / "
                        "Steps).");
      prm.declare_entry("Output file",
                        "point_curve.csv",
                        Patterns::FileName(Patterns::FileName::output),
                        "CSV file written with the curve.");
    }


    void
    PointDriver::Parameters::parse_parameters(ParameterHandler &prm)
    {
      const std::string t = prm.get("Type");
      type             = (t == "uniaxial tension") ? PathType::uniaxial_tension
                         : (t == "uniaxial compression") ? PathType::uniaxial_compression
                         : (t == "plane-strain compression")
                           ? PathType::plane_strain_compression
                           : PathType::simple_shear;
      max_strain       = prm.get_double("Max strain");
      n_steps          = prm.get_integer("Steps");
      confining_stress = prm.get_double("Confining stress");
      duration         = prm.get_double("Duration");
      output_file      = prm.get("Output file");
      AssertThrow(max_strain > 0.,
                  ExcMessage("Path: 'Max strain' must be > 0."));
      AssertThrow(duration > 0., ExcMessage("Path: 'Duration' must be > 0 s."));
    }


    PointDriver::PointDriver(const Material   &material,
                             const Parameters &parameters)
      : material(material)
      , parameters(parameters)
    {
    }


    std::vector<PointDriver::Record>
    PointDriver::run() const
    {
      const unsigned int  n_state = material.n_state_variables();
      std::vector<double> state(n_state), trial_state(n_state);
      double *const       trial_ptr = trial_state.data();

      // Indices of state variables reported when the model has them.
      const std::vector<std::string> names = material.state_variable_names();
      const auto index_of = [&](const std::string &name) -> int {
        const auto it = std::find(names.begin(), names.end(), name);
        return it == names.end() ? -1 : int(it - names.begin());
      };
      const int i_kappa   = index_of("kappa");
      const int i_plastic = index_of("plastic_strain");

      const double                p      = parameters.confining_stress;
      const SymmetricTensor<2, 3> sigma0 = -p * unit_symmetric_tensor<3>();
      material.initialize_state(sigma0, state.data());

      // Axial direction, stress-controlled lateral directions and sign.
      unsigned int              axial = 0;
      std::vector<unsigned int> lateral;
      double                    sign = 1.;
      switch (parameters.type)
        {
          case PathType::uniaxial_tension:
            lateral = {1, 2};
            break;
          case PathType::uniaxial_compression:
            lateral = {1, 2};
            sign    = -1.;
            break;
          case PathType::plane_strain_compression:
            axial   = 1;
            lateral = {0};
            sign    = -1.;
            break;
          case PathType::simple_shear:
            break;
        }
      const unsigned int n_lat = lateral.size();

      const double dt = parameters.duration / parameters.n_steps;
      // Stress tolerance of the lateral control: round-off of the stress is
      // about 1e-16 M per unit strain.
      const double M = material.p_wave_modulus();

      Tensor<2, 3>          F      = unit_symmetric_tensor<3>();
      SymmetricTensor<2, 3> stress = sigma0;
      std::array<double, 2> e_lat = {{0., 0.}}, e_lat_old = {{0., 0.}};

      Tensor<2, 3>          trial_F, delta_F;
      SymmetricTensor<2, 3> trial_stress;
      double                energy = 0., driver = 0.;
      MaterialBatch         batch;
      batch.n             = 1;
      batch.dt            = dt;
      batch.delta_F       = &delta_F;
      batch.F             = &trial_F;
      batch.state         = &trial_ptr;
      batch.stress        = &trial_stress;
      batch.stored_energy = &energy;
      batch.damage_driver = material.has_damage() ? &driver : nullptr;

      // Evaluate the step for the lateral log strains e: returns residuals.
      const auto evaluate = [&](const double                 strain,
                                const std::array<double, 2> &e) {
        trial_F = unit_symmetric_tensor<3>();
        if (parameters.type == PathType::simple_shear)
          trial_F[0][1] = strain;
        else
          {
            trial_F[axial][axial] = std::exp(strain);
            for (unsigned int l = 0; l < n_lat; ++l)
              trial_F[lateral[l]][lateral[l]] = std::exp(e[l]);
          }
        delta_F = trial_F * invert(F);
        std::copy(state.begin(), state.end(), trial_state.begin());
        trial_stress = stress;
        material.update(batch);
        std::array<double, 2> r = {{0., 0.}};
        for (unsigned int l = 0; l < n_lat; ++l)
          r[l] = trial_stress[lateral[l]][lateral[l]] + p;
        return r;
      };

      std::vector<Record> records;
      records.reserve(parameters.n_steps + 1);
      const auto record = [&](const double       time,
                              const double       strain,
                              const double       work,
                              const unsigned int iterations) {
        Record r;
        r.time           = time;
        r.strain         = strain;
        r.F              = F;
        r.stress         = stress;
        r.damage         = material.damage(state.data());
        r.kappa          = i_kappa >= 0 ? state[i_kappa] : 0.;
        r.plastic_strain = i_plastic >= 0 ? state[i_plastic] : 0.;
        r.damage_driver  = driver;
        r.stored_energy  = energy;
        const DissipatedEnergy dissipated =
          material.dissipated_energy(state.data());
        r.plastic_dissipation = dissipated.plastic;
        r.damage_dissipation  = dissipated.damage;
        r.external_work       = work;
        r.iterations          = iterations;
        records.push_back(r);
      };
      record(0., 0., 0., 0);

      double work = 0.;
      for (unsigned int step = 1; step <= parameters.n_steps; ++step)
        {
          const double strain =
            sign * parameters.max_strain * step / parameters.n_steps;
          // Extrapolated guess of the lateral strains.
          std::array<double, 2> e = {
            {2. * e_lat[0] - e_lat_old[0], 2. * e_lat[1] - e_lat_old[1]}};
          std::array<double, 2> r  = evaluate(strain, e);
          unsigned int          it = 0;
          for (; n_lat > 0 && it < 50; ++it)
            {
              double scale = std::abs(p);
              for (unsigned int i = 0; i < 3; ++i)
                scale = std::max(scale, std::abs(trial_stress[i][i]));
              const double tol = 1e-12 * M + 1e-11 * scale;
              if (std::abs(r[0]) <= tol && std::abs(r[1]) <= tol)
                break;
              // Newton with a finite-difference Jacobian (the response is
              // piecewise smooth: elastic, plastic, damaged).
              const double h        = 1e-8;
              double       Jm[2][2] = {{1., 0.}, {0., 1.}};
              for (unsigned int j = 0; j < n_lat; ++j)
                {
                  std::array<double, 2> ep = e;
                  ep[j] += h;
                  const std::array<double, 2> rp = evaluate(strain, ep);
                  for (unsigned int i = 0; i < n_lat; ++i)
                    Jm[i][j] = (rp[i] - r[i]) / h;
                }
              const double det = Jm[0][0] * Jm[1][1] - Jm[0][1] * Jm[1][0];
              AssertThrow(std::isfinite(det) && det != 0.,
                          ExcMessage("PointDriver: singular lateral "
                                     "stiffness at step " +
                                     std::to_string(step) + "."));
              e[0] -= (Jm[1][1] * r[0] - Jm[0][1] * r[1]) / det;
              e[1] -= (Jm[0][0] * r[1] - Jm[1][0] * r[0]) / det;
              r = evaluate(strain, e);
            }

          // Work per reference volume: tau : d dt, trapezoidal rule with
          // L dt = (F_n+1 - F_n) F_mid^-1.
          const Tensor<2, 3> L_dt = (trial_F - F) * invert(0.5 * (trial_F + F));
          const SymmetricTensor<2, 3> d_dt = symmetrize(L_dt);
          work +=
            0.5 *
            (determinant(F) * stress + determinant(trial_F) * trial_stress) *
            d_dt;

          // Accept the step.
          std::copy(trial_state.begin(), trial_state.end(), state.begin());
          stress    = trial_stress;
          F         = trial_F;
          e_lat_old = e_lat;
          e_lat     = e;
          if (material.has_damage())
            material.update_damage(driver, dt, state.data());
          record(step * dt, strain, work, it);
        }
      return records;
    }


    void
    PointDriver::write_csv(const std::vector<Record> &records,
                           std::ostream              &out)
    {
      out << "time,strain,F_xx,F_yy,F_zz,F_xy,sigma_xx,sigma_yy,sigma_zz,"
             "sigma_xy,sigma_yz,sigma_xz,damage,kappa,plastic_strain,"
             "damage_driver,stored_energy,plastic_dissipation,"
             "damage_dissipation,external_work,iterations\n";
      out << std::setprecision(12);
      for (const Record &r : records)
        out << r.time << ',' << r.strain << ',' << r.F[0][0] << ',' << r.F[1][1]
            << ',' << r.F[2][2] << ',' << r.F[0][1] << ',' << r.stress[0][0]
            << ',' << r.stress[1][1] << ',' << r.stress[2][2] << ','
            << r.stress[0][1] << ',' << r.stress[1][2] << ',' << r.stress[0][2]
            << ',' << r.damage << ',' << r.kappa << ',' << r.plastic_strain
            << ',' << r.damage_driver << ',' << r.stored_energy << ','
            << r.plastic_dissipation << ',' << r.damage_dissipation << ','
            << r.external_work << ',' << r.iterations << '\n';
    }
  } // namespace materials
} // namespace scarp
