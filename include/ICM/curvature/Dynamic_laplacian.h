// The linear algebra of every Newton step: the dynamic Laplacian restricted to the vertices
// whose u is free, with a sparse Cholesky whose pattern is analysed once.
//
// Restricting to a free set covers every use: Algorithm 1 pins one vertex (the kernel of
// Delta is the constant vector), the free-boundary optimum frees the non-singular vertices,
// and the harmonic layout frees the interior. Only the upper triangle is stored: Eigen's
// SimplicialLDLT factorizes it in place (from a lower triangle it would copy and transpose
// the matrix at every factorization and analysis) and CHOLMOD reads either.
//
// The unknowns are numbered in a fill-reducing (AMD) order computed once from the first
// pattern. A metric that flips its triangulation changes a few entries per Newton step;
// the order stays good for them, so re-analysing after flips costs only the elimination
// tree; a fresh AMD analysis after each flipping step was a large share of Newton's time
// (chosen by measurement; the parameterizers' times are in doc/benchmarks.md, Disks).

#ifndef ICM_CURVATURE_DYNAMIC_LAPLACIAN_H
#define ICM_CURVATURE_DYNAMIC_LAPLACIAN_H

#include <ICM/internal/Mesh_index.h>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#ifdef ICM_HAS_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include <algorithm>
#include <type_traits>
#include <utility>
#include <vector>

namespace ICM {

using Sparse_matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

/// Eigen's simplicial LDL^T, in the AMD order `Dynamic_laplacian` numbers its unknowns in:
/// always available, and the fastest choice for small and medium meshes (ahead of CHOLMOD's
/// supernodal LL^T; benchmark/kernels times both) because mesh Laplacians have small
/// supernodes.
///
/// The analysis reads the matrix in place: Eigen 3.4 recognises "no ordering" only as
/// `NaturalOrdering<Eigen::Index>`, which does not compile with int indices, and otherwise
/// copies the matrix twice per analysis (together about as long as a factorization).
class Simplicial_solver : public Eigen::SimplicialLDLT<Sparse_matrix, Eigen::Upper, Eigen::NaturalOrdering<int>>
{
public:
  void analyzePattern(const Sparse_matrix& matrix)
  {
    m_P.resize(0);
    m_Pinv.resize(0);
    analyzePattern_preordered(matrix, true);
  }
  /// Entries of the factor the last analysis predicts.
  Eigen::Index factor_nonzeros() const { return m_nonZerosPerCol.sum(); }
};

#ifdef ICM_HAS_CHOLMOD
/// CHOLMOD's supernodal LL^T with its default ordering (SuiteSparse).
using Cholmod_solver = Eigen::CholmodSupernodalLLT<Sparse_matrix, Eigen::Upper>;

/// CHOLMOD's simplicial LDL^T after a nested dissection ordering (NESDIS). AMD's fill grows
/// badly on large planar-like graphs: on a million faces a numeric factorization after nested
/// dissection takes a fraction of AMD's, but the dissection's analysis (done once) pays off
/// only from about 10^5 unknowns (chosen by measurement, one thread: doc/benchmarks.md,
/// Scaling).
class Nested_dissection_solver : public Eigen::CholmodDecomposition<Sparse_matrix, Eigen::Upper>
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
/// analysis and six factorizations, the cost of a parameterization, were timed for both
/// solvers across sizes; the switch is near where they cross: doc/benchmarks.md, Scaling).
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
  Eigen::ComputationInfo info() const { return nested_ ? nested_dissection_.info() : simplicial_.info(); }
  template <class Rhs>
  typename Rhs::PlainObject solve(const Eigen::MatrixBase<Rhs>& b) const
  {
    if(nested_)
      return nested_dissection_.solve(b);
    return simplicial_.solve(b);
  }
  /// Whether the last `analyzePattern` chose nested dissection.
  bool uses_nested_dissection() const { return nested_; }
  /// Entries of the simplicial factor the last analysis predicts; 0 after nested dissection,
  /// whose order does not go stale the way AMD's does.
  Eigen::Index factor_nonzeros() const { return nested_ ? 0 : simplicial_.factor_nonzeros(); }

private:
  bool nested_ = false;
  Simplicial_solver simplicial_;
  Nested_dissection_solver nested_dissection_;
};
using Default_sparse_solver = Size_adaptive_solver;
#else
using Default_sparse_solver = Simplicial_solver;
#endif

/// Whether a solver reports the fill of its factor (`factor_nonzeros()`).
template <class Solver, class = void>
struct Reports_fill : std::false_type
{};
template <class Solver>
struct Reports_fill<Solver, std::void_t<decltype(std::declval<const Solver&>().factor_nonzeros())>> : std::true_type
{};

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
    diagonal_slot_.resize(size());
    order_and_analyze();
  }

  /// Rebuilds the pattern from the edges of the index (after edge flips) and analyses it
  /// again; the next solve needs a new factorization. Flips can make the fill-reducing order
  /// stale: a first Newton step's flips of a small fraction of the edges can grow the factor
  /// by a sixth. When the solver reports its fill (`factor_nonzeros()`) and it grew by more
  /// than `max_fill_growth` since the unknowns were numbered, they are numbered again: AMD
  /// costs a fraction of a factorization there, and a factor 10% larger costs more than that
  /// over the remaining Newton steps. Returns whether the unknowns were renumbered.
  bool rebuild_pattern(double max_fill_growth = 0.1)
  {
    build_pattern();
    analyze();
    if(!(factor_nonzeros() > (1.0 + max_fill_growth) * ordered_fill_))
      return false;
    order_and_analyze();
    return true;
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
  bool solve_refined(const Eigen::MatrixBase<Rhs>& b, typename Rhs::PlainObject& x, double tolerance = 1e-13,
                     int max_refinements = 6) const
  {
    x = solver_.solve(b);
    for(int refinement = 0; refinement < max_refinements; ++refinement)
    {
      const typename Rhs::PlainObject correction =
        solver_.solve(b - matrix_.template selfadjointView<Eigen::Upper>() * x);
      x += correction;
      if(correction.norm() <= tolerance * x.norm())
        return x.allFinite();
    }
    return false;
  }

private:
  /// Numbers the unknowns in a fill-reducing order of the current edges, then analyses.
  void order_and_analyze()
  {
    build_pattern();
    number_unknowns_in_fill_reducing_order();
    build_pattern();
    analyze();
    ordered_fill_ = factor_nonzeros();
  }

  /// The fill the solver predicts, or 0 when it does not say.
  double factor_nonzeros() const
  {
    if constexpr(Reports_fill<SparseSolver>::value)
      return size() > 0 ? static_cast<double>(solver_.factor_nonzeros()) : 0.0;
    else
      return 0.0;
  }

  void analyze()
  {
    if(size() > 0)
      solver_.analyzePattern(matrix_);
    factorized_ = false;
  }

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

  /// The upper triangle of the free vertices' adjacency, column by column, and the slot of
  /// every edge in it, in two passes over the edges and no search: this runs again after
  /// every Newton step whose edge flips changed the triangulation.
  void build_pattern()
  {
    const int n = size();
    const int ne = index_.number_of_edges();
    // Entries of column j: (row i <= j, edge e), the diagonal with e = -1.
    std::vector<int>& start = column_start_;
    start.assign(n + 1, 0);
    for(int i = 0; i < n; ++i)
      start[i + 1] = 1;
    for(int e = 0; e < ne; ++e)
    {
      const int i = free_of_[index_.edges[e][0]], j = free_of_[index_.edges[e][1]];
      if(i >= 0 && j >= 0 && i != j)
        ++start[std::max(i, j) + 1];
    }
    for(int i = 0; i < n; ++i)
      start[i + 1] += start[i];
    entries_.resize(start[n]);
    next_.assign(start.begin(), start.end() - 1);
    for(int i = 0; i < n; ++i)
      entries_[next_[i]++] = {i, -1};
    edge_slot_.assign(ne, -1);
    for(int e = 0; e < ne; ++e)
    {
      const int i = free_of_[index_.edges[e][0]], j = free_of_[index_.edges[e][1]];
      if(i >= 0 && j >= 0 && i != j)
        entries_[next_[std::max(i, j)]++] = {std::min(i, j), e};
    }

    // Sort each column by row (a handful of entries: insertion sort) and merge the entries
    // of two edges that join the same vertices, possible in an intrinsic triangulation.
    matrix_.resize(n, n);
    matrix_.resizeNonZeros(start[n]);
    int* outer = matrix_.outerIndexPtr();
    int* inner = matrix_.innerIndexPtr();
    int nonzeros = 0;
    for(int j = 0; j < n; ++j)
    {
      std::pair<int, int>* first = entries_.data() + start[j];
      std::pair<int, int>* last = entries_.data() + start[j + 1];
      for(std::pair<int, int>* x = first + 1; x < last; ++x)
        for(std::pair<int, int>* y = x; y > first && y[-1].first > y[0].first; --y)
          std::swap(y[-1], y[0]);
      outer[j] = nonzeros;
      for(std::pair<int, int>* x = first; x < last; ++x)
      {
        if(x == first || x->first != x[-1].first)
          inner[nonzeros++] = x->first;
        if(x->second >= 0)
          edge_slot_[x->second] = nonzeros - 1;
        else
          diagonal_slot_[j] = nonzeros - 1;
      }
    }
    outer[n] = nonzeros;
    matrix_.resizeNonZeros(nonzeros);
    std::fill(matrix_.valuePtr(), matrix_.valuePtr() + nonzeros, 0.0);
  }

  const internal::Mesh_index& index_;
  std::vector<int> free_of_;
  std::vector<int> vertex_of_;
  double ordered_fill_ = 0; ///< factor_nonzeros() when the unknowns were numbered
  Sparse_matrix matrix_;
  std::vector<int> diagonal_slot_;
  std::vector<int> edge_slot_;
  std::vector<int> column_start_, next_; // build_pattern's scratch, kept between rebuilds
  std::vector<std::pair<int, int>> entries_;
  SparseSolver solver_;
  bool factorized_ = false;
};

} // namespace ICM

#endif // ICM_CURVATURE_DYNAMIC_LAPLACIAN_H
