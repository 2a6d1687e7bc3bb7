#ifndef scarp_simulation_scene_lists_h
#define scarp_simulation_scene_lists_h

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace scarp
{
  namespace simulation
  {
    using namespace dealii;

    /**
     * @brief The top-level lists of a scene file (dimension, materials,
     * bodies, pre-damaged regions, stages), read in a first, lenient pass so
     * that the named subsections can be declared before the strict pass.
     */
    struct SceneLists
    {
      unsigned int             dimension = 2;
      std::vector<std::string> materials = {"material"};
      std::vector<std::string> bodies    = {"body"};
      std::vector<std::string> regions   = {};
      std::vector<std::string> stages    = {"run"};

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);

      /// First pass over @p filename: only the lists, unknown entries are
      /// left for the strict pass.
      static SceneLists
      read(const std::string &filename);
    };
  } // namespace simulation
} // namespace scarp

#endif
