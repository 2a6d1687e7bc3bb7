#ifndef scarp_particles_pool_growth_h
#define scarp_particles_pool_growth_h

#include <deal.II/particles/particle_handler.h>

#include <cstddef>

namespace scarp
{
  namespace particles
  {
    using namespace dealii;

    /**
     * @brief Grows the particle handler's property pool in steps of 1/16
     * instead of std::vector's doubling.
     *
     * deal.II's PropertyPool takes a new slot with a resize by one of each
     * of its arrays (locations, reference locations, ids, properties) when
     * no slot is free, so that the arrays double whenever they are full:
     * a step whose moved points are inserted before the cells they leave
     * free their slots doubled the properties of every point (and held
     * three times them while copying). Called before a batch of
     * insertions, this reserves the slots the batch needs beyond the free
     * ones, rounded up to a fixed ladder of sizes 1/16 apart, so that the
     * pool stays within 1/16 of what it holds and a batch copies it at
     * most once. The slots a point takes, and with them every result, do
     * not change: only the capacity of the arrays does.
     */
    class PoolGrowth
    {
    public:
      /// Make room for @p n_new insertions into @p particles' pool.
      template <int dim>
      static void
      reserve(Particles::ParticleHandler<dim> &particles,
              const std::size_t                n_new)
      {
        const auto       &pool   = particles.get_property_pool();
        const std::size_t n_free = pool.n_slots() - pool.n_registered_slots();
        if (n_new <= n_free)
          return;
        particles.reserve(rung(pool.n_slots() + (n_new - n_free)));
      }

      /// The smallest size of the ladder 1024, 1088, 1156, ... (each 1/16
      /// above the one before) that is at least @p n: the same n gives the
      /// same size, so that a capacity reserved before is not reallocated
      /// by a later request for a little more.
      static std::size_t
      rung(const std::size_t n)
      {
        std::size_t size = 1024;
        while (size < n)
          size += size / 16;
        return size;
      }
    };
  } // namespace particles
} // namespace scarp

#endif
