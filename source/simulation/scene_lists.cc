#include <scarp/base/exceptions.h>
#include <scarp/base/parameter_tools.h>
#include <scarp/simulation/scene_lists.h>

#include <set>

namespace scarp
{
  namespace simulation
  {
    void
    SceneLists::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Dimension",
                        "2",
                        Patterns::Integer(2, 3),
                        "2 (plane strain) or 3.");
      prm.declare_entry("Materials",
                        "material",
                        Patterns::List(Patterns::Anything(), 1),
                        "Names of the materials; each has a subsection "
                        "'Material <name>'.");
      prm.declare_entry("Bodies",
                        "body",
                        Patterns::List(Patterns::Anything(), 1),
                        "Names of the bodies; each has a subsection "
                        "'Body <name>'. A point inside several bodies "
                        "belongs to the first.");
      prm.declare_entry("Pre-damaged regions",
                        "",
                        Patterns::List(Patterns::Anything()),
                        "Names of regions whose points start fully damaged "
                        "(d = 1); each has a subsection "
                        "'Pre-damaged region <name>' with a shape.");
      prm.declare_entry("Stages",
                        "run",
                        Patterns::List(Patterns::Anything(), 1),
                        "Names of the stages run one after the other; each "
                        "has a subsection 'Stage <name>'.");
    }


    void
    SceneLists::parse_parameters(ParameterHandler &prm)
    {
      dimension = prm.get_integer("Dimension");
      materials = ParameterTools::get_names(prm, "Materials");
      bodies    = ParameterTools::get_names(prm, "Bodies");
      regions   = ParameterTools::get_names(prm, "Pre-damaged regions");
      stages    = ParameterTools::get_names(prm, "Stages");
      for (const auto *list : {&materials, &bodies, &regions, &stages})
        {
          const std::set<std::string> unique(list->begin(), list->end());
          if (unique.size() != list->size())
            throw ScarpError("A name appears twice in the list <" +
                             prm.get(list == &materials ? "Materials"
                                     : list == &bodies  ? "Bodies"
                                     : list == &regions ? "Pre-damaged regions"
                                                        : "Stages") +
                             ">.");
        }
      if (materials.empty() || bodies.empty() || stages.empty())
        throw ScarpError("A scene needs at least one material, one body and "
                         "one stage.");
    }


    SceneLists
    SceneLists::read(const std::string &filename)
    {
      ParameterHandler prm;
      declare_parameters(prm);
      ParameterTools::parse_file(prm, filename, /*skip_undefined=*/true);
      SceneLists lists;
      lists.parse_parameters(prm);
      return lists;
    }
  } // namespace simulation
} // namespace scarp
