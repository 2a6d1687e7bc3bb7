// Simulation: the entries of a scene (declare_parameters) and reading
// them (parse_parameters), with the checks of what cannot run.
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/filtered_iterator.h>
#include <deal.II/grid/grid_tools.h>

#include <scarp/base/exceptions.h>
#include <scarp/base/parameter_tools.h>
#include <scarp/grid/refinement_marker.h>
#include <scarp/materials/chalk.h>
#include <scarp/materials/material_factory.h>
#include <scarp/particles/body_seeder.h>
#include <scarp/scenes/shape_factory.h>
#include <scarp/simulation/simulation.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>

namespace scarp
{
  namespace simulation
  {

    template <int dim>
    void
    Simulation<dim>::declare_parameters(ParameterHandler &prm,
                                        const SceneLists &lists)
    {
      SceneLists::declare_parameters(prm);
      prm.declare_entry("Output directory",
                        "output",
                        Patterns::DirectoryName(),
                        "Where the run writes its files (created if needed).");
      grid::BackgroundGrid<dim>::declare_parameters(prm);

      std::string material_names;
      for (const auto &name : lists.materials)
        {
          material_names += (material_names.empty() ? "" : "|") + name;
          prm.enter_subsection("Material " + name);
          materials::MaterialFactory::declare_parameters(prm);
          prm.leave_subsection();
        }
      for (const auto &name : lists.bodies)
        {
          prm.enter_subsection("Body " + name);
          prm.declare_entry("Material",
                            lists.materials.front(),
                            Patterns::Selection(material_names),
                            "Name of the material of this body.");
          prm.declare_entry("Particles per cell",
                            "2",
                            Patterns::Integer(1, 8),
                            "Material points per cell and direction.");
          prm.enter_subsection("Initial velocity");
          Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
          prm.leave_subsection();
          prm.enter_subsection("Initial stress");
          Functions::ParsedFunction<dim>::declare_parameters(prm, 6);
          prm.leave_subsection();
          prm.enter_subsection("Initial displacement");
          Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
          prm.declare_entry(
            "Enabled",
            "false",
            Patterns::Bool(),
            "Seed the points displaced: a point of the lattice position X "
            "starts at X + u(X) with F = I + grad u (difference quotients of "
            "this function of x, y[, z]; X stays the reference position), "
            "its stress from one elastic update with that F. For "
            "manufactured solutions whose initial displacement is not zero.");
          prm.leave_subsection();
          scenes::ShapeFactory<dim>::declare_parameters(prm);
          prm.leave_subsection();
        }
      for (const auto &name : lists.regions)
        {
          prm.enter_subsection("Pre-damaged region " + name);
          scenes::ShapeFactory<dim>::declare_parameters(prm);
          prm.leave_subsection();
        }
      prm.enter_subsection("Physics");
      prm.declare_entry("Gravity",
                        dim == 2 ? "0, -9.81" : "0, 0, -9.81",
                        *ParameterTools::double_list(dim),
                        "Gravitational acceleration [m/s^2].");
      prm.enter_subsection("Body force");
      Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
      prm.declare_entry("Enabled",
                        "false",
                        Patterns::Bool(),
                        "Add this body force per unit mass [m/s^2], a "
                        "function of the reference position (x, y[, z]) and "
                        "time t (for manufactured solutions). Its work is "
                        "booked in the energy balance (body_force_work).");
      prm.leave_subsection();
      prm.leave_subsection();
      prm.enter_subsection("Reference solution");
      Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
      prm.declare_entry(
        "Enabled",
        "false",
        Patterns::Bool(),
        "Measure the error against this exact displacement u(X, t), a "
        "function of the reference position (x, y[, z]) and time t: "
        "e = sqrt(sum V0 |x - X - u(X,t)|^2 / sum V0) over all points, "
        "written as the column reference_error of statistics.csv at every "
        "statistics row and, with its maximum over those rows and the same "
        "norm of u, to summary.json (reference_error).");
      prm.leave_subsection();
      prm.enter_subsection("Time");
      prm.declare_entry("CFL number",
                        "0.5",
                        Patterns::Double(0.),
                        "dt = CFL h_min / (c_p + max |v|), c_p the largest "
                        "p-wave speed of the materials. Stable up to about 1.");
      prm.declare_entry("Maximum time step",
                        "1e30",
                        Patterns::Double(0.),
                        "Upper bound on dt [s].");
      prm.declare_entry("Maximum steps",
                        "100000000",
                        Patterns::Integer(1),
                        "The run stops with an error after this many steps.");
      prm.leave_subsection();
      transfer::TransferParameters::declare_parameters(prm);
      nonlocal::NonlocalParameters::declare_parameters(prm);
      for (const auto &name : lists.stages)
        {
          prm.enter_subsection("Stage " + name);
          Stage::declare_parameters(prm);
          prm.leave_subsection();
        }
      prm.enter_subsection("Output");
      prm.declare_entry("Interval",
                        "0",
                        Patterns::Double(0.),
                        "Simulated time between VTU outputs [s]; 0: only at "
                        "the start and at the end of each stage.");
      prm.declare_entry("Statistics interval",
                        "10",
                        Patterns::Integer(1),
                        "Steps between rows of statistics.csv.");
      prm.declare_entry("Write mesh",
                        "true",
                        Patterns::Bool(),
                        "Write the background mesh with the particles.");
      prm.leave_subsection();
      prm.enter_subsection("Cliff diagnostics");
      postprocess::CliffDiagnostics::declare_parameters(prm);
      prm.declare_entry(
        "Failure speed",
        "0.1",
        Patterns::Double(0.),
        "Failure onset: the first time, in a stage with damage, "
        "that material points move faster than this [m/s] (more of them "
        "than <Failure volume>). Used only by scenes with a cliff body.");
      prm.declare_entry(
        "Failure volume",
        "0",
        Patterns::Double(0.),
        "The failure onset needs the points faster than <Failure speed> to "
        "hold more than this reference volume [m^2 in 2D, m^3 in 3D]: a "
        "flake of a few fully damaged points (at a notch) is not the "
        "failure of the cliff. 0: one point is enough.");
      prm.declare_entry(
        "Snapshot after failure",
        "1",
        Patterns::Double(),
        "Write cliff_after_failure_particles.csv this long after the "
        "failure onset [s]: the failed block has moved, the failure surface "
        "shows, and runs at different resolutions compare at the same stage "
        "of the motion. Negative: no such snapshot.");
      prm.declare_entry(
        "Stop after failure",
        "false",
        Patterns::Bool(),
        "End the run right after the <Snapshot after failure> (for "
        "resolution studies of the failure surface, which need not run the "
        "debris to rest). The summary then has no debris angle.");
      prm.leave_subsection();
      prm.enter_subsection("Load balancing");
      prm.declare_entry(
        "Check interval",
        "200",
        Patterns::Integer(0),
        "Every this many steps, compare the material points per rank and "
        "repartition the mesh (cells weighted by their points) when the "
        "largest count exceeds the mean by more than <Imbalance "
        "tolerance>: a collapsing cliff carries its points onto cells of "
        "another rank. 0: balance only after seeding and refinement.");
      prm.declare_entry(
        "Imbalance tolerance",
        "0.1",
        Patterns::Double(0.),
        "Repartition when max/mean - 1 of the points per rank exceeds this, "
        "at the checks and after the split of a refinement pass (whose own "
        "repartition weighs a refined cell's children as their parent). "
        "0: repartition again after every split.");
      prm.leave_subsection();
      Checkpoint<dim>::declare_parameters(prm);
      prm.enter_subsection("Stability");
      prm.declare_entry("Energy growth tolerance",
                        "0.1",
                        Patterns::Double(0.),
                        "Stop when the energy balance (kinetic + "
                        "gravitational + internal work + damping, boundary, "
                        "mass-scaling and transfer dissipation - body force "
                        "work) has grown by more than this fraction of the "
                        "largest energy of the run: the step is unstable.");
      prm.declare_entry("Points leaving the mesh",
                        "error",
                        Patterns::Selection("error|remove"),
                        "A material point that leaves the background box "
                        "stops the run (error) or is removed and counted.");
      prm.leave_subsection();
    }


    template <int dim>
    void
    Simulation<dim>::parse_parameters(ParameterHandler &prm)
    {
      lists.parse_parameters(prm);
      output_directory = prm.get("Output directory");
      grid.parse_parameters(prm);

      bool any_apic = false;
      materials.clear();
      for (const auto &name : lists.materials)
        {
          prm.enter_subsection("Material " + name);
          try
            {
              materials.push_back(materials::MaterialFactory::create(prm));
            }
          catch (const ExceptionBase &e)
            {
              // The model's own sentence, on one line, without deal.II's
              // source location and exception name.
              std::ostringstream info;
              e.print_info(info);
              std::string message = info.str();
              std::replace(message.begin(), message.end(), '\n', ' ');
              std::istringstream words(message);
              std::string        word, text;
              while (words >> word)
                text += (text.empty() ? "" : " ") + word;
              if (text.rfind("Material: ", 0) == 0)
                text.erase(0, 10);
              throw ScarpError("Material " + name + ": " + text);
            }
          catch (const std::exception &e)
            {
              throw ScarpError("Material " + name + ": " + e.what());
            }
          prm.leave_subsection();
          material_pointers.push_back(materials.back().get());
          if (materials.back()->has_damage())
            any_damage = true;
        }

      bodies.clear();
      for (const auto &name : lists.bodies)
        {
          prm.enter_subsection("Body " + name);
          Body body;
          body.name                  = name;
          const std::string material = prm.get("Material");
          body.material              = std::find(lists.materials.begin(),
                                    lists.materials.end(),
                                    material) -
                          lists.materials.begin();
          body.per_direction = prm.get_integer("Particles per cell");
          prm.enter_subsection("Initial velocity");
          body.velocity = std::make_unique<Functions::ParsedFunction<dim>>(dim);
          body.velocity->parse_parameters(prm);
          prm.leave_subsection();
          prm.enter_subsection("Initial stress");
          body.stress = std::make_unique<Functions::ParsedFunction<dim>>(6);
          body.stress->parse_parameters(prm);
          prm.leave_subsection();
          prm.enter_subsection("Initial displacement");
          if (prm.get_bool("Enabled"))
            {
              body.displacement =
                std::make_unique<Functions::ParsedFunction<dim>>(dim);
              body.displacement->parse_parameters(prm);
            }
          prm.leave_subsection();
          try
            {
              if (prm.get("Shape") == "cliff")
                {
                  if constexpr (dim == 2)
                    {
                      body.cliff =
                        scenes::ShapeFactory<dim>::create_cliff_profile(prm);
                      body.cliff->set_cell_size(grid.coarse_cell_size());
                      body.cliff->set_nonlocal_length(
                        materials[body.material]->nonlocal_length());
                      if (body.cliff->has_crack_band())
                        body.cliff->crack_band_half_width(); // needs l_c
                      // The base layer must lie inside the mesh.
                      const auto  &domain = grid.domain();
                      const double bottom = body.cliff->bottom_level();
                      if (body.cliff->has_base_layer() &&
                          (bottom < domain.lower_bound(1) - 1e-12 ||
                           body.cliff->base_layer_end() >
                             domain.upper_bound(0) + 1e-12))
                        throw ScarpError(
                          "Cliff/Base layer thickness (" +
                          Utilities::to_string(
                            body.cliff->get_parameters().base_layer_thickness) +
                          " m below Beach level, down to y = " +
                          Utilities::to_string(bottom) +
                          ") and Cliff/Base layer extent (to x = " +
                          Utilities::to_string(body.cliff->base_layer_end()) +
                          ") must fit in the mesh box from Mesh/Lower corner "
                          "(" +
                          Utilities::to_string(domain.lower_bound(0)) + ", " +
                          Utilities::to_string(domain.lower_bound(1)) +
                          ") to Mesh/Upper corner (" +
                          Utilities::to_string(domain.upper_bound(0)) + ", " +
                          Utilities::to_string(domain.upper_bound(1)) +
                          "): lower the Lower corner below the layer, or "
                          "reduce the layer.");
                    }
                  else
                    throw ScarpError("the cliff shape is two-dimensional.");
                }
              body.shape = scenes::ShapeFactory<dim>::create(prm);
            }
          catch (const std::exception &e)
            {
              throw ScarpError("Body " + name + ": " + e.what());
            }
          prm.leave_subsection();
          bodies.push_back(std::move(body));
        }
      predamaged.clear();
      for (const auto &name : lists.regions)
        {
          prm.enter_subsection("Pre-damaged region " + name);
          try
            {
              predamaged.push_back(scenes::ShapeFactory<dim>::create(prm));
            }
          catch (const std::exception &e)
            {
              throw ScarpError("Pre-damaged region " + name + ": " + e.what());
            }
          prm.leave_subsection();
        }

      prm.enter_subsection("Physics");
      gravity = ParameterTools::get_vector<dim>(prm, "Gravity");
      prm.enter_subsection("Body force");
      if (prm.get_bool("Enabled"))
        {
          body_force = std::make_unique<Functions::ParsedFunction<dim>>(dim);
          body_force->parse_parameters(prm);
        }
      prm.leave_subsection();
      prm.leave_subsection();
      prm.enter_subsection("Reference solution");
      if (prm.get_bool("Enabled"))
        {
          reference_displacement =
            std::make_unique<Functions::ParsedFunction<dim>>(dim);
          reference_displacement->parse_parameters(prm);
        }
      prm.leave_subsection();
      prm.enter_subsection("Time");
      cfl           = prm.get_double("CFL number");
      max_time_step = prm.get_double("Maximum time step");
      max_steps     = prm.get_integer("Maximum steps");
      prm.leave_subsection();
      if (!(cfl > 0))
        throw ScarpError("Time: <CFL number> must be positive.");
      transfer_parameters.parse_parameters(prm);
      any_apic = transfer_parameters.velocity_transfer ==
                 transfer::VelocityTransfer::apic;
      // APIC is verified on elastic problems only. In the flows of plastic
      // or damaging materials it creates energy that the balance books as
      // a negative transfer loss, so the energy check does not stop it
      // (doc/stability.md, "APIC in plastic and damaging flows").
      if (any_apic)
        for (unsigned int i = 0; i < materials.size(); ++i)
          if (materials[i]->has_plasticity() || materials[i]->has_damage())
            throw ScarpError(
              "Transfer: <Velocity transfer> = APIC is refused with Material " +
              lists.materials[i] +
              ", whose plasticity or damage makes the body flow: in such "
              "flows APIC creates energy (points shot off at 20 to 200 m/s "
              "in the granular column collapse and the Joss Bay debris; "
              "doc/stability.md, \"APIC in plastic and damaging flows\"). "
              "Use FLIP, with <FLIP fraction> or <PIC time scale>.");
      nonlocal::NonlocalParameters nonlocal_parameters;
      nonlocal_parameters.parse_parameters(prm);
      nonlocal_update_interval = nonlocal_parameters.update_interval;

      stages.clear();
      double previous_end = 0;
      for (const auto &name : lists.stages)
        {
          prm.enter_subsection("Stage " + name);
          Stage stage;
          stage.name = name;
          stage.parse_parameters(prm);
          prm.leave_subsection();
          if (stage.end_time < previous_end)
            throw ScarpError("Stage " + name + ": <End time> (" +
                             std::to_string(stage.end_time) +
                             ") lies before the end of the stage before it.");
          previous_end = stage.end_time;
          stages.push_back(stage);
        }
      prm.enter_subsection("Output");
      output_interval     = prm.get_double("Interval");
      statistics_interval = prm.get_integer("Statistics interval");
      write_mesh_files    = prm.get_bool("Write mesh");
      prm.leave_subsection();
      prm.enter_subsection("Cliff diagnostics");
      cliff_diagnostics.parse_parameters(prm);
      cliff_diagnostics.set_cell_size(grid.coarse_cell_size());
      failure_speed       = prm.get_double("Failure speed");
      failure_volume      = prm.get_double("Failure volume");
      after_failure_delay = prm.get_double("Snapshot after failure");
      stop_after_failure  = prm.get_bool("Stop after failure");
      if (stop_after_failure && after_failure_delay < 0)
        throw ScarpError("Cliff diagnostics: <Stop after failure> = true "
                         "needs <Snapshot after failure> >= 0.");
      prm.leave_subsection();
      for (const auto &body : bodies)
        if (body.cliff && !cliff)
          cliff = body.cliff.get();
      for (const auto &stage : stages)
        if (stage.deposit_rest && (!cliff || dim != 2))
          throw ScarpError("Stage " + stage.name +
                           ": <End on deposit at rest> measures the deposit "
                           "of a cliff, but this scene has no body with "
                           "<Shape> = cliff (2D); use <End on kinetic "
                           "energy>.");
      prm.enter_subsection("Load balancing");
      balance_interval  = prm.get_integer("Check interval");
      balance_tolerance = prm.get_double("Imbalance tolerance");
      prm.leave_subsection();
      prm.enter_subsection("Stability");
      growth_tolerance = prm.get_double("Energy growth tolerance");
      remove_outside   = prm.get("Points leaving the mesh") == "remove";
      prm.leave_subsection();
      removes_points = remove_outside;
      for (const auto &m : materials)
        removes_points = removes_points || m->removal_stretch() > 0;
      {
        // The defaults of this scene's declarations, for the fingerprint.
        ParameterHandler unset;
        declare_parameters(unset, lists);
        std::ostringstream defaults;
        unset.print_parameters(defaults, ParameterHandler::ShortPRM);
        checkpoint.parse_parameters(prm, lists.stages, defaults.str());
      }

      // The particle layout holds only what this scene needs.
      std::vector<std::string> state_names;
      for (const auto &m : materials)
        if (m->n_state_variables() > state_names.size())
          state_names = m->state_variable_names();
      layout.build(any_apic, state_names);
      checkpoint.set_particle_properties(layout.names());

      if (any_damage)
        {
          double               length = -1;
          nonlocal::WeightType weight = nonlocal::WeightType::bell;
          for (const auto &m : materials)
            if (m->has_damage())
              {
                const auto *chalk =
                  dynamic_cast<const materials::Chalk *>(m.get());
                nonlocal::WeightType w = nonlocal::WeightType::bell;
                if (chalk)
                  w = chalk->nonlocal_weight() ==
                          materials::NonlocalWeight::gaussian
                        ? nonlocal::WeightType::gaussian
                      : chalk->nonlocal_weight() ==
                          materials::NonlocalWeight::local
                        ? nonlocal::WeightType::local
                        : nonlocal::WeightType::bell;
                if (length >= 0 &&
                    (length != m->nonlocal_length() || w != weight))
                  throw ScarpError("All damage materials of a scene must "
                                   "share the non-local length scale and "
                                   "weight.");
                length = m->nonlocal_length();
                weight = w;
              }
          averager =
            std::make_unique<nonlocal::NonlocalAverager<dim>>(communicator);
          averager->reinit(weight,
                           std::max(length, 1e-300),
                           nonlocal_parameters.skin_fraction);
        }
      if (grid.adaptive_refinement && !any_damage)
        throw ScarpError(
          "Mesh/Refinement: <Adaptive refinement> = true refines where a "
          "material damages, but no material of this scene has damage "
          "(<Model> = chalk); switch it off, or use <Initial levels> and "
          "<Initial region> for a fixed refined region.");
      if (grid.setup_passes > 0)
        {
          const std::string what = "Mesh/Refinement: <Set-up passes> = " +
                                   std::to_string(grid.setup_passes);
          if (!grid.adaptive_refinement)
            throw ScarpError(what + " needs <Adaptive refinement> = true.");
          if (stages.size() < 2 || stages.front().damage)
            throw ScarpError(
              what +
              " reruns the first stage, which must be a loading stage "
              "without damage followed by another stage (this scene's "
              "first stage, " +
              stages.front().name +
              (stages.size() < 2 ? ", is its only one)." : ", has damage)."));
        }
    }


    // Instantiations (the other members are in the other
    // simulation_*.cc files).
    template void
    Simulation<2>::declare_parameters(ParameterHandler &prm,
                                      const SceneLists &lists);
    template void
    Simulation<3>::declare_parameters(ParameterHandler &prm,
                                      const SceneLists &lists);
    template void
    Simulation<2>::parse_parameters(ParameterHandler &prm);
    template void
    Simulation<3>::parse_parameters(ParameterHandler &prm);
  } // namespace simulation
} // namespace scarp
