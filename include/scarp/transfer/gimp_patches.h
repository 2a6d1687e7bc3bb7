#ifndef scarp_transfer_gimp_patches_h
#define scarp_transfer_gimp_patches_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/partitioner.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/affine_constraints.h>

#include <deque>
#include <set>
#include <vector>

namespace scarp
{
  namespace transfer
  {
    using namespace dealii;

    /**
     * @brief GIMP on any mesh the triangulation produces (uniform, or
     * adaptive with hanging nodes), in 2D and 3D, on any number of ranks.
     *
     * The weight of node j for a point with the axis-aligned domain
     * Omega_p (half-widths l_d) is the mean of the global, hanging-node
     * constrained Q1 basis function N_j over Omega_p:
     *
     *   S_j = 1/|Omega_p| int_{Omega_p} N_j,
     *   grad S_j = 1/|Omega_p| int_{Omega_p} grad N_j.
     *
     * N_j is, on every active cell K', the sum of K''s Q1 shape functions
     * phi_i times the constraint coefficient c_ij (1 for j = i, the
     * AffineConstraints weight if vertex i hangs on j). The Q1 functions
     * are multilinear, so the mean of phi_i and of grad phi_i over the box
     * Omega_p n K' are their values at the centre of that box: in closed
     * form,
     *
     *   S_j = sum_{K'} |Omega_p n K'|/|Omega_p| sum_i c_ij phi_i(m_K'),
     *
     * with m_K' the centre of Omega_p n K' (and the same for gradients).
     * On a uniform mesh this is uniform GIMP (Bardenhagen & Kober 2004)
     * exactly; for l -> 0 it is Q1.
     *
     * Rule for the domain across levels: l_d <= h_K / 2 with h_K the edge of
     * the cell that holds the point, so that Omega_p only reaches the
     * active cells that touch K; with at most one level of difference at
     * vertices (the triangulation's smoothing) these are all found from
     * K's vertices. The patch of a cell K lists those cells, with their
     * vertices already resolved through the constraints into the
     * unconstrained nodes ("patch nodes"): P2G adds straight into the
     * patch nodes and G2P reads them, and no constraint is applied in the
     * hot loops.
     */
    template <int dim>
    class GimpPatches
    {
    public:
      /// The cells a point of one cell can reach, with their vertices
      /// resolved into patch nodes.
      struct Patch
      {
        /// The unconstrained dofs of the patch and their positions.
        std::vector<types::global_dof_index> node_dofs;
        std::vector<Point<dim>>              node_positions;
        /// Their indices in the local storage of the grid vectors (owned,
        /// then ghost), for local_element() instead of a global lookup.
        std::vector<unsigned int> node_local;
        /// What evaluate() reads: per patch cell its box, edge, 1/h and
        /// the range [entry_begin[v], entry_begin[v + 1]) of vertex v's
        /// entries, and the (node, weight) entries (a vertex that hangs has
        /// one per master, the others one of weight 1).
        struct Cell
        {
          Point<dim>   lower, upper;
          double       h, inv_h;
          unsigned int entry_begin[(1u << dim) + 1];
        };
        std::vector<Cell>                            cells;
        std::vector<std::pair<unsigned int, double>> entries;

        /// A regular patch: the 3^dim cells around the point's cell, all of
        /// its size, none with a hanging vertex. Its nodes form a lattice of
        /// 4 per direction, and N_j is a tensor product of 1D hats, so the
        /// weights are products of 1D GIMP weights (evaluate_regular()).
        bool regular = false;
        /// Regular patches: the lattice coordinates per direction, the
        /// edge and its inverse. Their nodes are in lattice order: node
        /// a_0 + 4 a_1 (+ 16 a_2) is the one at lattice[d][a_d].
        double lattice[dim][4];
        double lattice_h = 0, lattice_inv_h = 0;

        unsigned int
        n_nodes() const
        {
          return node_dofs.size();
        }
      };

      /// Forget all patches; call after every change of the mesh or dofs.
      void
      reinit(const DoFHandler<dim>             &dof_handler,
             const AffineConstraints<double>   &constraints,
             const Utilities::MPI::Partitioner &partitioner);

      /// The patch of a locally owned cell (built the first time asked;
      /// the reference stays valid until the next reinit()).
      const Patch &
      patch(const typename DoFHandler<dim>::active_cell_iterator &cell);

      /// Weights @p value and gradients @p gradient (size n_nodes()) of a
      /// point at @p x with domain half-widths @p l (l_d <= h_K / 2, l_d = 0
      /// only on the boundary of the mesh box).
      static void
      evaluate(const Patch      &patch,
               const Point<dim> &x,
               const double (&l)[dim],
               std::vector<double>         &value,
               std::vector<Tensor<1, dim>> &gradient);

      /// The non-zero entries (weight or gradient) of a point at @p x with
      /// half-widths @p l > 0 on a regular patch with the lattice
      /// coordinates @p lattice and inverse edge @p inv_h: written to
      /// @p node (lattice
      /// index = patch node), @p value, @p gradient, which have room for
      /// 3^dim entries (l <= h/2 reaches at most 3 nodes per direction);
      /// returns their number. Products of 1D
      /// weights, equal to the general sum over the patch cells up to
      /// round-off.
      static unsigned int
      regular_nonzero(const double (&lattice)[dim][4],
                      const double      inv_h,
                      const Point<dim> &x,
                      const double (&l)[dim],
                      unsigned int   *node,
                      double         *value,
                      Tensor<1, dim> *gradient);

      /// The general sum over the patch cells, also on a regular patch (to
      /// test the regular path against it).
      static void
      evaluate_general(const Patch      &patch,
                       const Point<dim> &x,
                       const double (&l)[dim],
                       std::vector<double>         &value,
                       std::vector<Tensor<1, dim>> &gradient);

      /// Number of patches built since the last reinit (for statistics).
      unsigned int
      n_built() const
      {
        return patches.size();
      }

    private:
      /// Mark @p p regular if it is, and set its lattice (the point cell's
      /// lower vertex @p cell_lower and edge @p h).
      static void
      detect_regular(Patch &p, const Point<dim> &cell_lower, const double h);

      const DoFHandler<dim>             *dofs        = nullptr;
      const AffineConstraints<double>   *constraints = nullptr;
      const Utilities::MPI::Partitioner *partitioner = nullptr;
      /// Active cells at each vertex (only non-artificial cells).
      std::vector<std::vector<typename DoFHandler<dim>::active_cell_iterator>>
                       vertex_cells;
      std::vector<int> patch_index; ///< per active cell index
      /// A deque: a patch stays in place while others are added, so the
      /// transfer may keep pointers to the patches of a step.
      std::deque<Patch> patches;
      /// Scratch of patch(), kept between calls: a patch is built here and
      /// copied into arrays of its exact size (one allocation each, no
      /// slack from growing them one entry at a time).
      Patch                                                       scratch;
      std::vector<typename DoFHandler<dim>::active_cell_iterator> scratch_cells;
      std::vector<types::global_dof_index>                        scratch_dofs;
    };
  } // namespace transfer
} // namespace scarp

#endif
