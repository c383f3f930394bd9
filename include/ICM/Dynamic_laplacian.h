// The linear algebra of every Newton step: the dynamic Laplacian restricted to the vertices
// whose u is free, with a sparse Cholesky whose pattern is analysed once.
//
// Restricting to a free set covers every use: Algorithm 1 pins one vertex (the kernel of
// Delta is the constant vector), the free-boundary optimum frees the non-singular vertices,
// and the harmonic layout frees the interior. Only the lower triangle is stored, the layout
// both Eigen's SimplicialLDLT and CHOLMOD read.
//
// The unknowns are numbered in a fill-reducing (AMD) order computed once from the first
// pattern. A metric that flips its triangulation changes a few entries per Newton step;
// the order stays good for them, so re-analysing after flips costs only the elimination
// tree: lion-head spends 36 ms in three AMD analyses (of 89 ms in Newton) otherwise.

#ifndef ICM_DYNAMIC_LAPLACIAN_H
#define ICM_DYNAMIC_LAPLACIAN_H

#include <ICM/internal/Mesh_index.h>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#ifdef ICM_HAS_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include <algorithm>
#include <vector>

namespace ICM {

using Sparse_matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

/// Eigen's simplicial LDL^T, in the AMD order `Dynamic_laplacian` numbers its unknowns in:
/// always available, and the fastest choice for small and medium meshes (benchmark/kernels:
/// 0.40 ms at 3.7k faces, 43 ms at 59k, 0.48 s at 235k, ahead of CHOLMOD's supernodal LL^T)
/// because mesh Laplacians have small supernodes.
using Simplicial_solver = Eigen::SimplicialLDLT<Sparse_matrix, Eigen::Lower, Eigen::NaturalOrdering<int>>;

#ifdef ICM_HAS_CHOLMOD
/// CHOLMOD's supernodal LL^T with its default ordering (SuiteSparse).
using Cholmod_solver = Eigen::CholmodSupernodalLLT<Sparse_matrix, Eigen::Lower>;

/// CHOLMOD's simplicial LDL^T after a nested dissection ordering (NESDIS). AMD's fill grows
/// badly on large planar-like graphs: on lion-head refined to 1.07M faces one numeric
/// factorization takes 15.5 s with AMD and 2.7 s after nested dissection, whose analysis
/// (2.8 s, done once) only pays off from about 10^5 unknowns (measured, one thread).
class Nested_dissection_solver : public Eigen::CholmodDecomposition<Sparse_matrix, Eigen::Lower>
{
public:
  Nested_dissection_solver()
  {
    cholmod().nmethods = 1;
    cholmod().method[0].ordering = CHOLMOD_NESDIS;
    setMode(Eigen::CholmodLDLt);
  }
};

/// The default when SuiteSparse is present: `Simplicial_solver` below
/// `nested_dissection_min_unknowns`, `Nested_dissection_solver` from there on (one
/// analysis and six factorizations, the cost of a parameterization: 0.41 against 0.59 s at
/// 33k unknowns, 4.5 against 2.8 s at 133k, 94 against 19 s at 533k).
class Size_adaptive_solver
{
public:
  static constexpr Eigen::Index nested_dissection_min_unknowns = 75000;

  void analyzePattern(const Sparse_matrix& matrix)
  {
    nested_ = matrix.rows() >= nested_dissection_min_unknowns;
    if(nested_)
      nested_dissection_.analyzePattern(matrix);
    else
      simplicial_.analyzePattern(matrix);
  }
  void factorize(const Sparse_matrix& matrix)
  {
    if(nested_)
      nested_dissection_.factorize(matrix);
    else
      simplicial_.factorize(matrix);
  }
  Eigen::ComputationInfo info() const
  {
    return nested_ ? nested_dissection_.info() : simplicial_.info();
  }
  template <class Rhs>
  typename Rhs::PlainObject solve(const Eigen::MatrixBase<Rhs>& b) const
  {
    if(nested_)
      return nested_dissection_.solve(b);
    return simplicial_.solve(b);
  }
  /// Whether the last `analyzePattern` chose nested dissection.
  bool uses_nested_dissection() const { return nested_; }

private:
  bool nested_ = false;
  Simplicial_solver simplicial_;
  Nested_dissection_solver nested_dissection_;
};
using Default_sparse_solver = Size_adaptive_solver;
#else
using Default_sparse_solver = Simplicial_solver;
#endif

/// Delta(u) restricted to a free vertex set: Delta_ii = sum_j w_ij over all neighbours,
/// Delta_ij = -w_ij between free neighbours. Two edges between the same vertices (possible
/// in an intrinsic triangulation) share one entry. `SparseSolver` is an Eigen sparse Cholesky
/// (analyzePattern / factorize / solve / info).
template <class SparseSolver = Default_sparse_solver>
class Dynamic_laplacian
{
public:
  Dynamic_laplacian(const internal::Mesh_index& index, const std::vector<char>& is_free)
    : index_(index), free_of_(index.number_of_vertices(), -1)
  {
    for(int v = 0; v < index.number_of_vertices(); ++v)
      if(is_free[v])
      {
        free_of_[v] = static_cast<int>(vertex_of_.size());
        vertex_of_.push_back(v);
      }
    build_pattern();
    number_unknowns_in_fill_reducing_order();
    rebuild_pattern();
  }

  /// Rebuilds the pattern from the edges of the index (after edge flips) and analyses it
  /// again; the next solve needs a new factorization.
  void rebuild_pattern()
  {
    build_pattern();
    if(size() > 0)
      solver_.analyzePattern(matrix_);
    factorized_ = false;
  }

  int size() const { return static_cast<int>(vertex_of_.size()); }
  /// Position of vertex `v` among the unknowns, or -1 when it is fixed.
  int free_index(int v) const { return free_of_[v]; }
  int vertex(int i) const { return vertex_of_[i]; }
  const Sparse_matrix& matrix() const { return matrix_; }

  /// Writes the values of Delta for the per-edge weights `w` into the fixed pattern.
  void assemble(const std::vector<double>& w)
  {
    double* values = matrix_.valuePtr();
    std::fill(values, values + matrix_.nonZeros(), 0.0);
    for(int e = 0; e < index_.number_of_edges(); ++e)
    {
      if(index_.edges[e][0] == index_.edges[e][1])
        continue; // a loop of an intrinsic triangulation: w (u_i - u_i)^2 adds nothing
      const int i = free_of_[index_.edges[e][0]], j = free_of_[index_.edges[e][1]];
      if(i >= 0)
        values[diagonal_slot_[i]] += w[e];
      if(j >= 0)
        values[diagonal_slot_[j]] += w[e];
      if(edge_slot_[e] >= 0)
        values[edge_slot_[e]] -= w[e];
    }
  }

  /// Numeric factorization only; the symbolic analysis was done once in the constructor.
  bool factorize()
  {
    if(size() == 0)
      return true;
    solver_.factorize(matrix_);
    factorized_ = solver_.info() == Eigen::Success;
    return factorized_;
  }

  /// Whether a numeric factorization (of some earlier assembly) is available.
  bool has_factorization() const { return factorized_; }

  /// Solves Delta_FF x = b for right-hand sides given per free unknown, with the last
  /// factorization.
  template <class Rhs>
  typename Rhs::PlainObject solve(const Eigen::MatrixBase<Rhs>& b) const
  {
    return solver_.solve(b);
  }

  /// Solves with the matrix as assembled now, using the last factorization — of a nearby
  /// assembly — as preconditioner of an iterative refinement. When every weight changed by
  /// a relative epsilon since that factorization, the error contracts by epsilon per
  /// refinement (a Laplacian with non-negative weights is then within (1 +- epsilon) of the
  /// factorized one in the Loewner order). Returns false when `max_refinements` corrections
  /// do not shrink below `tolerance` relative to x.
  template <class Rhs>
  bool solve_refined(const Eigen::MatrixBase<Rhs>& b, typename Rhs::PlainObject& x,
                     double tolerance = 1e-13, int max_refinements = 6) const
  {
    x = solver_.solve(b);
    for(int refinement = 0; refinement < max_refinements; ++refinement)
    {
      const typename Rhs::PlainObject correction =
        solver_.solve(b - matrix_.template selfadjointView<Eigen::Lower>() * x);
      x += correction;
      if(correction.norm() <= tolerance * x.norm())
        return x.allFinite();
    }
    return false;
  }

private:
  /// Renumbers the unknowns by Eigen's AMD ordering of the current pattern.
  void number_unknowns_in_fill_reducing_order()
  {
    if(size() == 0)
      return;
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
    Eigen::AMDOrdering<int>()(matrix_, inverse); // orders the pattern of A + A^T
    const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order = inverse.inverse();
    for(int i = 0; i < size(); ++i)
      free_of_[vertex_of_[i]] = order.indices()[i];
    for(int v = 0; v < index_.number_of_vertices(); ++v)
      if(free_of_[v] >= 0)
        vertex_of_[free_of_[v]] = v;
  }

  void build_pattern()
  {
    const int n = size();
    std::vector<Eigen::Triplet<double, int>> entries;
    entries.reserve(n + index_.number_of_edges());
    for(int i = 0; i < n; ++i)
      entries.emplace_back(i, i, 1.0);
    for(const auto& e : index_.edges)
    {
      const int i = free_of_[e[0]], j = free_of_[e[1]];
      if(i >= 0 && j >= 0)
        entries.emplace_back(std::max(i, j), std::min(i, j), 1.0);
    }
    matrix_.resize(n, n);
    matrix_.setFromTriplets(entries.begin(), entries.end());
    matrix_.makeCompressed();

    diagonal_slot_.resize(n);
    for(int i = 0; i < n; ++i)
      diagonal_slot_[i] = slot(i, i);
    edge_slot_.assign(index_.number_of_edges(), -1);
    for(int e = 0; e < index_.number_of_edges(); ++e)
    {
      const int i = free_of_[index_.edges[e][0]], j = free_of_[index_.edges[e][1]];
      if(i >= 0 && j >= 0)
        edge_slot_[e] = slot(std::max(i, j), std::min(i, j));
    }
  }

  /// Offset of entry (row, col) in the compressed value array.
  int slot(int row, int col) const
  {
    const int* begin = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[col];
    const int* end = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[col + 1];
    return static_cast<int>(std::lower_bound(begin, end, row) - matrix_.innerIndexPtr());
  }

  const internal::Mesh_index& index_;
  std::vector<int> free_of_;
  std::vector<int> vertex_of_;
  Sparse_matrix matrix_;
  std::vector<int> diagonal_slot_;
  std::vector<int> edge_slot_;
  SparseSolver solver_;
  bool factorized_ = false;
};

} // namespace ICM

#endif // ICM_DYNAMIC_LAPLACIAN_H
