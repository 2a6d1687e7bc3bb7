#ifndef scarp_materials_point_driver_h
#define scarp_materials_point_driver_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <scarp/materials/material.h>

#include <ostream>
#include <string>
#include <vector>

namespace scarp
{
  namespace materials
  {
    /**
     * @brief Drives a single material point along a prescribed deformation
     * path and records the stress-strain curve (calibration and tests).
     *
     * Paths (axes fixed, so logarithmic strains are ln of the stretches):
     * - uniaxial tension / compression: axial log strain eps_xx from 0 to
     *   +-Max strain; the lateral stresses sigma_yy = sigma_zz = -Confining
     *   stress are enforced by Newton iterations on the lateral stretches;
     * - plane-strain compression: eps_yy from 0 to -Max strain, F_zz = 1,
     *   sigma_xx = -Confining stress (Newton on F_xx);
     * - simple shear: F = I + gamma e_x (x) e_y, gamma from 0 to Max strain.
     * The point starts from the isotropic stress -Confining stress I. Damage
     * models get update_damage(Y, dt, state) with their own local driver Y
     * (local model) after every converged step.
     */
    class PointDriver
    {
    public:
      enum class PathType
      {
        uniaxial_tension,
        uniaxial_compression,
        plane_strain_compression,
        simple_shear
      };

      /**
       * @brief Path entries (subsection `Path`).
       */
      struct Parameters
      {
        PathType     type             = PathType::uniaxial_tension;
        double       max_strain       = 1.e-3;
        unsigned int n_steps          = 1000;
        double       confining_stress = 0.;
        double       duration         = 1.e4;
        std::string  output_file      = "point_curve.csv";

        static void
        declare_parameters(ParameterHandler &prm);

        void
        parse_parameters(ParameterHandler &prm);
      };

      /**
       * @brief One row of the curve.
       */
      struct Record
      {
        double                time   = 0.;
        double                strain = 0.;
        Tensor<2, 3>          F;
        SymmetricTensor<2, 3> stress;
        double                damage              = 0.;
        double                kappa               = 0.;
        double                plastic_strain      = 0.;
        double                damage_driver       = 0.;
        double                stored_energy       = 0.;
        double                plastic_dissipation = 0.;
        double                damage_dissipation  = 0.;
        /// int tau : d dt per reference volume (trapezoidal rule).
        double external_work = 0.;
        /// Newton iterations of the step (stress-controlled components).
        unsigned int iterations = 0;
      };

      PointDriver(const Material &material, const Parameters &parameters);

      /// Run the path; returns n_steps + 1 records (the first is the start).
      std::vector<Record>
      run() const;

      /// Write records as CSV with a header line.
      static void
      write_csv(const std::vector<Record> &records, std::ostream &out);

    private:
      const Material  &material;
      const Parameters parameters;
    };
  } // namespace materials
} // namespace scarp

#endif
