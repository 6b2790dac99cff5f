// SubmapSlam's back end: the set-up of the per-scan path, the pose graph of submaps and nodes, loop
// closure and the final map. Floating point here only converts poses between the per-scan path's
// integers and the graph's doubles, and runs the graph's optimizer.
#include "intgrid/slam/submap_slam.hpp"

#include <algorithm>
#include <cmath>
#include <list>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include "intgrid/core/failure.hpp"
#include "intgrid/core/parallel.hpp"
#include "intgrid/core/ray_insertion.hpp"
#include "intgrid/core/resolution.hpp"
#include "intgrid/core/units.hpp"
#include "intgrid/optimization/pose_graph.hpp"
#include "intgrid/slam/grid_slam.hpp"
#include "submap_setup.hpp"
#include "submap_tracking.hpp"

namespace intgrid::slam {
namespace {

using core::angle_units;
using core::millimetres;
using core::radians;
using core::require_field;

core::Pose2 inverse(const core::Pose2& p) {
  return core::relative(p, {});
}

// What a match fixes of a node's position: the least sharp direction of the evidence's curvature
// at the pose found (an edge's weak_axis, optimization::Edge), in the frame of a submap whose
// anchor has heading anchor_theta, and its curvature as a fraction of the sharpest direction's.
// None when the evidence peaks in no direction.
struct MatchInformation {
  double weak_axis = 0.0;
  double curvature_ratio = 1.0;
};

template <class Cell>
std::optional<MatchInformation> match_information(const EvidenceCurvature<Cell>& k,
                                                  double anchor_theta) {
  const double xx = static_cast<double>(k.xx), xy = static_cast<double>(k.xy),
               yy = static_cast<double>(k.yy);
  const double spread = std::hypot(0.5 * (xx - yy), xy);
  const double sharpest = 0.5 * (xx + yy) + spread, least = 0.5 * (xx + yy) - spread;
  if (!(sharpest > 0.0)) return std::nullopt;
  // The least sharp direction is square to the sharpest, in the submap's grid frame.
  return MatchInformation{
      0.5 * std::atan2(2.0 * xy, xx - yy) + 0.5 * std::numbers::pi - anchor_theta,
      std::clamp(least / sharpest, 0.0, 1.0)};
}

}  // namespace

void check_submap_slam_config(const SubmapSlamConfig& c) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  const auto non_negative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  require_field(positive(c.cell) && c.cell >= 0.005 && c.cell <= 1.0, "cell",
                "must be in [0.005, 1] metres");
  require_field(std::abs(c.cell * 1000.0 - std::round(c.cell * 1000.0)) < 1e-6, "cell",
                "must be a whole number of millimetres");
  require_field(c.threads >= 0 && c.threads <= 256, "threads", "must be 0..256 (0: every core)");
  require_field(c.headings >= 64 && c.headings <= 16384 && (c.headings & (c.headings - 1)) == 0,
                "headings", "must be a power of two from 64 to 16384");
  core::check_range_sensor(c.sensor, "sensor");
  // The submaps' S_eps codec needs the ISM's Pmax in (1/2, 1) and eps in (0, 1/2).
  try {
    (void)make_codec(c);
  } catch (const std::invalid_argument& e) {
    core::fail<std::invalid_argument>("cell " + core::number_text(c.cell) +
                                      " m with sensor.sigma " + core::number_text(c.sensor.sigma) +
                                      " m gives no S_eps codec: " + e.what());
  }
  require_field(c.sensor.max_range <= 200.0 && c.sensor.max_range >= 2.0 * c.cell,
                "sensor.max_range", "must be in [2 cells, 200] metres");
  require_field(c.map.seps_bits >= 2 && c.map.seps_bits <= 8, "map.seps_bits",
                "must be 2..8 (the map is 8-bit)");
  require_field(c.map.seps_levels >= 1 && c.map.seps_levels < (1 << (c.map.seps_bits - 1)),
                "map.seps_levels", "must be >= 1 and below the largest index");
  require_field(c.map.empty_divisor >= 1 && c.map.empty_divisor <= 127, "map.empty_divisor",
                "must be 1..127");
  require_field(c.submaps.scans >= 1 && c.submaps.scans <= 100000, "submaps.scans",
                "must be 1..100000");
  require_field(c.submaps.handover_scans >= 0 && c.submaps.handover_scans <= c.submaps.scans,
                "submaps.handover_scans", "must be from 0 to submaps.scans");
  require_field(non_negative(c.filter.distance) && c.filter.distance <= 100.0, "filter.distance",
                "must be in [0, 100] metres");
  require_field(non_negative(c.filter.degrees) && c.filter.degrees <= 180.0, "filter.degrees",
                "must be in [0, 180]");
  require_field(non_negative(c.filter.seconds) && c.filter.seconds <= 1e6, "filter.seconds",
                "must be in [0, 1e6]");
  const auto window = [&](double m, double degrees, const char* m_name, const char* degrees_name) {
    require_field(non_negative(m) && m <= 20.0, m_name, "must be in [0, 20] metres");
    require_field(non_negative(degrees) && degrees <= 180.0, degrees_name, "must be in [0, 180]");
  };
  window(c.tracking.window, c.tracking.window_degrees, "tracking.window",
         "tracking.window_degrees");
  window(c.tracking.wide_window, c.tracking.wide_degrees, "tracking.wide_window",
         "tracking.wide_degrees");
  window(c.loops.window, c.loops.window_degrees, "loops.window", "loops.window_degrees");
  // Every pose of these windows is scored.
  require_field(c.tracking.window <= 2.0, "tracking.window", "must be at most 2 metres");
  require_field(c.tracking.wide_window <= 3.0, "tracking.wide_window", "must be at most 3 metres");
  require_field(non_negative(c.tracking.wide_below) && c.tracking.wide_below <= 1.0,
                "tracking.wide_below", "must be in [0, 1]");
  require_field(non_negative(c.tracking.prior_xy) && c.tracking.prior_xy <= 1000.0,
                "tracking.prior_xy", "must be in [0, 1000] metres (0: no prior)");
  require_field(non_negative(c.tracking.prior_degrees) && c.tracking.prior_degrees <= 1e4,
                "tracking.prior_degrees", "must be in [0, 1e4] (0: no prior)");
  require_field(non_negative(c.tracking.prior_xy_per_m) && c.tracking.prior_xy_per_m <= 100.0,
                "tracking.prior_xy_per_m", "must be in [0, 100]");
  require_field(non_negative(c.tracking.prior_degrees_per_degree) &&
                    c.tracking.prior_degrees_per_degree <= 100.0,
                "tracking.prior_degrees_per_degree", "must be in [0, 100]");
  require_field(c.tracking.min_hits >= 1 && c.tracking.min_hits <= 100000, "tracking.min_hits",
                "must be 1..100000");
  require_field(c.loops.every >= 1, "loops.every", "must be >= 1");
  require_field(c.loops.submaps >= 1, "loops.submaps", "must be >= 1");
  require_field(non_negative(c.loops.max_distance) && c.loops.max_distance <= 1000.0,
                "loops.max_distance", "must be in [0, 1000] metres");
  require_field(positive(c.loops.min_score) && c.loops.min_score <= 1.0, "loops.min_score",
                "must be in (0, 1]");
  require_field(non_negative(c.loops.drift) && c.loops.drift <= 1.0, "loops.drift",
                "must be in [0, 1]");
  require_field(positive(c.loops.switch_off), "loops.switch_off", "must be finite and > 0");
  for (const auto& [v, name] : {std::pair{c.loops.sigma_xy, "loops.sigma_xy"},
                                {c.loops.sigma_degrees, "loops.sigma_degrees"},
                                {c.graph.local_sigma_xy, "graph.local_sigma_xy"},
                                {c.graph.local_sigma_degrees, "graph.local_sigma_degrees"},
                                {c.graph.odometry_sigma_xy, "graph.odometry_sigma_xy"},
                                {c.graph.odometry_sigma_degrees, "graph.odometry_sigma_degrees"},
                                {c.graph.huber, "graph.huber"}})
    require_field(positive(v) && v <= 1000.0, name, "must be in (0, 1000]");
  require_field(c.graph.optimize_every >= 1, "graph.optimize_every", "must be >= 1");
  require_field(c.graph.iterations >= 1 && c.graph.iterations <= 1000, "graph.iterations",
                "must be 1..1000");
}

struct SubmapSlam::Engine {
  virtual ~Engine() = default;
  virtual void insert(const QuantizedScan& scan, std::shared_ptr<const SlamSensor> sensor,
                      double t) = 0;
  virtual void finish() = 0;
  virtual std::vector<core::Pose2> scan_poses() const = 0;  // SLAM frame
  virtual core::Grid<std::int8_t> map() const = 0;
  SubmapSlamConfig config;
  core::SepsCodec codec{8, 0.1};
  SubmapSlamStats stats;
};

template <class Cell>
struct SubmapSlam::EngineOf final : SubmapSlam::Engine {
  struct Node {
    SlamPose local;
    std::size_t vertex = 0;
    std::vector<std::int32_t> range_mm;
    std::shared_ptr<const SlamSensor> sensor;  // the geometry its scan stated
    double travel = 0.0;                       // m the front end moved from the first node to it
    double turn = 0.0;                         // rad it turned, in all
  };
  struct SubmapRecord {
    std::size_t vertex = 0;
    SlamPose anchor;
    std::vector<std::size_t> nodes;
    std::vector<std::size_t> local_edges;  // each node's edge to it, in the graph
    std::optional<LocalGrid<Cell>> grid;   // once finished
    // What its own nodes score in it, each at its pose, as a fraction of every hit on the
    // strongest cell: the median over those with at least min_hits hits (0: none had).
    double own_score = 0.0;
    // The trajectory's latest tie to it: its latest own node, or the node of the latest closure
    // to it, and where that node lies in its frame (the local frame): the front end's pose, or
    // the closure's.
    std::size_t tied_node = 0;
    SlamPose tied_pose{};
  };
  struct ScanRecord {
    std::size_t node;  // the last node at or before it (npos: none yet)
    SlamPose local;
  };

  EngineOf(const SubmapSlamConfig& c, const core::SepsCodec& codec_, TrackerSetup setup)
      : tracker(std::move(setup), make_table<Cell>(c, codec_)) {
    config = c;
    threads = core::threads_or_every_core(c.threads);
    codec = codec_;
    const TrackerSetup& s = tracker.setup();
    loop_window = search_window(c.loops.window, c.loops.window_degrees, 0.0, 0.0, s.cell_mm,
                                s.narrow.step_units);
  }

  LocalTracker<Cell> tracker;
  optimization::PoseGraph graph;
  std::vector<Node> nodes;
  std::vector<SubmapRecord> submaps;
  std::vector<ScanRecord> scans;
  SearchWindow loop_window;
  std::size_t pending_closures = 0, nodes_since_optimization = 0;
  // Most recently used first; shared with the searches of one node, which may outlive their
  // place in the cache.
  std::list<std::pair<std::size_t, std::shared_ptr<const MaxPyramid<Cell>>>> pyramids;
  int threads = 1;  // config.threads, 0 resolved

  // The local frame in the graph's: where the last node's local pose lands.
  core::Pose2 correction() const {
    if (nodes.empty()) return {};
    const Node& last = nodes.back();
    return core::compose(graph.poses()[last.vertex], inverse(to_pose2(last.local)));
  }

  std::shared_ptr<const MaxPyramid<Cell>> pyramid_of(std::size_t id) {
    for (auto it = pyramids.begin(); it != pyramids.end(); ++it)
      if (it->first == id) {
        pyramids.splice(pyramids.begin(), pyramids, it);
        return pyramids.front().second;
      }
    pyramids.emplace_front(id, std::make_shared<const MaxPyramid<Cell>>(
                                   *submaps[id].grid, pyramid_levels(loop_window.cells)));
    // Double cells take eight times the bytes of S_eps ones.
    std::size_t bytes = 0;
    for (const auto& p : pyramids) bytes += p.second->bytes();
    while (pyramids.size() > 1 &&
           (pyramids.size() > kPyramidCacheSubmaps || bytes > kPyramidCacheBytes)) {
      bytes -= pyramids.back().second->bytes();
      pyramids.pop_back();
    }
    stats.peak_pyramid_bytes = std::max(stats.peak_pyramid_bytes, bytes);
    return pyramids.front().second;
  }

  void insert(const QuantizedScan& scan, std::shared_ptr<const SlamSensor> sensor,
              double t) override {
    ++stats.scans;
    TrackStep step = tracker.localize(scan, *sensor);
    tracker.map(step, scan, *sensor, core::milliseconds(t));
    stats.wide_searches += step.wide;
    stats.handovers += step.handed_over;
    stats.unmatched_scans += !step.matched;
    for (Submap<Cell>& done : tracker.take_finished()) finish_submap(std::move(done));
    if (step.node) add_node(step, scan, std::move(sensor));
    scans.push_back({nodes.empty() ? static_cast<std::size_t>(-1) : nodes.size() - 1, step.pose});
  }

  // A correct closure scores about what the submap's own scans score in it: that depends on how
  // many beams a scan has and how often each cell was seen (half the beams, half the score, on
  // the Telecom log), which an absolute threshold would have to be tuned to.
  void finish_submap(Submap<Cell>&& done) {
    SubmapRecord& s = submaps[done.id];
    s.grid = std::move(done.grid);
    const TrackerSetup& setup = tracker.setup();
    std::vector<ScanPoints> points(s.nodes.size());
    std::vector<std::optional<double>> own(s.nodes.size());  // none: too few hits
    core::run_parts(s.nodes.size(), threads, [&](std::size_t j) {
      const Node& n = nodes[s.nodes[j]];
      points[j] = scan_points(tracker.rays(), *n.sensor, n.range_mm, setup.max_range_mm);
      if (static_cast<int>(points[j].size()) < setup.min_hits) return;
      const Match<Cell> at_pose =
          match_exhaustive(*s.grid, tracker.rays(), points[j], n.local, SearchWindow{},
                           setup.max_index, MatchScore<Cell>{});
      own[j] = static_cast<double>(at_pose.evidence) /
               (static_cast<double>(points[j].size()) * setup.max_index);
    });
    std::vector<double> scores;
    for (const std::optional<double>& v : own)
      if (v) scores.push_back(*v);
    if (scores.empty()) return;
    const auto middle = scores.begin() + static_cast<std::ptrdiff_t>(scores.size() / 2);
    std::nth_element(scores.begin(), middle, scores.end());
    s.own_score = *middle;
    if (config.submaps.rematch) rematch_young_nodes(s, points);
  }

  // The front end matches a scan against the older active submap only. A submap's first nodes,
  // up to submaps.scans of them, were therefore placed in it through another submap, or against
  // the few scans it held then (the first submap, or one that took over early as the target,
  // submaps.handover_scans): matched again against it once it is complete,
  // as the front end would (its narrow window, the prior weighed by what the submap's own nodes
  // score in it), each of their edges to it takes the pose found.
  void rematch_young_nodes(const SubmapRecord& s, const std::vector<ScanPoints>& points) {
    const TrackerSetup& setup = tracker.setup();
    SearchWindow window = setup.narrow;
    window.prior_weight_permille =
        std::clamp<std::int64_t>(std::llround(s.own_score * 1000.0), 1, 1000);
    const std::size_t young =
        std::min(s.nodes.size(), static_cast<std::size_t>(config.submaps.scans));
    struct Found {
      SlamPose pose;
      EvidenceCurvature<Cell> curvature;
    };
    std::vector<std::optional<Found>> found(young);
    core::run_parts(young, threads, [&](std::size_t j) {
      if (static_cast<int>(points[j].size()) < setup.min_hits) return;
      const SlamPose& local = nodes[s.nodes[j]].local;
      const Match<Cell> lattice = match_exhaustive(*s.grid, tracker.rays(), points[j], local,
                                                   window, setup.max_index, MatchScore<Cell>{});
      const SlamPose pose =
          refine_match(*s.grid, tracker.rays(), points[j], local, window, setup.max_index, lattice)
              .pose;
      found[j] = Found{pose, evidence_curvature(*s.grid, tracker.rays(), points[j], pose)};
    });
    const core::Pose2 anchor = to_pose2(s.anchor);
    for (std::size_t j = 0; j < young; ++j) {
      if (!found[j]) continue;
      const core::Pose2 measured = core::relative(anchor, to_pose2(found[j]->pose));
      if (const std::optional<MatchInformation> information =
              match_information(found[j]->curvature, anchor.theta))
        graph.set_measurement(s.local_edges[j], measured, information->weak_axis,
                              information->curvature_ratio);
      else
        graph.set_measurement(s.local_edges[j], measured);
    }
  }

  void add_node(const TrackStep& step, const QuantizedScan& scan,
                std::shared_ptr<const SlamSensor> sensor) {
    const core::Pose2 corr = correction();
    const core::Pose2 local = to_pose2(step.pose);
    const auto& g = config.graph;
    for (const std::size_t id : step.submaps)
      if (id == submaps.size()) {
        SlamPose anchor{step.pose.x_mm, step.pose.y_mm, 0};
        submaps.push_back(
            {graph.add_node(core::compose(corr, to_pose2(anchor))), anchor, {}, {}, {}});
        ++stats.submaps;
      }
    Node node{step.pose, graph.add_node(core::compose(corr, local)), scan.range_mm,
              std::move(sensor), 0.0};
    if (!nodes.empty()) {
      const double dx = static_cast<double>(step.pose.x_mm - nodes.back().local.x_mm) * 1e-3,
                   dy = static_cast<double>(step.pose.y_mm - nodes.back().local.y_mm) * 1e-3;
      node.travel = nodes.back().travel + std::hypot(dx, dy);
      node.turn = nodes.back().turn +
                  std::abs(static_cast<double>(step.pose.theta - nodes.back().local.theta)) *
                      core::kRadiansPerAngleUnit;
    }
    for (const std::size_t id : step.submaps) {
      SubmapRecord& s = submaps[id];
      s.local_edges.push_back(graph.edges());
      optimization::Edge edge{s.vertex,
                              node.vertex,
                              core::relative(to_pose2(s.anchor), local),
                              g.local_sigma_xy,
                              radians(g.local_sigma_degrees),
                              false};
      // The node's place in its submaps is what the front end's match fixed: in a corridor with
      // plain walls, nothing along it (the odometry put it there), and an edge at full weight
      // in every direction would hold the corridor's length against every closure that
      // corrects it (a blind corridor's 6.7 m, SubmapSlamLongLoop).
      if (const std::optional<MatchInformation> information =
              match_information(tracker.node_curvature(), to_pose2(s.anchor).theta)) {
        edge.weak_axis = information->weak_axis;
        edge.weak_weight = information->curvature_ratio;
      }
      graph.add_edge(edge);
      s.nodes.push_back(nodes.size());
      s.tied_node = nodes.size();
      s.tied_pose = step.pose;
    }
    if (!nodes.empty())
      graph.add_edge({nodes.back().vertex, node.vertex,
                      core::relative(to_pose2(nodes.back().local), local), g.odometry_sigma_xy,
                      radians(g.odometry_sigma_degrees), false});
    nodes.push_back(std::move(node));
    ++stats.nodes;
    if (nodes.size() % static_cast<std::size_t>(config.loops.every) == 0) search_loops(step);
    ++nodes_since_optimization;
    if (pending_closures > 0 &&
        nodes_since_optimization >= static_cast<std::size_t>(g.optimize_every))
      optimize(g.iterations);
  }

  void search_loops(const TrackStep& step) {
    const Node& node = nodes.back();
    const core::Pose2 global = graph.poses()[node.vertex];
    const ScanPoints& points = tracker.points();
    const std::int64_t full = static_cast<std::int64_t>(points.size()) * tracker.setup().max_index;
    const double reach2 = config.loops.max_distance * config.loops.max_distance;
    // The nearest finished submaps (by their middle node), nearest first.
    std::vector<std::pair<double, std::size_t>> near;
    for (std::size_t id = 0; id < submaps.size(); ++id) {
      const SubmapRecord& s = submaps[id];
      if (!s.grid || s.own_score <= 0.0 ||
          std::find(step.submaps.begin(), step.submaps.end(), id) != step.submaps.end())
        continue;
      const core::Pose2 middle = graph.poses()[nodes[s.nodes[s.nodes.size() / 2]].vertex];
      const double dx = middle.x - global.x, dy = middle.y - global.y;
      if (dx * dx + dy * dy <= reach2) near.emplace_back(dx * dx + dy * dy, id);
    }
    std::sort(near.begin(), near.end());
    near.resize(std::min(near.size(), static_cast<std::size_t>(config.loops.submaps)));
    // Each submap's search is set up here, run on the threads (they read the node's scan and
    // their submap only), and its closure judged below in the submaps' order: the graph is the
    // same for any thread count.
    struct Search {
      std::size_t id = 0;
      core::Pose2 guess_pose, from_tie;
      double reach = 0.0;
      SearchWindow window;
      MatchScore<Cell> min_score{};
      std::shared_ptr<const MaxPyramid<Cell>> pyramid;
      Match<Cell> lattice, refined;
      EvidenceCurvature<Cell> curvature;
    };
    std::vector<Search> searches;
    for (const auto& [distance2, id] : near) {
      const SubmapRecord& s = submaps[id];
      const core::Pose2 submap_pose = graph.poses()[s.vertex];
      const core::Pose2 guess_pose =
          core::compose(to_pose2(s.anchor), core::relative(submap_pose, global));
      // A correct closure puts the node within what the front end can have drifted since the
      // trajectory was last tied to this submap (its own nodes or the latest closure to it); a
      // scan of a look-alike corridor matches a submap of its twin well, but metres away. Two
      // places may stand for where the node is: the graph's estimate, and the tie carried along
      // the graph's chain from the tied node to this one. Either suffices: a closure accepted
      // since the last optimization has not moved the estimate yet, and the next ones to the
      // same place agree with it, not with the estimate; a wrong closure that slipped through
      // must not turn the true ones after it away, and those agree with the estimate.
      const Node& tied = nodes[s.tied_node];
      const core::Pose2 chain = core::relative(graph.poses()[tied.vertex], global);
      const core::Pose2 from_tie = core::compose(to_pose2(s.tied_pose), chain);
      // A heading error along the chain moves the node by its distance from the tie.
      const double lever = std::hypot(chain.x, chain.y);
      const double reach =
          config.tracking.window +
          config.loops.drift * (node.travel - tied.travel + lever * (node.turn - tied.turn));
      // The search covers both places' reach and no more (at most loops.window): the window
      // follows the uncertainty grown since the tie, small just after one, wide after a long
      // way round.
      SearchWindow window = loop_window;
      const double span = reach + std::hypot(from_tie.x - guess_pose.x, from_tie.y - guess_pose.y);
      window.cells = std::min(window.cells,
                              static_cast<int>(std::ceil(span * 1000.0 / tracker.setup().cell_mm)));
      const auto min_score = static_cast<MatchScore<Cell>>(
          std::llround(static_cast<double>(full) * config.loops.min_score * s.own_score));
      Search search;
      search.id = id;
      search.guess_pose = guess_pose;
      search.from_tie = from_tie;
      search.reach = reach;
      search.window = window;
      search.min_score = min_score;
      search.pyramid = pyramid_of(id);
      searches.push_back(std::move(search));
    }
    const int max_index = tracker.setup().max_index;
    core::run_parts(searches.size(), threads, [&](std::size_t i) {
      Search& c = searches[i];
      const LocalGrid<Cell>& grid = *submaps[c.id].grid;
      const SlamPose guess = to_slam_pose(c.guess_pose);
      c.lattice = match_branch_and_bound(*c.pyramid, tracker.rays(), points, guess, c.window,
                                         max_index, c.min_score);
      if (!c.lattice.found) return;
      c.refined = refine_match(grid, tracker.rays(), points, guess, c.window, max_index, c.lattice);
      c.curvature = evidence_curvature(grid, tracker.rays(), points, c.refined.pose);
    });
    for (const Search& c : searches) {
      SubmapRecord& s = submaps[c.id];
      ++stats.loop_searches;
      if (!c.lattice.found) continue;
      const core::Pose2 found = to_pose2(c.refined.pose);
      const double jump = std::min(std::hypot(found.x - c.from_tie.x, found.y - c.from_tie.y),
                                   std::hypot(found.x - c.guess_pose.x, found.y - c.guess_pose.y));
      if (jump > c.reach) {
        ++stats.rejected_closures;
        continue;
      }
      // What the match fixes of the node's position, direction by direction (a match in a
      // corridor fixes nothing along it, and a full-weight closure would pin the node wherever
      // noise put it); one that peaks in no direction is no closure.
      const std::optional<MatchInformation> information =
          match_information(c.curvature, to_pose2(s.anchor).theta);
      if (!information) {
        ++stats.rejected_closures;
        continue;
      }
      s.tied_node = nodes.size() - 1;
      s.tied_pose = c.refined.pose;
      optimization::Edge closure{s.vertex,
                                 node.vertex,
                                 core::relative(to_pose2(s.anchor), to_pose2(c.refined.pose)),
                                 config.loops.sigma_xy,
                                 radians(config.loops.sigma_degrees),
                                 true};
      // Along its least sharp direction a closure's position is the best of its whole window,
      // found with no prior: where the evidence is nearly flat, noise picks it, so it counts
      // there with the square of the curvature ratio, where a node's edges to its submaps,
      // placed by the front end at the odometry's prediction, count with the ratio itself. (With
      // the ratio, and the nodes' edges weighted alike, the closures of a featureless corridor
      // start pulled its nodes 0.74 m along it, SubmapSlam.HoldsAStartInAFeaturelessCorridor*.)
      closure.weak_axis = information->weak_axis;
      closure.weak_weight = information->curvature_ratio * information->curvature_ratio;
      graph.add_edge(closure);
      ++stats.loop_closures;
      ++pending_closures;
    }
  }

  void optimize(int iterations) {
    optimization::OptimizeOptions options;
    options.max_iterations = iterations;
    options.huber_scale = config.graph.huber;
    graph.optimize(options);
    // Each closure re-checked where the optimized graph puts its two ends: one that the rest of
    // the graph disagrees with by more than loops.switch_off sigmas is switched off, one that
    // agrees again is switched on; if any changed, the graph is solved again without them.
    bool changed = false;
    stats.switched_off_closures = 0;
    for (std::size_t e = 0; e < graph.edges(); ++e) {
      if (!graph.edge_list()[e].robust) continue;
      const bool agrees = graph.whitened_error(e) <= config.loops.switch_off;
      if (agrees != graph.edge_list()[e].active) {
        graph.set_active(e, agrees);
        changed = true;
      }
      stats.switched_off_closures += !agrees;
    }
    if (changed) graph.optimize(options);
    ++stats.optimizations;
    pending_closures = 0;
    nodes_since_optimization = 0;
  }

  void finish() override {
    if (graph.edges() > 0) optimize(3 * config.graph.iterations);
  }

  std::vector<core::Pose2> scan_poses() const override {
    std::vector<core::Pose2> out;
    out.reserve(scans.size());
    for (const ScanRecord& s : scans) {
      if (s.node == static_cast<std::size_t>(-1)) {
        out.push_back(to_pose2(s.local));
        continue;
      }
      const Node& n = nodes[s.node];
      out.push_back(core::compose(graph.poses()[n.vertex],
                                  core::relative(to_pose2(n.local), to_pose2(s.local))));
    }
    return out;
  }

  core::Grid<std::int8_t> map() const override {
    const TrackerSetup& s = tracker.setup();
    const core::IsmTable<Cell> table = make_table<Cell>(config, codec);
    const core::IntegerRays rays = tracker.rays();
    LocalGrid<Cell> grid(s.cell_mm);
    grid.cover(-1, -1, 1, 1);
    for (const Node& n : nodes) {
      const SlamPose p = to_slam_pose(graph.poses()[n.vertex]);
      const SlamSensor& sensor = *n.sensor;
      const auto [mx, my] =
          rays.rotate(static_cast<std::int32_t>(p.theta), sensor.mount_x_mm, sensor.mount_y_mm);
      grid.insert(rays, table, p.x_mm + mx, p.y_mm + my,
                  static_cast<std::int32_t>(p.theta + sensor.mount_theta), sensor.bearing,
                  n.range_mm, s.max_range_mm, s.max_index);
    }
    const double cell = s.cell_mm * 1e-3;
    core::Grid<std::int8_t> out(
        core::GridGeometry{grid.width(), grid.height(), cell, (grid.x0() - 0.5) * cell,
                           (grid.y0() - 0.5) * cell},
        std::int8_t{0});
    const std::span<const Cell> cells = grid.cells();
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if constexpr (std::is_same_v<Cell, LogOdds>)
        out.cells[i] = static_cast<std::int8_t>(std::lround(cells[i].steps));
      else
        out.cells[i] = cells[i];
    }
    return out;
  }
};

SubmapSlam::SubmapSlam(const SubmapSlamConfig& config, core::Arithmetic arithmetic,
                       const core::Scan& first)
    : first_t_(first.t), frame_(first.robot), previous_robot_(first.robot) {
  check_submap_slam_config(config);
  recent_sensor(sensors_, first, scan_label(1, first.t));
  const core::SepsCodec codec = make_codec(config);
  TrackerSetup s = make_tracker_setup(config, codec);
  if (arithmetic == core::Arithmetic::integer)
    engine_ = std::make_unique<EngineOf<std::int8_t>>(config, codec, std::move(s));
  else
    engine_ = std::make_unique<EngineOf<LogOdds>>(config, codec, std::move(s));
}

double pyramid_cache_bytes(const SubmapSlamConfig& config, core::Arithmetic arithmetic,
                           double submap_cells) {
  const SearchWindow loops = search_window(config.loops.window, config.loops.window_degrees, 0.0,
                                           0.0, static_cast<std::int32_t>(millimetres(config.cell)),
                                           core::kAngleUnitsPerTurn / config.headings);
  const double cell_bytes = arithmetic == core::Arithmetic::integer ? 1.0 : sizeof(LogOdds);
  // The grid's own cells, then one byte a cell for each level above it (MaxPyramid).
  const double one = (cell_bytes + pyramid_levels(loops.cells)) * submap_cells;
  // The cache, and the pyramids one node's searches hold while they run (loops.submaps of them,
  // which the cache may have let go meanwhile).
  return std::min(static_cast<double>(kPyramidCacheSubmaps) * one,
                  std::max(static_cast<double>(kPyramidCacheBytes), one)) +
         static_cast<double>(config.loops.submaps) * one;
}

SubmapSlam::~SubmapSlam() = default;
SubmapSlam::SubmapSlam(SubmapSlam&&) noexcept = default;
SubmapSlam& SubmapSlam::operator=(SubmapSlam&&) noexcept = default;

void SubmapSlam::insert(const core::Scan& scan) {
  const std::size_t number = engine_->stats.scans + 1;
  const std::string label = scan_label(number, scan.t);
  std::shared_ptr<const SlamSensor> sensor = recent_sensor(sensors_, scan, label);
  const QuantizedScan q =
      quantize_scan(scan, number > 1 ? &previous_robot_ : nullptr, engine_->config.sensor.max_range,
                    label, engine_->stats.readings, engine_->stats.unusable_readings);
  engine_->insert(q, std::move(sensor), scan.t - first_t_);
  previous_robot_ = scan.robot;
  times_.push_back(scan.t);
}

void SubmapSlam::finish() {
  engine_->finish();
}

core::Pose2 SubmapSlam::pose() const {
  const std::vector<core::Pose2> poses = engine_->scan_poses();
  if (poses.empty()) return frame_;
  core::Pose2 p = core::compose(frame_, poses.back());
  p.theta = core::wrap_angle(p.theta);
  return p;
}

std::vector<TimedPose> SubmapSlam::trajectory() const {
  const std::vector<core::Pose2> poses = engine_->scan_poses();
  std::vector<TimedPose> out;
  out.reserve(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    core::Pose2 p = core::compose(frame_, poses[i]);
    p.theta = core::wrap_angle(p.theta);
    out.push_back({times_[i], p});
  }
  return out;
}

core::Grid<std::int8_t> SubmapSlam::map() const {
  return engine_->map();
}
const core::SepsCodec& SubmapSlam::codec() const {
  return engine_->codec;
}
SubmapSlamStats SubmapSlam::stats() const {
  return engine_->stats;
}

SlamRun run_submap_slam(const core::Log& log, const SubmapSlamConfig& config,
                        core::Arithmetic arithmetic, SubmapSlamStats* stats,
                        const core::Progress& progress) {
  check_submap_slam_config(config);
  check_slam_log(log);
  SubmapSlam slam(config, arithmetic, log.scans.front());
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    slam.insert(log.scans[i]);
    if (progress) progress(i + 1, log.scans.size());
  }
  slam.finish();
  SlamRun run;
  run.trajectory = slam.trajectory();
  run.map = slam.map();
  run.codec = slam.codec();
  run.frame = slam.frame();
  const SubmapSlamStats s = slam.stats();
  run.scans = s.scans;
  run.localizations = s.scans - s.unmatched_scans;
  run.mappings = s.nodes;
  run.skipped_scans = s.unmatched_scans;
  run.readings = s.readings;
  run.unusable_readings = s.unusable_readings;
  if (stats) *stats = s;
  return run;
}

}  // namespace intgrid::slam
