#ifndef scarp_nonlocal_weight_function_h
#define scarp_nonlocal_weight_function_h

#include <cmath>
#include <string>

namespace scarp
{
  namespace nonlocal
  {
    /**
     * Kind of weight of the non-local average (doc/nonlocal.md).
     */
    enum class WeightType
    {
      /// No averaging: Ybar = Y, no search, no communication.
      local,
      /// Bell w = (1 - r^2/R^2)^2 for r < R = sqrt(7) l_c, else 0.
      bell,
      /// Gaussian w = exp(-r^2/(2 l_c^2)) for r < 3 l_c, else 0.
      gaussian
    };

    /// The accepted names, for a Patterns::Selection: "local|bell|gaussian".
    std::string
    weight_type_names();

    /// The WeightType of a name in weight_type_names(); throws otherwise.
    WeightType
    parse_weight_type(const std::string &name);

    /// The name of a WeightType, as accepted by parse_weight_type().
    std::string
    to_string(const WeightType type);

    /**
     * @brief Radial weight of the non-local average, with its cut-off radius.
     *
     * Both weights use @p length_scale l_c as their standard deviation: the
     * bell's cut-off R = sqrt(7) l_c is chosen so that its second moment
     * equals that of the Gaussian exp(-r^2/(2 l_c^2)). The weight is a
     * function of the squared distance so that no square root is taken in the
     * hot loop.
     */
    class WeightFunction
    {
    public:
      /// A local weight (no averaging).
      WeightFunction() = default;

      WeightFunction(const WeightType type, const double length_scale);

      WeightType
      type() const
      {
        return weight_type;
      }

      /// l_c.
      double
      length_scale() const
      {
        return l_c;
      }

      /// Distance beyond which the weight is zero: sqrt(7) l_c for the bell,
      /// 3 l_c for the Gaussian, 0 for local.
      double
      cutoff_radius() const
      {
        return cutoff;
      }

      /// Weight at squared distance @p r2 (not normalised; w(0) = 1).
      double
      value_from_squared_distance(const double r2) const
      {
        switch (weight_type)
          {
            case WeightType::bell:
              return bell(r2);
            case WeightType::gaussian:
              return gaussian(r2);
            default:
              return r2 == 0. ? 1. : 0.;
          }
      }

      /// The bell, for a loop that has already dispatched on type().
      double
      bell(const double r2) const
      {
        // Written with one multiplication and no branch but the cut-off, so
        // that every rank computes bit-identical weights.
        const double t = 1. - r2 * inverse_cutoff_squared;
        return r2 < cutoff_squared ? t * t : 0.;
      }

      /// The truncated Gaussian, for a loop that has already dispatched.
      double
      gaussian(const double r2) const
      {
        return r2 < cutoff_squared ? std::exp(-r2 * inverse_two_lc_squared)
                                   : 0.;
      }

    private:
      WeightType weight_type            = WeightType::local;
      double     l_c                    = 0.;
      double     cutoff                 = 0.;
      double     cutoff_squared         = 0.;
      double     inverse_cutoff_squared = 0.;
      double     inverse_two_lc_squared = 0.;
    };
  } // namespace nonlocal
} // namespace scarp

#endif
