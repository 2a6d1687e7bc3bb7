#ifndef scarp_simulation_checkpoint_h
#define scarp_simulation_checkpoint_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/particles/particle_handler.h>

#include <string>
#include <vector>

namespace scarp
{
  namespace simulation
  {
    using namespace dealii;

    /**
     * @brief Checkpoints of a run and resuming from them: when they are due
     * (<Checkpoint/Wall time interval>, <Time interval>, the end of a
     * stage, SIGTERM or SIGINT), how they are written (into
     * <checkpoint.tmp>, then renamed to <checkpoint> once complete, the
     * previous one kept as <checkpoint.old> until then), and how they are
     * checked and read back (manifest with format, dimension, scene hash
     * and file sizes).
     *
     * A checkpoint directory holds the mesh with the particles attached
     * (parallel::distributed::Triangulation::save() after
     * ParticleHandler::prepare_for_serialization()), the loop state of the
     * Simulation (an opaque string here), copies of files of the output
     * directory that must be cut back to the checkpoint on restart
     * (statistics.csv) and, written last, the manifest: a directory without
     * a complete manifest is no checkpoint.
     */
    template <int dim>
    class Checkpoint
    {
    public:
      /// What poll() found due after a step.
      enum class Due
      {
        nothing,
        interval, ///< an interval has passed: write and go on
        stop      ///< SIGTERM/SIGINT on some rank: write and stop
      };

      explicit Checkpoint(MPI_Comm communicator);

      /// The subsection Checkpoint.
      static void
      declare_parameters(ParameterHandler &prm);
      /// Reads the subsection Checkpoint and <Output directory>, and
      /// fingerprints the scene (at the top level of @p prm): the entries
      /// that differ from @p defaults (the ShortPRM text of the same
      /// declarations, unset), but those of Checkpoint, <Output directory>,
      /// the <End time> of the stages @p stage_names and the skin of the
      /// non-local lists (which changes the cost, not the result).
      void
      parse_parameters(ParameterHandler               &prm,
                       const std::vector<std::string> &stage_names,
                       const std::string              &defaults);

      /// The names of the particle properties (the layout this scene's
      /// points carry): a checkpoint whose points carry others, from
      /// another version of scarp, is refused.
      void
      set_particle_properties(const std::vector<std::string> &names);

      /// Resume from @p directory (the command line's --resume, which
      /// overrides <Resume from>); empty: start afresh.
      void
      set_resume_directory(const std::string &directory);
      /// True when the run resumes from a checkpoint.
      bool
      resuming() const
      {
        return !resume_from.empty();
      }

      /// Install the SIGTERM/SIGINT handlers (they only set a flag that
      /// poll() reads) and start the wall-time interval.
      void
      start();
      /// Collective, once per step: whether a checkpoint is due at the
      /// simulated time @p time. The signal flag and the wall clock (of
      /// rank 0) are combined with one MPI max reduction, so that all ranks
      /// decide alike. (Test hook: the environment variable
      /// SCARP_TEST_SIGTERM_AT_STEP=N makes rank 0 send itself SIGTERM at
      /// step @p step = N.)
      Due
      poll(const double time, const unsigned int step);
      /// Write a checkpoint at the end of every stage but the last.
      bool
      at_stage_ends() const
      {
        return stage_ends;
      }
      /// The signal that asked the run to stop ("SIGTERM", "SIGINT").
      std::string
      signal_name() const;

      /// Write a checkpoint (collective): the mesh and the particles, the
      /// loop state @p state (significant on rank 0), and copies of
      /// @p files (paths; rank 0). Atomic as described above.
      void
      write(const parallel::distributed::Triangulation<dim> &triangulation,
            Particles::ParticleHandler<dim>                 &particles,
            const std::string                               &state,
            const std::vector<std::string>                  &files,
            const unsigned int                               step,
            const double                                     time);

      /// Check the checkpoint to resume from and read it (collective): the
      /// mesh into @p triangulation (which holds the coarse mesh only),
      /// the particles into @p particles (initialized on it). Returns the
      /// loop state, the same on every rank. Throws ScarpError saying why
      /// a checkpoint is refused (another scene, version or dimension, a
      /// file missing or truncated).
      std::string
      load(parallel::distributed::Triangulation<dim> &triangulation,
           Particles::ParticleHandler<dim>           &particles);
      /// After load(): the directory read (a checkpoint.old when the newer
      /// one was incomplete), and the number of ranks that wrote it.
      const std::string &
      loaded_directory() const
      {
        return loaded;
      }
      unsigned int
      loaded_n_ranks() const
      {
        return n_ranks_at_save;
      }

      /// Where the checkpoints of this run go: <Output directory>/checkpoint.
      std::string
      directory() const
      {
        return output_directory + "/checkpoint";
      }

      /// The state of the intervals that belongs to the loop state.
      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &next_time;
      }

    private:
      /// Rank 0: the checkpoint directory that @p path names (a checkpoint
      /// itself, or an output directory that holds one), with a complete
      /// manifest; checkpoint.old when the newer one is incomplete. Throws
      /// with the reason otherwise.
      std::string
      resolve(const std::string &path) const;
      /// Rank 0: check the manifest of @p directory against this scene;
      /// empty if it fits, else why not.
      std::string
      check(const std::string &directory) const;

      MPI_Comm    communicator;
      std::string output_directory = "output";
      std::string resume_from;
      std::string scene_hash;
      /// The fingerprint as scarp computed it before 2026-12-05 (the lines
      /// as ShortPRM pads them), accepted on resume.
      std::string  legacy_scene_hash;
      std::string  properties;
      double       wall_interval = 0;
      double       time_interval = 0;
      bool         stage_ends    = true;
      double       next_time     = 0;
      Timer        wall_clock;
      double       last_wall = 0;
      std::string  loaded;
      unsigned int n_ranks_at_save = 0;
      unsigned int n_written       = 0;
    };
  } // namespace simulation
} // namespace scarp

#endif
