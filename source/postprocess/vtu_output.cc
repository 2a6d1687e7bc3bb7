#include <deal.II/base/data_out_base.h>
#include <deal.II/numerics/data_out.h>

#include <scarp/postprocess/particle_vtu_writer.h>
#include <scarp/postprocess/vtu_output.h>

#include <cstdio>
#include <fstream>

namespace scarp
{
  namespace postprocess
  {
    template <int dim>
    VtuOutput<dim>::VtuOutput(const std::string &directory,
                              MPI_Comm           communicator)
      : directory(directory)
      , communicator(communicator)
    {
    }


    template <int dim>
    void
    VtuOutput<dim>::write_pvd(
      const std::string                                 &name,
      const std::vector<std::pair<double, std::string>> &records) const
    {
      if (Utilities::MPI::this_mpi_process(communicator) != 0)
        return;
      const std::string filename  = directory + "/" + name + ".pvd";
      const std::string temporary = filename + ".tmp";
      {
        std::ofstream file(temporary);
        DataOutBase::write_pvd_record(file, records);
      }
      std::rename(temporary.c_str(), filename.c_str());
    }


    template <int dim>
    void
    VtuOutput<dim>::restore_records(
      const std::pair<std::vector<std::pair<double, std::string>>,
                      std::vector<std::pair<double, std::string>>> &records)
    {
      particle_records = records.first;
      mesh_records     = records.second;
      write_pvd("particles", particle_records);
      if (!mesh_records.empty())
        write_pvd("mesh", mesh_records);
    }


    template <int dim>
    void
    VtuOutput<dim>::write_particles(
      const Particles::ParticleHandler<dim> &particles,
      const particles::PropertyLayout<dim>  &layout,
      const double                           time,
      const unsigned int                     index)
    {
      // A chunk of points at a time (postprocess/particle_vtu_writer.h):
      // Particles::DataOut would hold a patch per point of the rank.
      const ParticleVtuWriter<dim> writer(layout.names(),
                                          layout.interpretations());
      DataOutBase::VtkFlags        flags;
      flags.time = time;
      flags.compression_level =
        DataOutBase::VtkFlags::ZlibCompressionLevel::best_speed;
      const std::string name = writer.write(
        particles, directory + "/", "particles", index, flags, communicator);
      particle_records.emplace_back(time, name);
      write_pvd("particles", particle_records);
    }


    template <int dim>
    void
    VtuOutput<dim>::write_mesh(const grid::BackgroundGrid<dim> &grid,
                               const Vector                    &nodal_mass,
                               const std::array<Vector, dim>   &velocity,
                               const double                     time,
                               const unsigned int               index)
    {
      const auto           &tria = grid.dof_handler().get_triangulation();
      dealii::Vector<float> level(tria.n_active_cells()),
        rank(tria.n_active_cells());
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            level(cell->active_cell_index()) = cell->level();
            rank(cell->active_cell_index())  = cell->subdomain_id();
          }
      DataOut<dim> data_out;
      data_out.attach_dof_handler(grid.dof_handler());
      data_out.add_data_vector(nodal_mass, "nodal_mass");
      static const char *names[] = {"velocity_x", "velocity_y", "velocity_z"};
      for (unsigned int d = 0; d < dim; ++d)
        data_out.add_data_vector(velocity[d], names[d]);
      data_out.add_data_vector(level, "refinement_level");
      data_out.add_data_vector(rank, "mpi_rank");
      data_out.build_patches(grid.mapping());
      DataOutBase::VtkFlags flags;
      flags.time = time;
      data_out.set_flags(flags);
      const std::string name = data_out.write_vtu_with_pvtu_record(
        directory + "/", "mesh", index, communicator, 5, 0);
      mesh_records.emplace_back(time, name);
      write_pvd("mesh", mesh_records);
    }

    template class VtuOutput<2>;
    template class VtuOutput<3>;
  } // namespace postprocess
} // namespace scarp
