// Sparse Levenberg-Marquardt on a 2D pose graph (docs/algorithms.md, "Pose graph back end").
//
// The normal equations H dx = -g, H = J^T W J and g = J^T W r over the free nodes' 3 variables
// each, are assembled in 3x3 blocks (one on the diagonal per free node, one above it per pair
// of free nodes an edge joins) whose pattern is built once, in a fill-reducing order of the
// nodes (AMD on the node graph). A sparse Cholesky factorization by 3x3 blocks finds the
// patterns of its factor once too: every iteration only refills the values, adds the damping
// to the diagonal and refactorizes. Everything runs in a fixed order on one thread, so the
// same graph gives the same poses bit for bit.
#include "intgrid/optimization/pose_graph.hpp"

#include <Eigen/Core>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace intgrid::optimization {

namespace {

bool is_positive(double v) {
  return std::isfinite(v) && v > 0.0;
}

bool is_finite(const core::Pose2& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

// The unwhitened residual of an edge between poses a (from) and b (to).
Eigen::Vector3d residual(const core::Pose2& a, const core::Pose2& b, const core::Pose2& m) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  const double dx = b.x - a.x, dy = b.y - a.y;
  return {c * dx + s * dy - m.x, -s * dx + c * dy - m.y,
          core::wrap_angle(b.theta - a.theta - m.theta)};
}

// The information of an edge's translation, in `from`'s frame (Edge).
Eigen::Matrix2d translation_information(const Edge& e) {
  const Eigen::Vector2d d(std::cos(e.weak_axis), std::sin(e.weak_axis));
  return (Eigen::Matrix2d::Identity() - (1.0 - e.weak_weight) * d * d.transpose()) /
         (e.sigma_xy * e.sigma_xy);
}

// The squared whitened norm of a residual.
double squared_norm(const Eigen::Vector3d& r, const Edge& e) {
  const Eigen::Vector2d t = r.head<2>();
  return t.dot(translation_information(e) * t) + r.z() * r.z() / (e.sigma_theta * e.sigma_theta);
}

// rho(s): s, or for a robust edge past k sigmas the Huber loss 2 k sqrt(s) - k^2.
double loss(double s, bool robust, double k) {
  return robust && s > k * k ? 2.0 * k * std::sqrt(s) - k * k : s;
}

// rho'(s): the IRLS weight.
double weight(double s, bool robust, double k) {
  return robust && s > k * k ? k / std::sqrt(s) : 1.0;
}

double total_cost(const std::vector<core::Pose2>& poses, const std::vector<Edge>& edges, double k) {
  double cost = 0.0;
  for (const Edge& e : edges) {
    if (!e.active) continue;
    const double s = squared_norm(residual(poses[e.from], poses[e.to], e.measured), e);
    cost += loss(s, e.robust, k);
  }
  return 0.5 * cost;
}

std::size_t count_downweighted(const std::vector<core::Pose2>& poses,
                               const std::vector<Edge>& edges, double k) {
  std::size_t n = 0;
  for (const Edge& e : edges) {
    if (!e.robust || !e.active) continue;
    const double s = squared_norm(residual(poses[e.from], poses[e.to], e.measured), e);
    if (s > k * k) ++n;
  }
  return n;
}

using Block = Eigen::Matrix3d;  // column-major 3x3

// The Cholesky factor L L^T of a sparse symmetric positive definite matrix of 3x3 blocks, given
// by its upper triangle in the order to eliminate. Up-looking: block row k of L is a sparse
// triangular solve against the rows above it. The pattern of every row and column of L is
// found once (analyze); each factorize only does the 3x3 block arithmetic.
class BlockCholesky {
 public:
  // Column k of the upper triangle holds blocks at rows above_row[above_start[k] ..
  // above_start[k + 1]), each < k.
  void analyze(const std::vector<int>& above_start, const std::vector<int>& above_row) {
    n_ = static_cast<int>(above_start.size()) - 1;
    const auto un = static_cast<std::size_t>(n_);
    // Elimination tree, with path compression.
    std::vector<int> parent(un, -1), ancestor(un, -1);
    for (int k = 0; k < n_; ++k) {
      for (int p = above_start[uz(k)]; p < above_start[uz(k + 1)]; ++p) {
        for (int i = above_row[uz(p)]; i != -1 && i < k;) {
          const int next = ancestor[uz(i)];
          ancestor[uz(i)] = k;
          if (next == -1) parent[uz(i)] = k;
          i = next;
        }
      }
    }
    // The pattern of each row of L, in an order where every block comes after those it
    // depends on (the tree paths from the upper triangle's blocks up to the diagonal).
    row_start_.assign(un + 1, 0);
    row_col_.clear();
    std::vector<int> mark(un, -1), paths, ends;
    std::vector<int> count(un, 0);
    for (int k = 0; k < n_; ++k) {
      // Each path, bottom up, stops below the nodes already found; emitting the paths last
      // first puts every node after its descendants (CSparse's ereach).
      mark[uz(k)] = k;
      paths.clear();
      ends.clear();
      for (int p = above_start[uz(k)]; p < above_start[uz(k + 1)]; ++p) {
        for (int i = above_row[uz(p)]; mark[uz(i)] != k; i = parent[uz(i)]) {
          paths.push_back(i);
          mark[uz(i)] = k;
        }
        ends.push_back(static_cast<int>(paths.size()));
      }
      for (std::size_t q = ends.size(); q-- > 0;) {
        const int begin = q == 0 ? 0 : ends[q - 1];
        row_col_.insert(row_col_.end(), paths.begin() + begin, paths.begin() + ends[q]);
      }
      for (int q = row_start_[uz(k)]; q < static_cast<int>(row_col_.size()); ++q) {
        ++count[uz(row_col_[uz(q)])];
      }
      row_start_[uz(k + 1)] = static_cast<int>(row_col_.size());
    }
    // Columns: the rows below the diagonal, increasing, and where each row's block goes.
    col_start_.assign(un + 1, 0);
    for (int i = 0; i < n_; ++i) col_start_[uz(i + 1)] = col_start_[uz(i)] + count[uz(i)];
    col_row_.assign(row_col_.size(), 0);
    row_slot_.assign(row_col_.size(), 0);
    std::vector<int> filled(col_start_.begin(), col_start_.end() - 1);
    for (int k = 0; k < n_; ++k) {
      for (int q = row_start_[uz(k)]; q < row_start_[uz(k + 1)]; ++q) {
        const int slot = filled[uz(row_col_[uz(q)])]++;
        col_row_[uz(slot)] = k;
        row_slot_[uz(q)] = slot;
      }
    }
    lower_.assign(row_col_.size(), Block::Zero());
    diagonal_.assign(un, Block::Zero());
    work_.assign(un, Block::Zero());
  }

  // Factorizes the matrix with these upper blocks (in analyze's order) and diagonal blocks.
  // False if it is not numerically positive definite.
  bool factorize(const std::vector<Block>& upper, const std::vector<int>& above_start,
                 const std::vector<int>& above_row, const std::vector<Block>& diagonal) {
    for (int k = 0; k < n_; ++k) {
      for (int p = above_start[uz(k)]; p < above_start[uz(k + 1)]; ++p) {
        work_[uz(above_row[uz(p)])] = upper[uz(p)];
      }
      Block d = diagonal[uz(k)];
      for (int q = row_start_[uz(k)]; q < row_start_[uz(k + 1)]; ++q) {
        const int i = row_col_[uz(q)];
        const int slot = row_slot_[uz(q)];
        // Y = L_ii^-1 (H_ik - sum of the rows above), then L_ki = Y^T.
        const Block y = diagonal_[uz(i)].triangularView<Eigen::Lower>().solve(work_[uz(i)]);
        work_[uz(i)].setZero();
        for (int t = col_start_[uz(i)]; t < slot; ++t)
          work_[uz(col_row_[uz(t)])].noalias() -= lower_[uz(t)] * y;
        lower_[uz(slot)] = y.transpose();
        d.noalias() -= y.transpose() * y;
      }
      if (!cholesky3(d, diagonal_[uz(k)])) return false;
    }
    return true;
  }

  // Solves L L^T x = b in place.
  void solve(Eigen::VectorXd& b) const {
    for (int i = 0; i < n_; ++i) {
      diagonal_[uz(i)].triangularView<Eigen::Lower>().solveInPlace(b.segment<3>(3 * i));
      const Eigen::Vector3d bi = b.segment<3>(3 * i);
      for (int t = col_start_[uz(i)]; t < col_start_[uz(i + 1)]; ++t) {
        b.segment<3>(3 * col_row_[uz(t)]).noalias() -= lower_[uz(t)] * bi;
      }
    }
    for (int i = n_ - 1; i >= 0; --i) {
      Eigen::Vector3d bi = b.segment<3>(3 * i);
      for (int t = col_start_[uz(i)]; t < col_start_[uz(i + 1)]; ++t) {
        bi.noalias() -= lower_[uz(t)].transpose() * b.segment<3>(3 * col_row_[uz(t)]);
      }
      diagonal_[uz(i)].transpose().triangularView<Eigen::Upper>().solveInPlace(bi);
      b.segment<3>(3 * i) = bi;
    }
  }

 private:
  static std::size_t uz(int i) { return static_cast<std::size_t>(i); }

  // The lower Cholesky factor of a symmetric 3x3 block (its lower triangle is read).
  static bool cholesky3(const Block& a, Block& l) {
    l.setZero();
    const double d0 = a(0, 0);
    if (!(d0 > 0.0) || !std::isfinite(d0)) return false;
    l(0, 0) = std::sqrt(d0);
    l(1, 0) = a(1, 0) / l(0, 0);
    l(2, 0) = a(2, 0) / l(0, 0);
    const double d1 = a(1, 1) - l(1, 0) * l(1, 0);
    if (!(d1 > 0.0) || !std::isfinite(d1)) return false;
    l(1, 1) = std::sqrt(d1);
    l(2, 1) = (a(2, 1) - l(2, 0) * l(1, 0)) / l(1, 1);
    const double d2 = a(2, 2) - l(2, 0) * l(2, 0) - l(2, 1) * l(2, 1);
    if (!(d2 > 0.0) || !std::isfinite(d2)) return false;
    l(2, 2) = std::sqrt(d2);
    return true;
  }

  int n_ = 0;
  std::vector<int> row_start_, row_col_, row_slot_;  // rows of L: columns, in dependency order
  std::vector<int> col_start_, col_row_;             // columns of L: rows below the diagonal
  std::vector<Block> lower_;                         // L's blocks below the diagonal, by column
  std::vector<Block> diagonal_;                      // L's diagonal blocks, lower triangular
  std::vector<Block> work_;                          // one block row, scattered
};

// The normal equations over the free nodes, 3 variables each, in 3x3 blocks, in a fill-reducing
// order of the nodes (AMD on the node graph, once): the diagonal blocks and, for each block
// column, one block for each neighbour above the diagonal in that order. The pattern is built
// and the factorization analysed once; each assembly refills the values.
class NormalEquations {
 public:
  NormalEquations(const std::vector<bool>& fixed, const std::vector<Edge>& edges) {
    // The free nodes, numbered in node order.
    std::vector<int> free_index(fixed.size(), -1);
    int free_nodes = 0;
    for (std::size_t n = 0; n < fixed.size(); ++n) {
      if (!fixed[n]) free_index[n] = free_nodes++;
    }
    nodes_ = free_nodes;
    const auto un = static_cast<std::size_t>(free_nodes);

    // Their graph, both directions, and its AMD order.
    std::vector<Eigen::Triplet<double, int>> links;
    links.reserve(2 * edges.size() + un);
    for (int f = 0; f < free_nodes; ++f) links.emplace_back(f, f, 1.0);
    for (const Edge& e : edges) {
      const int a = free_index[e.from], b = free_index[e.to];
      if (a >= 0 && b >= 0) {
        links.emplace_back(a, b, 1.0);
        links.emplace_back(b, a, 1.0);
      }
    }
    Eigen::SparseMatrix<double, Eigen::ColMajor, int> graph(free_nodes, free_nodes);
    graph.setFromTriplets(links.begin(), links.end());
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;  // new -> old
    Eigen::AMDOrdering<int>()(graph, order);
    std::vector<int> position(un);
    for (int k = 0; k < free_nodes; ++k) position[static_cast<std::size_t>(order.indices()[k])] = k;
    block_.assign(fixed.size(), -1);
    for (std::size_t n = 0; n < fixed.size(); ++n) {
      if (free_index[n] >= 0) block_[n] = position[static_cast<std::size_t>(free_index[n])];
    }

    // Each block column's neighbours above the diagonal, sorted.
    std::vector<std::vector<int>> above(un);
    for (const Edge& e : edges) {
      const int a = block_[e.from], b = block_[e.to];
      if (a >= 0 && b >= 0) {
        above[static_cast<std::size_t>(std::max(a, b))].push_back(std::min(a, b));
      }
    }
    above_start_.assign(un + 1, 0);
    for (std::size_t j = 0; j < un; ++j) {
      auto& rows = above[j];
      std::sort(rows.begin(), rows.end());
      rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
      above_start_[j + 1] = above_start_[j] + static_cast<int>(rows.size());
      above_row_.insert(above_row_.end(), rows.begin(), rows.end());
    }
    upper_.assign(above_row_.size(), Block::Zero());
    diagonal_.assign(un, Block::Zero());
    damped_.assign(un, Block::Zero());

    // Where each edge's off-diagonal block goes.
    slots_.resize(edges.size());
    for (std::size_t n = 0; n < edges.size(); ++n) {
      const int a = block_[edges[n].from], b = block_[edges[n].to];
      if (a < 0 || b < 0) continue;
      const int i = std::min(a, b), j = std::max(a, b);
      const auto& rows = above[static_cast<std::size_t>(j)];
      slots_[n].block =
          above_start_[static_cast<std::size_t>(j)] +
          static_cast<int>(std::lower_bound(rows.begin(), rows.end(), i) - rows.begin());
      slots_[n].from_above = a < b;
    }
    cholesky_.analyze(above_start_, above_row_);
  }

  int dim() const { return 3 * nodes_; }
  // The first variable of a node in the system, -1 for a fixed node.
  int variable(std::size_t node) const { return block_[node] < 0 ? -1 : 3 * block_[node]; }

  // H and g at the poses, with the IRLS weights of the robust edges there.
  void assemble(const std::vector<core::Pose2>& poses, const std::vector<Edge>& edges, double k) {
    std::fill(upper_.begin(), upper_.end(), Block::Zero());
    std::fill(diagonal_.begin(), diagonal_.end(), Block::Zero());
    g_.setZero(dim());
    for (std::size_t n = 0; n < edges.size(); ++n) {
      const Edge& e = edges[n];
      const int bi = block_[e.from], bj = block_[e.to];
      if ((bi < 0 && bj < 0) || !e.active) continue;
      // With (u, v) = R(theta_from)^T (t_to - t_from), w = (v, -u), the translation's
      // information A and the heading's b, the Jacobians are J_from = [-R^T, w; 0 0 -1] and
      // J_to = [R^T, 0; 0 0 1], so that J^T info J and J^T info r have the blocks below.
      const core::Pose2& pa = poses[e.from];
      const core::Pose2& pb = poses[e.to];
      const double c = std::cos(pa.theta), s = std::sin(pa.theta);
      Eigen::Matrix2d rotation;
      rotation << c, -s, s, c;
      const Eigen::Vector2d t = rotation.transpose() * Eigen::Vector2d(pb.x - pa.x, pb.y - pa.y);
      const Eigen::Vector2d w(t.y(), -t.x());
      const Eigen::Vector2d r = t - Eigen::Vector2d(e.measured.x, e.measured.y);
      const double r2 = core::wrap_angle(pb.theta - pa.theta - e.measured.theta);
      const Eigen::Matrix2d info = translation_information(e);
      const double ith = 1.0 / (e.sigma_theta * e.sigma_theta);
      const double weight_here = weight(r.dot(info * r) + r2 * r2 * ith, e.robust, k);
      const Eigen::Matrix2d a = weight_here * info;
      const double b = weight_here * ith;
      const Eigen::Matrix2d rar = rotation * a * rotation.transpose();  // the translations' block
      const Eigen::Vector2d raw =
          rotation * (a * w);  // J_to's translation against J_from's heading
      const Eigen::Vector2d ra_r = rotation * (a * r);
      const double br2 = b * r2;
      if (bi >= 0) {
        Block& h = diagonal_[static_cast<std::size_t>(bi)];
        h.topLeftCorner<2, 2>() += rar;
        h.block<2, 1>(0, 2) -= raw;
        h.block<1, 2>(2, 0) -= raw.transpose();
        h(2, 2) += w.dot(a * w) + b;
        g_.segment<2>(3 * bi) -= ra_r;
        g_(3 * bi + 2) += w.dot(a * r) - br2;
      }
      if (bj >= 0) {
        Block& h = diagonal_[static_cast<std::size_t>(bj)];
        h.topLeftCorner<2, 2>() += rar;
        h(2, 2) += b;
        g_.segment<2>(3 * bj) += ra_r;
        g_(3 * bj + 2) += br2;
      }
      if (bi >= 0 && bj >= 0) {
        Block h = Block::Zero();  // J_from^T info J_to
        h.topLeftCorner<2, 2>() = -rar;
        h.block<1, 2>(2, 0) = raw.transpose();
        h(2, 2) = -b;
        Block& target = upper_[static_cast<std::size_t>(slots_[n].block)];
        if (slots_[n].from_above) {
          target += h;
        } else {
          target += h.transpose();
        }
      }
    }
  }

  // Factorizes H + lambda D, D the diagonal of H (Marquardt's scaling, floored so that a
  // variable no edge reaches stays solvable). False if that is not positive definite.
  bool factorize(double lambda) {
    for (int j = 0; j < nodes_; ++j) {
      Block& d = damped_[static_cast<std::size_t>(j)];
      d = diagonal_[static_cast<std::size_t>(j)];
      for (int c = 0; c < 3; ++c) d(c, c) += lambda * scale_at(3 * j + c);
    }
    return cholesky_.factorize(upper_, above_start_, above_row_, damped_);
  }

  // The step of the last factorization: (H + lambda D) dx = -g.
  void solve(Eigen::VectorXd& step) const {
    step = -g_;
    cholesky_.solve(step);
  }

  // The diagonal of D, for the predicted reduction.
  double scale_at(int d) const {
    return std::max(diagonal_[static_cast<std::size_t>(d / 3)](d % 3, d % 3), 1e-12);
  }

  const Eigen::VectorXd& gradient() const { return g_; }

 private:
  struct Slots {
    int block = -1;           // the edge's block in upper_
    bool from_above = false;  // the edge's `from` node comes first: the block is H_from,to
  };

  int nodes_ = 0;
  std::vector<int> block_;        // node -> its block in the order, -1 if fixed
  std::vector<int> above_start_;  // block column -> its first block in upper_
  std::vector<int> above_row_;    // block row of each block in upper_
  std::vector<Block> upper_;      // H's blocks above the diagonal
  std::vector<Block> diagonal_;   // H's diagonal blocks
  std::vector<Block> damped_;     // with the damping
  std::vector<Slots> slots_;
  Eigen::VectorXd g_;
  BlockCholesky cholesky_;
};

// An edge's information along its weak axis (Edge::weak_axis, Edge::weak_weight), as add_edge and
// set_measurement take it.
void check_weak_information(double weak_axis, double weak_weight) {
  if (!std::isfinite(weak_axis)) {
    throw std::invalid_argument("pose graph edge: weak_axis must be finite");
  }
  if (!(weak_weight >= 0.0 && weak_weight <= 1.0)) {
    throw std::invalid_argument("pose graph edge: weak_weight must be in [0, 1]");
  }
}

}  // namespace

std::size_t PoseGraph::add_node(const core::Pose2& initial) {
  if (!is_finite(initial)) throw std::invalid_argument("pose graph node: pose must be finite");
  poses_.push_back(initial);
  fixed_.push_back(poses_.size() == 1);
  return poses_.size() - 1;
}

void PoseGraph::add_edge(const Edge& edge) {
  const std::size_t n = poses_.size();
  if (edge.from >= n || edge.to >= n) {
    throw std::invalid_argument("pose graph edge " + std::to_string(edge.from) + " -> " +
                                std::to_string(edge.to) + ": no such node (" + std::to_string(n) +
                                " nodes)");
  }
  if (edge.from == edge.to) {
    throw std::invalid_argument("pose graph edge " + std::to_string(edge.from) + " -> " +
                                std::to_string(edge.to) + ": from and to are the same node");
  }
  if (!is_positive(edge.sigma_xy)) {
    throw std::invalid_argument("pose graph edge: sigma_xy must be finite and > 0");
  }
  if (!is_positive(edge.sigma_theta)) {
    throw std::invalid_argument("pose graph edge: sigma_theta must be finite and > 0");
  }
  check_weak_information(edge.weak_axis, edge.weak_weight);
  if (!is_finite(edge.measured)) {
    throw std::invalid_argument("pose graph edge: measured must be finite");
  }
  edges_.push_back(edge);
}

void PoseGraph::set_active(std::size_t edge, bool active) {
  if (edge >= edges_.size()) throw std::out_of_range("pose graph: no edge " + std::to_string(edge));
  edges_[edge].active = active;
}

void PoseGraph::set_measurement(std::size_t edge, const core::Pose2& measured) {
  if (edge >= edges_.size()) throw std::out_of_range("pose graph: no edge " + std::to_string(edge));
  if (!is_finite(measured))
    throw std::invalid_argument("pose graph: edge " + std::to_string(edge) +
                                " measured as a pose that is not finite");
  edges_[edge].measured = measured;
}

void PoseGraph::set_measurement(std::size_t edge, const core::Pose2& measured, double weak_axis,
                                double weak_weight) {
  if (edge >= edges_.size()) throw std::out_of_range("pose graph: no edge " + std::to_string(edge));
  check_weak_information(weak_axis, weak_weight);
  set_measurement(edge, measured);
  edges_[edge].weak_axis = weak_axis;
  edges_[edge].weak_weight = weak_weight;
}

double PoseGraph::whitened_error(std::size_t edge) const {
  if (edge >= edges_.size()) throw std::out_of_range("pose graph: no edge " + std::to_string(edge));
  const Edge& e = edges_[edge];
  return std::sqrt(squared_norm(residual(poses_[e.from], poses_[e.to], e.measured), e));
}

void PoseGraph::set_fixed(std::size_t node, bool fixed) {
  if (node >= poses_.size()) throw std::out_of_range("pose graph: no node " + std::to_string(node));
  fixed_[node] = fixed;
}

bool PoseGraph::is_fixed(std::size_t node) const {
  if (node >= poses_.size()) throw std::out_of_range("pose graph: no node " + std::to_string(node));
  return fixed_[node];
}

void PoseGraph::set_pose(std::size_t node, const core::Pose2& pose) {
  if (node >= poses_.size()) throw std::out_of_range("pose graph: no node " + std::to_string(node));
  if (!is_finite(pose)) throw std::invalid_argument("pose graph node: pose must be finite");
  poses_[node] = pose;
}

OptimizeSummary PoseGraph::optimize(const OptimizeOptions& options) {
  if (options.max_iterations < 0) {
    throw std::invalid_argument("optimize: max_iterations must be >= 0");
  }
  if (!is_positive(options.huber_scale)) {
    throw std::invalid_argument("optimize: huber_scale must be finite and > 0");
  }
  if (!(options.tolerance >= 0.0)) {
    throw std::invalid_argument("optimize: tolerance must be >= 0");
  }
  const double k = options.huber_scale;
  OptimizeSummary summary;
  double cost = total_cost(poses_, edges_, k);
  summary.initial_cost = cost;

  const bool has_free_node = std::find(fixed_.begin(), fixed_.end(), false) != fixed_.end();
  if (has_free_node && cost > 0.0 && options.max_iterations > 0) {
    NormalEquations normal(fixed_, edges_);
    double lambda = 1e-4;  // relative to H's diagonal
    double nu = 2.0;
    bool linearized = false;
    std::vector<core::Pose2> candidate;
    Eigen::VectorXd step;
    while (summary.iterations < options.max_iterations) {
      if (!linearized) {
        normal.assemble(poses_, edges_, k);
        linearized = true;
      }
      const bool factorized = normal.factorize(lambda);
      ++summary.iterations;
      bool accepted = false;
      bool done = false;  // the model has nothing left to gain
      double new_cost = cost;
      if (factorized) {
        const Eigen::VectorXd& g = normal.gradient();
        normal.solve(step);
        // The linear model's reduction: 0.5 dx . (lambda D dx - g).
        double predicted = 0.0;
        double largest_step = 0.0, largest_value = 0.0;
        for (int d = 0; d < normal.dim(); ++d) {
          predicted += step[d] * (lambda * normal.scale_at(d) * step[d] - g[d]);
          largest_step = std::max(largest_step, std::abs(step[d]));
        }
        predicted *= 0.5;
        candidate = poses_;
        for (std::size_t n = 0; n < candidate.size(); ++n) {
          const int c = normal.variable(n);
          if (c < 0) continue;
          core::Pose2& p = candidate[n];
          largest_value = std::max({largest_value, std::abs(p.x), std::abs(p.y)});
          p.x += step[c];
          p.y += step[c + 1];
          p.theta = core::wrap_angle(p.theta + step[c + 2]);
        }
        if (std::isfinite(predicted)) {
          done = predicted <= options.tolerance * cost ||
                 largest_step <= 1e-12 * (1.0 + largest_value);
          new_cost = total_cost(candidate, edges_, k);
          // A step the model calls final is taken if it costs nothing, as round-off may
          // leave its true reduction at zero.
          if (new_cost < cost || (done && new_cost <= cost)) {
            accepted = true;
            if (predicted > 0.0) {
              const double t = 2.0 * (cost - new_cost) / predicted - 1.0;
              lambda = std::max(lambda * std::max(1.0 / 3.0, 1.0 - t * t * t), 1e-15);
            }
            nu = 2.0;
          }
        }
      }
      if (accepted) {
        const double decrease = (cost - new_cost) / cost;
        poses_.swap(candidate);
        cost = new_cost;
        linearized = false;
        if (done || decrease < options.tolerance || cost == 0.0) break;
      } else {
        if (done) break;
        lambda *= nu;
        nu *= 2.0;
        if (!(lambda < 1e16)) break;
      }
    }
  }
  summary.final_cost = cost;
  summary.downweighted_edges = count_downweighted(poses_, edges_, k);
  return summary;
}

}  // namespace intgrid::optimization
