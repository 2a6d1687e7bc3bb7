// Shared pieces of the chalk damage tests (doc/damage_verification.md):
// scene text for a chalk material and gathering the material points.
// Building a scene on a chosen communicator, output, checks and the case
// dispatcher are in common/scene_runner.h.
#ifndef scarp_tests_chalk_chalk_tools_h
#define scarp_tests_chalk_chalk_tools_h

#include <deal.II/base/mpi.h>

#include <scarp/materials/chalk.h>
#include <scarp/simulation/simulation.h>

#include "../common/scene_runner.h"

#include <algorithm>
#include <string>
#include <vector>

namespace scarp_chalk_test
{
  using namespace dealii;
  using namespace scarp;
  // Not all of scarp_test: its mesh_text would make the one below ambiguous.
  using scarp_test::check;
  using scarp_test::communicator_of;
  using scarp_test::list;
  using scarp_test::make_scene;
  using scarp_test::num;
  using scarp_test::out;
  using scarp_test::refusal_message;
  using scarp_test::run_cases_with_args;

  /// Parameters of a chalk material (Joss Bay defaults, design note
  /// chalk-model.md section 5).
  struct ChalkText
  {
    double      density             = 1700;
    double      young               = 1e9;
    double      poisson             = 0.24;
    double      cohesion            = 1e6;
    double      friction_angle      = 50;
    double      dilation_angle      = 0;
    double      damage_angle        = 60;
    double      initiation_stress   = 20e3;
    double      ductility           = 5;
    double      characteristic_time = 1;
    double      length_scale        = 0.18;
    std::string weight              = "bell";
    double      r_t                 = 1e-9;
    double      r_c                 = 1e-2;
    double      r_g                 = 5e-3;
    /// Further entries of subsection Damage (each a full "    set" line).
    std::string damage_extra;

    std::string
    text(const std::string &name) const
    {
      return "subsection Material " + name +
             "\n  set Model = chalk\n  set Density = " + num(density) +
             "\n  subsection Elasticity\n    set Young's modulus = " +
             num(young) + "\n    set Poisson's ratio = " + num(poisson) +
             "\n  end\n  subsection Mohr-Coulomb\n    set Cohesion = " +
             num(cohesion) +
             "\n    set Friction angle = " + num(friction_angle) +
             "\n    set Dilation angle = " + num(dilation_angle) +
             "\n  end\n  subsection Damage\n    set Damage angle = " +
             num(damage_angle) +
             "\n    set Initiation stress = " + num(initiation_stress) +
             "\n    set Ductility = " + num(ductility) +
             "\n    set Characteristic time = " + num(characteristic_time) +
             "\n    set Length scale = " + num(length_scale) +
             "\n    set Nonlocal weight = " + weight +
             "\n    set Residual tensile ratio = " + num(r_t) +
             "\n    set Residual compressive ratio = " + num(r_c) +
             "\n    set Residual shear ratio = " + num(r_g) + "\n" +
             damage_extra + "  end\nend\n";
    }
  };

  /// Mesh subsection; @p faces: Left, Right, Bottom, Top; with the friction
  /// coefficient of the walls.
  inline std::string
  mesh_text(const std::vector<double>      &lower,
            const std::vector<double>      &upper,
            const double                    h,
            const std::vector<std::string> &faces,
            const double                    friction = 0.5)
  {
    return scarp_test::mesh_text(lower,
                                 upper,
                                 h,
                                 faces,
                                 "    set Friction coefficient = " +
                                   num(friction) + "\n");
  }

  /// Body subsection: a box of the named material.
  inline std::string
  box_body_text(const std::string         &name,
                const std::string         &material,
                const std::vector<double> &corners,
                const unsigned int         ppc,
                const std::string         &velocity  = "0; 0",
                const std::string         &constants = "")
  {
    return "subsection Body " + name + "\n  set Material = " + material +
           "\n  set Particles per cell = " + std::to_string(ppc) +
           "\n  set Shape = box\n  set Box corners = " + list(corners) +
           "\n  subsection Initial velocity\n    set Function constants = " +
           constants + "\n    set Function expression = " + velocity +
           "\n  end\nend\n";
  }

  /// A pre-damaged box region.
  inline std::string
  region_text(const std::string &name, const std::vector<double> &corners)
  {
    return "subsection Pre-damaged region " + name +
           "\n  set Shape = box\n  set Box corners = " + list(corners) +
           "\nend\n";
  }

  /// A stage subsection.
  inline std::string
  stage_text(const std::string &name,
             const double       end_time,
             const bool         plasticity  = true,
             const bool         damage      = true,
             const std::string &damping     = "none",
             const double       coefficient = 0)
  {
    return "subsection Stage " + name + "\n  set End time = " + num(end_time) +
           "\n  set Plasticity = " + (plasticity ? "true" : "false") +
           "\n  set Damage = " + (damage ? "true" : "false") +
           "\n  set Damping type = " + damping +
           "\n  set Damping = " + num(coefficient) + "\nend\n";
  }

  /// An L-shaped chalk overhang on a floor: a wall [0, 0.5] x [0, 2] with a
  /// cantilever [0.5, 1.5] x [1.5, 2]; left face slip (the cliff goes on),
  /// floor with friction. Cantilever root: sigma ~ 6 M / t^2 = 3 rho g
  /// a^2 / t = 100 kPa (a = 1 m, t = 0.5 m), five times sigma_f, so the root
  /// damages and the cantilever breaks off and falls 1.5 m.
  inline std::string
  overhang_scene(const ChalkText   &chalk,
                 const double       h,
                 const std::string &stages,
                 const std::string &regions    = "",
                 const double       mesh_width = 3,
                 const std::string &directory  = "output_overhang")
  {
    return "set Dimension = 2\nset Materials = chalk\nset Bodies = cliff\n"
           "set Stages = " +
           stages + "\nset Pre-damaged regions = " + regions +
           "\nset Output directory = " + directory + "\n" +
           mesh_text({0, 0},
                     {mesh_width, 2.5},
                     h,
                     {"slip", "free", "friction", "free"}) +
           chalk.text("chalk") +
           "subsection Body cliff\n  set Material = chalk\n"
           "  set Particles per cell = 2\n  set Shape = polygon\n"
           "  set Vertices = 0, 0; 0.5, 0; 0.5, 1.5; 1.5, 1.5; 1.5, 2; 0, 2\n"
           "end\n"
           "subsection Physics\n  set Gravity = 0, -9.81\nend\n"
           "subsection Time\n  set CFL number = 0.5\nend\n";
  }

  /// The Joss Bay chalk with a short delay (tau = 0.01 s instead of 1 s)
  /// and a lower cohesion (100 kPa, so that plasticity also acts).
  inline ChalkText
  overhang_chalk()
  {
    ChalkText chalk;
    chalk.characteristic_time = 0.01;
    chalk.cohesion            = 1e5;
    chalk.friction_angle      = 30;
    return chalk;
  }

  /// What the tests look at of one material point.
  template <int dim>
  struct PointRecord
  {
    Point<dim>            reference;
    Point<dim>            position;
    double                reference_volume = 0;
    double                damage           = 0;
    double                kappa            = 0;
    double                plastic          = 0; ///< per reference volume
    double                dissipated       = 0; ///< damage, per ref. volume
    SymmetricTensor<2, 3> stress;
  };

  /// All material points of the simulation, gathered on every rank of its
  /// communicator and sorted by reference position (x, then y).
  template <int dim>
  std::vector<PointRecord<dim>>
  gather_points(const simulation::Simulation<dim> &sim)
  {
    constexpr unsigned int n_values = 2 * dim + 5 + 6;
    const auto            &layout   = sim.property_layout();
    std::vector<double>    local;
    for (const auto &particle : sim.particle_handler())
      {
        const double *p = particle.get_properties().data();
        const auto   &m =
          sim.material(static_cast<unsigned int>(p[layout.material_id]));
        const auto   dissipated = m.dissipated_energy(p + layout.state);
        const double plastic = dissipated.plastic, damage = dissipated.damage;
        for (unsigned int d = 0; d < dim; ++d)
          local.push_back(p[layout.reference_position + d]);
        for (unsigned int d = 0; d < dim; ++d)
          local.push_back(particle.get_location()[d]);
        local.push_back(p[layout.reference_volume]);
        local.push_back(m.damage(p + layout.state));
        local.push_back(
          m.has_damage() ? p[layout.state + materials::Chalk::kappa] : 0.);
        local.push_back(plastic);
        local.push_back(damage);
        const SymmetricTensor<2, 3> s = layout.get_stress(p, layout.stress);
        for (unsigned int k = 0; k < 6; ++k)
          local.push_back(s.access_raw_entry(k));
      }
    const auto all = Utilities::MPI::all_gather(communicator_of(sim), local);
    std::vector<PointRecord<dim>> points;
    for (const auto &chunk : all)
      for (std::size_t k = 0; k + n_values <= chunk.size(); k += n_values)
        {
          PointRecord<dim> r;
          const double    *c = chunk.data() + k;
          for (unsigned int d = 0; d < dim; ++d)
            {
              r.reference[d] = c[d];
              r.position[d]  = c[dim + d];
            }
          r.reference_volume = c[2 * dim];
          r.damage           = c[2 * dim + 1];
          r.kappa            = c[2 * dim + 2];
          r.plastic          = c[2 * dim + 3];
          r.dissipated       = c[2 * dim + 4];
          for (unsigned int j = 0; j < 6; ++j)
            r.stress.access_raw_entry(j) = c[2 * dim + 5 + j];
          points.push_back(r);
        }
    std::sort(points.begin(),
              points.end(),
              [](const PointRecord<dim> &a, const PointRecord<dim> &b) {
                for (unsigned int d = 0; d < dim; ++d)
                  if (a.reference[d] != b.reference[d])
                    return a.reference[d] < b.reference[d];
                return false;
              });
    return points;
  }
} // namespace scarp_chalk_test

#endif
