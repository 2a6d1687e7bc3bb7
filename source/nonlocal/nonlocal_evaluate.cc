// NonlocalAverager: the weighted sums over the neighbour lists, with the
// vector kernels (SSE2, AVX2, AVX-512) chosen at run time.

#include <scarp/nonlocal/nonlocal_averager.h>
#include <scarp/nonlocal/nonlocal_averager_internal.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

namespace scarp
{
  namespace nonlocal
  {
    using namespace internal;


    // No fused multiply-add in the sums, even where the instruction set has
    // one (avx512f implies fma in GCC): it would round differently from the
    // plain loop, and from the same loop without FMA on another rank.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC push_options
#pragma GCC optimize("fp-contract=off")
#endif
    namespace
    {
      // Vectors of 2, 4 and 8 doubles: SSE2 (or NEON), AVX2 and AVX-512
      // registers.
      using v2d = double __attribute__((vector_size(16)));
      using v4d = double __attribute__((vector_size(32)));
      using v8d = double __attribute__((vector_size(64)));

      // The bell of WeightFunction for a vector of squared distances, with
      // the same operations, so bit-identical to the scalar one.
      struct BellWeights
      {
        // As in WeightFunction: 1 / R^2 and R^2.
        double inverse_cutoff_squared, cutoff_squared;

        template <typename VD>
        __attribute__((always_inline)) inline VD
        operator()(const VD r2) const
        {
          using VI    = decltype(r2 < r2);
          const VD t  = 1. - r2 * inverse_cutoff_squared;
          const VD tt = t * t;
          return (VD)((VI)tt & (r2 < cutoff_squared));
        }
      };

      /**
       * The sums of groups of G receivers, G / lanes vectors VD of lanes
       * doubles. Lane l of group g is the receiver at slot slots[G g + l];
       * it adds w V_q Y_q and w V_q of every source q of the group's list,
       * one term at a time in list (= id) order, exactly as a loop over its
       * own list would: the other sources of the union are beyond the
       * cut-off now (each point moved less than skin/2 since the build) and
       * add +-0, which leaves a sum unchanged.
       *
       * The bell is evaluated in the vectors. The Gaussian's std::exp is
       * not vectorised (a vector exp rounds differently): its weights are
       * computed in a separate scalar pass over a buffer, since a call
       * inside the vector loop would spill all live vectors.
       *
       * Written as one inline body so that it is compiled for each
       * instruction set, all without FMA: a fused multiply-add rounds
       * differently from the plain loop.
       */
      template <int dim, typename VD, unsigned int G>
      __attribute__((always_inline)) inline void
      group_sums(const WeightFunction              &weight,
                 const std::array<double, dim + 2> *data,
                 const unsigned int                *slots,
                 const std::size_t                 *start,
                 const unsigned int                *list,
                 const unsigned char               *active,
                 const std::size_t                  n_groups,
                 std::vector<double>               &buffer,
                 std::vector<unsigned int>         &inside,
                 double                            *numerators,
                 double                            *denominators,
                 std::int64_t                      *interacting)
      {
        using VI                    = decltype(VD() < VD());
        constexpr unsigned int L    = sizeof(VD) / sizeof(double);
        constexpr unsigned int V    = G / L;
        const bool             bell = weight.type() == WeightType::bell;
        const double      R2 = weight.cutoff_radius() * weight.cutoff_radius();
        const BellWeights bell_weights{1. / R2, R2};
        for (std::size_t g = 0; g < n_groups; ++g)
          {
            if (!active[g])
              continue;
            VD x[V][dim];
            for (unsigned int v = 0; v < V; ++v)
              for (unsigned int l = 0; l < L; ++l)
                for (unsigned int d = 0; d < dim; ++d)
                  x[v][d][l] = data[slots[G * g + L * v + l]][d];
            const auto squared_distances = [&x](const double      *q,
                                                const unsigned int v) {
              // As squared_distance(x_p, x_q): 0 + dx^2 is dx^2.
              VD dx = x[v][0] - q[0];
              VD r2 = dx * dx;
              for (unsigned int d = 1; d < dim; ++d)
                {
                  dx = x[v][d] - q[d];
                  r2 += dx * dx;
                }
              return r2;
            };

            const std::size_t begin = start[g], end = start[g + 1];
            if (!bell)
              {
                // Gaussian weights of the whole group, scalar.
                // (memcpy: the buffer is not aligned for a VD.)
                buffer.resize(G * (end - begin));
                double *b = buffer.data();
                for (std::size_t j = begin; j < end; ++j)
                  for (unsigned int v = 0; v < V; ++v, b += L)
                    {
                      const VD r2 = squared_distances(data[list[j]].data(), v);
                      std::memcpy(b, &r2, sizeof(VD));
                    }
                // List those within the cut-off (R2, as in WeightFunction)
                // and zero the others without a branch, then take the exps
                // of the listed: no mispredicted branch per lane.
                std::size_t n_inside = 0;
                inside.resize(buffer.size());
                for (std::size_t k = 0; k < buffer.size(); ++k)
                  {
                    const bool in    = buffer[k] < R2;
                    inside[n_inside] = k;
                    n_inside += in;
                    buffer[k] = in ? buffer[k] : 0.;
                  }
                for (std::size_t k = 0; k < n_inside; ++k)
                  buffer[inside[k]] = weight.gaussian(buffer[inside[k]]);
              }
            const double *b = buffer.data();

            VD num[V], den[V];
            VI count[V];
            for (unsigned int v = 0; v < V; ++v)
              {
                num[v]   = VD{};
                den[v]   = VD{};
                count[v] = VI{};
              }
            for (std::size_t j = begin; j < end; ++j)
              {
                const double *q = data[list[j]].data();
                for (unsigned int v = 0; v < V; ++v)
                  {
                    VD w;
                    if (bell)
                      w = bell_weights(squared_distances(q, v));
                    else
                      {
                        std::memcpy(&w, b, sizeof(VD));
                        b += L;
                      }
                    num[v] += w * q[dim + 1];
                    den[v] += w * q[dim];
                    count[v] -= (w > 0.); // true is -1
                  }
              }
            for (unsigned int v = 0; v < V; ++v)
              for (unsigned int l = 0; l < L; ++l)
                {
                  const std::size_t k = G * g + L * v + l;
                  numerators[k]       = num[v][l];
                  denominators[k]     = den[v][l];
                  interacting[k]      = count[v][l];
                }
          }
      }

#define SCARP_NONLOCAL_GROUP_SUMS(name, attributes, VD)                 \
  template <int dim, unsigned int G>                                    \
  attributes void name(const WeightFunction              &weight,       \
                       const std::array<double, dim + 2> *data,         \
                       const unsigned int                *slots,        \
                       const std::size_t                 *start,        \
                       const unsigned int                *list,         \
                       const unsigned char               *active,       \
                       const std::size_t                  n_groups,     \
                       std::vector<double>               &buffer,       \
                       std::vector<unsigned int>         &inside,       \
                       double                            *numerators,   \
                       double                            *denominators, \
                       std::int64_t                      *interacting)  \
  {                                                                     \
    group_sums<dim, VD, G>(weight,                                      \
                           data,                                        \
                           slots,                                       \
                           start,                                       \
                           list,                                        \
                           active,                                      \
                           n_groups,                                    \
                           buffer,                                      \
                           inside,                                      \
                           numerators,                                  \
                           denominators,                                \
                           interacting);                                \
  }

      SCARP_NONLOCAL_GROUP_SUMS(group_sums_default, , v2d)
#if defined(__GNUC__) && defined(__x86_64__)
#define SCARP_NONLOCAL_X86
      // The same for AVX2 and AVX-512 (neither with FMA), chosen at run time.
      SCARP_NONLOCAL_GROUP_SUMS(group_sums_avx2,
                                __attribute__((target("avx2"))),
                                v4d)
      SCARP_NONLOCAL_GROUP_SUMS(group_sums_avx512,
                                __attribute__((target("avx512f"))),
                                v8d)
#endif
#undef SCARP_NONLOCAL_GROUP_SUMS
    } // namespace
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC pop_options
#endif


    template <int dim>
    void
    NonlocalAverager<dim>::evaluate(const std::vector<double> &values,
                                    const std::vector<bool>   &is_receiver,
                                    std::vector<double>       &averages)
    {
      const std::size_t n_local  = slot_of_local.size();
      const std::size_t n_groups = group_start.size() - 1;

      std::size_t listed = 0;
      for (std::size_t i = 0; i < n_local; ++i)
        if (is_receiver[i])
          listed += list_length[i];
        else
          averages[i] = values[i];

      // Groups of former receivers only are skipped.
      group_active.assign(n_groups, 0);
      for (std::size_t k = 0; k < group_members.size(); ++k)
        if (group_members[k] != numbers::invalid_unsigned_int &&
            is_receiver[group_members[k]])
          group_active[k / group_size] = 1;
      group_numerators.resize(group_members.size());
      group_denominators.resize(group_members.size());
      group_interacting.resize(group_members.size());

      auto sums = &group_sums_default<dim, group_size>;
#ifdef SCARP_NONLOCAL_X86
      if (__builtin_cpu_supports("avx512f"))
        sums = &group_sums_avx512<dim, group_size>;
      else if (__builtin_cpu_supports("avx2"))
        sums = &group_sums_avx2<dim, group_size>;
#endif
      sums(weight,
           source_data.data(),
           group_slots.data(),
           group_start.data(),
           group_neighbours.data(),
           group_active.data(),
           n_groups,
           weight_buffer,
           inside_buffer,
           group_numerators.data(),
           group_denominators.data(),
           group_interacting.data());

      std::size_t interacting = 0;
      for (std::size_t k = 0; k < group_members.size(); ++k)
        {
          const unsigned int i = group_members[k];
          if (i == numbers::invalid_unsigned_int || !is_receiver[i])
            continue;
          const double denominator = group_denominators[k];
          interacting += group_interacting[k];
          // The point itself has weight 1; only zero volumes (or points
          // left out of the sums) can leave the denominator at zero, and
          // then there is nothing to average.
          averages[i] =
            denominator > 0. ? group_numerators[k] / denominator : values[i];
        }
      listed_pair_count      = listed;
      interacting_pair_count = interacting;
    }


    // Instantiations (the other members are in the other nonlocal_*.cc
    // files).
    template void
    NonlocalAverager<2>::evaluate(const std::vector<double> &values,
                                  const std::vector<bool>   &is_receiver,
                                  std::vector<double>       &averages);
    template void
    NonlocalAverager<3>::evaluate(const std::vector<double> &values,
                                  const std::vector<bool>   &is_receiver,
                                  std::vector<double>       &averages);
  } // namespace nonlocal
} // namespace scarp
