#ifndef scarp_postprocess_vtu_output_h
#define scarp_postprocess_vtu_output_h

#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/particles/particle_handler.h>

#include <scarp/grid/background_grid.h>
#include <scarp/particles/property_layout.h>

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace scarp
{
  namespace postprocess
  {
    using namespace dealii;

    /**
     * @brief Writes the material points (all properties) and the background
     * mesh (refinement level, MPI rank, nodal mass and velocity) as
     * VTU/PVTU files with PVD time series that ParaView opens directly.
     */
    template <int dim>
    class VtuOutput
    {
    public:
      using Vector = LinearAlgebra::distributed::Vector<double>;

      VtuOutput(const std::string &directory, MPI_Comm communicator);

      void
      write_particles(const Particles::ParticleHandler<dim> &particles,
                      const particles::PropertyLayout<dim>  &layout,
                      const double                           time,
                      const unsigned int                     index);

      void
      write_mesh(const grid::BackgroundGrid<dim> &grid,
                 const Vector                    &nodal_mass,
                 const std::array<Vector, dim>   &nodal_velocity,
                 const double                     time,
                 const unsigned int               index);

      /// The (time, file) records of the PVD files: the particles' and
      /// the mesh's (for checkpoints).
      std::pair<std::vector<std::pair<double, std::string>>,
                std::vector<std::pair<double, std::string>>>
      records() const
      {
        return {particle_records, mesh_records};
      }

      /// Take the records of a checkpoint and rewrite the PVD files with
      /// them: outputs written after the checkpoint drop out, the next
      /// output continues the series.
      void
      restore_records(
        const std::pair<std::vector<std::pair<double, std::string>>,
                        std::vector<std::pair<double, std::string>>> &records);

    private:
      void
      write_pvd(
        const std::string                                 &name,
        const std::vector<std::pair<double, std::string>> &records) const;

      std::string                                 directory;
      MPI_Comm                                    communicator;
      std::vector<std::pair<double, std::string>> particle_records;
      std::vector<std::pair<double, std::string>> mesh_records;
    };
  } // namespace postprocess
} // namespace scarp

#endif
