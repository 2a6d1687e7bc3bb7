#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <scarp/base/exceptions.h>
#include <scarp/nonlocal/parameters.h>
#include <scarp/simulation/checkpoint.h>
#include <scarp/simulation/stage.h>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <sstream>

#include <signal.h>

namespace scarp
{
  namespace simulation
  {
    namespace
    {
      namespace fs = std::filesystem;

      /// Bump when the content of a checkpoint changes (the loop state of
      /// the Simulation, the particle properties, the files): older
      /// checkpoints are then refused by name.
      constexpr unsigned int format_version = 4;
      const std::string      magic          = "scarp checkpoint";

      /// The signal that asked for a stop (0: none); set by the handler.
      volatile std::sig_atomic_t received_signal = 0;

      extern "C" void
      handle_stop_signal(int signal)
      {
        received_signal = signal;
        // A second signal of the same kind ends the process at once.
        std::signal(signal, SIG_DFL);
      }

      /// FNV-1a, 64 bit, as hex digits: a fingerprint of the scene text.
      std::string
      fingerprint(const std::string &text)
      {
        std::uint64_t h = 1469598103934665603ULL;
        for (const unsigned char c : text)
          {
            h ^= c;
            h *= 1099511628211ULL;
          }
        std::ostringstream s;
        s << std::hex << std::setw(16) << std::setfill('0') << h;
        return s.str();
      }

      /// @p line with the padding before " = " collapsed: ShortPRM pads
      /// the names of a subsection to its longest, which a new, longer
      /// entry would change.
      std::string
      without_padding(const std::string &line)
      {
        const auto equal = line.find(" = ");
        if (equal == std::string::npos)
          return line;
        const auto name_end = line.find_last_not_of(' ', equal);
        return line.substr(0, name_end + 1) + line.substr(equal);
      }

      /// The entries of @p text (ShortPRM) whose value differs from
      /// @p defaults (the same declarations, unset), one per line with its
      /// subsection path: what a scene file really sets. Entries a later
      /// scarp adds (at their defaults) leave it unchanged. @p keep_padding:
      /// the lines as ShortPRM pads them (the fingerprint before 2026-12-05).
      std::string
      changed_entries(const std::string &text,
                      const std::string &defaults,
                      const bool         keep_padding)
      {
        std::istringstream       a(text), b(defaults);
        std::string              line, default_line, out;
        std::vector<std::string> path;
        while (std::getline(a, line))
          {
            if (!std::getline(b, default_line))
              return text; // another structure: the whole text
            const auto first = line.find_first_not_of(' ');
            if (first == std::string::npos)
              continue;
            const std::string trimmed = line.substr(first);
            if (trimmed.rfind("subsection ", 0) == 0)
              path.push_back(trimmed.substr(11));
            else if (trimmed == "end")
              {
                if (!path.empty())
                  path.pop_back();
              }
            else if (line != default_line)
              {
                for (const auto &p : path)
                  out += p + "/";
                out +=
                  (keep_padding ? trimmed : without_padding(trimmed)) + "\n";
              }
          }
        return out;
      }

      /// Whether @p directory holds a manifest whose last line is "end".
      bool
      is_complete(const std::string &directory)
      {
        std::ifstream in(directory + "/manifest");
        if (!in)
          return false;
        std::string line, last;
        while (std::getline(in, line))
          if (!line.empty())
            last = line;
        return last == "end";
      }
    } // namespace


    template <int dim>
    Checkpoint<dim>::Checkpoint(MPI_Comm communicator)
      : communicator(communicator)
    {
    }


    template <int dim>
    void
    Checkpoint<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Checkpoint");
      prm.declare_entry(
        "Wall time interval",
        "0",
        Patterns::Double(0.),
        "Write a checkpoint every this many seconds of wall time (measured "
        "on rank 0, checked after every step); 0: never by wall time. "
        "Checkpoints go to <Output directory>/checkpoint; resume with "
        "scarp --resume DIR scene.prm or <Resume from>.");
      prm.declare_entry("Time interval",
                        "0",
                        Patterns::Double(0.),
                        "Write a checkpoint every this much simulated time "
                        "[s]; 0: never by simulated time.");
      prm.declare_entry(
        "At stage ends",
        "true",
        Patterns::Bool(),
        "Write a checkpoint at the end of every stage but the last. "
        "Independent of this, SIGTERM or SIGINT makes the run write a "
        "checkpoint after the step it is in and stop (exit status 1).");
      prm.declare_entry(
        "Resume from",
        "",
        Patterns::Anything(),
        "Resume from this checkpoint directory (or an output directory "
        "that holds one in checkpoint/) instead of seeding the bodies; "
        "empty: start afresh; auto: resume from <Output directory>/"
        "checkpoint if the output directory holds one (also when only "
        "checkpoint.old is left), else start afresh, so that the same "
        "command continues a run in parts (a job chain on a cluster). "
        "The command line's --resume overrides it. "
        "The checkpoint must come from this scene: every entry but those "
        "of this subsection, <Output directory>, the stages' <End time> "
        "and <Non-local average/Skin distance fraction> must be the same; a "
        "checkpoint that is not (also with auto) stops "
        "the run with the reason.");
      prm.leave_subsection();
    }


    template <int dim>
    void
    Checkpoint<dim>::parse_parameters(
      ParameterHandler               &prm,
      const std::vector<std::string> &stage_names,
      const std::string              &defaults)
    {
      output_directory = prm.get("Output directory");
      prm.enter_subsection("Checkpoint");
      wall_interval = prm.get_double("Wall time interval");
      time_interval = prm.get_double("Time interval");
      stage_ends    = prm.get_bool("At stage ends");
      if (resume_from.empty())
        {
          resume_from = prm.get("Resume from");
          if (resume_from == "auto")
            {
              // Decided on rank 0 (the file system the checkpoints share),
              // alike on every rank.
              bool found = false;
              if (Utilities::MPI::this_mpi_process(communicator) == 0)
                found = fs::exists(output_directory + "/checkpoint") ||
                        fs::exists(output_directory + "/checkpoint.old");
              found       = Utilities::MPI::broadcast(communicator, found, 0);
              resume_from = found ? output_directory : "";
            }
        }
      prm.leave_subsection();
      next_time = time_interval;

      // The fingerprint of the scene: every entry that differs from its
      // default, with those that may differ between a run and its restart
      // (the checkpoint's own, the stages' end times, the output directory,
      // the skin of the non-local lists) set to their defaults.
      const std::vector<std::pair<std::string, std::string>> free_entries{
        {"Wall time interval", "0"},
        {"Time interval", "0"},
        {"At stage ends", "true"},
        {"Resume from", ""}};
      std::vector<std::string> saved;
      prm.enter_subsection("Checkpoint");
      for (const auto &[name, value] : free_entries)
        {
          saved.push_back(prm.get(name));
          prm.set(name, value);
        }
      prm.leave_subsection();
      // The stages' end times and deposit criteria: a resumed run may stop
      // earlier or go on longer than the run that wrote the checkpoint
      // (they only decide when the loop stops). Set to their defaults.
      std::vector<std::pair<std::string, std::string>> stage_free;
      {
        ParameterHandler fresh;
        Stage::declare_parameters(fresh);
        for (const std::string name : {"End time",
                                       "End on deposit at rest",
                                       "Deposit check interval",
                                       "Deposit settle time",
                                       "Deposit shift tolerance",
                                       "Deposit area tolerance"})
          stage_free.emplace_back(name, fresh.get(name));
      }
      std::vector<std::vector<std::string>> stage_saved;
      for (const auto &name : stage_names)
        {
          prm.enter_subsection("Stage " + name);
          stage_saved.emplace_back();
          for (const auto &[entry, value] : stage_free)
            {
              stage_saved.back().push_back(prm.get(entry));
              prm.set(entry, value);
            }
          prm.leave_subsection();
        }
      // The skin of the non-local lists changes the cost, not the result
      // (doc/nonlocal.md): a resumed run may take another one. Set to its
      // default, so that the fingerprint of a scene is what it was before
      // the entry was exempt.
      std::string skin_fraction;
      {
        ParameterHandler fresh;
        nonlocal::NonlocalParameters::declare_parameters(fresh);
        fresh.enter_subsection("Non-local average");
        const std::string default_skin = fresh.get("Skin distance fraction");
        fresh.leave_subsection();
        prm.enter_subsection("Non-local average");
        skin_fraction = prm.get("Skin distance fraction");
        prm.set("Skin distance fraction", default_skin);
        prm.leave_subsection();
      }
      const std::string directory = prm.get("Output directory");
      prm.set("Output directory", "output");
      std::ostringstream text;
      prm.print_parameters(text, ParameterHandler::ShortPRM);
      prm.set("Output directory", directory);
      prm.enter_subsection("Non-local average");
      prm.set("Skin distance fraction", skin_fraction);
      prm.leave_subsection();
      for (std::size_t k = 0; k < stage_names.size(); ++k)
        {
          prm.enter_subsection("Stage " + stage_names[k]);
          for (std::size_t e = 0; e < stage_free.size(); ++e)
            prm.set(stage_free[e].first, stage_saved[k][e]);
          prm.leave_subsection();
        }
      prm.enter_subsection("Checkpoint");
      for (std::size_t k = 0; k < free_entries.size(); ++k)
        prm.set(free_entries[k].first, saved[k]);
      prm.leave_subsection();
      scene_hash = fingerprint(changed_entries(text.str(), defaults, false));
      // Checkpoints of scarp before 2026-12-05 hashed the padded lines.
      legacy_scene_hash =
        fingerprint(changed_entries(text.str(), defaults, true));
    }


    template <int dim>
    void
    Checkpoint<dim>::set_particle_properties(
      const std::vector<std::string> &names)
    {
      properties.clear();
      for (const auto &name : names)
        properties += (properties.empty() ? "" : ",") + name;
    }


    template <int dim>
    void
    Checkpoint<dim>::set_resume_directory(const std::string &directory)
    {
      resume_from = directory;
    }


    template <int dim>
    void
    Checkpoint<dim>::start()
    {
      received_signal = 0;
      struct sigaction action
      {
      };
      action.sa_handler = handle_stop_signal;
      sigemptyset(&action.sa_mask);
      action.sa_flags = 0;
      sigaction(SIGTERM, &action, nullptr);
      sigaction(SIGINT, &action, nullptr);
      wall_clock.restart();
      last_wall = 0;
    }


    template <int dim>
    typename Checkpoint<dim>::Due
    Checkpoint<dim>::poll(const double time, const unsigned int step)
    {
      if (Utilities::MPI::this_mpi_process(communicator) == 0)
        if (const char *at = std::getenv("SCARP_TEST_SIGTERM_AT_STEP"))
          if (std::atoi(at) == static_cast<int>(step))
            std::raise(SIGTERM);
      int flags[2] = {static_cast<int>(received_signal), 0};
      if (wall_interval > 0 &&
          Utilities::MPI::this_mpi_process(communicator) == 0 &&
          wall_clock.wall_time() - last_wall >= wall_interval)
        flags[1] = 1;
      MPI_Allreduce(MPI_IN_PLACE, flags, 2, MPI_INT, MPI_MAX, communicator);
      if (flags[0] != 0)
        {
          received_signal = flags[0];
          return Due::stop;
        }
      bool due = flags[1] != 0;
      if (time_interval > 0 && time >= next_time * (1 - 1e-12))
        {
          due = true;
          while (next_time <= time * (1 + 1e-12))
            next_time += time_interval;
        }
      return due ? Due::interval : Due::nothing;
    }


    template <int dim>
    std::string
    Checkpoint<dim>::signal_name() const
    {
      return received_signal == SIGINT ? "SIGINT"
             : received_signal == SIGTERM
               ? "SIGTERM"
               : "signal " + std::to_string(received_signal);
    }


    template <int dim>
    void
    Checkpoint<dim>::write(
      const parallel::distributed::Triangulation<dim> &triangulation,
      Particles::ParticleHandler<dim>                 &particles,
      const std::string                               &state,
      const std::vector<std::string>                  &files,
      const unsigned int                               step,
      const double                                     time)
    {
      const bool root = Utilities::MPI::this_mpi_process(communicator) == 0;
      const std::string final_name = directory();
      const std::string tmp        = final_name + ".tmp";
      const std::string old        = final_name + ".old";
      ++n_written;

      // Every step of rank 0 reports its failure to all ranks, so that no
      // rank waits for a rank that has given up.
      const auto collective = [&](const std::function<void()> &work) {
        std::string error;
        if (root)
          try
            {
              work();
            }
          catch (const std::exception &e)
            {
              error = e.what();
            }
        error = Utilities::MPI::broadcast(communicator, error, 0);
        if (!error.empty())
          throw ScarpError("Cannot write the checkpoint <" + tmp +
                           ">: " + error);
      };

      collective([&]() {
        fs::remove_all(tmp);
        fs::create_directories(tmp);
      });
      particles.prepare_for_serialization();
      triangulation.save(tmp + "/mesh");
      collective([&]() {
        {
          std::ofstream out(tmp + "/state", std::ios::binary);
          out.write(state.data(), state.size());
          if (!out)
            throw ScarpError("cannot write <" + tmp + "/state>");
        }
        for (const auto &file : files)
          if (fs::exists(file))
            fs::copy_file(file,
                          tmp + "/" + fs::path(file).filename().string(),
                          fs::copy_options::overwrite_existing);
        // Test hook: die as from SIGKILL in the middle of writing the
        // checkpoint with this number (1 = the first of this process).
        if (const char *abort_at = std::getenv("SCARP_TEST_KILL_IN_CHECKPOINT"))
          if (std::atoi(abort_at) == static_cast<int>(n_written))
            std::raise(SIGKILL);
        // The manifest, written last: without its "end" line the directory
        // is no checkpoint.
        std::vector<std::pair<std::string, std::uintmax_t>> sizes;
        for (const auto &entry : fs::directory_iterator(tmp))
          if (entry.is_regular_file())
            sizes.emplace_back(entry.path().filename().string(),
                               entry.file_size());
        std::sort(sizes.begin(), sizes.end());
        {
          std::ofstream out(tmp + "/manifest");
          out << std::setprecision(17) << magic << "\n"
              << "format " << format_version << "\n"
              << "dimension " << dim << "\n"
              << "scene " << scene_hash << "\n"
              << "properties " << properties << "\n"
              << "ranks " << Utilities::MPI::n_mpi_processes(communicator)
              << "\n"
              << "step " << step << "\n"
              << "time " << time << "\n";
          for (const auto &[name, size] : sizes)
            out << "file " << name << " " << size << "\n";
          out << "end\n";
          out.close();
          if (!out)
            throw ScarpError("cannot write <" + tmp + "/manifest>");
        }
        // Keep the previous checkpoint until the new one has its name.
        if (fs::exists(final_name))
          {
            fs::remove_all(old);
            fs::rename(final_name, old);
          }
        fs::rename(tmp, final_name);
        fs::remove_all(old);
      });
      last_wall = wall_clock.wall_time();
    }


    template <int dim>
    std::string
    Checkpoint<dim>::resolve(const std::string &path) const
    {
      // Killed between the two renames, a run leaves only checkpoint.old.
      if (!fs::is_directory(path))
        {
          if (is_complete(path + ".old"))
            return path + ".old";
          throw ScarpError("cannot resume from <" + path +
                           ">: no such directory.");
        }
      std::string candidate = path;
      if (!fs::exists(path + "/manifest") &&
          (fs::is_directory(path + "/checkpoint") ||
           fs::is_directory(path + "/checkpoint.old")))
        candidate = path + "/checkpoint";
      if (is_complete(candidate))
        return candidate;
      // Interrupted while the new checkpoint replaced the old one: the
      // previous checkpoint is still complete.
      if (is_complete(candidate + ".old"))
        return candidate + ".old";
      if (fs::exists(candidate + "/manifest"))
        throw ScarpError("cannot resume from <" + candidate +
                         ">: its manifest is incomplete (the writing of "
                         "the checkpoint was interrupted).");
      throw ScarpError("cannot resume from <" + path +
                       ">: it holds no checkpoint (no file <manifest>, "
                       "neither there nor in <" +
                       path + "/checkpoint>).");
    }


    template <int dim>
    std::string
    Checkpoint<dim>::check(const std::string &dir) const
    {
      std::ifstream in(dir + "/manifest");
      std::string   line;
      std::getline(in, line);
      if (line != magic)
        return "<" + dir + "/manifest> is not a scarp checkpoint manifest.";
      std::string  key, value;
      unsigned int format = 0, dimension = 0;
      std::string  hash, saved_properties;
      std::vector<std::pair<std::string, std::uintmax_t>> files;
      while (in >> key)
        {
          if (key == "end")
            break;
          if (key == "file")
            {
              std::string    name;
              std::uintmax_t size = 0;
              in >> name >> size;
              files.emplace_back(name, size);
              continue;
            }
          if (key == "properties")
            {
              in >> std::ws;
              std::getline(in, saved_properties);
              continue;
            }
          in >> value;
          if (key == "format")
            format = std::stoul(value);
          else if (key == "dimension")
            dimension = std::stoul(value);
          else if (key == "scene")
            hash = value;
        }
      if (format != format_version)
        return "it was written by another version of scarp (checkpoint "
               "format " +
               std::to_string(format) + ", this scarp reads format " +
               std::to_string(format_version) + ").";
      if (dimension != dim)
        return "it holds a " + std::to_string(dimension) +
               "D run, this scene is " + std::to_string(dim) + "D.";
      if (hash != scene_hash && hash != legacy_scene_hash)
        return "it was written for another scene (scene fingerprint " + hash +
               ", this scene's is " + scene_hash +
               "): every entry but those of <Checkpoint>, <Output "
               "directory>, the stages' <End time> and deposit criterion "
               "(<End on deposit at rest>, <Deposit ...>) and <Non-local "
               "average/Skin distance fraction> must be the same as in the "
               "run that wrote it.";
      if (saved_properties != properties)
        return "its material points carry other properties (" +
               saved_properties + ") than this scarp gives them (" +
               properties + "): it was written by another version of scarp.";
      for (const auto &[name, size] : files)
        {
          const std::string file = dir + "/" + name;
          if (!fs::exists(file))
            return "the file <" + name + "> is missing.";
          if (fs::file_size(file) != size)
            return "the file <" + name + "> has " +
                   std::to_string(fs::file_size(file)) +
                   " bytes, the manifest says " + std::to_string(size) +
                   " (truncated or damaged).";
        }
      bool has_state = false;
      for (const auto &f : files)
        has_state = has_state || f.first == "state";
      if (!has_state)
        return "the manifest lists no file <state>.";
      return "";
    }


    template <int dim>
    std::string
    Checkpoint<dim>::load(
      parallel::distributed::Triangulation<dim> &triangulation,
      Particles::ParticleHandler<dim>           &particles)
    {
      std::string error, state, dir;
      if (Utilities::MPI::this_mpi_process(communicator) == 0)
        try
          {
            dir   = resolve(resume_from);
            error = check(dir);
            if (!error.empty())
              error = "cannot resume from <" + dir + ">: " + error;
            else
              {
                std::ifstream      in(dir + "/state", std::ios::binary);
                std::ostringstream s;
                s << in.rdbuf();
                state = s.str();
                std::ifstream manifest(dir + "/manifest");
                std::string   key;
                while (manifest >> key)
                  if (key == "ranks")
                    manifest >> n_ranks_at_save;
              }
          }
        catch (const std::exception &e)
          {
            error = e.what();
          }
      error = Utilities::MPI::broadcast(communicator, error, 0);
      if (!error.empty())
        throw ScarpError(error);
      dir   = Utilities::MPI::broadcast(communicator, dir, 0);
      state = Utilities::MPI::broadcast(communicator, state, 0);
      n_ranks_at_save =
        Utilities::MPI::broadcast(communicator, n_ranks_at_save, 0);
      loaded = dir;
      triangulation.load(dir + "/mesh");
      particles.deserialize();
      return state;
    }


    template class Checkpoint<2>;
    template class Checkpoint<3>;
  } // namespace simulation
} // namespace scarp
