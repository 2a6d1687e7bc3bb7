#ifndef scarp_postprocess_particle_vtu_writer_h
#define scarp_postprocess_particle_vtu_writer_h

#include <deal.II/base/data_out_base.h>
#include <deal.II/particles/particle_handler.h>

#include <string>
#include <tuple>
#include <vector>

namespace scarp
{
  namespace postprocess
  {
    using namespace dealii;

    /**
     * @brief Writes the material points of a rank as one VTU file of
     * several pieces, a chunk of points at a time, with the fields that
     * Particles::DataOut writes ("id", then the properties).
     *
     * Particles::DataOut builds one patch, with a table of its own, for
     * every point of the rank, and write_vtu() copies them all into its
     * arrays once more: about 500 bytes per point for the time of the
     * write, the largest transient of a run (doc/performance/memory.md,
     * "Memory"). Here at most @p chunk_size points are held at a time: each
     * chunk goes out as one <Piece> of the same file (DataOutBase::
     * write_vtu_main() between one header and one footer), which VTK
     * readers and tools/read_particles.py concatenate. File names, the
     * PVTU record and the values are those of
     * DataOutInterface::write_vtu_with_pvtu_record() with no groups.
     */
    template <int dim>
    class ParticleVtuWriter
    {
    public:
      /// @p names and @p interpretations: one per property, as for
      /// Particles::DataOut::build_patches().
      ParticleVtuWriter(
        const std::vector<std::string> &names,
        const std::vector<
          DataComponentInterpretation::DataComponentInterpretation>
                          &interpretations,
        const unsigned int chunk_size = 4096);

      /// Write directory/prefix_NNNNN.R.vtu on every rank and, on rank 0,
      /// directory/prefix_NNNNN.pvtu; returns the name of the latter
      /// (without the directory).
      std::string
      write(const Particles::ParticleHandler<dim> &particles,
            const std::string                     &directory,
            const std::string                     &prefix,
            const unsigned int                     index,
            const DataOutBase::VtkFlags           &flags,
            const MPI_Comm                         communicator) const;

    private:
      /// "id" and the property names.
      std::vector<std::string> names;
      /// The vectors and tensors among them (first and last component,
      /// name, kind), as DataOutInterface::get_nonscalar_data_ranges().
      std::vector<
        std::tuple<unsigned int,
                   unsigned int,
                   std::string,
                   DataComponentInterpretation::DataComponentInterpretation>>
                   ranges;
      unsigned int chunk_size;
    };
  } // namespace postprocess
} // namespace scarp

#endif
