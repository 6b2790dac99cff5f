// The pose grid's search (docs/algorithms.md 7): screening, hypotheses, their verification or
// refinement, ranking and ambiguity, for one scan (search_pose_grid) or a sequence (PoseTracker).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "intgrid/core/failure.hpp"
#include "intgrid/core/parallel.hpp"
#include "intgrid/localization/global_localization.hpp"
#include "search_support.hpp"

namespace intgrid::localization {

// One scan as the search applies it: its usable readings, their claims on the lattice and, per
// refinement level, on the map's own cells, and its screening sums.
struct ScanEvidence {
  std::vector<RangeReading> screen, verify;
  bool same = false;  // the verification readings are the screening ones
  std::vector<ReadingClaims> screen_claims;
  std::vector<ReadingClaims> verify_claims;          // refine_levels 0 and not `same` only
  std::vector<std::vector<FineClaims>> fine_screen;  // [level - 1]
  std::vector<FineClaims> fine_verify;               // the last level's; empty when `same`
  // When tracking: the claims of the scan once it is past, at level 0 (the pose lattice's
  // sigma_eff) for every level, since odometry gives its pose no better than the lattice does.
  std::vector<FineClaims> past_screen, past_verify;  // past_verify empty when `same`
  std::vector<std::int32_t> sums;                    // screening sums, candidate layout

  const std::vector<ReadingClaims>& lattice_verification() const {
    return same ? screen_claims : verify_claims;
  }
  const std::vector<FineClaims>& fine_verification() const {
    return same ? fine_screen.back() : fine_verify;
  }
  const std::vector<FineClaims>& past_verification() const {
    return same ? past_screen : past_verify;
  }
};

namespace {

constexpr std::int32_t kNotFree = std::numeric_limits<std::int32_t>::min();

std::vector<ReadingClaims> claims_of(const LocalizationMap& map,
                                     std::span<const RangeReading> readings, int threads) {
  std::vector<ReadingClaims> out(readings.size());
  core::run_parts(readings.size(), threads,
                  [&](std::size_t r) { out[r] = map.claims(readings[r]); });
  return out;
}

// The refinement's schedule. Level l (1..refine_levels) steps pose_res / 2^l in position and
// heading_bin / 2^l in heading; its claims take the same steps into sigma_eff (rule 1), with the
// map's cell for the first hit's own rounding:
//   sigma_l(z) = sqrt(sigma^2 + (pose_res / 2^l)^2 + map_res^2 + (heading_bin / 2^l * z)^2).
// The first level searches every pose within kFirstLevelReach of its steps in position (0.3 m at
// the default 0.2 m cell) and kFirstLevelTurns in heading (one heading bin) of the screening's
// cell, and keeps its kFirstLevelBeam best; each further level searches one step around each
// kept pose and keeps kLevelBeam. A beam rather than the single best: the sharper claims of the
// next level may prefer a pose that was second at this one. The reaches and the number of
// hypotheses refined (PoseSearchOptions::verified) were chosen on simulated trials in the room
// map scaled six times (docs/results.md).
constexpr int kFirstLevelReach = 3;
constexpr int kFirstLevelTurns = 2;
constexpr std::size_t kFirstLevelBeam = 8;
constexpr std::size_t kLevelBeam = 4;

double level_sigma(const LocalizationMap& map, int level, double z) {
  const GlobalLocConfig& c = map.config();
  const double step = c.pose_res / double(1 << level);
  const double bin = map.heading_bin() / double(1 << level);
  const double cell = map.fine().geometry().resolution;
  return std::sqrt(c.sensor.sigma * c.sensor.sigma + step * step + cell * cell +
                   (bin * z) * (bin * z));
}

std::vector<FineClaims> fine_claims_of(const LocalizationMap& map,
                                       std::span<const RangeReading> readings, int level,
                                       int threads) {
  const GlobalLocConfig& c = map.config();
  std::vector<FineClaims> out(readings.size());
  core::run_parts(readings.size(), threads, [&](std::size_t r) {
    const RangeReading& reading = readings[r];
    out[r] =
        map.fine().claims(reading.range, reading.bearing, level_sigma(map, level, reading.range),
                          c.seps_levels, c.veto_levels);
  });
  return out;
}

std::unique_ptr<ScanEvidence> make_evidence(const LocalizationMap& map,
                                            std::span<const RangeReading> screening,
                                            std::span<const RangeReading> verification,
                                            bool tracking, int threads) {
  const GlobalLocConfig& config = map.config();
  auto e = std::make_unique<ScanEvidence>();
  e->screen = detail::usable_readings(screening, config.sensor.max_range);
  e->verify = detail::usable_readings(verification, config.sensor.max_range);
  e->same = std::equal(e->screen.begin(), e->screen.end(), e->verify.begin(), e->verify.end(),
                       [](const RangeReading& a, const RangeReading& b) {
                         return a.range == b.range && a.bearing == b.bearing;
                       });
  e->screen_claims = claims_of(map, e->screen, threads);
  const int levels = config.refine_levels;
  if (levels == 0 && !e->same) e->verify_claims = claims_of(map, e->verify, threads);
  for (int level = 1; level <= levels; ++level)
    e->fine_screen.push_back(fine_claims_of(map, e->screen, level, threads));
  if (levels > 0 && !e->same) e->fine_verify = fine_claims_of(map, e->verify, levels, threads);
  if (levels > 0 && tracking) {
    e->past_screen = fine_claims_of(map, e->screen, 0, threads);
    if (!e->same) e->past_verify = fine_claims_of(map, e->verify, 0, threads);
  }

  // Screening: every candidate pose cell, the headings split into contiguous parts.
  const int headings = map.headings();
  e->sums.assign(map.candidate_cells(), 0);
  const auto parts = std::size_t(std::min(threads, headings));
  core::run_parts(parts, threads, [&](std::size_t p) {
    const auto k_begin = static_cast<int>(std::size_t(headings) * p / parts);
    const auto k_end = static_cast<int>(std::size_t(headings) * (p + 1) / parts);
    map.add_readings_candidates(e->screen_claims, e->sums, k_begin, k_end);
  });
  return e;
}

// A fused scan: its evidence and where the sensor then was, seen from the latest scan's sensor.
// The latest scan comes first, with the identity.
struct FusedScan {
  const ScanEvidence* evidence;
  core::Pose2 to_scan;
  bool latest;
};

// The pose cell nearest a sensor pose, as (candidate, heading bin), if it is a candidate.
std::optional<std::pair<std::size_t, int>> nearest_candidate(const LocalizationMap& map,
                                                             const core::Pose2& p) {
  const core::Pose2 corner = map.pose_of(0, 0, 0);
  const double r = map.config().pose_res;
  const long long i = std::llround((p.x - corner.x) / r), j = std::llround((p.y - corner.y) / r);
  if (i < 0 || j < 0 || i >= map.width() || j >= map.height()) return std::nullopt;
  const std::int32_t c = map.candidate_index(int(i), int(j));
  if (c < 0) return std::nullopt;
  const long long k = std::llround(p.theta / map.heading_bin()) % map.headings();
  return std::pair{std::size_t(c), int(k < 0 ? k + map.headings() : k)};
}

// The fused grid: each scan's sums read at the pose cell where its motion puts each cell's pose
// (the latest scan's as they are). Per heading slice the motion is one rotated translation,
// rounded once to whole cells, and one turn, rounded to whole bins.
std::vector<std::int32_t> fuse_sums(const LocalizationMap& map, std::span<const FusedScan> scans,
                                    int threads) {
  const std::size_t n = map.candidates().size();
  const int headings = map.headings();
  const std::span<const std::uint32_t> candidates = map.candidates();
  const auto w = std::uint32_t(map.width());
  std::vector<std::int32_t> out(map.candidate_cells(), 0);
  core::run_parts(std::size_t(headings), threads, [&](std::size_t part) {
    const int k = int(part);
    std::int32_t* slice = out.data() + std::size_t(k) * n;
    for (const FusedScan& s : scans) {
      const core::Pose2& d = s.to_scan;
      const double theta = k * map.heading_bin();
      const long long turn = std::llround(d.theta / map.heading_bin()) % headings;
      const int k_then = int((k + turn + headings) % headings);
      const long long di = s.latest ? 0
                                    : std::llround((std::cos(theta) * d.x - std::sin(theta) * d.y) /
                                                   map.config().pose_res);
      const long long dj = s.latest ? 0
                                    : std::llround((std::sin(theta) * d.x + std::cos(theta) * d.y) /
                                                   map.config().pose_res);
      const std::int32_t* then = s.evidence->sums.data() + std::size_t(s.latest ? k : k_then) * n;
      if (s.latest) {
        for (std::size_t c = 0; c < n; ++c) slice[c] += then[c];
        continue;
      }
      for (std::size_t c = 0; c < n; ++c) {
        const long long i = (candidates[c] % w) + di, j = (candidates[c] / w) + dj;
        if (i < 0 || j < 0 || i >= map.width() || j >= map.height()) continue;
        const std::int32_t c_then = map.candidate_index(int(i), int(j));
        if (c_then >= 0) slice[c] += then[c_then];
      }
    }
  });
  return out;
}

// A candidate pose cell of the screening: element q = k * candidates + c of the sums.
struct ScoredCell {
  std::int32_t score;
  std::size_t q;
};
// Best first; equal scores in layout order, so the order does not depend on the threads.
bool better(const ScoredCell& a, const ScoredCell& b) {
  return a.score != b.score ? a.score > b.score : a.q < b.q;
}

// The screening cells the hypotheses are drawn from: the best ones, at most about kPool of them
// (all cells of the score levels that fit, from the best down; at least the best level's first
// kPool).
constexpr std::size_t kPool = std::size_t{1} << 16;

std::vector<ScoredCell> best_cells(std::span<const std::int32_t> sums) {
  const std::int32_t best = *std::max_element(sums.begin(), sums.end());
  // Levels below the best, counted over a window: the pool never reaches past it.
  constexpr std::int64_t kWindow = 1 << 16;
  std::vector<std::size_t> count(std::size_t(kWindow), 0);
  for (const std::int32_t v : sums) {
    const std::int64_t below = std::int64_t(best) - v;
    if (below < kWindow) ++count[std::size_t(below)];
  }
  std::int64_t levels = 1;  // the best level always
  std::size_t taken = count[0];
  while (levels < kWindow && taken + count[std::size_t(levels)] <= kPool)
    taken += count[std::size_t(levels++)];
  const std::int64_t floor = std::int64_t(best) - (levels - 1);
  std::vector<ScoredCell> pool;
  pool.reserve(std::min(taken, kPool));
  for (std::size_t q = 0; q < sums.size() && pool.size() < kPool; ++q)
    if (sums[q] >= floor) pool.push_back({sums[q], q});
  std::sort(pool.begin(), pool.end(), better);
  return pool;
}

double heading_gap(double a, double b) {
  return std::abs(core::wrap_angle(a - b));
}

// Verification on the lattice (refine_levels 0): the verification readings' sum at a pose cell,
// over the fused scans; kNotFree off the candidates at the latest scan.
std::int32_t lattice_score(const LocalizationMap& map, std::span<const FusedScan> scans, int i,
                           int j, int k) {
  std::int32_t sum = 0;
  for (const FusedScan& s : scans) {
    std::optional<std::pair<std::size_t, int>> cell;
    if (s.latest) {
      const std::int32_t c = map.candidate_index(i, j);
      if (c < 0) return kNotFree;
      cell = std::pair{std::size_t(c), k};
    } else {
      cell = nearest_candidate(map, core::compose(map.pose_of(i, j, k), s.to_scan));
    }
    if (!cell) continue;  // a past pose off the candidates adds nothing
    for (const ReadingClaims& r : s.evidence->lattice_verification())
      sum += map.claim_at(r, cell->first, cell->second);
  }
  return sum;
}

// A fine pose's sum over the fused scans, with the claims of a refinement level (the
// verification readings' at the last level when `verification`); kNotFree off the free cells
// at the latest scan.
std::int32_t fine_score(const LocalizationMap& map, std::span<const FusedScan> scans,
                        const FinePose& pose, int level, bool verification) {
  const FineMap& fine = map.fine();
  std::int32_t sum = 0;
  for (const FusedScan& s : scans) {
    const ScanEvidence& e = *s.evidence;
    const std::vector<FineClaims>& claims =
        !s.latest      ? (verification ? e.past_verification() : e.past_screen)
        : verification ? e.fine_verification()
                       : e.fine_screen[std::size_t(level - 1)];
    const FinePose then =
        s.latest ? pose : fine.fine_pose(core::compose(fine.pose_of(pose), s.to_scan));
    const std::int32_t v = fine.score(claims, then, map.config().grazing_hits);
    if (v == kNotFree) {
      if (s.latest) return kNotFree;
      continue;  // a past pose off the free cells adds nothing
    }
    sum += v;
  }
  return sum;
}

struct FineCandidate {
  std::int32_t score;
  FinePose pose;
};
// Heading, then row, then column: a fixed order for equal scores.
bool pose_before(const FinePose& a, const FinePose& b) {
  return a.k != b.k ? a.k < b.k : a.y != b.y ? a.y < b.y : a.x < b.x;
}
bool fine_better(const FineCandidate& a, const FineCandidate& b) {
  return a.score != b.score ? a.score > b.score : pose_before(a.pose, b.pose);
}

struct Verified {
  core::Pose2 sensor;
  std::int32_t score = kNotFree;
  std::size_t ties = 1;
};

// Refinement from a fine pose: the levels' beam search, then the kept poses scored with the
// verification readings; the best of those (first in pose order among ties).
Verified refine(const LocalizationMap& map, std::span<const FusedScan> scans,
                const FinePose& seed) {
  const FineMap& fine = map.fine();
  const int levels = map.config().refine_levels, headings = fine.headings();
  std::vector<FinePose> beam{seed};
  std::vector<FineCandidate> scored;
  std::vector<FinePose> poses;
  for (int level = 1; level <= levels; ++level) {
    const std::int64_t step =
        std::llround(map.config().pose_res / double(1 << level) * fine.units_per_metre());
    const int turn = 1 << (levels - level);
    const int reach = level == 1 ? kFirstLevelReach : 1;
    const int reach_k = level == 1 ? kFirstLevelTurns : 1;
    poses.clear();
    for (const FinePose& b : beam)
      for (int dk = -reach_k; dk <= reach_k; ++dk)
        for (int dy = -reach; dy <= reach; ++dy)
          for (int dx = -reach; dx <= reach; ++dx)
            poses.push_back({b.x + dx * step, b.y + dy * step,
                             ((b.k + dk * turn) % headings + headings) % headings});
    std::sort(poses.begin(), poses.end(), pose_before);
    poses.erase(std::unique(poses.begin(), poses.end()), poses.end());
    scored.clear();
    for (const FinePose& p : poses) {
      const std::int32_t v = fine_score(map, scans, p, level, false);
      if (v != kNotFree) scored.push_back({v, p});
    }
    if (scored.empty()) return {fine.pose_of(beam.front()), kNotFree, 1};
    const std::size_t keep = std::min(scored.size(), level == 1 ? kFirstLevelBeam : kLevelBeam);
    std::partial_sort(scored.begin(), scored.begin() + std::ptrdiff_t(keep), scored.end(),
                      fine_better);
    scored.resize(keep);
    beam.clear();
    for (const FineCandidate& c : scored) beam.push_back(c.pose);
  }
  // The verification readings, unless they are the screening ones (then scored already).
  if (std::any_of(scans.begin(), scans.end(), [](const FusedScan& s) { return !s.evidence->same; }))
    for (FineCandidate& c : scored) c.score = fine_score(map, scans, c.pose, levels, true);
  std::sort(scored.begin(), scored.end(), fine_better);
  Verified v{fine.pose_of(scored.front().pose), scored.front().score, 0};
  for (const FineCandidate& c : scored) v.ties += c.score == v.score ? 1 : 0;
  return v;
}

// Verification on the lattice: the best of the pose cells one cell and one heading bin around,
// the mean of those tied (headings by circular mean).
Verified verify_on_lattice(const LocalizationMap& map, std::span<const FusedScan> scans, int i0,
                           int j0, int k0) {
  const int headings = map.headings();
  std::int32_t best = kNotFree;
  std::vector<std::array<int, 3>> tied;
  for (int dk = -1; dk <= 1; ++dk)
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const int i = i0 + di, j = j0 + dj, k = ((k0 + dk) % headings + headings) % headings;
        if (i < 0 || j < 0 || i >= map.width() || j >= map.height()) continue;
        const std::int32_t v = lattice_score(map, scans, i, j, k);
        if (v == kNotFree) continue;
        if (v > best) best = v, tied.clear();
        if (v == best) tied.push_back({i, j, k});
      }
  double sx = 0.0, sy = 0.0, sc = 0.0, ss = 0.0;
  for (const auto& [i, j, k] : tied) {
    const core::Pose2 p = map.pose_of(i, j, k);
    sx += p.x, sy += p.y, sc += std::cos(p.theta), ss += std::sin(p.theta);
  }
  const auto t = static_cast<double>(tied.size());
  return {{sx / t, sy / t, std::atan2(ss, sc)}, best, tied.size()};
}

// Hypotheses from the (fused) screening sums, verified, ranked, and the ambiguity test.
PoseSearchResult search_from_sums(const LocalizationMap& map, std::span<const std::int32_t> sums,
                                  std::span<const FusedScan> scans, const core::Pose2& sensor_mount,
                                  const PoseSearchOptions& options) {
  // Hypotheses: the best cells, each `separation` from every better one.
  const auto hypothesis_count = std::size_t(std::max(options.hypotheses, options.verified));
  const auto pose_at = [&](std::size_t q) {
    const auto [i, j, k] = map.candidate_cell(q);
    return map.pose_of(i, j, k);
  };
  std::vector<ScoredCell> seeds;
  for (const ScoredCell& cell : best_cells(sums)) {
    const core::Pose2 p = pose_at(cell.q);
    const bool apart = std::all_of(seeds.begin(), seeds.end(), [&](const ScoredCell& s) {
      const core::Pose2 o = pose_at(s.q);
      return std::hypot(p.x - o.x, p.y - o.y) >= options.separation ||
             heading_gap(p.theta, o.theta) >= options.separation_heading;
    });
    if (apart) seeds.push_back(cell);
    if (seeds.size() == hypothesis_count) break;
  }

  // Verification of the best `verified` seeds, each on its own.
  const std::size_t verified = std::min(seeds.size(), std::size_t(options.verified));
  std::vector<Verified> checked(verified);
  core::run_parts(verified, options.threads, [&](std::size_t s) {
    const auto [i, j, k] = map.candidate_cell(seeds[s].q);
    checked[s] = map.config().refine_levels > 0
                     ? refine(map, scans, map.fine().fine_pose(map.pose_of(i, j, k)))
                     : verify_on_lattice(map, scans, i, j, k);
  });
  std::vector<std::size_t> order(verified);
  for (std::size_t s = 0; s < verified; ++s) order[s] = s;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return checked[a].score > checked[b].score;
  });
  // Verification moves a hypothesis within its neighbourhood: two may meet. The better keeps the
  // place, so that a second hypothesis is always another place.
  std::vector<std::size_t> kept;
  for (const std::size_t s : order) {
    const core::Pose2& p = checked[s].sensor;
    if (std::all_of(kept.begin(), kept.end(), [&](std::size_t o) {
          const core::Pose2& q = checked[o].sensor;
          return std::hypot(p.x - q.x, p.y - q.y) >= options.separation ||
                 heading_gap(p.theta, q.theta) >= options.separation_heading;
        }))
      kept.push_back(s);
  }
  order = std::move(kept);

  PoseSearchResult result;
  std::size_t screening_readings = 0;
  for (const FusedScan& s : scans) {
    result.verification_readings += s.evidence->verify.size();
    screening_readings += s.evidence->screen.size();
  }
  for (std::size_t r = 0; r < order.size() && r < std::size_t(options.hypotheses); ++r) {
    const Verified& v = checked[order[r]];
    PoseHypothesis h;
    h.sensor = v.sensor;
    h.robot = detail::robot_of(v.sensor, sensor_mount);
    h.screening_score = seeds[order[r]].score;
    h.score = v.score;
    h.ties = v.ties;
    result.hypotheses.push_back(h);
  }
  // The margin is per reading of one scan (their mean over the fused scans): evidence that tells
  // two places apart builds up over the scans that see what differs, not over every reading.
  const double readings_a_scan = double(result.verification_readings) / double(scans.size());
  result.ambiguous =
      order.size() >= 2 && double(checked[order[0]].score) - double(checked[order[1]].score) <=
                               options.ambiguity_levels * readings_a_scan;
  const PoseHypothesis& top = result.hypotheses.front();
  result.estimate.sensor = top.sensor;
  result.estimate.robot = top.robot;
  result.estimate.score = top.score;
  result.estimate.ties = top.ties;
  result.estimate.readings_used = screening_readings;
  return result;
}

}  // namespace

void check_pose_search_options(const PoseSearchOptions& o) {
  if (o.hypotheses < 1 || o.hypotheses > 1000)
    core::fail<std::invalid_argument>("hypotheses must be 1..1000, got " +
                                      std::to_string(o.hypotheses));
  if (o.verified < 1 || o.verified > 1000)
    core::fail<std::invalid_argument>("verified must be 1..1000, got " +
                                      std::to_string(o.verified));
  if (!(o.separation >= 0.0) || !std::isfinite(o.separation))
    core::fail<std::invalid_argument>("separation must be a non-negative finite number");
  if (!(o.separation_heading >= 0.0) || !std::isfinite(o.separation_heading))
    core::fail<std::invalid_argument>("separation_heading must be a non-negative finite number");
  if (!(o.ambiguity_levels >= 0.0) || !std::isfinite(o.ambiguity_levels))
    core::fail<std::invalid_argument>("ambiguity_levels must be a non-negative finite number");
  if (o.threads < 1 || o.threads > 256)
    core::fail<std::invalid_argument>("threads must be 1..256, got " + std::to_string(o.threads));
}

PoseSearchResult search_pose_grid(const LocalizationMap& map,
                                  std::span<const RangeReading> screening,
                                  std::span<const RangeReading> verification,
                                  const core::Pose2& sensor_mount, const PoseSearchOptions& options,
                                  PoseScores* scores) {
  check_pose_search_options(options);
  const std::unique_ptr<ScanEvidence> evidence =
      make_evidence(map, screening, verification, false, options.threads);
  const FusedScan scan{evidence.get(), core::Pose2{}, true};
  PoseSearchResult result =
      search_from_sums(map, evidence->sums, std::span(&scan, 1), sensor_mount, options);
  if (scores)
    *scores = {GlobalMethod::pose_grid,
               detail::in_pose_layout(map, std::span<const std::int32_t>(evidence->sums),
                                      std::numeric_limits<std::int32_t>::min()),
               {}};
  return result;
}

PoseHypothesis refine_pose(const LocalizationMap& map, std::span<const RangeReading> screening,
                           std::span<const RangeReading> verification, const core::Pose2& sensor,
                           const core::Pose2& sensor_mount) {
  if (map.config().refine_levels < 1)
    core::fail<std::invalid_argument>("refine_levels: refine_pose needs at least one level");
  if (!std::isfinite(sensor.x) || !std::isfinite(sensor.y) || !std::isfinite(sensor.theta))
    core::fail<std::invalid_argument>("sensor: the pose must be finite");
  const std::unique_ptr<ScanEvidence> evidence =
      make_evidence(map, screening, verification, false, 1);
  const FusedScan scan{evidence.get(), core::Pose2{}, true};
  const Verified v = refine(map, std::span(&scan, 1), map.fine().fine_pose(sensor));
  PoseHypothesis h;
  h.sensor = v.sensor;
  h.robot = detail::robot_of(v.sensor, sensor_mount);
  h.score = v.score;
  h.ties = v.ties;
  return h;
}

// ---------------------------------------------------------------------------------------------
// Sequences

PoseTracker::PoseTracker(const LocalizationMap& map, const PoseSearchOptions& options,
                         std::size_t max_scans)
    : map_(&map), options_(options), max_scans_(max_scans) {
  check_pose_search_options(options);
  if (max_scans < 1 || max_scans > 1000)
    core::fail<std::invalid_argument>("max_scans must be 1..1000, got " +
                                      std::to_string(max_scans));
  // Each scan's sums, and the fused ones, beside the map's tables (which count one scan's).
  const double bytes = double(map.memory_bytes()) +
                       double(max_scans) * double(map.candidate_cells()) * sizeof(std::int32_t);
  const std::size_t limit = map.config().memory_limit;
  if (bytes > double(limit))
    core::fail<std::invalid_argument>(
        "memory_limit: fusing " + std::to_string(max_scans) + " scans over " +
        std::to_string(map.candidate_cells()) + " candidate pose cells needs about " +
        std::to_string(static_cast<long long>(std::ceil(bytes / 1e6))) + " MB, above the " +
        std::to_string(limit / 1000000) + " MB limit: fewer scans or a coarser pose grid");
}

PoseTracker::~PoseTracker() = default;
PoseTracker::PoseTracker(PoseTracker&&) noexcept = default;
PoseTracker& PoseTracker::operator=(PoseTracker&&) noexcept = default;

void PoseTracker::add_scan(std::span<const RangeReading> screening,
                           std::span<const RangeReading> verification, const core::Pose2& motion) {
  if (evidence_.size() >= max_scans_)
    core::fail<std::invalid_argument>("max_scans: " + std::to_string(max_scans_) +
                                      " scans are fused already");
  if (!std::isfinite(motion.x) || !std::isfinite(motion.y) || !std::isfinite(motion.theta))
    core::fail<std::invalid_argument>("motion must be finite");
  sensor_.push_back(sensor_.empty() ? core::Pose2{} : core::compose(sensor_.back(), motion));
  evidence_.push_back(make_evidence(*map_, screening, verification, true, options_.threads));
}

namespace {
std::vector<FusedScan> fused_scans(const std::vector<std::unique_ptr<ScanEvidence>>& evidence,
                                   const std::vector<core::Pose2>& sensor) {
  std::vector<FusedScan> scans;
  scans.push_back({evidence.back().get(), core::Pose2{}, true});
  for (std::size_t s = 0; s + 1 < evidence.size(); ++s)
    scans.push_back({evidence[s].get(), core::relative(sensor.back(), sensor[s]), false});
  return scans;
}
}  // namespace

PoseScores PoseTracker::fused_scores() const {
  if (evidence_.empty()) core::fail<std::invalid_argument>("scans: none fused yet");
  const std::vector<std::int32_t> sums =
      fuse_sums(*map_, fused_scans(evidence_, sensor_), options_.threads);
  return {GlobalMethod::pose_grid,
          detail::in_pose_layout(*map_, std::span<const std::int32_t>(sums),
                                 std::numeric_limits<std::int32_t>::min()),
          {}};
}

PoseSearchResult PoseTracker::search(const core::Pose2& sensor_mount) const {
  if (evidence_.empty()) core::fail<std::invalid_argument>("scans: none fused yet");
  const std::vector<FusedScan> scans = fused_scans(evidence_, sensor_);
  const std::vector<std::int32_t> sums = fuse_sums(*map_, scans, options_.threads);
  return search_from_sums(*map_, sums, scans, sensor_mount, options_);
}

}  // namespace intgrid::localization
