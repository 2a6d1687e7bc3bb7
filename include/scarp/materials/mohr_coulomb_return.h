#ifndef scarp_materials_mohr_coulomb_return_h
#define scarp_materials_mohr_coulomb_return_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <scarp/materials/isotropic_elasticity.h>

#include <array>

namespace scarp
{
  namespace materials
  {
    /**
     * @brief Mohr-Coulomb return mapping in principal stress space after
     * Clausen, Damkilde & Andersen (2006, 2007): closed-form returns to the
     * yield plane, to its two edges and to the apex, selected from the
     * position of the trial point relative to the boundary planes.
     *
     * Tension positive, principal stresses ordered s1 >= s2 >= s3:
     * yield f = k s1 - s3 - sigma_c, k = (1 + sin phi)/(1 - sin phi),
     * sigma_c = 2 c sqrt(k); plastic potential g = m s1 - s3,
     * m = (1 + sin psi)/(1 - sin psi). The stresses are the (Kirchhoff)
     * principal stresses of a Hencky model, whose principal elastic
     * stiffness is that of @p elasticity.
     *
     * The return is exact (no iteration); works with c = 0 (sand) and with
     * phi = 0 (Tresca, no apex).
     */
    class MohrCoulombReturn
    {
    public:
      /// Which part of the yield surface a trial point returned to.
      enum class Region
      {
        elastic,
        plane,
        edge_1, ///< s1 = s2
        edge_2, ///< s2 = s3
        apex
      };

      /**
       * @brief Strength parameters of the Mohr-Coulomb surface.
       */
      struct Parameters
      {
        /// Cohesion c [Pa]; Joss Bay default 1 MPa (see doc/materials.md).
        double cohesion = 1.e6;
        /// Friction angle phi [deg].
        double friction_angle = 50.;
        /// Dilation angle psi [deg], psi <= phi.
        double dilation_angle = 0.;

        /// Declare `Cohesion`, `Friction angle`, `Dilation angle` in the
        /// current subsection.
        static void
        declare_parameters(ParameterHandler &prm);

        /// Read and check them (current subsection).
        void
        parse_parameters(ParameterHandler &prm);

        /// Throw ExcMessage naming the entry if a value is impossible.
        void
        check() const;
      };

      MohrCoulombReturn() = default;

      MohrCoulombReturn(const IsotropicElasticity &elasticity,
                        const Parameters          &parameters);

      /// Yield function of ordered principal stresses, k s1 - s3 - sigma_c.
      double
      yield_function(const std::array<double, 3> &s) const
      {
        return k * s[0] - s[2] - sigma_c;
      }

      /// Yield function for principal stresses in any order (the largest of
      /// the six Mohr-Coulomb planes).
      double
      yield_function_unordered(const std::array<double, 3> &s) const;

      /**
       * Return the ordered principal trial stresses @p s (s[0] >= s[1] >=
       * s[2]) to the yield surface in place; returns the region used. The
       * corrected stresses stay ordered.
       */
      Region
      return_stress(std::array<double, 3> &s) const;

      double
      friction_coefficient_k() const
      {
        return k;
      }

      double
      dilation_coefficient_m() const
      {
        return m;
      }

      /// Uniaxial compressive strength sigma_c = 2 c sqrt(k) [Pa].
      double
      compressive_strength() const
      {
        return sigma_c;
      }

      /// Whether the surface has an apex (phi > 0).
      bool
      has_apex() const
      {
        return with_apex;
      }

      /// Hydrostatic stress of the apex sigma_c / (k - 1) [Pa].
      double
      apex_stress() const
      {
        return apex;
      }

    private:
      double k         = 1.;
      double m         = 1.;
      double sigma_c   = 0.;
      double apex      = 0.;
      bool   with_apex = false;

      /// Plane return direction r_p = D dg / (df . D dg).
      Tensor<1, 3> r_p;
      /// Edge directions l1 = (1,1,k), l2 = (1,k,k) and their points at
      /// s1 = 0, o1 = (0,0,-sigma_c), o2 = (0,-sigma_c,-sigma_c).
      Tensor<1, 3> l1, l2, o1, o2;
      /// Normals of the planes spanned by the two return directions of
      /// each edge, and the denominators N.l of the line parameter.
      Tensor<1, 3> n1, n2;
      double       n1_dot_l1 = 1., n2_dot_l2 = 1.;
    };
  } // namespace materials
} // namespace scarp

#endif
