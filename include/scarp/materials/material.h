#ifndef scarp_materials_material_h
#define scarp_materials_material_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <limits>
#include <string>
#include <vector>

namespace scarp
{
  namespace materials
  {
    using namespace dealii;

    /**
     * @brief Which inelastic parts of the constitutive models act in a
     * step (staging: gravity loading runs elastic). Models without them
     * ignore these.
     */
    struct InelasticSwitches
    {
      /// The plastic return mapping.
      bool plasticity = true;
      /// Growth of damage (the existing damage still degrades the stress).
      bool damage = true;
    };

    /**
     * @brief Cumulative energies dissipated per reference volume at a
     * point (Material::dissipated_energy()).
     */
    struct DissipatedEnergy
    {
      /// By plasticity [J/m^3].
      double plastic;
      /// By damage [J/m^3].
      double damage;
    };

    /**
     * @brief The points of one cell that share a material, handed to a
     * constitutive model in one call (no virtual call per point).
     *
     * Tensors are always 3x3: in plane strain the out-of-plane row and
     * column of the deformation increment are those of the identity.
     * All arrays have length @p n.
     */
    struct MaterialBatch
    {
      /// Number of points in the batch.
      unsigned int n = 0;
      /// Time step of this update [s].
      double dt = 0.;
      /// Deformation increment of the step, dF = I + dt L.
      const Tensor<2, 3> *delta_F = nullptr;
      /// Total deformation gradient after the increment, F_{n+1}.
      const Tensor<2, 3> *F = nullptr;
      /// Per point: pointer to its n_state_variables() state values.
      double *const *state = nullptr;
      /// In: Cauchy stress of step n. Out: Cauchy stress of step n+1 [Pa].
      SymmetricTensor<2, 3> *stress = nullptr;
      /// Out: stored (recoverable) energy per reference volume [J/m^3].
      double *stored_energy = nullptr;
      /// Out: local damage driver Y per point [Pa]; only for materials with
      /// has_damage(), nullptr otherwise.
      double *damage_driver = nullptr;
      /// The inelastic parts that act in this update (the stage's).
      InelasticSwitches inelastic;
    };

    /**
     * @brief Constitutive model at a single material point: no mesh, no
     * particles. The simulation owns one object per material of a scene.
     *
     * State (for instance the elastic logarithmic strain, plastic strain,
     * damage) lives in a flat array of doubles per point, whose layout the
     * model defines. The Cauchy stress is kept by the caller.
     */
    class Material
    {
    public:
      virtual ~Material() = default;

      /// Mass density in the reference configuration [kg/m^3].
      virtual double
      density() const = 0;

      /// Undamaged p-wave (constrained) modulus M = K + 4G/3 [Pa], for the
      /// critical time step.
      virtual double
      p_wave_modulus() const = 0;

      /// Number of doubles of state per point.
      virtual unsigned int
      n_state_variables() const = 0;

      /// Names of the state variables, as written to the output.
      virtual std::vector<std::string>
      state_variable_names() const = 0;

      /// Initialise the state of a point that starts with the Cauchy stress
      /// @p initial_stress (F = I).
      virtual void
      initialize_state(const SymmetricTensor<2, 3> &initial_stress,
                       double                      *state) const = 0;

      /// Advance all points of the batch by one step.
      virtual void
      update(const MaterialBatch &batch) const = 0;

      /// True if the model has a plastic return (it dissipates energy).
      virtual bool
      has_plasticity() const
      {
        return false;
      }

      /// True if the model has scalar damage driven by a non-local average
      /// of damage_driver; then update_damage() must be called every step.
      virtual bool
      has_damage() const
      {
        return false;
      }

      /// Characteristic length l_c of the non-local average [m] (damage
      /// models only).
      virtual double
      nonlocal_length() const
      {
        return 0.;
      }

      /// Whether a point with this state can still change its damage (so
      /// that it takes part in the non-local average as a receiver), in a
      /// step where damage grows at all (InelasticSwitches::damage).
      virtual bool
      damage_can_change(const double * /*state*/) const
      {
        return false;
      }

      /// Damage d of a point in [0,1] (0 for models without damage).
      virtual double
      damage(const double * /*state*/) const
      {
        return 0.;
      }

      /// Give a point an initial damage @p d in [0, 1] with a consistent
      /// history (a pre-damage band). Models without damage accept only 0.
      virtual void
      set_initial_damage(double * /*state*/, const double d) const
      {
        AssertThrow(d <= 0.,
                    ExcMessage("This material model has no damage: its "
                               "points cannot start damaged."));
      }

      /// Whether a point with this state is a source of the non-local
      /// average (true unless the model leaves fully damaged points out of
      /// both sums).
      virtual bool
      is_nonlocal_source(const double * /*state*/) const
      {
        return true;
      }

      /// A factor > 1 if points of this material are removed once damaged
      /// and stretched beyond it (removable() decides, from the state); 0
      /// (the default): never removed.
      virtual double
      removal_stretch() const
      {
        return 0.;
      }

      /// Whether a point with this state is to be removed: damaged enough
      /// and stretched beyond removal_stretch().
      virtual bool
      removable(const double * /*state*/) const
      {
        return false;
      }

      /// Set a point to fully damaged (d = 1), e.g. a pre-existing crack.
      /// The value the non-local driver must exceed for damage to grow
      /// (refinement ahead of the damage front); +inf without damage.
      virtual double
      damage_threshold(const double * /*state*/) const
      {
        return std::numeric_limits<double>::infinity();
      }

      virtual void
      set_fully_damaged(double * /*state*/) const
      {
      }

      /// The non-local driver Ybar that update_damage() last received (0
      /// for models that do not keep it). Steps between two non-local
      /// averages (Non-local average/Update interval) reuse it.
      virtual double
      last_nonlocal_driver(const double * /*state*/) const
      {
        return 0.;
      }

      /// Update the history (kappa) and damage of a point from the
      /// non-local driver @p nonlocal_driver over the step @p dt. Damage is
      /// used in the stress from the next update() on. Called only in steps
      /// where damage grows (InelasticSwitches::damage).
      virtual void
      update_damage(const double /*nonlocal_driver*/,
                    const double /*dt*/,
                    double * /*state*/) const
      {
      }

      /// Cumulative energy dissipated per reference volume [J/m^3] by
      /// plasticity and by damage at a point with this state. A value (two
      /// doubles come back in registers): written through references, the
      /// pair was read back from the stack in one 16-byte load over two
      /// 8-byte stores, a failed store forwarding per point (perf annotate
      /// of the G2P write-back).
      virtual DissipatedEnergy
      dissipated_energy(const double * /*state*/) const
      {
        return {0., 0.};
      }
    };
  } // namespace materials
} // namespace scarp

#endif
