// The linear algebra of every Newton step: the dynamic Laplacian restricted to the vertices
// whose u is free, with a sparse Cholesky whose pattern is analysed once.
//
// Restricting to a free set covers every use: Algorithm 1 pins one vertex (the kernel of
// Delta is the constant vector), the free-boundary optimum frees the non-singular vertices,
// and the harmonic layout frees the interior. Only the lower triangle is stored, the layout
// both Eigen's SimplicialLDLT and CHOLMOD read.

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

/// Eigen's simplicial LDL^T with AMD ordering: always available, and the default. Measured
/// with benchmark/kernels (numeric factorization of the interior Laplacian, 2 cores) it
/// beats CHOLMOD's supernodal LL^T at every size up to 235k faces: 0.40 vs 2.1 ms at
/// 3.7k faces, 4.7 vs 18 ms at 15k, 43 vs 101 ms at 59k, 0.48 vs 0.78 s at 235k, because
/// mesh Laplacians have small supernodes.
using Simplicial_solver = Eigen::SimplicialLDLT<Sparse_matrix, Eigen::Lower, Eigen::AMDOrdering<int>>;
using Default_sparse_solver = Simplicial_solver;
#ifdef ICM_HAS_CHOLMOD
/// CHOLMOD's supernodal LL^T (SuiteSparse), for users who prefer it or have larger meshes.
using Cholmod_solver = Eigen::CholmodSupernodalLLT<Sparse_matrix, Eigen::Lower>;
#endif

/// Delta(u) restricted to a free vertex set: Delta_ii = sum_j w_ij over all neighbours,
/// Delta_ij = -w_ij between free neighbours. `SparseSolver` is an Eigen sparse Cholesky
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
    if(size() > 0)
      solver_.analyzePattern(matrix_);
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
    return solver_.info() == Eigen::Success;
  }

  /// Solves Delta_FF x = b for right-hand sides given per free unknown.
  template <class Rhs>
  typename Rhs::PlainObject solve(const Eigen::MatrixBase<Rhs>& b) const
  {
    return solver_.solve(b);
  }

private:
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
};

} // namespace ICM

#endif // ICM_DYNAMIC_LAPLACIAN_H
