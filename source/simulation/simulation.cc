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

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>

namespace scarp
{
  namespace simulation
  {
    namespace
    {
      std::string
      format_seconds(const double s)
      {
        const long         t = static_cast<long>(s + 0.5);
        std::ostringstream o;
        o << std::setfill('0') << std::setw(2) << t / 3600 << ":"
          << std::setw(2) << (t / 60) % 60 << ":" << std::setw(2) << t % 60;
        return o.str();
      }
    } // namespace


    template <int dim>
    Simulation<dim>::Simulation(MPI_Comm communicator, const SceneLists &lists)
      : communicator(communicator)
      , lists(lists)
      , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
      , timer(pcout, TimerOutput::never, TimerOutput::wall_times)
      , grid(communicator)
      , checkpoint(communicator)
    {
    }


    template <int dim>
    Simulation<dim>::~Simulation() = default;


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
                        "time t (for manufactured solutions). Its work is not "
                        "part of the energy balance.");
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
        "that a material point of the cliff moves faster than "
        "this [m/s]. Used only by scenes with a cliff body.");
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
      prm.declare_entry("Imbalance tolerance",
                        "0.1",
                        Patterns::Double(0.),
                        "Repartition when max/mean - 1 of the points per "
                        "rank exceeds this.");
      prm.leave_subsection();
      Checkpoint<dim>::declare_parameters(prm);
      prm.enter_subsection("Stability");
      prm.declare_entry("Energy growth tolerance",
                        "0.1",
                        Patterns::Double(0.),
                        "Stop when the energy balance (kinetic + "
                        "gravitational + internal work + damping and boundary "
                        "dissipation) has grown by more than this fraction of "
                        "the largest energy of the run: the step is unstable.");
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
      nonlocal::NonlocalParameters nonlocal_parameters;
      nonlocal_parameters.parse_parameters(prm);

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
      after_failure_delay = prm.get_double("Snapshot after failure");
      stop_after_failure  = prm.get_bool("Stop after failure");
      if (stop_after_failure && after_failure_delay < 0)
        throw ScarpError("Cliff diagnostics: <Stop after failure> = true "
                         "needs <Snapshot after failure> >= 0.");
      prm.leave_subsection();
      for (const auto &body : bodies)
        if (body.cliff && !cliff)
          cliff = body.cliff.get();
      prm.enter_subsection("Load balancing");
      balance_interval  = prm.get_integer("Check interval");
      balance_tolerance = prm.get_double("Imbalance tolerance");
      prm.leave_subsection();
      prm.enter_subsection("Stability");
      growth_tolerance = prm.get_double("Energy growth tolerance");
      remove_outside   = prm.get("Points leaving the mesh") == "remove";
      prm.leave_subsection();
      checkpoint.parse_parameters(prm);

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
    }


    template <int dim>
    void
    Simulation<dim>::setup()
    {
      if (mpm)
        return;
      TimerOutput::Scope scope(timer, "setup");
      if (checkpoint.resuming())
        load_checkpoint();
      else
        {
          grid.create_mesh();
          grid.setup_dofs();
          particles.initialize(grid.triangulation(),
                               grid.mapping(),
                               layout.n_properties());
          seed_bodies();
          balance_load();
        }
      mpm = std::make_unique<transfer::MpmTransfer<dim>>(
        grid, particles, layout, material_pointers, transfer_parameters);
      mpm->setup();
      mpm->set_body_force(body_force.get());
      double rho_max = 0;
      for (const auto &m : materials)
        rho_max = std::max(rho_max, m->density());
      mpm->set_mass_cutoff_density(transfer_parameters.mass_cutoff * rho_max);
      if (checkpoint.resuming())
        return; // the loop state came with the checkpoint
      last_report = measure();
      initial_energy =
        last_report.kinetic_energy + last_report.gravitational_energy;
      scale_of_energy = last_report.kinetic_energy;
    }


    template <int dim>
    void
    Simulation<dim>::rebalance_if_needed()
    {
      const unsigned int n_ranks =
        Utilities::MPI::n_mpi_processes(communicator);
      if (n_ranks == 1)
        return;
      const double n_local = particles.n_locally_owned_particles();
      const double n_max   = Utilities::MPI::max(n_local, communicator);
      const double n_mean =
        Utilities::MPI::sum(n_local, communicator) / n_ranks;
      if (!(n_max > (1. + balance_tolerance) * n_mean))
        return;
      TimerOutput::Scope scope(timer, "load balancing");
      balance_load();
      mpm->setup();
      local_boxes.clear();
      if (averager)
        averager->invalidate_neighbour_lists();
      ++n_rebalances;
    }


    template <int dim>
    void
    Simulation<dim>::balance_load()
    {
      if (Utilities::MPI::n_mpi_processes(communicator) == 1)
        return;
      // The work is per material point, not per cell: weigh cells by their
      // points (as in step-68), so that a cliff filling part of the box is
      // shared evenly. deal.II 9.4 adds no base weight once a function is
      // connected, so the empty-cell cost is ours too. The connection stays
      // for every later refinement.
      if (!weight_connection.connected())
        weight_connection = grid.triangulation().signals.weight.connect(
          [this](const typename Triangulation<dim>::cell_iterator &cell,
                 const typename Triangulation<dim>::CellStatus     status)
            -> unsigned int {
            unsigned int n = 0;
            if (status == Triangulation<dim>::CELL_COARSEN)
              {
                for (const auto &child : cell->child_iterators())
                  if (child->is_active())
                    n += particles.n_particles_in_cell(child);
              }
            else if (cell->is_active())
              n = particles.n_particles_in_cell(cell);
            return 10 + 100 * n;
          });
      particles.prepare_for_coarsening_and_refinement();
      grid.triangulation().repartition();
      particles.unpack_after_coarsening_and_refinement();
      grid.setup_dofs();
    }


    template <int dim>
    void
    Simulation<dim>::seed_bodies()
    {
      types::particle_index next_id = 0;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          const Body                &body     = bodies[b];
          const materials::Material &material = *materials[body.material];
          const auto                 inside   = [&](const Point<dim> &x) {
            if (!body.shape->contains(x))
              return false;
            for (unsigned int c = 0; c < b; ++c)
              if (bodies[c].shape->contains(x))
                return false;
            return true;
          };
          const auto initialize =
            [&](const Point<dim> &x, const double volume, double *p) {
              p[layout.mass]             = material.density() * volume;
              p[layout.reference_volume] = volume;
              Vector<double> v(dim), s(6);
              body.velocity->vector_value(x, v);
              body.stress->vector_value(x, s);
              for (unsigned int d = 0; d < dim; ++d)
                {
                  p[layout.velocity + d]                       = v[d];
                  p[layout.reference_position + d]             = x[d];
                  p[layout.deformation_gradient + d * dim + d] = 1.;
                }
              // APIC: the affine matrix starts as the gradient of the
              // initial velocity (else the first step is a PIC step).
              if (layout.has_affine)
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    const Tensor<1, dim> g = body.velocity->gradient(x, d);
                    for (unsigned int e = 0; e < dim; ++e)
                      p[layout.affine + d * dim + e] = g[e];
                  }
              SymmetricTensor<2, 3> sigma;
              for (unsigned int k = 0; k < 6; ++k)
                sigma.access_raw_entry(k) = s[k];
              layout.set_stress(p, layout.stress, sigma);
              p[layout.material_id] = body.material;
              p[layout.body_id]     = b;
              material.initialize_state(sigma, p + layout.state);
              bool damaged = false;
              for (const auto &region : predamaged)
                damaged = damaged || region->contains(x);
              if constexpr (dim == 2)
                if (body.cliff && body.cliff->has_crack())
                  {
                    // A pre-damage band replaces the fully damaged box.
                    if (body.cliff->has_crack_band())
                      {
                        const double d = body.cliff->crack_band_damage(x);
                        if (d > 0. && !damaged)
                          material.set_initial_damage(p + layout.state, d);
                      }
                    else if (body.cliff->crack_region().contains(x))
                      damaged = true;
                  }
              if (damaged)
                material.set_fully_damaged(p + layout.state);
            };
          const auto n =
            particles::BodySeeder<dim>::seed(grid.triangulation(),
                                             particles,
                                             body.shape->bounding_box(),
                                             inside,
                                             body.per_direction,
                                             next_id,
                                             initialize);
          if (n == 0)
            throw ScarpError("Body " + body.name +
                             " has no material point inside the background "
                             "mesh: is it outside the mesh, or smaller than "
                             "a cell?");
          // Any part of the body outside the mesh would be silently lost.
          const BoundingBox<dim> box = body.shape->bounding_box();
          for (unsigned int d = 0; d < dim; ++d)
            if (box.lower_bound(d) < grid.domain().lower_bound(d) - 1e-12 ||
                box.upper_bound(d) > grid.domain().upper_bound(d) + 1e-12)
              throw ScarpError("Body " + body.name +
                               " reaches outside the background mesh in "
                               "direction " +
                               std::to_string(d) +
                               ": enlarge the <Mesh> box or move the body.");
          pcout << "Body " << body.name << ": " << n << " material points"
                << std::endl;
          next_id += n;
        }
      particles.update_cached_numbers();
      apply_initial_displacement();
    }


    template <int dim>
    void
    Simulation<dim>::apply_initial_displacement()
    {
      bool any = false;
      for (const auto &body : bodies)
        any = any || body.displacement;
      if (!any)
        return;
      for (auto &m : materials)
        m->set_inelastic_enabled(false, false);
      for (auto &particle : particles)
        {
          double     *p = particle.get_properties().data();
          const Body &body =
            bodies[static_cast<unsigned int>(p[layout.body_id])];
          if (!body.displacement)
            continue;
          const Point<dim> X(layout.get_vector(p, layout.reference_position));
          Tensor<2, dim>   F = unit_symmetric_tensor<dim>();
          Point<dim>       x = X;
          for (unsigned int d = 0; d < dim; ++d)
            {
              x[d] += body.displacement->value(X, d);
              F[d] += body.displacement->gradient(X, d);
            }
          layout.set_matrix(p, layout.deformation_gradient, F);
          particle.set_location(x);
          Tensor<2, 3> F3;
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              F3[i][j] = (i < dim && j < dim) ? F[i][j] : (i == j ? 1. : 0.);
          SymmetricTensor<2, 3>    sigma  = layout.get_stress(p, layout.stress);
          double                   stored = 0, driver = 0;
          double                  *state = p + layout.state;
          materials::MaterialBatch batch;
          batch.n             = 1;
          batch.dt            = 1.;
          batch.delta_F       = &F3;
          batch.F             = &F3;
          batch.state         = &state;
          batch.stress        = &sigma;
          batch.stored_energy = &stored;
          if (materials[body.material]->has_damage())
            batch.damage_driver = &driver;
          materials[body.material]->update(batch);
          layout.set_stress(p, layout.stress, sigma);
        }
      particles.sort_particles_into_subdomains_and_cells();
      particles.update_cached_numbers();
    }


    template <int dim>
    double
    Simulation<dim>::reference_error(double *norm) const
    {
      if (!reference_displacement)
        return -1;
      reference_displacement->set_time(current_time);
      double sums[3] = {0, 0, 0};
      for (const auto &particle : particles)
        {
          const double    *p = particle.get_properties().data();
          const Point<dim> X(layout.get_vector(p, layout.reference_position));
          const double     V0 = p[layout.reference_volume];
          double           e2 = 0, u2 = 0;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double u = reference_displacement->value(X, d);
              const double e = particle.get_location()[d] - X[d] - u;
              e2 += e * e;
              u2 += u * u;
            }
          sums[0] += V0 * e2;
          sums[1] += V0 * u2;
          sums[2] += V0;
        }
      Utilities::MPI::sum(ArrayView<const double>(sums, 3),
                          communicator,
                          ArrayView<double>(sums, 3));
      if (norm)
        *norm = std::sqrt(sums[1] / std::max(sums[2], 1e-300));
      return std::sqrt(sums[0] / std::max(sums[2], 1e-300));
    }


    template <int dim>
    transfer::StepReport
    Simulation<dim>::measure() const
    {
      transfer::StepReport report = mpm->measure(gravity);
      report.reduce(communicator);
      return report;
    }


    template <int dim>
    double
    Simulation<dim>::stable_time_step() const
    {
      double c = 0;
      for (const auto &m : materials)
        c = std::max(c, std::sqrt(m->p_wave_modulus() / m->density()));
      // Mass scaling slows the waves by the square root of its factor.
      return std::min(max_time_step,
                      cfl * grid.minimum_cell_size() /
                        (c / std::sqrt(inertia_scale) + last_report.max_speed));
    }


    template <int dim>
    void
    Simulation<dim>::nonlocal_damage_step(const Stage &stage)
    {
      const bool gather_precursors = precursors_due(step);
      if (!averager || !(stage.damage || gather_precursors))
        return;
      TimerOutput::Scope scope(timer, "non-local damage");
      // Without damage (gravity loading) no point is a receiver; for the
      // refinement criterion every point that is not fully damaged is.
      if (!stage.damage)
        for (std::size_t k = 0; k < damage_points.receiver.size(); ++k)
          damage_points.receiver[k] =
            materials[static_cast<unsigned int>(
                        damage_points.properties[k][layout.material_id])]
              ->damage(damage_points.properties[k] + layout.state) < 1.;
      // This rank's region: the bounding box of its locally owned cells.
      // (GridTools::compute_mesh_predicate_bounding_box() at refinement
      // level 1 reads past the last level of an unrefined mesh and
      // crashed; at level 0 its merge is cubic in the number of coarse
      // cells. One box is always a cover, which is all the averager needs.)
      if (local_boxes.empty())
        {
          Point<dim> lower, upper;
          for (unsigned int d = 0; d < dim; ++d)
            {
              lower[d] = std::numeric_limits<double>::max();
              upper[d] = std::numeric_limits<double>::lowest();
            }
          bool any = false;
          for (const auto &cell : grid.triangulation().active_cell_iterators())
            if (cell->is_locally_owned())
              {
                any = true;
                for (const unsigned int v : cell->vertex_indices())
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      lower[d] = std::min(lower[d], cell->vertex(v)[d]);
                      upper[d] = std::max(upper[d], cell->vertex(v)[d]);
                    }
              }
          if (any)
            local_boxes.emplace_back(std::make_pair(lower, upper));
        }
      // Fully damaged points of materials with 'Nonlocal exclude fully
      // damaged' are left out of both sums of the average.
      std::vector<bool> is_source(damage_points.position.size());
      for (std::size_t k = 0; k < is_source.size(); ++k)
        {
          const double *p = damage_points.properties[k];
          is_source[k] =
            materials[static_cast<unsigned int>(p[layout.material_id])]
              ->is_nonlocal_source(p + layout.state);
        }
      averager->compute(local_boxes,
                        damage_points.position,
                        damage_points.volume,
                        damage_points.driver,
                        damage_points.receiver,
                        is_source,
                        damage_points.id,
                        nonlocal_driver);
      // Points whose driver approaches their damage threshold seed the
      // refinement pass at the end of this step (before the update: the
      // threshold the driver is compared with is the one it had to pass).
      for (std::size_t k = 0; k < damage_points.position.size(); ++k)
        if (damage_points.receiver[k])
          {
            double     *p = damage_points.properties[k];
            const auto &m =
              *materials[static_cast<unsigned int>(p[layout.material_id])];
            if (gather_precursors &&
                nonlocal_driver[k] > grid.refinement_driver_fraction *
                                       m.damage_threshold(p + layout.state))
              precursor_ids.push_back(damage_points.id[k]);
            if (stage.damage)
              m.update_damage(nonlocal_driver[k], dt, p + layout.state);
          }
      if (gather_precursors)
        std::sort(precursor_ids.begin(), precursor_ids.end());
    }


    template <int dim>
    void
    Simulation<dim>::check(const transfer::StepReport &report,
                           const Stage                &stage)
    {
      std::string cause;
      std::string failure = report.failure_message();
      if (report.n_outside > 0 && remove_outside &&
          report.n_failures() == report.n_outside)
        failure.clear();
      if (!failure.empty())
        {
          if (report.n_outside > 0 && report.n_failures() == report.n_outside)
            cause = "a body leaves the background mesh: enlarge the <Mesh> "
                    "box, or set <Points leaving the mesh> = remove.";
          else if (report.n_inverted > 0 && report.n_not_finite == 0 &&
                   report.n_too_fast == 0)
            cause = "extreme distortion of a material point: a time step "
                    "too large for the stiffness (<CFL number>), or a "
                    "material too soft for the load.";
          else
            cause = "an unstable step: the <CFL number> (" +
                    std::to_string(cfl) +
                    ") is too large for the stiffness and speed, or nodes "
                    "with tiny mass (<Small mass cutoff>, USL).";
        }
      else
        {
          // Energy balance: everything that entered minus what left.
          // With mass scaling the kinetic energy of the scaled inertia.
          const double kinetic = inertia_scale * report.kinetic_energy;
          const double balance = kinetic + report.gravitational_energy +
                                 internal_work + damping_dissipation +
                                 boundary_dissipation + mass_scaling_loss;
          last_residual   = balance - initial_energy;
          scale_of_energy = std::max(
            {scale_of_energy,
             kinetic,
             std::abs(report.gravitational_energy -
                      (initial_energy - last_report.kinetic_energy * 0)),
             std::abs(internal_work),
             report.stored_energy});
          if (last_residual > growth_tolerance * scale_of_energy &&
              scale_of_energy > 0)
            {
              std::ostringstream s;
              s << "The energy grew by " << last_residual << " J ("
                << 100 * last_residual / scale_of_energy
                << " % of the largest energy of the run, tolerance "
                << 100 * growth_tolerance << " %).";
              failure = s.str();
              cause   = "an unstable step: the <CFL number> (" +
                      std::to_string(cfl) +
                      ") is too large for the stiffness and speed.";
            }
        }
      if (failure.empty())
        return;
      std::ostringstream message;
      message << "Stage " << stage.name << ", step " << step
              << " (t = " << current_time << " s, dt = " << dt
              << " s): " << failure << " Likely cause: " << cause;
      write_summary("error: " + message.str());
      throw ScarpError(message.str());
    }


    template <int dim>
    void
    Simulation<dim>::advance(const Stage &stage)
    {
      const double scale = (stage.mass_scaling > 1 && !mass_scaling_ended)
                             ? stage.mass_scaling
                             : 1;
      if (scale > inertia_scale)
        {
          // Mass scaling begins: the kinetic energy is kept (velocities
          // times sqrt(old / new)). Keeping the velocities would multiply
          // the energy of the vibrations left from the previous stage by
          // m_s, and real time would get it back as m_s times stronger
          // vibrations when the scaling ends.
          const double f = std::sqrt(inertia_scale / scale);
          for (auto &particle : particles)
            {
              double *p = particle.get_properties().data();
              for (unsigned int d = 0; d < dim; ++d)
                p[layout.velocity + d] *= f;
              if (layout.has_affine)
                for (unsigned int i = 0; i < dim * dim; ++i)
                  p[layout.affine + i] *= f;
            }
          last_report.kinetic_energy *= f * f;
          last_report.max_speed *= f;
          inertia_scale = scale;
        }
      else if (scale < inertia_scale)
        {
          // Mass scaling ends: the velocities (the failure's motion) are
          // kept, and the kinetic energy of the inertia that goes is booked
          // so that the balance stays closed.
          mass_scaling_loss +=
            (inertia_scale - scale) * last_report.kinetic_energy;
          inertia_scale = scale;
        }
      mpm->set_mass_scale(inertia_scale);
      dt = stable_time_step();
      if (current_time + dt > stage.end_time)
        dt = std::max(stage.end_time - current_time, 1e-300);
      for (auto &m : materials)
        m->set_inelastic_enabled(stage.plasticity, stage.damage);

      if (body_force)
        body_force->set_time(current_time);
      transfer::StepReport report;
      {
        TimerOutput::Scope scope(timer, "MPM step");
        // Points of damage materials are gathered for the non-local step:
        // in damage stages every step; in the others (gravity loading) in
        // the step before a refinement check, so that cells refine where
        // the driver approaches the threshold while the loading is still
        // damped (their transients die out before the collapse starts).
        const bool gather =
          any_damage && (stage.damage || precursors_due(step + 1));
        report = mpm->step(dt,
                           gravity,
                           stage.damping,
                           gather ? &damage_points : nullptr);
        report.reduce(communicator);
      }
      internal_work += report.internal_work;
      damping_dissipation += report.damping_dissipation;
      boundary_dissipation += report.boundary_dissipation;
      current_time += dt;
      ++step;
      check(report, stage);
      if (inertia_scale > 1 && stage.mass_scaling_end_speed > 0 &&
          report.max_speed > stage.mass_scaling_end_speed)
        {
          // Real time from the next step on.
          mass_scaling_ended    = true;
          mass_scaling_end_time = current_time;
          pcout << "Stage " << stage.name << ": a point moves at "
                << report.max_speed << " m/s (> "
                << stage.mass_scaling_end_speed
                << " m/s): mass scaling ends at t = " << current_time << " s"
                << std::endl;
        }
      nonlocal_damage_step(stage);
      {
        TimerOutput::Scope scope(timer, "sort particles");
        if (report.n_changed_cell > 0)
          particles.sort_particles_into_subdomains_and_cells();
        else
          mpm->update_reference_locations();
      }
      if (report.n_outside > 0)
        n_removed += report.n_outside;
      if (first_damage_time < 0 && report.max_damage > 0.5 && stage.damage &&
          any_damage)
        first_damage_time = current_time;
      last_report = report;
      if (cliff && stage.damage && failure_time < 0 &&
          report.max_speed > failure_speed)
        {
          failure_time = current_time;
          cliff_snapshot("failure");
        }
      if (refinement_due())
        refine_mesh();
      else if (balance_interval > 0 && step % balance_interval == 0)
        rebalance_if_needed();
      if (step >= max_steps)
        {
          write_summary("error: maximum number of steps reached");
          throw ScarpError("Stage " + stage.name +
                           ": the run reached <Maximum "
                           "steps> = " +
                           std::to_string(max_steps) +
                           " at t = " + std::to_string(current_time) + " s.");
        }
    }


    template <int dim>
    bool
    Simulation<dim>::refinement_due() const
    {
      return grid.adaptive_refinement && step % grid.refinement_interval == 0;
    }


    template <int dim>
    bool
    Simulation<dim>::precursors_due(const unsigned int s) const
    {
      return grid.adaptive_refinement && grid.refinement_driver_fraction > 0 &&
             s % grid.refinement_interval == 0;
    }


    template <int dim>
    void
    Simulation<dim>::refine_mesh()
    {
      TimerOutput::Scope scope(timer, "refinement");
      auto              &tria = grid.triangulation();
      ++n_refinement_checks;
      // Seeds: cells with a damaged point, or with a point whose non-local
      // driver approaches its damage threshold (gathered in the non-local
      // step). Both are properties of the points, so the seeds do not
      // depend on the partition.
      std::vector<typename Triangulation<dim>::active_cell_iterator> seeds;
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto &particle : particles.particles_in_cell(cell))
            {
              const double *p = particle.get_properties().data();
              const auto   &m =
                *materials[static_cast<unsigned int>(p[layout.material_id])];
              if (m.damage(p + layout.state) > grid.refinement_damage_limit ||
                  std::binary_search(precursor_ids.begin(),
                                     precursor_ids.end(),
                                     particle.get_id()))
                {
                  seeds.push_back(cell);
                  break;
                }
            }
      precursor_ids.clear();
      const double buffer =
        grid.refinement_buffer * (averager ? averager->cutoff_radius() : 0.);
      if (grid::RefinementMarker<dim>::mark(
            tria, seeds, buffer, grid.max_refinement_level) == 0)
        return;
      particles.prepare_for_coarsening_and_refinement();
      tria.execute_coarsening_and_refinement();
      particles.unpack_after_coarsening_and_refinement();
      std::vector<unsigned int> per_direction;
      for (const auto &body : bodies)
        per_direction.push_back(body.per_direction);
      n_split += particles::PointSplitter<dim>::split(
        particles, layout, per_direction, grid.domain(), communicator);
      particles.sort_particles_into_subdomains_and_cells();
      // Splitting changed the points per cell: repartition by them.
      if (Utilities::MPI::n_mpi_processes(communicator) > 1)
        balance_load();
      else
        grid.setup_dofs();
      mpm->setup();
      local_boxes.clear();
      if (averager)
        averager->invalidate_neighbour_lists();
      ++n_refinement_passes;
    }


    template <int dim>
    void
    Simulation<dim>::write_output()
    {
      if (!outputs_enabled)
        return;
      TimerOutput::Scope scope(timer, "output");
      vtu->write_particles(particles, layout, current_time, output_index);
      if (write_mesh_files)
        vtu->write_mesh(grid,
                        mpm->nodal_mass(),
                        mpm->nodal_velocity(),
                        current_time,
                        output_index);
      ++output_index;
    }


    template <int dim>
    void
    Simulation<dim>::write_statistics(const transfer::StepReport &r,
                                      const Stage                &stage)
    {
      (void)stage;
      if (!statistics)
        return;
      const double material_dissipation = internal_work - r.stored_energy;
      std::vector<double> row({double(step),
                               current_time,
                               dt,
                               double(current_stage),
                               r.kinetic_energy,
                               r.stored_energy,
                               r.gravitational_energy,
                               internal_work,
                               damping_dissipation,
                               boundary_dissipation,
                               r.plastic_dissipation,
                               r.damage_dissipation,
                               material_dissipation,
                               last_residual,
                               r.momentum[0],
                               r.momentum[1],
                               r.momentum[2],
                               r.angular_momentum[0],
                               r.angular_momentum[1],
                               r.angular_momentum[2],
                               r.n_points,
                               r.mass,
                               r.max_speed,
                               r.max_damage,
                               r.damaged_volume,
                               wall_clock.wall_time()});
      if (reference_displacement)
        {
          double       norm    = 0;
          const double e       = reference_error(&norm);
          reference_error_last = e;
          reference_error_max  = std::max(reference_error_max, e);
          reference_norm_max   = std::max(reference_norm_max, norm);
          row.push_back(e);
        }
      if (grid.boundary_conditions().has_prescribed_velocity())
        {
          const auto f = grid.boundary_conditions().take_reaction(communicator);
          for (unsigned int d = 0; d < dim; ++d)
            row.push_back(f[d]);
        }
      statistics->write_row(row);
    }


    template <int dim>
    void
    Simulation<dim>::print_progress(const transfer::StepReport &r,
                                    const Stage                &stage,
                                    const bool                  force)
    {
      const double wall = wall_clock.wall_time();
      if (!force && wall - last_progress_wall < 2.)
        return;
      last_progress_wall = wall;
      const double done  = current_time / stages.back().end_time;
      const double eta   = done > 0 ? wall * (1 - done) / done : 0;
      pcout << "  " << std::setw(8) << stage.name << "  step " << std::setw(7)
            << step << "  t = " << std::setw(10) << std::setprecision(5)
            << current_time << " s  dt = " << std::setw(9)
            << std::setprecision(3) << dt << " s  E_kin = " << std::setw(10)
            << r.kinetic_energy << " J  max d = " << std::setw(5)
            << std::setprecision(3) << r.max_damage << "  wall "
            << format_seconds(wall) << "  ETA <= " << format_seconds(eta)
            << std::endl;
    }


    template <int dim>
    void
    Simulation<dim>::write_summary(const std::string &how_it_ended)
    {
      if (!outputs_enabled ||
          Utilities::MPI::this_mpi_process(communicator) != 0)
        return;
      postprocess::JsonObject summary;
      summary.add("ended", how_it_ended);
      summary.add("dimension", double(dim));
      summary.add("mpi_ranks",
                  double(Utilities::MPI::n_mpi_processes(communicator)));
      summary.add("steps", double(step));
      summary.add("load_rebalances", double(n_rebalances));
      if (grid.adaptive_refinement)
        {
          postprocess::JsonObject refinement;
          refinement.add("checks", double(n_refinement_checks));
          refinement.add("passes", double(n_refinement_passes));
          refinement.add("points_split", double(n_split));
          refinement.add("finest_cell", grid.minimum_cell_size());
          summary.add("refinement", refinement);
        }
      summary.add("time", current_time);
      summary.add("material_points", last_report.n_points);
      summary.add("cells",
                  double(grid.triangulation().n_global_active_cells()));
      summary.add("wall_time", wall_clock.wall_time());
      const double point_steps = last_report.n_points * step;
      summary.add("particle_steps_per_second",
                  point_steps / std::max(wall_clock.wall_time(), 1e-9));
      postprocess::JsonObject energies;
      energies.add("kinetic", last_report.kinetic_energy);
      energies.add("strain", last_report.stored_energy);
      energies.add("gravitational", last_report.gravitational_energy);
      energies.add("internal_work", internal_work);
      energies.add("damping_dissipation", damping_dissipation);
      if (mass_scaling_loss != 0)
        energies.add("mass_scaling_dissipation", mass_scaling_loss);
      energies.add("boundary_dissipation", boundary_dissipation);
      energies.add("plastic_dissipation", last_report.plastic_dissipation);
      energies.add("damage_dissipation", last_report.damage_dissipation);
      energies.add("balance_residual", last_residual);
      summary.add("energies", energies);
      postprocess::JsonObject phases;
      for (const auto &[name, seconds] :
           timer.get_summary_data(TimerOutput::total_wall_time))
        phases.add(name, seconds);
      summary.add("wall_time_per_phase", phases);
      summary.add("stages", stage_summaries);
      if (cliff)
        summary.add("cliff", cliff_summary);
      summary.add("max_damage", last_report.max_damage);
      summary.add("first_damage_time", first_damage_time);
      summary.add("points_removed", n_removed);
      if (averager)
        {
          // How often the non-local lists were rebuilt, reused as they
          // were, or reused for the same points in a new order.
          postprocess::JsonObject lists;
          lists.add("rebuilds", double(averager->n_rebuilds()));
          lists.add("reuses", double(averager->n_reuses()));
          lists.add("reorders", double(averager->n_reorders()));
          summary.add("nonlocal_lists", lists);
        }
      if (reference_displacement)
        {
          postprocess::JsonObject ref;
          ref.add("final", reference_error_last);
          ref.add("max", reference_error_max);
          ref.add("norm_max", reference_norm_max);
          ref.add("relative_max",
                  reference_error_max / std::max(reference_norm_max, 1e-300));
          summary.add("reference_error", ref);
        }
      summary.write(output_directory + "/summary.json");
    }


    template <int dim>
    void
    Simulation<dim>::run_until(const double t)
    {
      outputs_enabled = false;
      if (!mpm)
        setup();
      Stage stage = stages.front();
      for (const auto &s : stages)
        if (current_time < s.end_time)
          {
            stage = s;
            break;
          }
      stage.end_time = t;
      while (current_time < t * (1 - 1e-12))
        advance(stage);
    }


    template <int dim>
    void
    Simulation<dim>::run()
    {
      if (Utilities::MPI::this_mpi_process(communicator) == 0)
        std::filesystem::create_directories(output_directory);
      MPI_Barrier(communicator);
      wall_clock.restart();
      setup();
      pcout << "scarp: " << dim << "D, "
            << grid.triangulation().n_global_active_cells() << " cells, "
            << last_report.n_points << " material points on "
            << Utilities::MPI::n_mpi_processes(communicator) << " rank(s)"
            << std::endl;
      vtu = std::make_unique<postprocess::VtuOutput<dim>>(output_directory,
                                                          communicator);
      std::vector<std::string> columns{"step",
                                       "time",
                                       "dt",
                                       "stage",
                                       "kinetic_energy",
                                       "strain_energy",
                                       "gravitational_energy",
                                       "internal_work",
                                       "damping_dissipation",
                                       "boundary_dissipation",
                                       "plastic_dissipation",
                                       "damage_dissipation",
                                       "material_dissipation",
                                       "energy_residual",
                                       "momentum_x",
                                       "momentum_y",
                                       "momentum_z",
                                       "angular_momentum_x",
                                       "angular_momentum_y",
                                       "angular_momentum_z",
                                       "material_points",
                                       "mass",
                                       "max_speed",
                                       "max_damage",
                                       "damaged_volume",
                                       "wall_time"};
      if (reference_displacement)
        columns.push_back("reference_error");
      for (const auto &name :
           grid.boundary_conditions().reaction_column_names())
        columns.push_back(name);
      // Resumed: statistics.csv and the PVD files as they were at the
      // checkpoint (the rows and outputs after it drop out), then appended.
      statistics = std::make_unique<postprocess::StatisticsFile>(
        output_directory + "/statistics.csv",
        columns,
        Utilities::MPI::this_mpi_process(communicator) == 0,
        checkpoint.resuming());
      if (checkpoint.resuming())
        {
          vtu->restore_records(restored_records);
          pcout << "Resumed from " << checkpoint.loaded_directory()
                << " at step " << step << ", t = " << current_time << " s"
                << std::endl;
        }
      else
        {
          write_statistics(last_report, stages.front());
          write_output();
          next_output   = output_interval;
          current_stage = 0;
        }
      checkpoint.start();

      for (; current_stage < stages.size(); ++current_stage)
        {
          const Stage &stage = stages[current_stage];
          if (!stage_in_progress)
            {
              stage_start_time      = current_time;
              stage_start_step      = step;
              stage_peak_kinetic    = 0;
              settled_since         = -1;
              stage_in_progress     = true;
              mass_scaling_ended    = false;
              mass_scaling_end_time = -1;
            }
          const double       start_time = stage_start_time;
          const unsigned int start_step = stage_start_step;
          const double       start_wall = wall_clock.wall_time();
          std::string        reason     = "end time";
          pcout << "Stage " << stage.name << " (to t = " << stage.end_time
                << " s)" << std::endl;
          if (cliff && stage.damage && damage_stage_start < 0)
            {
              damage_stage_start = current_time;
              cliff_snapshot("start");
            }
          while (current_time < stage.end_time * (1 - 1e-12))
            {
              advance(stage);
              if (step % statistics_interval == 0)
                write_statistics(last_report, stage);
              if (output_interval > 0 &&
                  current_time >= next_output * (1 - 1e-12))
                {
                  write_output();
                  while (next_output <= current_time * (1 + 1e-12))
                    next_output += output_interval;
                }
              print_progress(last_report, stage, false);
              if (failure_time >= 0 && after_failure_delay >= 0 &&
                  !after_failure_taken &&
                  current_time >= failure_time + after_failure_delay)
                {
                  after_failure_taken = true;
                  cliff_snapshot("after_failure");
                  if (stop_after_failure)
                    {
                      reason = "stopped after failure";
                      break;
                    }
                }
              if (stage.settle)
                {
                  stage_peak_kinetic =
                    std::max(stage_peak_kinetic, last_report.kinetic_energy);
                  const bool quiet = step - start_step > 20 &&
                                     last_report.kinetic_energy <=
                                       stage.kinetic_ratio * stage_peak_kinetic;
                  if (!quiet)
                    settled_since = -1;
                  else if (settled_since < 0)
                    settled_since = current_time;
                  if (quiet &&
                      current_time - settled_since >= stage.settle_time)
                    {
                      reason = "kinetic energy settled";
                      break;
                    }
                }
              checkpoint_if_due();
            }
          if (stage.reset_displacement)
            for (auto &particle : particles)
              layout.set_vector(particle.get_properties().data(),
                                layout.reference_position,
                                particle.get_location());
          write_statistics(last_report, stage);
          write_output();
          print_progress(last_report, stage, true);
          postprocess::JsonObject s;
          s.add("end_reason", reason);
          s.add("start_time", start_time);
          s.add("end_time", current_time);
          s.add("steps", double(step - start_step));
          s.add("wall_time", wall_clock.wall_time() - start_wall);
          s.add("kinetic_energy", last_report.kinetic_energy);
          if (stage.mass_scaling > 1)
            {
              s.add("mass_scaling", stage.mass_scaling);
              s.add("mass_scaling_end_time", mass_scaling_end_time);
            }
          stage_summaries.add(stage.name, s);
          pcout << "Stage " << stage.name << " ended (" << reason
                << ") at t = " << current_time << " s after "
                << step - start_step << " steps" << std::endl;
          stage_in_progress = false;
          if (after_failure_taken && stop_after_failure)
            break;
          if (checkpoint.at_stage_ends() && current_stage + 1 < stages.size())
            write_checkpoint();
        }
      if (cliff && after_failure_taken && stop_after_failure)
        {
          // The debris is still moving: only the onset means something.
          const double onset = failure_time - damage_stage_start;
          cliff_summary.add("failure_onset_s", onset);
          cliff_summary.add("max_damage", last_report.max_damage);
          pcout << "Cliff: failure onset " << onset
                << " s after the start of damage; stopped "
                << after_failure_delay << " s later (no debris diagnostics)"
                << std::endl;
          write_summary("stopped after failure");
        }
      else
        {
          if (cliff)
            cliff_snapshot("end");
          write_summary("completed");
        }
      timer.print_wall_time_statistics(communicator);
      pcout << "Wall time " << format_seconds(wall_clock.wall_time()) << ", "
            << step << " steps, "
            << last_report.n_points * step /
                 std::max(wall_clock.wall_time(), 1e-9)
            << " particle-steps/s. Output in " << output_directory << "/"
            << std::endl;
    }

    template <int dim>
    std::vector<postprocess::CliffDiagnostics::Particle>
    Simulation<dim>::gather_cliff_points() const
    {
      std::vector<double> local;
      for (const auto &particle : particles)
        {
          const double *p = particle.get_properties().data();
          if (!bodies[static_cast<unsigned int>(p[layout.body_id])].cliff)
            continue;
          const auto &m =
            *materials[static_cast<unsigned int>(p[layout.material_id])];
          const Point<dim> x = particle.get_location();
          const double     J =
            determinant(layout.get_matrix(p, layout.deformation_gradient));
          local.insert(local.end(),
                       {x[0],
                        x[1],
                        p[layout.reference_position],
                        p[layout.reference_position + 1],
                        p[layout.reference_volume] * J,
                        m.damage(p + layout.state)});
        }
      const auto all = Utilities::MPI::gather(communicator, local, 0);
      std::vector<postprocess::CliffDiagnostics::Particle> points;
      for (const auto &chunk : all)
        for (std::size_t k = 0; k + 5 < chunk.size(); k += 6)
          {
            postprocess::CliffDiagnostics::Particle q;
            q.position         = Point<2>(chunk[k], chunk[k + 1]);
            q.initial_position = Point<2>(chunk[k + 2], chunk[k + 3]);
            q.volume           = chunk[k + 4];
            q.damage           = chunk[k + 5];
            points.push_back(q);
          }
      return points;
    }


    template <int dim>
    void
    Simulation<dim>::cliff_snapshot(const std::string &tag)
    {
      if (!outputs_enabled || !cliff || dim != 2)
        return;
      TimerOutput::Scope scope(timer, "cliff diagnostics");
      const auto         points = gather_cliff_points();
      if (Utilities::MPI::this_mpi_process(communicator) != 0)
        return;
      postprocess::CliffDiagnostics::write_particles_csv(
        output_directory + "/cliff_" + tag + "_particles.csv", points);
      if (tag != "end")
        return;
      const auto profile =
        cliff_diagnostics.surface_profile(points,
                                          cliff->get_parameters().beach_level,
                                          grid.domain().lower_bound(0),
                                          grid.domain().upper_bound(0));
      const auto r = cliff_diagnostics.analyse(profile, points, *cliff);
      postprocess::CliffDiagnostics::write_profile_csv(
        output_directory + "/cliff_profile.csv", profile, &r);
      const double onset =
        failure_time >= 0 ? failure_time - damage_stage_start : -1;
      cliff_summary.add("debris_angle_deg", r.debris_angle);
      cliff_summary.add("run_out_m", r.run_out);
      cliff_summary.add("debris_toe_x_m", r.debris_toe);
      cliff_summary.add("failed_area_m2", r.failed_area);
      cliff_summary.add("scarp_position_x_m", r.scarp_position);
      cliff_summary.add("scarp_retreat_m", r.scarp_retreat);
      cliff_summary.add("failure_onset_s", onset);
      cliff_summary.add("max_damage", last_report.max_damage);
      cliff_summary.add("dissipated_energy_J",
                        last_report.plastic_dissipation +
                          last_report.damage_dissipation);
      cliff_summary.add("plastic_dissipation_J",
                        last_report.plastic_dissipation);
      cliff_summary.add("damage_dissipation_J", last_report.damage_dissipation);
      std::ostringstream s;
      s << std::setprecision(4) << "Cliff: debris angle " << r.debris_angle
        << " deg, run-out " << r.run_out << " m, failed area " << r.failed_area
        << " m^2, scarp at x = " << r.scarp_position << " m, failure onset "
        << onset << " s after the start of damage, "
        << "max damage " << last_report.max_damage << ", dissipated "
        << last_report.plastic_dissipation + last_report.damage_dissipation
        << " J/m";
      std::cout << s.str() << std::endl;
    }


    template class Simulation<2>;
    template class Simulation<3>;
  } // namespace simulation
} // namespace scarp
