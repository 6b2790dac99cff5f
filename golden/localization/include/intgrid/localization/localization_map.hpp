// The map as global localization uses it, prepared once: pose-cell classes, rays along digital
// lines per direction bin, and each reading's claims on the pose grid (docs/algorithms.md 7).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "intgrid/core/grid.hpp"
#include "intgrid/core/seps.hpp"
#include "intgrid/core/types.hpp"
#include "intgrid/localization/fine_map.hpp"
#include "intgrid/localization/global_loc_config.hpp"
#include "intgrid/localization/range_reading.hpp"

namespace intgrid::localization {

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

}  // namespace intgrid::localization
