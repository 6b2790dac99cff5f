// The back end of a submap SLAM: a 2D pose graph (nodes are poses, edges relative-pose
// measurements) solved by sparse Levenberg-Marquardt, with an optional Huber loss on the loop
// closures (docs/algorithms.md, "Pose graph back end"). Floating point, off the per-scan path.
#pragma once

#include <cstddef>
#include <vector>

#include "intgrid/core/types.hpp"

namespace intgrid::optimization {

// A measurement of node `to`'s pose in node `from`'s frame. Its residual is
//   r_t = R(theta_from)^T (t_to - t_from) - t_meas,  r_theta = wrap(theta_to - theta_from -
//   theta_meas),
// and its squared whitened norm r_t^T A r_t + r_theta^2 / sigma_theta^2, where the translation's
// information A = (I - (1 - weak_weight) d d^T) / sigma_xy^2, d = (cos weak_axis, sin weak_axis):
// sigma_xy in every direction for weak_weight 1 (the default), less information along d for a
// measurement that fixes that direction less well (a match in a corridor: nothing along it for
// weak_weight 0). Every 2x2 information matrix is of this form, scaled by its largest eigenvalue.
struct Edge {
  std::size_t from = 0;
  std::size_t to = 0;
  core::Pose2 measured;      // pose of `to` in `from`'s frame
  double sigma_xy = 0.0;     // standard deviation of the position across weak_axis (m), > 0
  double sigma_theta = 0.0;  // standard deviation of the heading (rad), > 0
  bool robust = false;       // Huber loss (loop closures)
  bool active = true;        // an inactive edge adds nothing: a loop closure switched off
  double weak_axis = 0.0;    // the direction d of less information, in `from`'s frame (rad)
  double weak_weight = 1.0;  // the information along d, a fraction of 1 / sigma_xy^2, in [0, 1]
};

struct OptimizeOptions {
  int max_iterations = 20;   // factorizations, for steps taken or refused; >= 0
  double huber_scale = 1.0;  // where the Huber loss turns linear, in sigmas of the edge; > 0
  double tolerance = 1e-9;   // stop when an accepted step lowers the cost by less, relatively
};

struct OptimizeSummary {
  int iterations = 0;         // factorizations done
  double initial_cost = 0.0;  // 0.5 sum rho(|r|^2), rho(s) = s or 2 k sqrt(s) - k^2 (Huber)
  double final_cost = 0.0;
  std::size_t downweighted_edges = 0;  // active robust edges past huber_scale at the final poses
};

class PoseGraph {
 public:
  // Adds a node with its initial guess and returns its index; the first node is fixed.
  // Throws std::invalid_argument for a pose that is not finite.
  std::size_t add_node(const core::Pose2& initial);
  // Throws std::invalid_argument for an index that is no node, from == to, a sigma that is not
  // finite and > 0, a weak_axis that is not finite, a weak_weight outside [0, 1] or a
  // measurement that is not finite.
  void add_edge(const Edge& edge);
  // A fixed node keeps its pose. Throws std::out_of_range for an index that is no node.
  void set_fixed(std::size_t node, bool fixed = true);
  bool is_fixed(std::size_t node) const;

  const std::vector<core::Pose2>& poses() const { return poses_; }
  // Throws std::out_of_range for an index that is no node, std::invalid_argument for a pose
  // that is not finite.
  void set_pose(std::size_t node, const core::Pose2& pose);
  std::size_t nodes() const { return poses_.size(); }
  std::size_t edges() const { return edges_.size(); }
  const std::vector<Edge>& edge_list() const { return edges_; }
  // Switches an edge on or off (Edge::active). Throws std::out_of_range for an index that is no
  // edge.
  void set_active(std::size_t edge, bool active);
  // Replaces an edge's measurement (a constraint measured again). Throws std::out_of_range for an
  // index that is no edge, std::invalid_argument for a measurement that is not finite.
  void set_measurement(std::size_t edge, const core::Pose2& measured);
  // The same, with the measurement's information along the position's weak axis (Edge::weak_axis,
  // Edge::weak_weight) measured again too. Also throws std::invalid_argument for a weak_axis that
  // is not finite or a weak_weight outside [0, 1].
  void set_measurement(std::size_t edge, const core::Pose2& measured, double weak_axis,
                       double weak_weight);
  // How far the current poses are from an edge's measurement, in its sigmas: the norm of its
  // whitened residual (active or not). Throws std::out_of_range for an index that is no edge.
  double whitened_error(std::size_t edge) const;

  // Moves the free nodes to a minimum of the cost (sparse Levenberg-Marquardt on the normal
  // equations, Huber by iteratively reweighted least squares). The headings of the nodes it
  // moves are wrapped to (-pi, pi]. Deterministic: the same graph and options give the same poses,
  // bit for bit. Throws std::invalid_argument for max_iterations < 0, huber_scale not > 0 or
  // tolerance < 0.
  OptimizeSummary optimize(const OptimizeOptions& options = {});

 private:
  std::vector<core::Pose2> poses_;
  std::vector<bool> fixed_;
  std::vector<Edge> edges_;
};

}  // namespace intgrid::optimization
