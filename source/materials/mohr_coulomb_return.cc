#include <deal.II/base/exceptions.h>
#include <deal.II/base/numbers.h>

#include <scarp/materials/mohr_coulomb_return.h>

#include <algorithm>
#include <cmath>

namespace scarp
{
  namespace materials
  {
    void
    MohrCoulombReturn::Parameters::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Cohesion",
                        "1e6",
                        Patterns::Double(0.),
                        "Cohesion c [Pa], >= 0 (0: cohesionless, e.g. sand). "
                        "Joss Bay chalk: 1e6 (the paper prints 1000 MPa; "
                        "its authors' code uses 1 MPa).");
      prm.declare_entry("Friction angle",
                        "50",
                        Patterns::Double(0., 90.),
                        "Friction angle phi [deg], in [0, 90). Joss Bay "
                        "chalk: 50.");
      prm.declare_entry("Dilation angle",
                        "0",
                        Patterns::Double(0., 90.),
                        "Dilation angle psi [deg], in [0, 90) and not larger "
                        "than the friction angle. psi = phi is associated "
                        "flow. Joss Bay chalk: 0.");
    }


    void
    MohrCoulombReturn::Parameters::parse_parameters(ParameterHandler &prm)
    {
      cohesion       = prm.get_double("Cohesion");
      friction_angle = prm.get_double("Friction angle");
      dilation_angle = prm.get_double("Dilation angle");
      check();
    }


    void
    MohrCoulombReturn::Parameters::check() const
    {
      AssertThrow(cohesion >= 0.,
                  ExcMessage("Material: 'Cohesion' must be >= 0 Pa."));
      AssertThrow(friction_angle >= 0. && friction_angle < 90.,
                  ExcMessage("Material: 'Friction angle' must lie in "
                             "[0, 90) deg, got " +
                             std::to_string(friction_angle) + "."));
      AssertThrow(dilation_angle >= 0. && dilation_angle < 90.,
                  ExcMessage("Material: 'Dilation angle' must lie in "
                             "[0, 90) deg, got " +
                             std::to_string(dilation_angle) + "."));
      AssertThrow(dilation_angle <= friction_angle,
                  ExcMessage("Material: 'Dilation angle' (" +
                             std::to_string(dilation_angle) +
                             " deg) must not exceed 'Friction angle' (" +
                             std::to_string(friction_angle) + " deg)."));
    }


    MohrCoulombReturn::MohrCoulombReturn(const IsotropicElasticity &elasticity,
                                         const Parameters          &parameters)
    {
      parameters.check();
      const double deg  = numbers::PI / 180.;
      const double sphi = std::sin(parameters.friction_angle * deg);
      const double spsi = std::sin(parameters.dilation_angle * deg);
      k                 = (1. + sphi) / (1. - sphi);
      m                 = (1. + spsi) / (1. - spsi);
      sigma_c           = 2. * parameters.cohesion * std::sqrt(k);
      // phi = 0 (Tresca): the edges are parallel to the hydrostatic axis.
      with_apex = (k - 1. > 1e-12);
      apex      = with_apex ? sigma_c / (k - 1.) : 0.;

      // Principal elastic stiffness applied to a vector.
      const auto D = [&](const Tensor<1, 3> &v) {
        const std::array<double, 3> s =
          elasticity.principal_stress({{v[0], v[1], v[2]}});
        return Tensor<1, 3>({s[0], s[1], s[2]});
      };
      const Tensor<1, 3> df({k, 0., -1.});
      // Return directions of the three planes active in the ordered sextant:
      // a: k s1 - s3, b: k s2 - s3 (s2 major), c: k s1 - s2 (s2 minor).
      const Tensor<1, 3> r_a = D(Tensor<1, 3>({m, 0., -1.}));
      const Tensor<1, 3> r_b = D(Tensor<1, 3>({0., m, -1.}));
      const Tensor<1, 3> r_c = D(Tensor<1, 3>({m, -1., 0.}));
      r_p                    = r_a / (df * r_a);

      l1 = Tensor<1, 3>({1., 1., k});
      l2 = Tensor<1, 3>({1., k, k});
      o1 = Tensor<1, 3>({0., 0., -sigma_c});
      o2 = Tensor<1, 3>({0., -sigma_c, -sigma_c});
      // The stress returned to an edge is o + t l, and sigma_B - (o + t l)
      // lies in the span of the two return directions: N . (sigma_B - o - t
      // l) = 0 with N normal to that span.
      n1        = cross_product_3d(r_a, r_b);
      n2        = cross_product_3d(r_a, r_c);
      n1_dot_l1 = n1 * l1;
      n2_dot_l2 = n2 * l2;
    }


    double
    MohrCoulombReturn::yield_function_unordered(
      const std::array<double, 3> &s) const
    {
      const double smax = std::max({s[0], s[1], s[2]});
      const double smin = std::min({s[0], s[1], s[2]});
      return k * smax - smin - sigma_c;
    }


    MohrCoulombReturn::Region
    MohrCoulombReturn::return_stress(std::array<double, 3> &s) const
    {
      const double f = yield_function(s);
      if (f <= 0.)
        return Region::elastic;

      // Plane return along r_p. Its ordering decides the region: p_I =
      // s1 - s2 and p_II = s2 - s3 of the plane return are affine in the
      // trial stress and vanish exactly on the boundary planes of
      // Clausen et al. (through edge 1 resp. edge 2, spanned with r_p).
      const double c1   = s[0] - f * r_p[0];
      const double c2   = s[1] - f * r_p[1];
      const double c3   = s[2] - f * r_p[2];
      const double p_I  = c1 - c2;
      const double p_II = c2 - c3;
      if (p_I >= 0. && p_II >= 0.)
        {
          s = {{c1, c2, c3}};
          return Region::plane;
        }

      const Tensor<1, 3> sB({s[0], s[1], s[2]});
      // Line parameters t = s1 on the edge; the apex is at t = apex, valid
      // edge points have t <= apex.
      if (p_I < 0.)
        {
          const double t1 = n1 * (sB - o1) / n1_dot_l1;
          if (!with_apex || t1 < apex)
            {
              s = {
                {o1[0] + t1 * l1[0], o1[1] + t1 * l1[1], o1[2] + t1 * l1[2]}};
              // Exact equality on the edge (round-off could swap them).
              s[1] = s[0];
              return Region::edge_1;
            }
        }
      if (p_II < 0.)
        {
          const double t2 = n2 * (sB - o2) / n2_dot_l2;
          if (!with_apex || t2 < apex)
            {
              s = {
                {o2[0] + t2 * l2[0], o2[1] + t2 * l2[1], o2[2] + t2 * l2[2]}};
              s[2] = s[1];
              return Region::edge_2;
            }
        }
      s = {{apex, apex, apex}};
      return Region::apex;
    }
  } // namespace materials
} // namespace scarp
