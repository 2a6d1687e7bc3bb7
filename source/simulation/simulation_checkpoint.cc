// Simulation: checkpoints and resuming from them (the files and their
// checks are the job of Checkpoint; here is what the Simulation puts in).
#include <deal.II/base/mpi.h>

#include <scarp/base/exceptions.h>
#include <scarp/simulation/simulation.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/binary_object.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <filesystem>
#include <sstream>

namespace scarp
{
  namespace simulation
  {
    template <int dim>
    template <class Archive>
    void
    Simulation<dim>::serialize_loop_state(Archive &ar)
    {
      // The loop state, the records of the stages (and of the cliff) so
      // far and the checkpoint's own clock; the particles and the mesh
      // travel in the triangulation's files.
      ar &loop &stage_summaries &cliff_summary &checkpoint;
      // A plain struct of numbers, as far as checkpoints of format 4 hold
      // it.
      boost::serialization::binary_object report(
        &last_report, transfer::StepReport::checkpoint_size());
      ar &report;
    }


    template <int dim>
    void
    Simulation<dim>::load_checkpoint()
    {
      grid.create_coarse_mesh();
      particles.initialize(grid.triangulation(),
                           grid.mapping(),
                           layout.n_properties());
      const std::string state =
        checkpoint.load(grid.triangulation(), particles);
      try
        {
          std::istringstream              in(state);
          boost::archive::binary_iarchive archive(in);
          serialize_loop_state(archive);
          archive &restored_records;
        }
      catch (const std::exception &e)
        {
          throw ScarpError(
            "cannot resume from <" + checkpoint.loaded_directory() +
            ">: its loop state cannot be read (" + e.what() + ").");
        }
      // A checkpoint at the end of a stage resumes with the next one.
      if (!loop.stage.in_progress)
        ++loop.stage.index;
      particles.update_cached_numbers();
      // deal.II 9.4's load() partitions by cells when the number of ranks
      // changed: partition by the points again.
      if (Utilities::MPI::n_mpi_processes(communicator) > 1)
        balance_load();
      else
        grid.setup_dofs();
      // The non-local neighbour lists are rebuilt (the averager is new).
      local_boxes.clear();
      if (averager)
        averager->invalidate_neighbour_lists();
      // statistics.csv and cliff_history.csv as they were at the
      // checkpoint (a history the checkpoint has no copy of starts anew:
      // its rows after the checkpoint would mislead).
      if (Utilities::MPI::this_mpi_process(communicator) == 0 &&
          outputs_enabled)
        for (const std::string name : {"statistics.csv", "cliff_history.csv"})
          {
            const std::string saved =
              checkpoint.loaded_directory() + "/" + name;
            const std::string current = output_directory + "/" + name;
            if (std::filesystem::exists(saved))
              std::filesystem::copy_file(
                saved,
                current,
                std::filesystem::copy_options::overwrite_existing);
            else if (name == "cliff_history.csv")
              std::filesystem::remove(current);
          }
    }


    template <int dim>
    void
    Simulation<dim>::write_checkpoint()
    {
      TimerOutput::Scope scope(timer, "checkpoint");
      order_points();
      std::ostringstream out;
      {
        boost::archive::binary_oarchive archive(out);
        serialize_loop_state(archive);
        auto     records = vtu ? vtu->records() : restored_records;
        archive &records;
      }
      checkpoint.write(grid.triangulation(),
                       particles,
                       out.str(),
                       {output_directory + "/statistics.csv",
                        output_directory + "/cliff_history.csv"},
                       loop.step,
                       loop.time);
      pcout << "  checkpoint at step " << loop.step << " (t = " << loop.time
            << " s) in " << checkpoint.directory() << std::endl;
    }


    template <int dim>
    void
    Simulation<dim>::checkpoint_if_due()
    {
      const auto due = checkpoint.poll(loop.time, loop.step);
      if (due == Checkpoint<dim>::Due::nothing)
        return;
      write_checkpoint();
      if (due != Checkpoint<dim>::Due::stop)
        return;
      std::ostringstream message;
      message << "interrupted by " << checkpoint.signal_name() << " at step "
              << loop.step << " (t = " << loop.time
              << " s); a checkpoint is in " << checkpoint.directory()
              << ": resume with scarp --resume " << checkpoint.directory()
              << " SCENE.prm";
      write_summary("interrupted: " + message.str());
      throw ScarpError(message.str());
    }


    template void
    Simulation<2>::load_checkpoint();
    template void
    Simulation<3>::load_checkpoint();
    template void
    Simulation<2>::write_checkpoint();
    template void
    Simulation<3>::write_checkpoint();
    template void
    Simulation<2>::checkpoint_if_due();
    template void
    Simulation<3>::checkpoint_if_due();
  } // namespace simulation
} // namespace scarp
