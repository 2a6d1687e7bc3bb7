// Mass scaling (Stage/Mass scaling, Mass scaling until speed):
// the scaled system is the real one with m_s times the inertia, so a bar
// with m_s = 4 is the bar of density 4 (same weightless stresses, same time
// steps), and a free fall runs at g / m_s until its speed passes
// the limit, then at g. See doc/user_guide.md (Stages).

#include "core_tools.h"

using namespace scarp_test;

namespace
{
  // The vibrating bar of verification problem 5 (L = 25, E = 100, nu = 0,
  // fixed at x = 0, free at x = L, v(X, 0) = v0 sin(beta X)), h = 0.5,
  // either with density rho and no mass scaling, or density 1 and mass
  // scaling m_s.
  // With mass scaling the initial velocity is sqrt(m_s) v0: the scaling
  // keeps the kinetic energy when it begins (velocities / sqrt(m_s)), so
  // the bar starts at v0 as the heavy one.
  std::unique_ptr<simulation::Simulation<2>>
  make_bar(const double rho, const double mass_scaling, const double t_end)
  {
    const double L = 25, v0 = 0.01 * std::sqrt(mass_scaling);
    return make_scene<2>(
      scene_header(2) + material_text("linear elastic", 100, 0, rho) +
      mesh_text({0, 0}, {30, 1}, 0.5, {"fixed", "free", "slip", "slip"}) +
      body_text("body",
                box_shape({0, 0, L, 1}),
                2,
                "v0*sin(pi*x/(2*L)); 0",
                "0; 0; 0; 0; 0; 0",
                "v0=" + num(v0) + ", L=" + num(L)) +
      run_text({0, 0},
               0.5,
               t_end,
               "FLIP",
               "MUSL",
               1e30,
               "  set Mass scaling = " + num(mass_scaling) + "\n") +
      "subsection Stability\n  set Energy growth tolerance = 0.05\nend\n");
  }

  void
  bar()
  {
    const double ms = 4, L = 25, beta = M_PI / (2 * L);
    // omega = beta sqrt(E / (m_s rho)): the period doubles to 20 s.
    const double omega = beta * std::sqrt(100. / ms), A = 0.01 / omega;
    auto         scaled = make_bar(1, ms, 20), heavy = make_bar(ms, 1, 20);
    const auto  &layout      = scaled->property_layout();
    double       worst_exact = 0, worst_same = 0, worst_residual = 0;
    for (const double t : {5., 10., 15., 20.})
      {
        scaled->run_until(t);
        heavy->run_until(t);
        // Displacement error against the closed form, per amplitude.
        const auto error = [&](const simulation::Simulation<2> &sim) {
          const double e2 =
            sum_over_points<2>(sim, [&](const double *p, const Point<2> &x) {
              const Point<2> X(layout.get_vector(p, layout.reference_position));
              const double u = A * std::sin(omega * t) * std::sin(beta * X[0]);
              return p[layout.reference_volume] *
                     (Tensor<1, 2>({x[0] - X[0] - u, x[1] - X[1]}))
                       .norm_square();
            });
          return std::sqrt(e2 / L) / A;
        };
        const double e_scaled = error(*scaled), e_heavy = error(*heavy);
        const double residual =
          std::abs(scaled->energy_residual() / scaled->energy_scale() -
                   heavy->energy_residual() / heavy->energy_scale());
        out() << std::setprecision(10) << "  t = " << t
              << ": error / amplitude, m_s = 4: " << e_scaled
              << ", rho = 4: " << e_heavy << "; dt " << scaled->time_step()
              << " vs " << heavy->time_step() << "; balance residual / energy "
              << residual << std::endl;
        worst_exact    = std::max(worst_exact, e_scaled);
        worst_same     = std::max(worst_same, std::abs(e_scaled - e_heavy));
        worst_residual = std::max(worst_residual, residual);
      }
    // The two runs take the same steps (c / sqrt(m_s) = sqrt(E / (m_s
    // rho))) and the same nodal updates up to the order of the products
    // (f / (m_s m) against f / m): round-off, ~1e-16 per step and 1600
    // steps, relative to the amplitude: 1e-10 leaves a wide margin.
    check(worst_same < 1e-10,
          "mass scaling 4 = density 4 (error difference below 1e-10)");
    // The start-up phase error omega dt / 2 (doc/verification_core.md,
    // problem 5), dt = 0.5 h / c = 0.05: 0.008.
    check(worst_exact < omega * 0.05 / 2,
          "period 2 pi / (beta sqrt(E / (m_s rho))): error below omega dt/2");
    // The relative balance residual equals that of the heavy bar (the
    // start-up and the FLIP/PIC share, ~1e-3): without the factor m_s on
    // the kinetic energy it would differ by up to (m_s - 1) / m_s = 75 %.
    // Round-off: 1e-8.
    check(worst_residual < 1e-8, "energy balance closed with m_s E_kin");
  }

  // A free fall (no stress: uniform nodal velocities) at g / m_s while the
  // speed stays below v_lim, then at g. With a fixed dt every point has
  // v_n = -g dt n / m_s up to the step n_s after which the speed first
  // exceeds v_lim, then v_n = v_{n_s} - g dt (n - n_s).
  void
  free_fall_switch()
  {
    const double g = 10, dt = 1e-3, ms = 100, v_lim = 0.01115;
    const auto   stage = "  set Mass scaling = " + num(ms) +
                       "\n  set Mass scaling until speed = " + num(v_lim) +
                       "\n";
    // The falling block with the given stage entries.
    const auto fall_scene = [&](const std::string &stage_entries) {
      return scene_header(2) + material_text("linear elastic", 100, 0.3, 1) +
             mesh_text({0, 0}, {1, 1}, 0.1, {"free", "free", "free", "free"}) +
             body_text("body", box_shape({0.3, 0.5, 0.7, 0.9}), 2, "0; 0") +
             run_text({0, -g}, 0.5, 1, "FLIP", "MUSL", dt, stage_entries);
    };
    // The largest deviation of a point's velocity from (0, v).
    const auto velocity_error = [](const simulation::Simulation<2> &sim,
                                   const double                     v) {
      const auto &layout = sim.property_layout();
      return max_over_points<2>(sim, [&](const double *p, const Point<2> &) {
        return (layout.get_vector(p, layout.velocity) - Tensor<1, 2>({0., v}))
          .norm();
      });
    };
    auto         sim = make_scene<2>(fall_scene(stage));
    const double M   = sim->measure().mass;
    // The step after which the speed first exceeds v_lim (112).
    unsigned int n_s = 1;
    while (g * dt * n_s / ms <= v_lim)
      ++n_s;
    const double t_end = 0.3;
    // c_p = 11.6 m/s (10x slower scaled); CFL dt = 0.05 / (11.6 + 3) >
    // dt: the fixed dt holds throughout.
    sim->run_until(t_end);
    const unsigned int n     = sim->step_number();
    const double       v_n   = -g * dt * n_s / ms - g * dt * (n - n_s);
    const double       v_err = velocity_error(*sim, v_n);
    // The balance of the discrete fall: x += dt v^{n+1} makes the weight
    // do M g dt sum |v_k| of work, slightly more than the kinetic energy
    // gains (an O(dt) residual, as in core_free_fall). Expected residual:
    // m_s(n) E_kin,n - M g dt sum |v_k| + (m_s - 1) E_kin,n_s, the last term
    // being what the switch books.
    double drop = 0;
    for (unsigned int k = 1; k <= n; ++k)
      drop += dt * (k <= n_s ? g * dt * k / ms
                             : g * dt * n_s / ms + g * dt * (k - n_s));
    const double booked   = (ms - 1) * 0.5 * M * std::pow(g * dt * n_s / ms, 2);
    const double expected = 0.5 * M * v_n * v_n - M * g * drop + booked;
    const double residual = sim->energy_residual();
    out() << std::setprecision(16) << "  switch after step " << n_s
          << " (t = " << n_s * dt << " s); at step " << n << ": v = " << v_n
          << ", max |v_p - v| = " << v_err << "; balance residual " << residual
          << " J, expected " << expected << " J (booked " << booked << " J)"
          << std::endl;
    // Round-off of 300 steps of O(1) sums (see core_free_fall): 1e-11.
    check(v_err < 1e-11,
          "velocity g/m_s before the switch and g after it, at every point");
    // Sums of 300 terms of O(1e-3) J: round-off ~1e-15 J; the booking is
    // 1e-3 J. Bound 1e-10 J.
    check(std::abs(residual - expected) < 1e-10,
          "energy balance: the switch books (m_s - 1) E_kin");

    // The same fall with a volume condition: the falling block holds
    // 0.16 m^2; with 0.2 m^2 required the scaling never ends (v = -g t /
    // m_s at the end), with 0.1 m^2 it ends after step n_s as above.
    for (const double volume : {0.2, 0.1})
      {
        auto s = make_scene<2>(fall_scene(
          stage + "  set Mass scaling until volume = " + num(volume) + "\n"));
        s->run_until(t_end);
        const unsigned int m = s->step_number();
        const double       v = volume > 0.16
                                 ? -g * dt * m / ms
                                 : -g * dt * n_s / ms - g * dt * (m - n_s);
        const double       e = velocity_error(*s, v);
        out() << "  until volume " << volume
              << " m^2 (body 0.16 m^2): v = " << v << ", max |v_p - v| = " << e
              << std::endl;
        const bool kept = volume > 0.16;
        check(e < 1e-11,
              kept ? "a body smaller than the volume keeps the scaling"
                   : "a body larger than the volume ends it");
      }

    // An end speed without mass scaling is refused.
    const std::string message = refusal_message<2, ScarpError>(
      fall_scene("  set Mass scaling until speed = 1\n"));
    out() << "  refused: " << message << std::endl;
    const bool refused =
      message.find("<Mass scaling> is 1") != std::string::npos;
    check(refused, "an end speed without mass scaling is refused");
  }
} // namespace

int
main(int argc, char **argv)
{
  return run_cases(argc,
                   argv,
                   {{"bar", bar}, {"free_fall_switch", free_fall_switch}});
}
