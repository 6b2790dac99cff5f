// Global localization with pose occupancy grids (docs/algorithms.md 7, thesis chapter 4), and the
// baselines a user would pick instead, on the same pose grid and readings.
//
// The robot knows the map, not its pose. The pose grid covers the map at pose_res over
// `headings` heading bins; its cells hold the SENSOR's pose (rule 3): the estimate steps back
// by the mounting pose to report the robot's. Rays run along a family of parallel digital
// lines per direction bin (one line through every pose cell, so the lines partition the grid),
// which makes the forward "first hit from a pose" and the backward "walk from a source" two
// exact views of one relation: the dense form and the walk form give identical grids.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <type_traits>
#include <vector>

#include "intgrid/core/grid.hpp"
#include "intgrid/core/seps.hpp"
#include "intgrid/core/types.hpp"
#include "intgrid/localization/fine_map.hpp"

namespace intgrid::localization {

enum class GlobalMethod {
  pose_grid,         // the pose occupancy grid: S_eps index sums, integer only per reading
  markov,            // Markov localization, Gaussian beam model, double
  markov_mixture,    // Markov localization, hit + short + random + max mixture, double
  likelihood_field,  // Markov localization, likelihood field (ROS AMCL's default), double
};

struct GlobalLocConfig {
  double pose_res = 0.2;    // pose-grid step (m); not finer than the map's resolution
  int headings = 64;        // heading bins, also the rays' direction bins
  double sigma = 0.03;      // range noise of the readings (m)
  double max_range = 30.0;  // readings at or past this are not used (m)
  int seps_bits = 8;        // per-reading index width
  // Each reading's claims are quantized with its own eps, such that its strongest claim is this
  // index: with one eps for all, a far reading (sigma_eff grows with the heading step times z)
  // claims 0 to 2 against a near one's 16, and a pose near any wall outscores the true one.
  int seps_levels = 16;
  // A reading's negative claims are bounded by this (rule 2 bounds them by its strongest claim):
  // a reading cut short or contaminated that runs past the true pose's first hit would otherwise
  // veto the true pose with the weight of a match.
  int veto_levels = 8;
  // Baselines' beam-model weights (Probabilistic Robotics 6.3; AMCL's defaults).
  // z_hit and lambda_short must be positive, the others non-negative.
  double z_hit = 0.95, z_short = 0.1, z_max = 0.05, z_rand = 0.05, lambda_short = 0.1;
  // The most a map's tables and one localization's scores may take (bytes): a LocalizationMap or
  // MarkovLocalization that would need more is refused before it allocates.
  std::size_t memory_limit = 1'000'000'000;
  // Levels of the pose grid's refinement on the map's own cells, each halving the position and
  // heading steps (0: none, the hypotheses stay on the pose lattice). Its finest heading bin is
  // 2 pi / (headings 2^refine_levels).
  int refine_levels = 4;
  // The refinement reads a reading whose first hit lies before its range, while its ray runs
  // along a wall from there to its endpoint, as a hit at its range: a wall met at a grazing angle
  // is entered up to cell / sin(angle) before its surface where the map's wall is ragged, and its
  // early first hit would veto the true pose. Off by default: measured on the benchmark logs
  // only, not yet on the sweeps the defaults are reported on (docs/results.md).
  bool grazing_hits = false;
};

// Throws std::invalid_argument naming the offending field.
void check_global_loc_config(const GlobalLocConfig& config);

// One reading in the sensor frame.
struct RangeReading {
  double range = 0.0;    // m
  double bearing = 0.0;  // rad, from the sensor's heading
};

// The usable readings of a scan (valid for the scan and below max_range), `beams` of them spread
// evenly over the scan (all when beams <= 0 or beams >= the usable count): usable reading
// floor(i * usable / beams) for i = 0..beams-1.
std::vector<RangeReading> readings_of(const core::Scan& scan, int beams, double max_range);

// One reading's claims on the pose grid (rules 1 and 2), built once per reading in floating
// point; applying them is integer only. A pose with heading bin k reads the reading along direction
// bin d = (k + shift) mod headings; claim[d][rho] is the S_eps index of a pose whose first hit
// along d lies rho steps away: the narrow ISM of z on that direction's step with sigma_eff,
// quantized to the nearest step of the reading's own S_eps scale (lambda = max(logit(the
// table's Pmax), 1e-9) / seps_levels) and clamped to [-min(n_top[d], veto_levels), n_top[d]]
// (n_top[d] the largest positive index of the table, 0 if none). rho = 0 (never a candidate's first
// hit) holds 0; claim[d] ends with one 0, past z plus the ISM's window of 8 sigma_eff, which every
// rho past the table (or no hit) reads.
//
// The same claims in double precision (Score = double, log_odds_claims) hold the log-odds the
// indices round: n lambda before rounding, bounded alike. They are the floating-point form of the
// pose grid, kept to measure what the integer arithmetic saves.
template <class Score>
struct BasicReadingClaims {
  int shift = 0;
  double sigma_eff = 0.0;  // hypot(sigma, pose_res, bin * z), bin = 2 pi / headings (rule 1)
  std::vector<std::vector<Score>> claim;  // [direction bin][rho]
  std::vector<Score> n_top;               // [direction bin]
};
using ReadingClaims = BasicReadingClaims<std::int32_t>;
using LogOddsClaims = BasicReadingClaims<double>;

// The class of a pose cell, from the map cells whose centres fall in it.
enum class PoseCellClass : std::uint8_t {
  free,      // every one <= free_threshold: a candidate
  unknown,   // neither: rays pass over it, the robot is not placed on it
  occupied,  // any one >= occupied_threshold: stops rays (a source)
};

// The map, prepared once: pose-cell classes, and per direction bin the first-hit distance of
// every pose cell and each source's free run (what does not depend on the readings).
//
// Direction bin d points at angle 2 pi d / headings. Its rays run along a family of parallel
// digital lines: for an x-major direction (|cos| >= |sin|) the line through pose cell (i, j) is
// {(i', c + floor(i' m + 1/2))}, c = j - floor(i m + 1/2), with m = tan held in fixed point
// (slope_fixed(d) / 2^kSlopeBits) so the offsets are exact integers; y-major directions swap x and
// y (m = cot). The lines partition the pose lattice; one step along a line is one cell along the
// major axis, step_length(d) = pose_res / max(|cos|, |sin|) metres.
class LocalizationMap {
 public:
  static constexpr int kSlopeBits = 30;
  // first_hit_steps when the ray leaves the lattice without meeting an occupied cell.
  static constexpr std::uint16_t kNoHit = 0xFFFF;

  // Bytes per candidate pose cell: its first hit per direction (uint16) and, while a scan is
  // localized, its index sum (int32). Non-candidate cells cost neither.
  static constexpr std::size_t kBytesPerCandidatePoseCell = 6;

  // Throws std::invalid_argument: a pose resolution finer than the map's, a map without any
  // free pose cell, thresholds outside [0, 1] or free_threshold >= occupied_threshold, a bad
  // configuration, a lattice of 65535 cells or more along an axis, tables and scores that would
  // exceed config.memory_limit (the message starts "memory_limit", before anything is allocated
  // past the map's own size).
  LocalizationMap(const core::ProbabilityGrid& map, double occupied_threshold,
                  double free_threshold, const GlobalLocConfig& config);

  const GlobalLocConfig& config() const { return config_; }
  int width() const { return width_; }  // pose cells in x
  int height() const { return height_; }
  int headings() const { return config_.headings; }
  std::size_t pose_cells() const;       // width * height * headings
  std::size_t candidate_cells() const;  // free pose cells * headings
  // The sensor pose at the centre of pose cell (i, j) with heading bin k.
  core::Pose2 pose_of(int i, int j, int k) const;
  // Pose cell of element q of a PoseScores vector: q = (k * height + j) * width + i.
  std::size_t index(int i, int j, int k) const;

  PoseCellClass cell_class(int i, int j) const {
    return class_[std::size_t(j) * std::size_t(width_) + std::size_t(i)];
  }
  bool is_candidate(int i, int j) const { return cell_class(i, j) == PoseCellClass::free; }
  // The candidate positions (free pose cells) in xy order, each as j * width + i; a candidate
  // pose cell is (candidate c, heading k), element k * candidates + c of a candidate-layout grid.
  std::span<const std::uint32_t> candidates() const { return candidates_; }
  // The pose cell (i, j, k) of element q = k * candidates + c of a candidate-layout grid.
  std::array<int, 3> candidate_cell(std::size_t q) const {
    const std::uint32_t xy = candidates_[q % candidates_.size()];
    return {int(xy % std::uint32_t(width_)), int(xy / std::uint32_t(width_)),
            int(q / candidates_.size())};
  }
  // c of position (i, j), or -1 for a non-candidate.
  std::int32_t candidate_index(int i, int j) const {
    return candidate_of_[std::size_t(j) * std::size_t(width_) + std::size_t(i)];
  }
  // What the tables and one scan's scores take (bytes), as the constructor checked it.
  std::size_t memory_bytes() const { return memory_bytes_; }
  // The map at its own resolution with headings 2^refine_levels times finer, for the
  // refinement; empty when refine_levels is 0.
  const FineMap& fine() const { return fine_; }
  double heading_bin() const;  // 2 pi / headings (rad)

  // The digital lines of direction bin d.
  bool x_major(int d) const;
  int major_sign(int d) const;            // +1 or -1: the rays' way along the major axis
  std::int64_t slope_fixed(int d) const;  // round(m 2^kSlopeBits), |m| <= 1
  double step_length(int d) const;        // metres per step
  // The cells (i, j) of the line through (i, j) along d, in the rays' order.
  std::vector<std::array<int, 2>> line_through(int i, int j, int d) const;
  // Steps from free pose cell (i, j) along d to the first occupied cell (>= 1), kNoHit if the ray
  // leaves the lattice first. Non-candidate cells hold kNoHit.
  std::uint16_t first_hit_steps(int i, int j, int d) const;
  // The same for every candidate position of direction d, element c (candidates()).
  std::span<const std::uint16_t> first_hit_table(int d) const;
  // Live sources along d: occupied cells with at least one free cell on their run (the cells
  // before them on their line, back to the previous occupied cell or the lattice's edge).
  std::size_t live_sources(int d) const;
  // Distance (m) from (x, y) to the nearest occupied map cell centre (the likelihood field's
  // distance transform, computed once); infinity outside the map or without occupied cells.
  double distance_to_occupied(double x, double y) const;

  // sigma_eff of a reading of range z (rule 1).
  double effective_sigma(double z) const;
  // The claims of one reading. Throws std::invalid_argument for a range that is not finite and
  // positive or not below max_range, or a bearing that is not finite.
  ReadingClaims claims(const RangeReading& reading) const;
  LogOddsClaims log_odds_claims(const RangeReading& reading) const;
  // Dense form: pog[q] += claim[d][first_hit_steps] for every candidate q (heading bin k reading
  // along d = (k + shift) mod headings). pog has pose_cells() elements, laid out as index().
  // Allocates nothing. Score is std::int32_t or double.
  template <class Score>
  void add_reading_dense(const BasicReadingClaims<Score>& claims,
                         std::span<std::type_identity_t<Score>> pog) const;
  // Candidate form: the dense form of every reading at once on the candidate layout
  // (scores[k * candidates + c] += claim of each reading), for the headings [k_begin, k_end) only,
  // so that threads can share one grid by headings. The candidates are walked in tiles that stay
  // in cache across the readings; the sums are the dense form's, cell for cell.
  void add_readings_candidates(std::span<const ReadingClaims> claims,
                               std::span<std::int32_t> scores, int k_begin, int k_end) const;
  // The claim of one reading on one candidate pose cell: what the candidate form adds there.
  std::int32_t claim_at(const ReadingClaims& claims, std::size_t c, int k) const {
    const auto d = std::size_t((k + claims.shift) % config_.headings);
    const std::vector<std::int32_t>& t = claims.claim[d];
    return t[std::min<std::size_t>(directions_[d].first_hit[c], t.size() - 1)];
  }
  // Walk form: from every live source along every d, walk back over its run adding claim[d][rho]
  // to the free cells rho steps before it, until the claims end. The same grid as the dense form.
  void add_reading_walk(const ReadingClaims& claims, std::span<std::int32_t> pog) const;

 private:
  struct Source {
    std::int32_t line = 0;   // c
    std::int32_t major = 0;  // major-axis coordinate of the source
    std::int32_t run = 0;    // cells before it on its line, back to an occupied cell or the edge
  };
  struct Direction {
    bool x_major = true;
    int sign = 1;
    std::int64_t slope = 0;
    double step = 0.0;
    int step_group = 0;                    // directions of one step length share their ISM tables
    std::vector<std::int32_t> offset;      // floor(u m + 1/2) for u along the major axis
    std::vector<std::uint16_t> first_hit;  // per candidate position
    std::vector<Source> sources;           // live ones
  };

  GlobalLocConfig config_;
  int width_ = 0, height_ = 0;
  double origin_x_ = 0.0, origin_y_ = 0.0;
  double occupied_threshold_ = 0.0, free_threshold_ = 0.0;
  std::vector<PoseCellClass> class_;  // per xy cell
  std::size_t free_cells_ = 0;
  std::vector<std::uint32_t> candidates_;   // xy of each candidate position
  std::vector<std::int32_t> candidate_of_;  // per xy cell: its candidate index, or -1
  std::size_t memory_bytes_ = 0;
  std::vector<Direction> directions_;
  std::vector<double> group_step_;  // step length of each step group
  core::GridGeometry map_geometry_;
  std::vector<double> occupied_distance_;  // per map cell, metres
  FineMap fine_;

  void build_direction(int d);
  template <class Score>
  BasicReadingClaims<Score> make_claims(const RangeReading& reading) const;
};

// Markov localization over the candidates of a map, the baselines (markov, markov_mixture,
// likelihood_field) in double as a user would write them: each reading multiplies every
// candidate's belief by p(z | x), one exp per candidate, and normalizes (bel <- eta p(z|x) bel).
// Beam models read the expected range from the map's first-hit table: first_hit_steps *
// step_length capped at max_range, max_range with no hit.
//   markov:           p = N(z; expected, sigma_eff)
//   markov_mixture:   p = z_hit N(z; expected, sigma_eff) + z_short lambda e^(-lambda z) /
//                     (1 - e^(-lambda expected)) below expected + z_rand / max_range (+ z_max at
//                     max_range, which a usable reading never is); the Gaussian is not truncated
//                     to [0, max_range] (as in ROS AMCL)
//   likelihood_field: p = z_hit N(d; sigma_eff) + z_rand / max_range, d the distance of the
//                     reading's endpoint (from the pose cell's centre along heading + bearing, not
//                     binned) to the nearest occupied map cell, no hit term outside the map
// N is the normalized Gaussian density and sigma_eff the pose grid's (rule 1).
class MarkovLocalization {
 public:
  // Uniform prior over the candidates. Throws std::invalid_argument for pose_grid, and (naming
  // memory_limit) when the two beliefs beside the map's tables would exceed the configuration's
  // memory limit.
  MarkovLocalization(const LocalizationMap& map, GlobalMethod method);

  // Fuses one reading. Returns false, leaving the belief unchanged, when every candidate's
  // product is 0 in double (the textbook's eta is then undefined). Throws std::invalid_argument
  // for a range that is not finite and positive or not below max_range, or a bearing that is not
  // finite.
  bool update(const RangeReading& reading);
  // candidate_cells() elements in the candidate layout (k * candidates + c), summing to 1.
  std::span<const double> belief() const { return belief_; }
  std::size_t dropped() const { return dropped_; }

 private:
  const LocalizationMap* map_;
  GlobalMethod method_;
  std::vector<double> belief_, next_;
  std::size_t dropped_ = 0;
};

// Every pose cell's score after all readings, and what made it.
struct PoseScores {
  GlobalMethod method = GlobalMethod::pose_grid;
  std::vector<std::int32_t> index_sum;  // pose_grid: S_eps sums; non-candidates hold INT32_MIN
  std::vector<double> posterior;        // baselines: normalized; non-candidates hold 0
};

struct GlobalEstimate {
  core::Pose2 sensor;  // the pose grid's estimate: best cell (ties: their mean)
  core::Pose2 robot;   // the sensor pose stepped back by the mounting pose
  double score = 0.0;  // pose_grid: the best index sum; baselines: the best cell's posterior
  std::size_t ties = 1;
  std::size_t readings_used = 0;     // the usable readings (finite, positive, below max_range)
  std::size_t readings_dropped = 0;  // baselines: readings that zeroed every candidate
};

// One place a scan fits: the best pose of its neighbourhood, at least `separation` (or
// `separation_heading`) from every better hypothesis.
struct PoseHypothesis {
  // refine_levels > 0: the refined pose; else the mean of the pose cells tied at `score` around
  // the hypothesis's cell.
  core::Pose2 sensor;
  core::Pose2 robot;                 // the sensor pose stepped back by the mounting pose
  std::int32_t screening_score = 0;  // index sum of the screening readings at its screening cell
  std::int32_t score = 0;            // index sum of the verification readings at `sensor`
  std::size_t ties = 1;              // poses tied at `score` among those its last step compared
};

struct PoseSearchOptions {
  int hypotheses = 1;  // reported, best first
  // The best screening hypotheses verified: refined on the map's own cells (refine_levels > 0)
  // or rescored over their neighbourhood on the lattice (one cell and one heading bin around),
  // with the verification readings. The screening's coarse claims cannot tell apart places that
  // look alike at 5.6 degrees and 0.2 m; sharper claims and the whole scan often can.
  int verified = 32;
  double separation = 1.0;             // m: two hypotheses differ by at least this in position,
  double separation_heading = 0.5236;  // or this in heading (rad, 30 degrees)
  // The answer is ambiguous when a second hypothesis scores within this many S_eps levels per
  // verification reading of a scan (their mean over the fused scans when tracking) of the best:
  // a user should wait for another scan.
  double ambiguity_levels = 0.5;
  int threads = 1;  // the screening's headings and the hypotheses split across threads; any
                    // count, the same result
};

struct PoseSearchResult {
  GlobalEstimate estimate;                 // the best hypothesis
  std::vector<PoseHypothesis> hypotheses;  // best first, at most max(hypotheses, 1)
  bool ambiguous = false;
  std::size_t verification_readings = 0;  // over every fused scan
};

// Throws std::invalid_argument naming the field.
void check_pose_search_options(const PoseSearchOptions& options);

// The pose grid's search: every candidate pose cell scored with the screening readings (the
// candidate form), the best cells grouped into hypotheses `separation` apart, the best
// `verified` of them verified with the verification readings (refined, see GlobalLocConfig's
// refine_levels), ranked by that score. Readings that are not usable are dropped, as
// localize_global does. `scores`, when given, receives the screening scores in the PoseScores
// layout.
PoseSearchResult search_pose_grid(const LocalizationMap& map,
                                  std::span<const RangeReading> screening,
                                  std::span<const RangeReading> verification,
                                  const core::Pose2& sensor_mount, const PoseSearchOptions& options,
                                  PoseScores* scores = nullptr);

// The refinement from a given sensor pose instead of a screening cell: the pose within the first
// level's reach of it (0.3 m and one heading bin at the defaults) that the readings fit best, and
// the verification readings' score there (screening_score 0). It checks a reference: when a
// reference pose, so refined, scores below the search's answer, the map agrees with the answer,
// not with the reference. Throws std::invalid_argument when refine_levels is 0 or the pose is
// not finite; score is INT32_MIN when no pose there is free.
PoseHypothesis refine_pose(const LocalizationMap& map, std::span<const RangeReading> screening,
                           std::span<const RangeReading> verification, const core::Pose2& sensor,
                           const core::Pose2& sensor_mount);

// Global localization from a sequence of scans: the multi-measurement pose grid over time,
// motion-compensated by odometry. Each scan's screening sums are kept; the fused grid scores a
// pose cell at the latest scan with the sum, over the fused scans, of each scan's sums at the
// pose cell where odometry puts the sensor then (its heading slice shifted by the rotated
// translation and the turn, each rounded once from that scan's motion, so rounding does not
// accumulate; a place off the candidates adds nothing). Hypotheses, their refinement and the
// ambiguity test then run as search_pose_grid's, each pose scored over every fused scan.
struct ScanEvidence;
class PoseTracker {
 public:
  // Throws std::invalid_argument naming the field: bad options, max_scans outside 1..1000, or
  // memory_limit when max_scans screening grids beside the map's tables would exceed the map's
  // limit (refused before anything is allocated).
  PoseTracker(const LocalizationMap& map, const PoseSearchOptions& options, std::size_t max_scans);
  ~PoseTracker();
  PoseTracker(PoseTracker&&) noexcept;
  PoseTracker& operator=(PoseTracker&&) noexcept;

  // Fuses one scan. `motion`: the sensor's pose at this scan in the frame of the sensor at the
  // scan added before (from odometry; ignored for the first). Throws std::invalid_argument when
  // max_scans are fused already or the motion is not finite.
  void add_scan(std::span<const RangeReading> screening, std::span<const RangeReading> verification,
                const core::Pose2& motion);
  std::size_t scans() const { return evidence_.size(); }
  std::size_t max_scans() const { return max_scans_; }
  // Hypotheses for the sensor at the latest scan, from every fused scan. Requires a scan.
  PoseSearchResult search(const core::Pose2& sensor_mount) const;
  // The fused grid's sums in the PoseScores layout (non-candidates INT32_MIN). Requires a scan.
  PoseScores fused_scores() const;

 private:
  const LocalizationMap* map_;
  PoseSearchOptions options_;
  std::size_t max_scans_;
  std::vector<std::unique_ptr<ScanEvidence>> evidence_;
  std::vector<core::Pose2> sensor_;  // each scan's sensor pose in the first scan's frame
};

// Localizes one set of readings from no prior. Readings that are not finite and positive, at or
// past max_range, or with a non-finite bearing are not used. `scores`, when given, receives every
// cell's. Baselines: the sensor estimate is the best candidate cell's pose (pose_of), the mean of
// the tied ones (headings by circular mean). The pose grid: search_pose_grid's best hypothesis with
// the readings as both screening and verification readings, one thread (ties is then the count of
// cells at the best score; the estimate, the mean of those around the first of them).
// robot = compose(sensor, inverse of sensor_mount).
GlobalEstimate localize_global(const LocalizationMap& map, std::span<const RangeReading> readings,
                               const core::Pose2& sensor_mount, GlobalMethod method,
                               PoseScores* scores = nullptr);

// The same for one scan, in SI units as every algorithm takes it: `beams` of its usable readings
// (readings_of; all when beams <= 0), with the scan's sensor mount.
GlobalEstimate localize_scan(const LocalizationMap& map, const core::Scan& scan, int beams,
                             GlobalMethod method, PoseScores* scores = nullptr);

}  // namespace intgrid::localization
