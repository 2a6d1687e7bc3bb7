#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <scarp/postprocess/particle_vtu_writer.h>

#include <fstream>
#include <limits>

namespace scarp
{
  namespace postprocess
  {
    template <int dim>
    ParticleVtuWriter<dim>::ParticleVtuWriter(
      const std::vector<std::string> &property_names,
      const std::vector<
        DataComponentInterpretation::DataComponentInterpretation>
                        &interpretations,
      const unsigned int chunk_size)
      : chunk_size(std::max(1u, chunk_size))
    {
      AssertThrow(property_names.size() == interpretations.size(),
                  ExcMessage("one interpretation per property name"));
      names = {"id"};
      names.insert(names.end(), property_names.begin(), property_names.end());
      // Component c of the output is property c - 1 (the id is first).
      for (unsigned int i = 0; i < interpretations.size();)
        {
          const auto   kind = interpretations[i];
          unsigned int n    = 1;
          if (kind == DataComponentInterpretation::component_is_part_of_vector)
            n = dim;
          else if (kind ==
                   DataComponentInterpretation::component_is_part_of_tensor)
            n = dim * dim;
          if (n > 1)
            {
              AssertThrow(i + n <= interpretations.size(),
                          ExcMessage("vector or tensor property '" +
                                     property_names[i] + "' is cut short"));
              std::string name = property_names[i];
              for (unsigned int c = 1; c < n; ++c)
                if (interpretations[i + c] != kind ||
                    property_names[i + c] != name)
                  name = "";
              ranges.emplace_back(i + 1, i + n, name, kind);
            }
          i += n;
        }
    }


    template <int dim>
    std::string
    ParticleVtuWriter<dim>::write(
      const Particles::ParticleHandler<dim> &particles,
      const std::string                     &directory,
      const std::string                     &prefix,
      const unsigned int                     index,
      const DataOutBase::VtkFlags           &flags,
      const MPI_Comm                         communicator) const
    {
      const unsigned int rank = Utilities::MPI::this_mpi_process(communicator);
      const unsigned int n_ranks =
        Utilities::MPI::n_mpi_processes(communicator);
      const std::string base =
        prefix + "_" + Utilities::int_to_string(index, 5);
      const unsigned int rank_digits = Utilities::needed_digits(n_ranks - 1);
      const auto         piece_name  = [&](const unsigned int r) {
        return base + "." + Utilities::int_to_string(r, rank_digits) + ".vtu";
      };

      {
        const std::string filename = directory + piece_name(rank);
        std::ofstream     out(filename);
        AssertThrow(out, ExcMessage("cannot open " + filename + " to write"));
        DataOutBase::write_vtu_header(out, flags);
        // The time goes once into the file, with the first piece.
        DataOutBase::VtkFlags later_flags = flags;
        later_flags.time                  = std::numeric_limits<double>::min();
        later_flags.cycle = std::numeric_limits<unsigned int>::min();
        bool                                    first = true;
        std::vector<DataOutBase::Patch<0, dim>> patches;
        patches.reserve(
          std::min<std::size_t>(chunk_size,
                                particles.n_locally_owned_particles()));
        const auto flush = [&]() {
          DataOutBase::write_vtu_main(
            patches, names, ranges, first ? flags : later_flags, out);
          first = false;
          patches.clear();
        };
        for (const auto &point : particles)
          {
            patches.emplace_back();
            DataOutBase::Patch<0, dim> &patch = patches.back();
            patch.vertices[0]                 = point.get_location();
            patch.patch_index                 = patches.size() - 1;
            patch.data.reinit(names.size(), 1);
            patch.data(0, 0)                         = point.get_id();
            const ArrayView<const double> properties = point.get_properties();
            for (unsigned int c = 1; c < names.size(); ++c)
              patch.data(c, 0) = properties[c - 1];
            if (patches.size() == chunk_size)
              flush();
          }
        // A rank without points (or the rest) still writes a piece.
        if (first || !patches.empty())
          flush();
        DataOutBase::write_vtu_footer(out);
        AssertThrow(out, ExcMessage("error while writing " + filename));
      }

      const std::string record = base + ".pvtu";
      if (rank == 0)
        {
          std::vector<std::string> pieces;
          for (unsigned int r = 0; r < n_ranks; ++r)
            pieces.push_back(piece_name(r));
          const std::string filename = directory + record;
          std::ofstream     out(filename);
          AssertThrow(out, ExcMessage("cannot open " + filename + " to write"));
          DataOutBase::write_pvtu_record(out, pieces, names, ranges, flags);
        }
      return record;
    }

    template class ParticleVtuWriter<2>;
    template class ParticleVtuWriter<3>;
  } // namespace postprocess
} // namespace scarp
