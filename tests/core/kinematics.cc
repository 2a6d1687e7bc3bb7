// Verification problems 1-4 (kinematics and conservation), see
// doc/verification_core.md: free fall, rigid rotation of a disk, a
// pre-stressed block translating through the mesh, and the two colliding
// disks of Sulsky, Chen & Schreyer (1994).

#include "core_tools.h"

using namespace scarp_test;

namespace
{
  constexpr int dim = 2;
  using Sim         = simulation::Simulation<dim>;

  double
  max_stress(const Sim &sim)
  {
    const auto &layout = sim.property_layout();
    return max_over_points<dim>(sim, [&](const double *p, const Point<dim> &) {
      return layout.get_stress(p, layout.stress).norm();
    });
  }

  // 1. Free fall of a stress-free block: every node it touches gets the same
  // velocity v + g dt (partition of unity), so the velocity gradient is zero
  // and v_p = -g t exactly. The position update x += dt v^{n+1} gives
  // y_n = y0 - g dt^2 n (n+1) / 2 = y0 - g t^2 / 2 - g dt t / 2.
  void
  free_fall()
  {
    const double g = 10, dt = 1e-3, E = 100, rho = 1;
    // c_p = 11.6 m/s, CFL dt = 0.5 * 0.1 / (11.6 + 3) > 3e-3 > dt: dt fixed.
    const std::string text =
      scene_header(dim) + material_text("linear elastic", E, 0.3, rho) +
      mesh_text({0, 0}, {1, 1}, 0.1, {"free", "free", "free", "free"}) +
      body_text("body", box_shape({0.3, 0.5, 0.7, 0.9}), 2, "0; 0") +
      run_text({0, -g}, 0.5, 1, "FLIP", "MUSL", dt);
    auto         sim    = make_scene<dim>(text);
    const auto  &layout = sim->property_layout();
    const double mass   = sim->measure().mass;
    const auto   y_cm   = [&]() {
      return sum_over_points<dim>(*sim,
                                  [&](const double *p, const Point<dim> &x) {
                                    return p[layout.mass] * x[1];
                                  }) /
             mass;
    };
    const auto x_cm = [&]() {
      return sum_over_points<dim>(*sim,
                                  [&](const double *p, const Point<dim> &x) {
                                    return p[layout.mass] * x[0];
                                  }) /
             mass;
    };
    const double y0 = y_cm(), x0 = x_cm();
    double       worst_y = 0, worst_v = 0, worst_s = 0, worst_x = 0;
    for (const double t : {0.1, 0.2, 0.3})
      {
        sim->run_until(t);
        const double exact = y0 - g * t * t / 2 - g * dt * t / 2;
        const double v_err =
          max_over_points<dim>(*sim, [&](const double *p, const Point<dim> &) {
            return (layout.get_vector(p, layout.velocity) -
                    Tensor<1, dim>({0., -g * t}))
              .norm();
          });
        out() << std::setprecision(16) << "  t = " << t << "  y_cm = " << y_cm()
              << "  exact " << exact << "  |dy| = " << std::abs(y_cm() - exact)
              << "  max|v + g t| = " << v_err
              << "  max|sigma| = " << max_stress(*sim)
              << "  |dx_cm| = " << std::abs(x_cm() - x0) << std::endl;
        worst_y = std::max(worst_y, std::abs(y_cm() - exact));
        worst_x = std::max(worst_x, std::abs(x_cm() - x0));
        worst_v = std::max(worst_v, v_err);
        worst_s = std::max(worst_s, max_stress(*sim));
      }
    // Round-off: ~300 steps of sums of O(1) numbers, eps = 2.2e-16 each.
    // Positions: 300 * eps * |y| < 1e-13; 1e-12 leaves a factor 10.
    check(worst_y < 1e-12 && worst_x < 1e-12,
          "centre of mass y0 - g t^2/2 - g dt t/2 to round-off (1e-12 m)");
    // Velocities: 300 steps * eps * |v| (3 m/s) ~ 2e-13.
    check(worst_v < 1e-11, "velocity -g t at every point to 1e-11 m/s");
    // A spurious velocity gradient is only round-off of equal nodal
    // velocities, |L| <~ eps |v| / h = 7e-15 1/s, so |sigma| <~ E * 300 *
    // dt * |L| = 2e-13 Pa; bound 1e-10 Pa = 1e-12 E.
    check(worst_s < 1e-12 * E, "stress stays zero (< 1e-12 E)");
  }

  // 2. Rigid rotation of an elastic disk (no gravity, free faces).
  struct RotationResult
  {
    double L0, L1, K0, K1, sigma;
  };

  RotationResult
  rotate(const std::string &transfer, const double omega, const double t_end)
  {
    const double      E = 1e3, rho = 1, R = 0.3;
    const std::string text =
      scene_header(dim) + material_text("linear elastic", E, 0.3, rho) +
      mesh_text({0, 0}, {1, 1}, 0.05, {"free", "free", "free", "free"}) +
      body_text("body",
                ball_shape({0.5, 0.5}, R),
                2,
                "-w*(y-0.5); w*(x-0.5)",
                "0; 0; 0; 0; 0; 0",
                "w=" + num(omega)) +
      run_text({0, 0}, 0.5, t_end, transfer, "MUSL") +
      // Since the transfer loss is booked (issue 11), the balance residual
      // of this scene is what the explicit step and the rim remap (below)
      // leave: it reaches 10.0 % of the largest energy at t = 0.38 s, just
      // over the default 10 % growth check, which the unbooked PIC loss used
      // to hide. 0.2 keeps the check on; the test bounds E_kin itself.
      "subsection Stability\n  set Energy growth tolerance = 0.2\nend\n";
    auto           sim = make_scene<dim>(text);
    RotationResult r;
    auto           m0 = sim->measure();
    r.L0              = m0.angular_momentum[2] - 0.5 * m0.momentum[1] +
           0.5 * m0.momentum[0]; // about the centre (0.5, 0.5)
    r.K0 = m0.kinetic_energy;
    sim->run_until(t_end);
    auto m1 = sim->measure();
    r.L1 = m1.angular_momentum[2] - 0.5 * m1.momentum[1] + 0.5 * m1.momentum[0];
    r.K1 = m1.kinetic_energy;
    r.sigma = max_stress(*sim);
    out() << std::setprecision(8) << "  " << transfer << ": "
          << sim->step_number() << " steps, L " << r.L0 << " -> " << r.L1
          << " (rel. change " << (r.L1 - r.L0) / r.L0 << "), E_kin " << r.K0
          << " -> " << r.K1 << " (rel. change " << (r.K1 - r.K0) / r.K0
          << "), max |sigma| = " << r.sigma << " Pa" << std::endl;
    return r;
  }

  void
  rigid_rotation()
  {
    const double omega = 1, t_end = 0.5, E = 1e3, rho = 1, R = 0.3;
    const auto   apic = rotate("APIC", omega, t_end);
    const auto   pic  = rotate("PIC", omega, t_end);
    // The centrifugal stress of a spinning disk is ~ (3+nu)/8 rho omega^2 R^2
    // = 0.037 Pa (static; at most twice that while it is suddenly loaded).
    // A non-objective update would instead turn the rotation angle into
    // strain: |sigma| ~ E (1 - cos(omega t)) = 122 Pa.
    const double centrifugal   = (3 + 0.3) / 8 * rho * omega * omega * R * R;
    const double non_objective = E * (1 - std::cos(omega * t_end));
    out() << "  centrifugal stress scale " << centrifugal
          << " Pa, non-objective scale " << non_objective << " Pa" << std::endl;
    // What remains with APIC is not a failure of the (Cayley, exactly
    // rotating) update but of the MUSL remap: it maps the point velocities
    // only (see mpm_transfer.cc), and at the rim the partly filled nodes
    // get the velocity of their points' centre of mass, not of the node, so
    // the remapped field there has a spurious symmetric gradient of order
    // omega. That stress changes sign as points change cells; bound: a
    // tenth of the non-objective level (measured: about 5 %).
    check(apic.sigma < 0.1 * non_objective,
          "APIC: stress far below the non-objective level E (1 - cos wt)");
    // x += dt v^{n+1} moves a point along the tangent: r^2 grows by
    // (w dt)^2 per step, and the rim remap above exchanges kinetic and
    // strain energy of the order of the strain energy it makes
    // (sigma^2 / 2E over the rim ring: 1e-4 of E_kin per Pa^2 here).
    // Bound: 2 % for L and E_kin over the half radian.
    check(std::abs(apic.L1 - apic.L0) < 0.02 * std::abs(apic.L0),
          "APIC: angular momentum constant to 2 %");
    check(std::abs(apic.K1 - apic.K0) < 0.02 * apic.K0,
          "APIC: kinetic energy constant to 2 %");
    check(pic.L0 - pic.L1 > 10 * std::abs(apic.L1 - apic.L0),
          "PIC: angular momentum decays, ten times more than with APIC");
    check(pic.K1 < apic.K1, "PIC: kinetic energy decays below APIC's");
  }

  // 3. A block in plane strain between slip faces (bottom and top), with the
  // equilibrium stress sigma_yy = -p, sigma_zz = nu sigma_yy, sigma_xx = 0,
  // translating at v0 along x through ten cells.
  void
  translating_block()
  {
    const double      E = 1e3, nu = 0.3, rho = 1, p = 1, v0 = 1, h = 0.1;
    const std::string text =
      scene_header(dim) + material_text("linear elastic", E, nu, rho) +
      mesh_text({0, 0}, {2.5, 1}, h, {"free", "free", "slip", "slip"}) +
      body_text("body",
                box_shape({0.2, 0, 1.2, 1}),
                2,
                num(v0) + "; 0",
                "0; " + num(-p) + "; " + num(-nu * p) + "; 0; 0; 0") +
      run_text({0, 0}, 0.5, 1.0, "FLIP", "MUSL");
    auto        sim    = make_scene<dim>(text);
    const auto &layout = sim->property_layout();
    double      dv = 0, ds = 0;
    for (const double t : {0.25, 0.5, 0.75, 1.0})
      {
        sim->run_until(t);
        const double v_err =
          max_over_points<dim>(*sim, [&](const double *q, const Point<dim> &) {
            return (layout.get_vector(q, layout.velocity) -
                    Tensor<1, dim>({v0, 0.}))
              .norm();
          });
        const double s_err =
          max_over_points<dim>(*sim, [&](const double *q, const Point<dim> &) {
            SymmetricTensor<2, 3> s0;
            s0[1][1] = -p;
            s0[2][2] = -nu * p;
            return (layout.get_stress(q, layout.stress) - s0).norm();
          });
        out() << "  t = " << t << " (" << v0 * t / h
              << " cells)  max|v - v0| = " << v_err
              << "  max|sigma - sigma0| = " << s_err << std::endl;
        dv = std::max(dv, v_err);
        ds = std::max(ds, s_err);
      }
    // The stress has no component along the motion (sigma_xx = sigma_xy = 0)
    // and the block does not move in y, so every node's force is the
    // y-integral of d S_i / dy over a full column of points, which the two
    // points per cell integrate exactly: zero. Cell crossing therefore
    // makes no noise here, and what remains is round-off: ~770 steps of eps
    // on |v0| = 1 m/s and on |sigma| = p; bound 1e-10 (relative).
    check(dv < 1e-10 * v0, "velocity stays v0 to 1e-10 v0");
    check(ds < 1e-10 * p, "stress stays the equilibrium state to 1e-10 p");
  }

  // 4. Two elastic disks (Sulsky, Chen & Schreyer 1994).
  void
  two_disks(const double cutoff)
  {
    const double E = 1000, nu = 0.3, rho = 1000, R = 0.2, v = 0.1, h = 0.05;
    // The mesh is larger than the unit square and shifted by a fraction of
    // a cell so that the point lattice is not symmetric about (0.5, 0.5):
    // zero momentum must then come from conservation, not from symmetry.
    const std::string text =
      scene_header(dim, "run", "a, b") +
      material_text("linear elastic", E, nu, rho) +
      mesh_text({-0.23, -0.23},
                {1.27, 1.27},
                h,
                {"free", "free", "free", "free"}) +
      body_text("a", ball_shape({0.2, 0.2}, R), 2, num(v) + "; " + num(v)) +
      body_text("b", ball_shape({0.8, 0.8}, R), 2, num(-v) + "; " + num(-v)) +
      run_text({0, 0},
               0.5,
               4.0,
               "FLIP",
               "MUSL",
               1e30,
               "",
               "  set Small mass cutoff = " + num(cutoff) + "\n");
    auto         sim     = make_scene<dim>(text);
    const auto   m0      = sim->measure();
    const double K_exact = 2 * 0.5 * rho * M_PI * R * R * 2 * v * v;
    // The points of a disk are the lattice points (spacing d = h/2) inside
    // it, each of area d^2: the union of their squares lies between the
    // disks of radius R -+ d/sqrt(2), so |A_h - A| <= 2 pi R r + pi r^2
    // with r = d / sqrt(2): a relative bound 2 r / R + (r/R)^2 = 0.19.
    // Typical lattice counts are far better (Gauss circle problem); the
    // measured error is printed.
    const double r_pt = 0.5 * h / std::sqrt(2.);
    out() << std::setprecision(8) << "  initial kinetic energy "
          << m0.kinetic_energy << " J/m (exact 2.513: " << K_exact
          << ", rel. error " << (m0.kinetic_energy - K_exact) / K_exact << ")"
          << std::endl;
    check(std::abs(m0.kinetic_energy - K_exact) <=
            (2 * r_pt / R + r_pt * r_pt / (R * R)) * K_exact,
          "initial kinetic energy 2.513 J/m to the lattice bound");
    const double E0      = m0.kinetic_energy + hencky_strain_energy(*sim);
    const double p_scale = m0.mass * v;
    double       worst_p = 0, worst_drift = 0, min_K = 1e300;
    for (double t = 0.25; t <= 4.0 + 1e-9; t += 0.25)
      {
        sim->run_until(t);
        const auto   m = sim->measure();
        const double U = hencky_strain_energy(*sim);
        const double P = std::hypot(m.momentum[0], m.momentum[1]);
        out() << "  t = " << std::setw(5) << t << "  E_kin = " << std::setw(11)
              << m.kinetic_energy << "  E_strain = " << std::setw(11) << U
              << "  total/E0 - 1 = " << std::setw(12)
              << (m.kinetic_energy + U) / E0 - 1
              << "  |P|/(m v) = " << P / p_scale << std::endl;
        worst_p = std::max(worst_p, P / p_scale);
        worst_drift =
          std::max(worst_drift, std::abs((m.kinetic_energy + U) / E0 - 1));
        min_K = std::min(min_K, m.kinetic_energy);
      }
    // P2G and G2P (FLIP and PIC parts) conserve momentum exactly and there
    // is no boundary force: with no mass cutoff only round-off, ~200 steps
    // of eps.
    if (cutoff == 0)
      check(worst_p < 1e-12, "total momentum zero to round-off (1e-12 m v)");
    else
      {
        // Nodes lighter than the cutoff get zero velocity: their momentum
        // (< m_cut v_max each) is lost, for at most every node of the mesh
        // in every step.
        const double m_cut = cutoff * rho * h * h;
        const double bound = sim->step_number() * std::pow(1.5 / h + 1, 2) *
                             m_cut * std::sqrt(2.) * v / p_scale;
        out() << "  cutoff bound on |P|/(m v): " << bound << std::endl;
        check(worst_p < bound, "total momentum within the mass-cutoff bound");
      }
    check(min_K < 0.5 * m0.kinetic_energy,
          "the disks collide (kinetic energy turns into strain energy)");
    // Energy: the central-difference-like update conserves energy up to
    // O((w dt)^2) of the resolved modes, but the 1 % PIC part of the
    // FLIP blend (FLIP fraction 0.99) damps the velocity the grid cannot
    // represent each step, and the impact (single-velocity contact) is
    // partly inelastic; Sulsky et al. report a loss of a few percent
    // through the collision. Bound: 10 % drift.
    check(worst_drift < 0.1, "total energy drift below 10 %");
  }
} // namespace

int
main(int argc, char **argv)
{
  return run_cases(argc,
                   argv,
                   {{"free_fall", free_fall},
                    {"rigid_rotation", rigid_rotation},
                    {"translating_block", translating_block},
                    {"two_disks", [] { two_disks(0); }},
                    {"two_disks_cutoff", [] { two_disks(1e-5); }}});
}
