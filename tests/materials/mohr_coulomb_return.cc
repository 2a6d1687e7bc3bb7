// Mohr-Coulomb closed forms (verification item 8): plane-strain compression
// yields at s1 = s3 N_phi + 2 c sqrt(N_phi) (compression positive); returns
// to plane, both edges and apex land on the surface in the right region
// with non-negative multipliers; psi = 0 gives zero plastic volume change;
// associated returns equal a brute-force closest point in the energy norm.

#include <deal.II/base/numbers.h>

#include <scarp/materials/mohr_coulomb.h>
#include <scarp/materials/mohr_coulomb_return.h>
#include <scarp/materials/point_driver.h>

#include "test_tools.h"

#include <array>
#include <map>
#include <random>

using namespace dealii;
using namespace scarp::materials;
using scarp_test::check;
using scarp_test::check_close;
using Region = MohrCoulombReturn::Region;
using Vec    = std::array<double, 3>;

namespace
{
  Tensor<1, 3>
  D_times(const IsotropicElasticity &el, const Tensor<1, 3> &v)
  {
    const Vec s = el.principal_stress({{v[0], v[1], v[2]}});
    return Tensor<1, 3>({s[0], s[1], s[2]});
  }

  /// Energy norm^2 of a principal stress difference, ds . C ds.
  double
  energy_norm2(const IsotropicElasticity &el, const Tensor<1, 3> &ds)
  {
    const Vec e = el.principal_strain({{ds[0], ds[1], ds[2]}});
    return ds[0] * e[0] + ds[1] * e[1] + ds[2] * e[2];
  }

  /// The six Mohr-Coulomb planes k s_i - s_j - sigma_c (i != j) and their
  /// flow directions m e_i - e_j.
  struct Planes
  {
    std::array<Tensor<1, 3>, 6> normal, flow;
    Planes(const double k, const double m)
    {
      unsigned int n = 0;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          if (i != j)
            {
              normal[n]    = Tensor<1, 3>();
              flow[n]      = Tensor<1, 3>();
              normal[n][i] = k;
              normal[n][j] = -1.;
              flow[n][i]   = m;
              flow[n][j]   = -1.;
              ++n;
            }
    }
  };

  /**
   * Brute force: closest point (energy norm) of the convex set {f_i <= 0,
   * i = 1..6} by enumerating every active set of 1, 2 or 3 planes, solving
   * the equality-constrained problem s = sB - D A^T mu, A s = sigma_c, and
   * keeping the feasible candidate of least distance.
   */
  Tensor<1, 3>
  brute_force_closest_point(const IsotropicElasticity &el,
                            const double               k,
                            const double               sigma_c,
                            const Tensor<1, 3>        &sB)
  {
    const Planes planes(k, k);
    double       best = std::numeric_limits<double>::max();
    Tensor<1, 3> best_s;
    const double scale = sB.norm() + sigma_c;
    for (unsigned int mask = 1; mask < 64; ++mask)
      {
        std::vector<unsigned int> act;
        for (unsigned int i = 0; i < 6; ++i)
          if (mask & (1u << i))
            act.push_back(i);
        if (act.size() > 3)
          continue;
        const unsigned int n = act.size();
        // G = A D A^T (n x n), rhs = A sB - sigma_c.
        double G[3][3] = {}, rhs[3] = {};
        for (unsigned int a = 0; a < n; ++a)
          {
            rhs[a] = planes.normal[act[a]] * sB - sigma_c;
            for (unsigned int b = 0; b < n; ++b)
              G[a][b] =
                planes.normal[act[a]] * D_times(el, planes.normal[act[b]]);
          }
        // Pad with G_00 on the diagonal so that det(Gt) scales like G^3.
        Tensor<2, 3> Gt = G[0][0] * unit_symmetric_tensor<3>();
        for (unsigned int a = 0; a < n; ++a)
          for (unsigned int b = 0; b < n; ++b)
            Gt[a][b] = G[a][b];
        const double det = determinant(Gt);
        if (std::abs(det) < 1e-8 * std::pow(Gt.norm(), 3))
          continue; // dependent planes (e.g. three through the apex)
        const Tensor<1, 3> mu =
          invert(Gt) * Tensor<1, 3>({rhs[0], rhs[1], rhs[2]});
        Tensor<1, 3> s = sB;
        for (unsigned int a = 0; a < n; ++a)
          s -= mu[a] * D_times(el, planes.normal[act[a]]);
        bool feasible = true;
        for (unsigned int i = 0; i < 6; ++i)
          feasible =
            feasible && (planes.normal[i] * s - sigma_c <= 1e-10 * scale);
        if (!feasible)
          continue;
        const double dist = energy_norm2(el, sB - s);
        if (dist < best)
          {
            best   = dist;
            best_s = s;
          }
      }
    return best_s;
  }

  /// Check one return: on the surface, ordered, in the region it reports,
  /// and sB - s = sum of non-negative multipliers times D dg of the planes
  /// active in that region. Returns the region.
  Region
  check_return(const MohrCoulombReturn   &mc,
               const IsotropicElasticity &el,
               const Vec                 &trial,
               Vec                       &s,
               unsigned int              &failures)
  {
    s                   = trial;
    const Region region = mc.return_stress(s);
    const double scale =
      std::abs(trial[0]) + std::abs(trial[2]) + mc.compressive_strength();
    const double k = mc.friction_coefficient_k(),
                 m = mc.dilation_coefficient_m();
    bool ok        = true;
    // On the surface: |f| ~ round-off of the closed forms, 1e-10 relative.
    ok = ok && std::abs(mc.yield_function_unordered(s)) <= 1e-10 * scale;
    ok = ok && s[0] >= s[1] - 1e-12 * scale && s[1] >= s[2] - 1e-12 * scale;
    // Return directions active in the region (sorted sextant):
    // a = k s1 - s3, b = k s2 - s3, c = k s1 - s2.
    const Tensor<1, 3> ra = D_times(el, Tensor<1, 3>({m, 0., -1.}));
    const Tensor<1, 3> rb = D_times(el, Tensor<1, 3>({0., m, -1.}));
    const Tensor<1, 3> rc = D_times(el, Tensor<1, 3>({m, -1., 0.}));
    const Tensor<1, 3> ds({trial[0] - s[0], trial[1] - s[1], trial[2] - s[2]});
    Tensor<2, 3>       basis;
    for (unsigned int i = 0; i < 3; ++i)
      {
        basis[i][0] = ra[i];
        basis[i][1] = (region == Region::edge_2) ? rc[i] : rb[i];
        basis[i][2] = rc[i];
      }
    switch (region)
      {
        case Region::plane:
          ok = ok &&
               cross_product_3d(ds, ra).norm() <= 1e-10 * ds.norm() * ra.norm();
          ok = ok && ds * ra > 0.;
          break;
        case Region::edge_1:
        case Region::edge_2:
          {
            // ds in span(ra, rb|rc) with both multipliers >= 0.
            const Tensor<1, 3> r2  = (region == Region::edge_1) ? rb : rc;
            const Tensor<1, 3> nrm = cross_product_3d(ra, r2);
            ok = ok && std::abs(nrm * ds) <= 1e-10 * nrm.norm() * ds.norm();
            // Solve ds = ga ra + g2 r2 by least squares (2x2 normal eq.).
            const double a11 = ra * ra, a12 = ra * r2, a22 = r2 * r2;
            const double b1 = ra * ds, b2 = r2 * ds;
            const double det = a11 * a22 - a12 * a12;
            const double ga  = (a22 * b1 - a12 * b2) / det;
            const double g2  = (a11 * b2 - a12 * b1) / det;
            const double tol = -1e-10 * ds.norm() / ra.norm();
            ok               = ok && ga >= tol && g2 >= tol;
            ok = ok && (region == Region::edge_1 ? s[0] == s[1] : s[1] == s[2]);
            break;
          }
        case Region::apex:
          {
            // In the apex region: the returns to both edge lines would land
            // beyond the apex, i.e. the trial lies beyond the planes through
            // the apex spanned by (ra, rb) and by (ra, rc).
            const Tensor<1, 3> sa(
              {mc.apex_stress(), mc.apex_stress(), mc.apex_stress()});
            const Tensor<1, 3> sB({trial[0], trial[1], trial[2]});
            const Tensor<1, 3> n1 = cross_product_3d(ra, rb);
            const Tensor<1, 3> n2 = cross_product_3d(ra, rc);
            const double t1 = n1 * (sB - sa) / (n1 * Tensor<1, 3>({1., 1., k}));
            const double t2 = n2 * (sB - sa) / (n2 * Tensor<1, 3>({1., k, k}));
            const double tol = -1e-10 * scale;
            ok               = ok && t1 >= tol && t2 >= tol;
            // With dilation (m > 1) the correction is a non-negative
            // combination of the return directions D dg of the six planes
            // active at the apex (Caratheodory: of three of them). With
            // psi = 0 every D dg is deviatoric and no such combination
            // exists: the apex return is then the tension cut-off.
            if (m > 1. + 1e-12)
              {
                const Planes pl(k, m);
                bool         in_cone = false;
                for (unsigned int i = 0; i < 6; ++i)
                  for (unsigned int j = i + 1; j < 6; ++j)
                    for (unsigned int l = j + 1; l < 6; ++l)
                      {
                        Tensor<2, 3>       B;
                        const Tensor<1, 3> gi = D_times(el, pl.flow[i]),
                                           gj = D_times(el, pl.flow[j]),
                                           gl = D_times(el, pl.flow[l]);
                        for (unsigned int r = 0; r < 3; ++r)
                          {
                            B[r][0] = gi[r];
                            B[r][1] = gj[r];
                            B[r][2] = gl[r];
                          }
                        if (std::abs(determinant(B)) <
                            1e-8 * std::pow(B.norm(), 3))
                          continue;
                        const Tensor<1, 3> g = invert(B) * ds;
                        const double tolg    = -1e-10 * ds.norm() / ra.norm();
                        in_cone = in_cone || (g[0] >= tolg && g[1] >= tolg &&
                                              g[2] >= tolg);
                      }
                ok = ok && in_cone;
              }
            ok = ok && s[0] == s[2];
            break;
          }
        case Region::elastic:
          ok = (s == trial) && mc.yield_function(trial) <= 0.;
          break;
      }
    if (!ok)
      {
        ++failures;
        if (failures < 5)
          std::cout << "  bad return: region " << int(region) << " trial "
                    << trial[0] << ' ' << trial[1] << ' ' << trial[2] << " -> "
                    << s[0] << ' ' << s[1] << ' ' << s[2]
                    << " f = " << mc.yield_function_unordered(s) << std::endl;
      }
    return region;
  }
} // namespace

int
main()
{
  const IsotropicElasticity el(1e7, 0.3);

  // 1. Regions, surface, multipliers, for several friction/dilation pairs
  //    and a cohesionless material.
  std::mt19937                           rng(42);
  std::uniform_real_distribution<double> uni(-1., 1.);
  for (const auto &[c, phi, psi] : {std::make_tuple(1e4, 30., 0.),
                                    std::make_tuple(1e4, 30., 10.),
                                    std::make_tuple(1e4, 30., 30.),
                                    std::make_tuple(1e6, 50., 0.),
                                    std::make_tuple(0., 35., 5.),
                                    std::make_tuple(1e4, 0., 0.)})
    {
      MohrCoulombReturn::Parameters prm;
      prm.cohesion       = c;
      prm.friction_angle = phi;
      prm.dilation_angle = psi;
      const MohrCoulombReturn mc(el, prm);
      const double            sc = std::max(mc.compressive_strength(), 1e3);
      const double            a  = mc.apex_stress();
      std::map<Region, unsigned int> count;
      unsigned int                   failures = 0;
      double                         max_dvol = 0.;
      for (unsigned int n = 0; n < 20000; ++n)
        {
          Vec t = {{a + 3. * sc * uni(rng),
                    a + 3. * sc * uni(rng),
                    a + 3. * sc * uni(rng)}};
          std::sort(t.begin(), t.end(), std::greater<double>());
          Vec          s;
          const Region r = check_return(mc, el, t, s, failures);
          ++count[r];
          if (psi == 0. && r != Region::apex)
            {
              // Plastic strain increment C (trial - s): its trace.
              const Vec de =
                el.principal_strain({{t[0] - s[0], t[1] - s[1], t[2] - s[2]}});
              const double norm =
                std::sqrt(de[0] * de[0] + de[1] * de[1] + de[2] * de[2]);
              if (norm > 0.)
                max_dvol =
                  std::max(max_dvol, std::abs(de[0] + de[1] + de[2]) / norm);
            }
        }
      const std::string name = "c=" + std::to_string(int(c)) +
                               " phi=" + std::to_string(int(phi)) +
                               " psi=" + std::to_string(int(psi));
      std::cout << name << ": elastic " << count[Region::elastic] << " plane "
                << count[Region::plane] << " edge1 " << count[Region::edge_1]
                << " edge2 " << count[Region::edge_2] << " apex "
                << count[Region::apex] << std::endl;
      check(name + ": every return on the surface, ordered, multipliers >= 0",
            failures == 0);
      check(name + ": all regions reached",
            count[Region::plane] > 0 && count[Region::edge_1] > 0 &&
              count[Region::edge_2] > 0 &&
              (count[Region::apex] > 0 || !mc.has_apex()));
      if (psi == 0.)
        // tr(dg) = m - 1 = 0 for every plane: zero up to round-off.
        check_close(name + ": max |plastic volume change| / |d eps_p|",
                    max_dvol,
                    0.,
                    1e-10);

      // 2. Associated flow: the return is the closest point in the energy
      //    norm; compare with the brute-force enumeration.
      if (psi == phi)
        {
          double max_err = 0.;
          for (unsigned int n = 0; n < 2000; ++n)
            {
              Vec t = {{a + 3. * sc * uni(rng),
                        a + 3. * sc * uni(rng),
                        a + 3. * sc * uni(rng)}};
              std::sort(t.begin(), t.end(), std::greater<double>());
              if (mc.yield_function(t) <= 0.)
                continue;
              Vec s = t;
              mc.return_stress(s);
              const Tensor<1, 3> bf =
                brute_force_closest_point(el,
                                          mc.friction_coefficient_k(),
                                          mc.compressive_strength(),
                                          Tensor<1, 3>({t[0], t[1], t[2]}));
              max_err =
                std::max(max_err,
                         (Tensor<1, 3>({s[0], s[1], s[2]}) - bf).norm() / sc);
            }
          // Both are closed-form solutions of the same linear systems:
          // round-off, 1e-9 relative to sigma_c.
          check_close(name + ": max |return - brute force| / sigma_c",
                      max_err,
                      0.,
                      1e-9);
        }
    }

  // 3. Plane-strain compression with confining stress p: the axial
  //    Kirchhoff stress at yield is N_phi p + 2 c sqrt(N_phi) (compression
  //    positive), and stays there (perfect plasticity, psi = 0).
  for (const auto &[c, phi, p] : {std::make_tuple(1e4, 30., 1e5),
                                  std::make_tuple(0., 35., 2e5),
                                  std::make_tuple(1e6, 50., 0.)})
    {
      MohrCoulombReturn::Parameters prm;
      prm.cohesion       = c;
      prm.friction_angle = phi;
      prm.dilation_angle = 0.;
      // Stiff enough that yield strains are ~1e-3 (small-strain onset).
      const IsotropicElasticity el(1e9, 0.3);
      const MohrCoulomb         mc(2000., el, prm);
      PointDriver::Parameters   path;
      path.type             = PointDriver::PathType::plane_strain_compression;
      path.confining_stress = p;
      path.n_steps          = 400;
      const double N        = (1. + std::sin(phi * numbers::PI / 180.)) /
                       (1. - std::sin(phi * numbers::PI / 180.));
      const double s1 = N * p + 2. * c * std::sqrt(N);
      // Elastic plane-strain modulus E/(1 - nu^2) times 4x the yield strain.
      path.max_strain    = 4. * (s1 - p) * (1. - 0.09) / 1e9;
      const auto records = PointDriver(mc, path).run();
      // First plastic step, and the stress at the end.
      unsigned int first = 0;
      for (unsigned int i = 0; i < records.size(); ++i)
        if (records[i].plastic_strain > 0.)
          {
            first = i;
            break;
          }
      const auto       &r    = records.back();
      const double      J    = determinant(r.F);
      const std::string name = "plane strain c=" + std::to_string(int(c)) +
                               " phi=" + std::to_string(int(phi)) +
                               " p=" + std::to_string(int(p));
      // The return is exact in Kirchhoff stress tau = J sigma, and the
      // driver holds the lateral Cauchy stress at -p (Kirchhoff -J p):
      // tau_axial = N J p + 2 c sqrt(N) up to the Newton tolerance 1e-12 M.
      check_close(name + ": axial Kirchhoff stress at yield",
                  -J * r.stress[1][1],
                  N * J * p + 2. * c * std::sqrt(N),
                  1e-9 * s1 + 1e-11 * el.p_wave_modulus());
      check_close(name + ": lateral stress",
                  -r.stress[0][0],
                  p,
                  1e-9 * s1 + 1e-11 * el.p_wave_modulus());
      // Cauchy: N p + 2 c sqrt(N) / J, within |1/J - 1| = O(strain) of the
      // small-strain closed form.
      check_close(name + ": axial Cauchy stress at yield",
                  -r.stress[1][1],
                  s1,
                  1.01 * std::abs(1. / J - 1.) * s1 + 1e-9 * s1);
      // Yield starts after a quarter of the path (elastic up to s1): the
      // onset step is exact to one strain increment (1/400 of the path)
      // plus the O(strain) = O(1e-3) finite-strain shift.
      check(name + ": onset of yield at 1/4 of the path (step " +
              std::to_string(first) + ")",
            first >= 99 && first <= 102);
      // Before the onset the axial Kirchhoff stress is below yield (up to
      // the lateral Newton tolerance).
      const auto  &before = records[first - 1];
      const double Jb     = determinant(before.F);
      check(name + ": elastic before yield",
            -Jb * before.stress[1][1] <
              N * Jb * p + 2. * c * std::sqrt(N) + 1e-9 * s1);
    }
  return 0;
}
