#include <deal.II/base/exceptions.h>

#include <scarp/nonlocal/weight_function.h>

namespace scarp
{
  namespace nonlocal
  {
    std::string
    weight_type_names()
    {
      return "local|bell|gaussian";
    }


    WeightType
    parse_weight_type(const std::string &name)
    {
      if (name == "local")
        return WeightType::local;
      if (name == "bell")
        return WeightType::bell;
      if (name == "gaussian")
        return WeightType::gaussian;
      AssertThrow(false,
                  dealii::ExcMessage("Unknown non-local weight <" + name +
                                     ">; accepted: " + weight_type_names()));
      return WeightType::local;
    }


    std::string
    to_string(const WeightType type)
    {
      switch (type)
        {
          case WeightType::bell:
            return "bell";
          case WeightType::gaussian:
            return "gaussian";
          default:
            return "local";
        }
    }


    WeightFunction::WeightFunction(const WeightType type,
                                   const double     length_scale)
      : weight_type(type)
      , l_c(length_scale)
    {
      if (type == WeightType::local)
        return;
      AssertThrow(length_scale > 0.,
                  dealii::ExcMessage(
                    "The non-local length scale must be positive."));
      // R = sqrt(7) l_c gives the bell the variance l_c^2 of the Gaussian.
      cutoff = (type == WeightType::bell ? std::sqrt(7.) : 3.) * length_scale;
      cutoff_squared         = cutoff * cutoff;
      inverse_cutoff_squared = 1. / cutoff_squared;
      inverse_two_lc_squared = 1. / (2. * length_scale * length_scale);
    }
  } // namespace nonlocal
} // namespace scarp
