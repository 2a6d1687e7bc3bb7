// Shared pieces of the core verification tests (doc/verification_core.md):
// scene text pieces and measures on material points. Building and running
// scenes, sums over points and the case dispatcher are in
// common/scene_runner.h.
#ifndef scarp_tests_core_core_tools_h
#define scarp_tests_core_core_tools_h

#include <deal.II/base/mpi.h>

#include <scarp/base/exceptions.h>
#include <scarp/materials/spectral_decomposition.h>

#include "../common/scene_runner.h"

#include <cmath>
#include <string>
#include <vector>

namespace scarp_test
{
  /// The header of a scene with one material and one body.
  inline std::string
  scene_header(const unsigned int dim,
               const std::string &stages = "run",
               const std::string &bodies = "body")
  {
    return "set Dimension = " + std::to_string(dim) +
           "\nset Materials = material\nset Bodies = " + bodies +
           "\nset Stages = " + stages + "\nset Output directory = output\n";
  }

  /// An elastic material subsection.
  inline std::string
  material_text(const std::string &model,
                const double       E,
                const double       nu,
                const double       rho)
  {
    return "subsection Material material\n  set Model = " + model +
           "\n  set Density = " + num(rho) +
           "\n  subsection Elasticity\n    set Young's modulus = " + num(E) +
           "\n    set Poisson's ratio = " + num(nu) + "\n  end\nend\n";
  }

  /// Body subsection with a box or ball shape, velocity and stress
  /// expressions (x, y[, z]).
  inline std::string
  body_text(const std::string &name,
            const std::string &shape_entries,
            const unsigned int ppc,
            const std::string &velocity,
            const std::string &stress    = "0; 0; 0; 0; 0; 0",
            const std::string &constants = "")
  {
    return "subsection Body " + name +
           "\n  set Material = material\n  set Particles per cell = " +
           std::to_string(ppc) + "\n" + shape_entries +
           "  subsection Initial velocity\n    set Function constants = " +
           constants + "\n    set Function expression = " + velocity +
           "\n  end\n  subsection Initial stress\n    set Function "
           "constants = " +
           constants + "\n    set Function expression = " + stress +
           "\n  end\nend\n";
  }

  inline std::string
  box_shape(const std::vector<double> &corners)
  {
    return "  set Shape = box\n  set Box corners = " + list(corners) + "\n";
  }

  inline std::string
  ball_shape(const std::vector<double> &centre, const double radius)
  {
    return "  set Shape = ball\n  set Centre = " + list(centre) +
           "\n  set Radius = " + num(radius) + "\n";
  }

  /// Physics, Time, Transfer and one stage.
  inline std::string
  run_text(const std::vector<double> &gravity,
           const double               cfl,
           const double               end_time,
           const std::string         &transfer       = "FLIP",
           const std::string         &scheme         = "MUSL",
           const double               max_time_step  = 1e30,
           const std::string         &stage_extra    = "",
           const std::string         &transfer_extra = "")
  {
    return "subsection Physics\n  set Gravity = " + list(gravity) +
           "\nend\nsubsection Time\n  set CFL number = " + num(cfl) +
           "\n  set Maximum time step = " + num(max_time_step) +
           "\nend\nsubsection Transfer\n  set Velocity transfer = " + transfer +
           "\n  set Update scheme = " + scheme + "\n" + transfer_extra +
           "end\nsubsection Stage run\n  set End time = " + num(end_time) +
           "\n" + stage_extra + "end\n";
  }

  /// p-wave modulus M = E (1 - nu) / ((1 + nu)(1 - 2 nu)).
  inline double
  p_wave_modulus(const double E, const double nu)
  {
    return E * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
  }

  /// Stored energy of a Hencky (linear elastic) point per reference volume:
  /// psi = tau : e / 2 with tau = J sigma and e the logarithmic elastic
  /// strain kept in the state (coaxial for an isotropic law).
  template <int dim>
  double
  hencky_energy_density(const particles::PropertyLayout<dim> &layout,
                        const double                         *p)
  {
    const double J =
      determinant(layout.get_matrix(p, layout.deformation_gradient));
    const SymmetricTensor<2, 3> sigma = layout.get_stress(p, layout.stress);
    const SymmetricTensor<2, 3> e = materials::load_symmetric(p + layout.state);
    return 0.5 * J * scalar_product(sigma, e);
  }

  /// Total strain energy of a Hencky scene (all ranks).
  template <int dim>
  double
  hencky_strain_energy(const simulation::Simulation<dim> &sim)
  {
    const auto &layout = sim.property_layout();
    return sum_over_points<dim>(sim, [&](const double *p, const Point<dim> &) {
      return p[layout.reference_volume] * hencky_energy_density(layout, p);
    });
  }
} // namespace scarp_test

#endif
