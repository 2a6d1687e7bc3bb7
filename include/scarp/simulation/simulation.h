#ifndef scarp_simulation_simulation_h
#define scarp_simulation_simulation_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/base/timer.h>
#include <deal.II/particles/particle_handler.h>

#include <scarp/grid/background_grid.h>
#include <scarp/materials/material.h>
#include <scarp/nonlocal/nonlocal_averager.h>
#include <scarp/nonlocal/parameters.h>
#include <scarp/particles/point_splitter.h>
#include <scarp/particles/property_layout.h>
#include <scarp/postprocess/cliff_diagnostics.h>
#include <scarp/postprocess/json_writer.h>
#include <scarp/postprocess/statistics_file.h>
#include <scarp/postprocess/vtu_output.h>
#include <scarp/scenes/cliff_profile.h>
#include <scarp/scenes/shape.h>
#include <scarp/simulation/checkpoint.h>
#include <scarp/simulation/loop_state.h>
#include <scarp/simulation/scene_lists.h>
#include <scarp/simulation/stage.h>
#include <scarp/transfer/mpm_transfer.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace scarp
{
  namespace simulation
  {
    using namespace dealii;

    /// Seconds as HH:MM:SS, for the progress line and the end of a run.
    std::string
    format_seconds(const double s);

    /**
     * @brief One scene run from a parameter file: the only place that knows
     * the mesh, the particles, the materials, the stages and the outputs,
     * and the time loop that joins them.
     */
    template <int dim>
    class Simulation
    {
    public:
      Simulation(MPI_Comm communicator, const SceneLists &lists);
      ~Simulation();

      /// Declare every entry of a scene with the named subsections.
      static void
      declare_parameters(ParameterHandler &prm, const SceneLists &lists);
      void
      parse_parameters(ParameterHandler &prm);

      /// Build the mesh and seed the bodies (no step yet); or, when the
      /// run resumes (set_resume_directory(), <Checkpoint/Resume from>),
      /// read the mesh, the points and the loop state of the checkpoint.
      void
      setup();

      /// Resume from this checkpoint directory (or an output directory
      /// holding one) instead of seeding: the command line's --resume.
      /// Before setup().
      void
      set_resume_directory(const std::string &directory)
      {
        checkpoint.set_resume_directory(directory);
      }

      /// Run all stages; writes outputs, statistics.csv and summary.json.
      void
      run();

      /// Run only up to (simulated) time @p t, without outputs: for tests.
      void
      run_until(const double t);

      /// Time, step, energies and counters of the time loop.
      const LoopState &
      loop_state() const
      {
        return loop;
      }

      /// Energies, momenta and counts of the particles now (reduced).
      transfer::StepReport
      measure() const;

      const Particles::ParticleHandler<dim> &
      particle_handler() const
      {
        return particles;
      }
      /// The particles for writing an initial state that a scene file
      /// cannot describe (tests: manufactured solutions, shifted lattices),
      /// after setup() and before the first step. Call sort_particles()
      /// after changing any location.
      Particles::ParticleHandler<dim> &
      particle_handler_for_initialisation()
      {
        return particles;
      }
      /// Sort the particles into cells and ranks after their locations were
      /// changed through particle_handler_for_initialisation(), and measure
      /// the initial state again (energies, largest speed for the first dt).
      void
      sort_particles()
      {
        particles.sort_particles_into_subdomains_and_cells();
        particles.update_cached_numbers();
        last_report = measure();
        if (loop.step == 0)
          {
            loop.energy.initial =
              last_report.kinetic_energy + last_report.gravitational_energy;
            loop.energy.scale = last_report.kinetic_energy;
          }
      }
      /// The time step the next step will take (before clipping to the end
      /// of a stage): min(<Maximum time step>, CFL h_min / (c_p + max |v|)).
      double
      stable_time_step() const;
      const particles::PropertyLayout<dim> &
      property_layout() const
      {
        return layout;
      }
      const materials::Material &
      material(const unsigned int i) const
      {
        return *materials[i];
      }
      double
      time() const
      {
        return loop.time;
      }
      unsigned int
      step_number() const
      {
        return loop.step;
      }
      double
      time_step() const
      {
        return loop.dt;
      }
      /// Whether this scene runs the non-local damage average at all (only
      /// scenes with a damage material do).
      bool
      has_nonlocal_average() const
      {
        return averager != nullptr;
      }
      const grid::BackgroundGrid<dim> &
      background_grid() const
      {
        return grid;
      }
      /// With a <Reference solution>: the volume-weighted L2 error of the
      /// point displacements against it at the current time,
      /// sqrt(sum V0 |x - X - u(X,t)|^2 / sum V0) (collective), and the
      /// same norm of u(X,t) itself in @p norm if given. -1 without one.
      double
      reference_error(double *norm = nullptr) const;
      /// Cumulative energy bookkeeping: the balance residual
      /// E_kin + E_grav + W_int + D_damping + D_boundary + D_mass_scaling +
      /// D_transfer - W_body - E_0 after the last step.
      double
      energy_residual() const
      {
        return loop.energy.residual;
      }
      /// The terms of the balance that are sums over the steps.
      double
      transfer_dissipation_total() const
      {
        return loop.energy.transfer_dissipation;
      }
      double
      body_force_work_total() const
      {
        return loop.energy.body_force_work;
      }
      double
      internal_work_total() const
      {
        return loop.energy.internal_work;
      }
      double
      boundary_dissipation_total() const
      {
        return loop.energy.boundary_dissipation;
      }
      double
      damping_dissipation_total() const
      {
        return loop.energy.damping_dissipation;
      }
      double
      energy_scale() const
      {
        return loop.energy.scale;
      }

    private:
      struct Body
      {
        std::string                                     name;
        unsigned int                                    material      = 0;
        unsigned int                                    per_direction = 2;
        std::unique_ptr<scenes::Shape<dim>>             shape;
        std::unique_ptr<scenes::CliffProfile>           cliff;
        std::unique_ptr<Functions::ParsedFunction<dim>> velocity;
        std::unique_ptr<Functions::ParsedFunction<dim>> stress;
        std::unique_ptr<Functions::ParsedFunction<dim>> displacement;
      };

      /// Apply the bodies' <Initial displacement>: points move to X + u(X),
      /// F = I + grad u (difference quotients), stress from one material
      /// update with dF = F (elastic).
      void
      apply_initial_displacement();

      void
      seed_bodies();
      /// Repartition the mesh so that every rank holds about as many
      /// material points (cells weighted by their points).
      void
      balance_load();
      /// Whether the points per rank have drifted apart by more than
      /// balance_tolerance (max/mean - 1; collective, false on one rank).
      bool
      points_out_of_balance() const;
      /// Repartition when the points per rank have drifted apart by more
      /// than balance_tolerance (collective; every balance_interval steps).
      void
      rebalance_if_needed();
      void
      advance(const Stage &stage);
      /// The settling criterion of @p stage after a step: true once the
      /// kinetic energy has stayed below its ratio of the stage's peak for
      /// the settle time (updates loop.stage).
      bool
      stage_settled(const Stage &stage);
      /// The deposit criterion of @p stage after a step (cliff scenes,
      /// after the failure onset): every Stage::deposit_check_interval,
      /// measure the debris toe, the scarp and the failed areas; a change
      /// beyond the tolerances opens a new quiet period, and the stage is
      /// settled once one has lasted Stage::deposit_settle_time. Each
      /// measurement is compared with the one that opened the period, not
      /// with the last, so that a slow creep adds up and is caught. Updates
      /// loop.deposit; collective.
      bool
      deposit_settled(const Stage &stage);
      /// Mesh/Refinement/Set-up passes: run the first stage without output,
      /// and after a pass that refined the mesh discard the points, seed
      /// the bodies anew on the refined mesh and reset the loop state.
      void
      run_setup_passes();
      /// Loop state and energy reference of a fresh start on the current
      /// points (set-up, and after a set-up pass).
      void
      start_loop_state();
      /// The reference volume of the points faster than @p speed (all
      /// ranks; collective): the onset of a failure and the end of mass
      /// scaling need more than a point or two (a flake at the notch).
      double
      fast_volume(const double speed);
      /// Put the particle handler's list of cells in order before an
      /// iteration over all points that depends on it (sums, output,
      /// splitting; transfer::MpmTransfer::restore_point_order()): the
      /// point mover leaves it out of order when points enter empty cells.
      /// Collective.
      void
      order_points()
      {
        mpm->restore_point_order();
      }

      /// Whether a stage scales the mass (statistics.csv then carries
      /// mass_scaling_dissipation).
      bool
      any_mass_scaling() const
      {
        for (const Stage &stage : stages)
          if (stage.mass_scaling > 1)
            return true;
        return false;
      }
      void
      nonlocal_damage_step(const Stage &stage);
      void
      check(const transfer::StepReport &report, const Stage &stage);
      void
      write_statistics(const transfer::StepReport &report, const Stage &stage);
      void
      write_output();
      void
      write_summary(const std::string &how_it_ended);
      /// Collective: the parts of the MPM step (MpmTransfer::PartTimes) as
      /// min, mean and max over the ranks, into @p part_statistics for the
      /// summary. A rank's compute time is the sum of the parts less its
      /// exchange; the rank that waits least is the one the others wait
      /// for.
      void
      gather_part_statistics();
      /// The table of part_statistics on the console.
      void
      print_part_statistics() const;
      /// The record of the current stage in summary.json: how it ended,
      /// its start and end, the end of its mass scaling. A stage that has
      /// ended (@p wall_time given: its wall time) also has its steps, wall
      /// time and final kinetic energy; one "in progress" (a run that
      /// stopped inside it) has not.
      postprocess::JsonObject
      stage_record(const Stage                 &stage,
                   const std::string           &end_reason,
                   const std::optional<double> &wall_time) const;
      void
      print_progress(const transfer::StepReport &report,
                     const Stage                &stage,
                     const bool                  force);
      /// A refinement pass: flags from the criteria, refinement, splitting,
      /// load balance (see doc/refinement.md). Does nothing when no cell is
      /// flagged anywhere.
      void
      refine_mesh();
      /// True when a refinement pass is due at the end of this step.
      bool
      refinement_due() const;
      /// True when the non-local driver of step @p s feeds the criterion
      /// "driver near the threshold" (the step before a refinement check).
      bool
      precursors_due(const unsigned int s) const;
      /// Checkpoints (source/simulation/simulation_checkpoint.cc): the
      /// loop state to and from an archive, reading a checkpoint in
      /// setup(), and writing one when due after a step.
      template <class Archive>
      void
      serialize_loop_state(Archive &ar);
      void
      load_checkpoint();
      void
      write_checkpoint();
      /// After a step: write a checkpoint when one is due; after SIGTERM or
      /// SIGINT write one and stop with a ScarpError.
      void
      checkpoint_if_due();
      /// Material points of the cliff bodies, gathered on rank 0.
      std::vector<postprocess::CliffDiagnostics::Particle>
      gather_cliff_points();
      /// Write cliff_<tag>_particles.csv (rank 0); at "end" also the surface
      /// profile and the diagnostics, which go into the summary.
      void
      cliff_snapshot(const std::string &tag);
      /// The free-surface profiles of the gathered cliff @p points over the
      /// whole mesh width (rank 0).
      postprocess::CliffDiagnostics::Profile
      cliff_surface_profile(
        const std::vector<postprocess::CliffDiagnostics::Particle> &points)
        const;
      /// Append the cliff diagnostics of now to cliff_history.csv (with
      /// every particle output; collective).
      void
      write_cliff_history();

      MPI_Comm            communicator;
      SceneLists          lists;
      ConditionalOStream  pcout;
      mutable TimerOutput timer;
      Timer               wall_clock;
      /// The step this run started from (a resumed run: the checkpoint's),
      /// for the speed of this run.
      unsigned int first_step = 0;
      /// The simulated time this run started from, for its estimate of the
      /// wall time left.
      double first_time = 0;

      grid::BackgroundGrid<dim>                         grid;
      Particles::ParticleHandler<dim>                   particles;
      particles::PropertyLayout<dim>                    layout;
      std::vector<std::unique_ptr<materials::Material>> materials;
      std::vector<const materials::Material *>          material_pointers;
      std::vector<Body>                                 bodies;
      std::vector<std::unique_ptr<scenes::Shape<dim>>>  predamaged;
      std::vector<Stage>                                stages;
      transfer::TransferParameters                      transfer_parameters;
      std::unique_ptr<transfer::MpmTransfer<dim>>       mpm;
      std::unique_ptr<nonlocal::NonlocalAverager<dim>>  averager;
      transfer::DamagePoints<dim>                       damage_points;
      std::vector<double>                               nonlocal_driver;
      bool                                              any_damage = false;
      std::vector<BoundingBox<dim>>                     local_boxes;
      /// Non-local average/Update interval: steps between two averages.
      unsigned int nonlocal_update_interval = 1;
      /// Refinement: ids of points whose non-local driver is near their
      /// damage threshold (sorted), gathered in the non-local step before a
      /// refinement pass.
      std::vector<types::particle_index> precursor_ids;
      boost::signals2::connection        weight_connection;

      Tensor<1, dim>                                  gravity;
      std::unique_ptr<Functions::ParsedFunction<dim>> body_force;
      std::unique_ptr<Functions::ParsedFunction<dim>> reference_displacement;
      double                                          cfl           = 0.5;
      double                                          max_time_step = 1e30;
      std::string  output_directory                                 = "output";
      double       output_interval                                  = 0;
      unsigned int statistics_interval                              = 10;
      bool         write_mesh_files                                 = true;
      double       growth_tolerance                                 = 0.1;
      /// Load balancing during the run (see rebalance_if_needed()).
      unsigned int balance_interval  = 200;
      double       balance_tolerance = 0.1;
      bool         remove_outside    = false;
      unsigned int max_steps         = 100000000;
      /// Points can leave the scene (remove_outside, or a material's
      /// removal of stretched damaged points): the statistics book their
      /// energy (removed_energy).
      bool removes_points = false;
      /// The first removal of stretched points of the run was announced.
      bool removal_reported = false;

      /// The state of the time loop (time, step, stage, energies, mass
      /// scaling, failure, counters): what a checkpoint saves of it.
      LoopState loop;
      /// Off in run_until() (tests): no files, no summary.
      bool outputs_enabled = true;
      /// Wall time of the last progress line (not saved: wall clock).
      double last_progress_wall = -1e9;
      /// The report of the last step (energies, largest speed for the next
      /// dt); saved with the loop state.
      transfer::StepReport                         last_report;
      std::unique_ptr<postprocess::StatisticsFile> statistics;
      std::unique_ptr<postprocess::VtuOutput<dim>> vtu;
      postprocess::JsonObject                      stage_summaries;
      postprocess::CliffDiagnostics                cliff_diagnostics;
      postprocess::JsonObject                      cliff_summary;
      /// Filled by gather_part_statistics() at the end of a run.
      std::vector<std::pair<std::string, Utilities::MPI::MinMaxAvg>>
                                  part_statistics;
      const scenes::CliffProfile *cliff          = nullptr;
      double                      failure_speed  = 0.1;
      double                      failure_volume = 0;
      /// Snapshot "after_failure" this long after the onset [s] (< 0: none);
      /// compares failure surfaces across resolutions at one stage of motion.
      double after_failure_delay = 1.;
      /// End the run once the after-failure snapshot is taken.
      bool stop_after_failure = false;

      Checkpoint<dim> checkpoint;
      /// The PVD records read from a checkpoint, for the VtuOutput.
      std::pair<std::vector<std::pair<double, std::string>>,
                std::vector<std::pair<double, std::string>>>
        restored_records;
    };
  } // namespace simulation
} // namespace scarp

#endif
