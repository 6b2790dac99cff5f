#include "intgrid/localization/global_localization.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "intgrid/core/failure.hpp"
#include "intgrid/core/map_distance.hpp"
#include "intgrid/core/parallel.hpp"
#include "intgrid/core/resolution.hpp"
#include "intgrid/core/sensor_model.hpp"
#include "intgrid/localization/claim_table.hpp"
#include "search_support.hpp"

namespace intgrid::localization {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

bool finite_positive(double v) {
  return std::isfinite(v) && v > 0.0;
}

// What is wrong with a reading, or nullptr if it can be used.
const char* reading_problem(const RangeReading& r, double max_range) {
  if (!finite_positive(r.range)) return "reading range must be a positive finite number";
  if (r.range >= max_range) return "reading range must be below max_range";
  if (!std::isfinite(r.bearing)) return "reading bearing must be finite";
  return nullptr;
}

bool usable(const RangeReading& r, double max_range) {
  return reading_problem(r, max_range) == nullptr;
}

void check_reading(const RangeReading& r, double max_range) {
  if (const char* problem = reading_problem(r, max_range))
    core::fail<std::invalid_argument>(problem);
}

const GlobalLocConfig& checked(const GlobalLocConfig& c) {
  check_global_loc_config(c);
  return c;
}

// The refusal of tables that would exceed the limit, before they are allocated; `hint` (empty or
// ": ...") says what makes them smaller.
[[noreturn]] void refuse_memory(const std::string& what, double bytes, std::size_t limit,
                                const std::string& hint = "") {
  core::fail<std::invalid_argument>("memory_limit: " + what + " needs about " +
                                    std::to_string(static_cast<long long>(std::ceil(bytes / 1e6))) +
                                    " MB, above the " + std::to_string(limit / 1000000) +
                                    " MB limit" + hint);
}

// Heading bin of a bearing: round(bearing / bin) mod headings.
int bearing_shift(double bearing, double bin, int headings) {
  const long long s = std::llround(bearing / bin) % headings;
  return static_cast<int>(s < 0 ? s + headings : s);
}

}  // namespace

void check_global_loc_config(const GlobalLocConfig& c) {
  using core::require_field;
  const auto positive = [](double v, const char* name) {
    require_field(finite_positive(v), name, "must be a positive finite number");
  };
  const auto weight = [](double v, const char* name) {
    require_field(v >= 0.0 && std::isfinite(v), name, "must be a non-negative finite number");
  };
  positive(c.pose_res, "pose_res");
  require_field(c.headings >= 4 && c.headings <= 4096, "headings",
                "must be 4..4096, got " + std::to_string(c.headings));
  core::check_range_sensor(c.sensor, "sensor");
  require_field(c.seps_bits >= 2 && c.seps_bits <= 16, "seps_bits",
                "must be 2..16, got " + std::to_string(c.seps_bits));
  require_field(c.seps_levels >= 1 && c.seps_levels <= core::max_index_for_bits(c.seps_bits),
                "seps_levels",
                "must be 1.." + std::to_string(core::max_index_for_bits(c.seps_bits)) + ", got " +
                    std::to_string(c.seps_levels));
  require_field(c.veto_levels >= 0 && c.veto_levels <= c.seps_levels, "veto_levels",
                "must be 0..seps_levels, got " + std::to_string(c.veto_levels));
  positive(c.z_hit, "z_hit");
  weight(c.z_short, "z_short");
  weight(c.z_max, "z_max");
  weight(c.z_rand, "z_rand");
  positive(c.lambda_short, "lambda_short");
  require_field(
      c.refine_levels >= 0 && c.refine_levels <= 8 && (c.headings << c.refine_levels) <= 65536,
      "refine_levels",
      "must be 0..8 and keep headings x 2^levels at most 65536, got " +
          std::to_string(c.refine_levels));
}

std::vector<RangeReading> readings_of(const core::Scan& scan, int beams, double max_range) {
  std::vector<RangeReading> valid;
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const RangeReading r{scan.ranges[i], scan.bearing(i)};
    if (scan.is_valid_range(r.range) && usable(r, max_range)) valid.push_back(r);
  }
  if (beams <= 0 || static_cast<std::size_t>(beams) >= valid.size()) return valid;
  std::vector<RangeReading> out;
  const auto n = valid.size(), b = static_cast<std::size_t>(beams);
  for (std::size_t i = 0; i < b; ++i) out.push_back(valid[i * n / b]);
  return out;
}

namespace detail {
std::vector<RangeReading> usable_readings(std::span<const RangeReading> readings,
                                          double max_range) {
  std::vector<RangeReading> used;
  for (const RangeReading& r : readings)
    if (usable(r, max_range)) used.push_back(r);
  return used;
}
}  // namespace detail

// ---------------------------------------------------------------------------------------------
// The map

LocalizationMap::LocalizationMap(const core::ProbabilityGrid& map, double occupied_threshold,
                                 double free_threshold, const GlobalLocConfig& config)
    : config_(checked(config)) {
  const core::GridGeometry& g = map.geometry;
  core::check_geometry(g);
  if (map.cells.size() != g.size())
    core::fail<std::invalid_argument>("map: its cell count differs from its geometry");
  if (!(occupied_threshold > 0.0 && occupied_threshold <= 1.0))
    core::fail<std::invalid_argument>("occupied_threshold must lie in (0, 1]");
  if (!(free_threshold >= 0.0 && free_threshold < occupied_threshold))
    core::fail<std::invalid_argument>("free_threshold must lie in [0, occupied_threshold)");
  const double r = g.resolution, R = config_.pose_res;
  if (R < r)
    core::fail<std::invalid_argument>("pose_res: pose resolution " + std::to_string(R) +
                                      " is finer than the map's " + std::to_string(r));
  occupied_threshold_ = occupied_threshold;
  free_threshold_ = free_threshold;
  origin_x_ = g.origin_x;
  origin_y_ = g.origin_y;
  map_geometry_ = g;

  // The pose cell holding each map column's and row's centre.
  const auto pose_index = [&](int a) { return static_cast<int>(std::floor((a + 0.5) * r / R)); };
  std::vector<int> px(static_cast<std::size_t>(g.width)), py(static_cast<std::size_t>(g.height));
  for (int a = 0; a < g.width; ++a) px[std::size_t(a)] = pose_index(a);
  for (int b = 0; b < g.height; ++b) py[std::size_t(b)] = pose_index(b);
  width_ = px.back() + 1;
  height_ = py.back() + 1;
  if (width_ >= 0xFFFF || height_ >= 0xFFFF)
    core::fail<std::invalid_argument>(
        "pose_res: the pose lattice has 65535 cells or more along an axis");

  const std::size_t wh = std::size_t(width_) * std::size_t(height_);
  std::vector<std::uint8_t> any_occupied(wh, 0), all_free(wh, 1);
  for (int b = 0; b < g.height; ++b)
    for (int a = 0; a < g.width; ++a) {
      const double p = map.cells[g.index(a, b)];
      const std::size_t xy =
          std::size_t(py[std::size_t(b)]) * std::size_t(width_) + std::size_t(px[std::size_t(a)]);
      if (p >= occupied_threshold) any_occupied[xy] = 1;
      if (!(p <= free_threshold)) all_free[xy] = 0;
    }
  class_.resize(wh);
  for (std::size_t xy = 0; xy < wh; ++xy) {
    class_[xy] = any_occupied[xy] ? PoseCellClass::occupied
                 : all_free[xy]   ? PoseCellClass::free
                                  : PoseCellClass::unknown;
    free_cells_ += class_[xy] == PoseCellClass::free;
  }
  const bool map_has_free_cell = std::any_of(map.cells.begin(), map.cells.end(),
                                             [&](double p) { return p <= free_threshold; });
  if (free_cells_ == 0 && map_has_free_cell)
    core::fail<std::invalid_argument>("pose_res: " + core::number_text(R) +
                                      " m pose cells are too coarse for this map: no free pose "
                                      "cell (none holds free map cells only)");
  if (free_cells_ == 0)
    core::fail<std::invalid_argument>(
        "map: no free pose cell (every pose cell holds a map cell above " +
        std::to_string(free_threshold) + ")");

  // What the tables and one scan's scores will take, checked before they are allocated: the
  // first hits and index sums per candidate pose cell, the line offsets, at most one source per
  // occupied cell and direction, the per-position indices, the distance transform, the fine map,
  // and one scan's scores laid out over every pose cell (detail::in_pose_layout, for the first
  // scan's pose grid and the tracker's fused scores: doubles for the baselines).
  const auto headings = std::size_t(config_.headings);
  const std::size_t occupied_cells =
      static_cast<std::size_t>(std::count(class_.begin(), class_.end(), PoseCellClass::occupied));
  const double bytes =
      double(free_cells_) * double(headings) * double(kBytesPerCandidatePoseCell) +
      double(headings) * (double(std::max(width_, height_)) * 4.0 +
                          double(occupied_cells) * double(sizeof(Source))) +
      double(wh) * double(sizeof(std::int32_t)) + double(free_cells_) * 4.0 +
      double(wh) * double(headings) * double(sizeof(double)) +
      double(g.size()) * double(sizeof(double)) +
      (config_.refine_levels > 0
           ? double(FineMap::bytes_for(g, config_.headings << config_.refine_levels))
           : 0.0);
  if (bytes > double(config_.memory_limit))
    refuse_memory("a pose grid of " + std::to_string(width_) + " x " + std::to_string(height_) +
                      " cells x " + std::to_string(headings) + " heading bins (" +
                      std::to_string(free_cells_ * headings) + " candidate pose cells, " +
                      std::to_string(kBytesPerCandidatePoseCell) + " bytes each, and " +
                      std::to_string(wh * headings) + " pose cells of scores, 8 bytes each)",
                  bytes, config_.memory_limit, ": a coarser pose cell or fewer headings");
  memory_bytes_ = static_cast<std::size_t>(bytes);
  candidate_of_.assign(wh, -1);
  candidates_.reserve(free_cells_);
  for (std::size_t xy = 0; xy < wh; ++xy)
    if (class_[xy] == PoseCellClass::free) {
      candidate_of_[xy] = static_cast<std::int32_t>(candidates_.size());
      candidates_.push_back(static_cast<std::uint32_t>(xy));
    }

  // Directions, their step groups, then their lines.
  directions_.resize(std::size_t(config_.headings));
  std::vector<long long> group_key;
  for (int d = 0; d < config_.headings; ++d) {
    Direction& dir = directions_[std::size_t(d)];
    const double angle = 2.0 * std::numbers::pi * d / config_.headings;
    const double c = std::cos(angle), s = std::sin(angle);
    dir.x_major = std::abs(c) >= std::abs(s);
    dir.sign = (dir.x_major ? c : s) > 0.0 ? 1 : -1;
    dir.slope = std::llround(std::ldexp(dir.x_major ? s / c : c / s, kSlopeBits));
    const double major = std::max(std::abs(c), std::abs(s));
    const long long key = std::llround(major * 1e9);
    const auto it = std::find(group_key.begin(), group_key.end(), key);
    dir.step_group = static_cast<int>(it - group_key.begin());
    if (it == group_key.end()) {
      group_key.push_back(key);
      group_step_.push_back(R / major);
    }
    dir.step = group_step_[std::size_t(dir.step_group)];
    build_direction(d);
  }

  // The likelihood field's distances: a distance transform of the occupied map cells.
  std::vector<char> occupied(g.size());
  for (std::size_t q = 0; q < occupied.size(); ++q)
    occupied[q] = map.cells[q] >= occupied_threshold;
  std::vector<double> f = core::squared_distance_transform(occupied, g.width, g.height);
  for (double& e : f) e = std::sqrt(e) * r;  // infinity stays infinity
  occupied_distance_ = std::move(f);
  if (config_.refine_levels > 0)
    fine_ =
        FineMap(map, occupied_threshold, free_threshold, config_.headings << config_.refine_levels);
}

void LocalizationMap::build_direction(int d) {
  Direction& dir = directions_[std::size_t(d)];
  const int major_len = dir.x_major ? width_ : height_;
  const int minor_len = dir.x_major ? height_ : width_;
  dir.offset.resize(std::size_t(major_len));
  const std::int64_t half = std::int64_t{1} << (kSlopeBits - 1);
  for (int u = 0; u < major_len; ++u)
    dir.offset[std::size_t(u)] = static_cast<std::int32_t>((u * dir.slope + half) >> kSlopeBits);
  const auto [lo, hi] = std::minmax_element(dir.offset.begin(), dir.offset.end());
  dir.first_hit.assign(candidates_.size(), kNoHit);
  dir.sources.clear();

  std::vector<std::size_t> cells;  // one line's xy cells in the rays' order
  std::vector<int> majors;
  for (int line = -*hi; line <= minor_len - 1 - *lo; ++line) {
    cells.clear();
    majors.clear();
    for (int t = 0; t < major_len; ++t) {
      const int u = dir.sign > 0 ? t : major_len - 1 - t;
      const int v = line + dir.offset[std::size_t(u)];
      if (v < 0 || v >= minor_len) continue;
      cells.push_back(dir.x_major ? std::size_t(v) * std::size_t(width_) + std::size_t(u)
                                  : std::size_t(u) * std::size_t(width_) + std::size_t(v));
      majors.push_back(u);
    }
    // One pass: at each occupied cell, the cells since the previous one learn their first hit,
    // and the cell is a live source if a free cell lies among them.
    std::ptrdiff_t previous = -1;
    bool free_seen = false;
    for (std::size_t t = 0; t < cells.size(); ++t) {
      const PoseCellClass cls = class_[cells[t]];
      if (cls == PoseCellClass::free) {
        free_seen = true;
      } else if (cls == PoseCellClass::occupied) {
        for (auto s = std::size_t(previous + 1); s < t; ++s)
          if (class_[cells[s]] == PoseCellClass::free)
            dir.first_hit[std::size_t(candidate_of_[cells[s]])] = static_cast<std::uint16_t>(t - s);
        if (free_seen)
          dir.sources.push_back(
              {line, majors[t], static_cast<std::int32_t>(std::ptrdiff_t(t) - previous - 1)});
        previous = std::ptrdiff_t(t);
        free_seen = false;
      }
    }
  }
}

std::size_t LocalizationMap::pose_cells() const {
  return std::size_t(width_) * std::size_t(height_) * std::size_t(config_.headings);
}

std::size_t LocalizationMap::candidate_cells() const {
  return free_cells_ * std::size_t(config_.headings);
}

core::Pose2 LocalizationMap::pose_of(int i, int j, int k) const {
  return {origin_x_ + (i + 0.5) * config_.pose_res, origin_y_ + (j + 0.5) * config_.pose_res,
          core::wrap_angle(k * heading_bin())};
}

std::size_t LocalizationMap::index(int i, int j, int k) const {
  return (std::size_t(k) * std::size_t(height_) + std::size_t(j)) * std::size_t(width_) +
         std::size_t(i);
}

double LocalizationMap::heading_bin() const {
  return 2.0 * std::numbers::pi / config_.headings;
}

bool LocalizationMap::x_major(int d) const {
  return directions_.at(std::size_t(d)).x_major;
}
int LocalizationMap::major_sign(int d) const {
  return directions_.at(std::size_t(d)).sign;
}
std::int64_t LocalizationMap::slope_fixed(int d) const {
  return directions_.at(std::size_t(d)).slope;
}
double LocalizationMap::step_length(int d) const {
  return directions_.at(std::size_t(d)).step;
}
std::size_t LocalizationMap::live_sources(int d) const {
  return directions_.at(std::size_t(d)).sources.size();
}

std::vector<std::array<int, 2>> LocalizationMap::line_through(int i, int j, int d) const {
  const Direction& dir = directions_.at(std::size_t(d));
  const int major_len = dir.x_major ? width_ : height_;
  const int minor_len = dir.x_major ? height_ : width_;
  const int u0 = dir.x_major ? i : j, v0 = dir.x_major ? j : i;
  const int line = v0 - dir.offset[std::size_t(u0)];
  std::vector<std::array<int, 2>> out;
  for (int t = 0; t < major_len; ++t) {
    const int u = dir.sign > 0 ? t : major_len - 1 - t;
    const int v = line + dir.offset[std::size_t(u)];
    if (v < 0 || v >= minor_len) continue;
    out.push_back(dir.x_major ? std::array<int, 2>{u, v} : std::array<int, 2>{v, u});
  }
  return out;
}

std::uint16_t LocalizationMap::first_hit_steps(int i, int j, int d) const {
  const std::int32_t c = candidate_index(i, j);
  return c < 0 ? kNoHit : directions_.at(std::size_t(d)).first_hit[std::size_t(c)];
}

std::span<const std::uint16_t> LocalizationMap::first_hit_table(int d) const {
  return directions_.at(std::size_t(d)).first_hit;
}

double LocalizationMap::distance_to_occupied(double x, double y) const {
  const int a = map_geometry_.cell_x(x), b = map_geometry_.cell_y(y);
  if (!map_geometry_.contains(a, b)) return kInfinity;
  return occupied_distance_[map_geometry_.index(a, b)];
}

double LocalizationMap::effective_sigma(double z) const {
  return std::hypot(config_.sensor.sigma, config_.pose_res, heading_bin() * z);
}

template <class Score>
BasicReadingClaims<Score> LocalizationMap::make_claims(const RangeReading& reading) const {
  check_reading(reading, config_.sensor.max_range);
  BasicReadingClaims<Score> out;
  out.sigma_eff = effective_sigma(reading.range);
  out.shift = bearing_shift(reading.bearing, heading_bin(), config_.headings);
  // No first hit is farther than the longest line: longer tables would only hold unused claims.
  const std::size_t longest = std::size_t(std::max(width_, height_));
  std::vector<std::vector<Score>> group_claims(group_step_.size());
  std::vector<Score> group_top(group_step_.size(), 0);
  for (std::size_t gi = 0; gi < group_step_.size(); ++gi) {
    ClaimTable<Score> table = claim_table<Score>(reading.range, out.sigma_eff, group_step_[gi],
                                                 config_.seps_levels, config_.veto_levels, longest);
    group_claims[gi] = std::move(table.claim);
    group_top[gi] = table.top;
  }
  out.claim.resize(std::size_t(config_.headings));
  out.n_top.resize(std::size_t(config_.headings));
  for (std::size_t d = 0; d < out.claim.size(); ++d) {
    const auto gi = std::size_t(directions_[d].step_group);
    out.claim[d] = group_claims[gi];
    out.n_top[d] = group_top[gi];
  }
  return out;
}

ReadingClaims LocalizationMap::claims(const RangeReading& reading) const {
  return make_claims<std::int32_t>(reading);
}

LogOddsClaims LocalizationMap::log_odds_claims(const RangeReading& reading) const {
  return make_claims<double>(reading);
}

namespace {
template <class Score>
void check_claims(const LocalizationMap& map, const BasicReadingClaims<Score>& claims) {
  if (claims.claim.size() != std::size_t(map.headings()) || claims.shift < 0 ||
      claims.shift >= map.headings() ||
      std::any_of(claims.claim.begin(), claims.claim.end(),
                  [](const std::vector<Score>& t) { return t.empty() || t.back() != 0; }))
    core::fail<std::invalid_argument>("claims: not made for this map's headings");
}

template <class Score>
void check_pog(const LocalizationMap& map, const BasicReadingClaims<Score>& claims,
               std::size_t size) {
  if (size != map.pose_cells())
    core::fail<std::invalid_argument>("pog: its size differs from the pose grid's");
  check_claims(map, claims);
}
}  // namespace

template <class Score>
void LocalizationMap::add_reading_dense(const BasicReadingClaims<Score>& claims,
                                        std::span<std::type_identity_t<Score>> pog) const {
  check_pog(*this, claims, pog.size());
  const std::size_t wh = std::size_t(width_) * std::size_t(height_);
  const int headings = config_.headings;
  for (int k = 0; k < headings; ++k) {
    const auto d = std::size_t((k + claims.shift) % headings);
    // Every step count past the table (and kNoHit) reads the table's final 0: the loop has no
    // branch to mispredict (2.1x faster at 10^6).
    const Score* claim = claims.claim[d].data();
    const std::size_t past = claims.claim[d].size() - 1;
    const std::uint16_t* hit = directions_[d].first_hit.data();
    Score* out = pog.data() + std::size_t(k) * wh;
    for (std::size_t c = 0; c < candidates_.size(); ++c)
      out[candidates_[c]] += claim[std::min<std::size_t>(hit[c], past)];
  }
}

namespace {
// out[c] += claim[min(hit[c], past)]: the screening's inner loop. Where the processor has AVX2
// the compiler vectorizes the minimum and the additions around the table reads; the sums are the
// same integers either way.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx2", "default")))
#endif
void add_claims(std::int32_t* __restrict out, const std::uint16_t* __restrict hit, std::size_t n,
                const std::int32_t* __restrict claim, std::uint32_t past) {
  for (std::size_t c = 0; c < n; ++c) out[c] += claim[std::min<std::uint32_t>(hit[c], past)];
}
}  // namespace

void LocalizationMap::add_readings_candidates(std::span<const ReadingClaims> claims,
                                              std::span<std::int32_t> scores, int k_begin,
                                              int k_end) const {
  const std::size_t n = candidates_.size();
  const int headings = config_.headings;
  if (scores.size() != n * std::size_t(headings))
    core::fail<std::invalid_argument>("scores: its size differs from the candidate pose cells'");
  if (k_begin < 0 || k_end > headings || k_begin > k_end)
    core::fail<std::invalid_argument>("headings: the range lies outside the pose grid's");
  for (const ReadingClaims& c : claims) check_claims(*this, c);
  // A tile's sums (16 KB) and first hits (8 KB a reading) stay in the first-level cache while
  // every reading adds to it.
  constexpr std::size_t kTile = 4096;
  for (int k = k_begin; k < k_end; ++k) {
    std::int32_t* out = scores.data() + std::size_t(k) * n;
    for (std::size_t begin = 0; begin < n; begin += kTile) {
      const std::size_t end = std::min(n, begin + kTile);
      for (const ReadingClaims& r : claims) {
        const auto d = std::size_t((k + r.shift) % headings);
        const std::int32_t* claim = r.claim[d].data();
        const std::size_t past = r.claim[d].size() - 1;
        const std::uint16_t* hit = directions_[d].first_hit.data();
        add_claims(out + begin, hit + begin, end - begin, claim, std::uint32_t(past));
      }
    }
  }
}
template void LocalizationMap::add_reading_dense<std::int32_t>(const ReadingClaims&,
                                                               std::span<std::int32_t>) const;
template void LocalizationMap::add_reading_dense<double>(const LogOddsClaims&,
                                                         std::span<double>) const;

void LocalizationMap::add_reading_walk(const ReadingClaims& claims,
                                       std::span<std::int32_t> pog) const {
  check_pog(*this, claims, pog.size());
  const std::size_t wh = std::size_t(width_) * std::size_t(height_);
  const int headings = config_.headings;
  const auto w = std::size_t(width_);
  for (int k = 0; k < headings; ++k) {
    const auto d = std::size_t((k + claims.shift) % headings);
    const Direction& dir = directions_[d];
    const std::int32_t* claim = claims.claim[d].data();
    const auto last = static_cast<std::int32_t>(claims.claim[d].size()) - 1;
    std::int32_t* out = pog.data() + std::size_t(k) * wh;
    for (const Source& source : dir.sources) {
      const std::int32_t reach = std::min(source.run, last);
      for (std::int32_t rho = 1; rho <= reach; ++rho) {
        const std::int32_t u = source.major - dir.sign * rho;
        const std::int32_t v = source.line + dir.offset[std::size_t(u)];
        const std::size_t xy =
            dir.x_major ? std::size_t(v) * w + std::size_t(u) : std::size_t(u) * w + std::size_t(v);
        if (class_[xy] == PoseCellClass::free) out[xy] += claim[rho];
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Baselines

MarkovLocalization::MarkovLocalization(const LocalizationMap& map, GlobalMethod method)
    : map_(&map), method_(method) {
  if (method == GlobalMethod::pose_grid)
    core::fail<std::invalid_argument>("method: Markov localization needs a baseline method");
  // The two beliefs beside the map's tables, against the one limit (as PoseTracker counts).
  const double bytes =
      double(map.memory_bytes()) + 2.0 * sizeof(double) * double(map.candidate_cells());
  if (bytes > double(map.config().memory_limit))
    refuse_memory("Markov localization's two beliefs over " +
                      std::to_string(map.candidate_cells()) +
                      " candidate pose cells, beside the map's tables,",
                  bytes, map.config().memory_limit);
  belief_.assign(map.candidate_cells(), 1.0 / static_cast<double>(map.candidate_cells()));
  next_.assign(map.candidate_cells(), 0.0);
}

bool MarkovLocalization::update(const RangeReading& reading) {
  check_reading(reading, map_->config().sensor.max_range);
  const LocalizationMap& map = *map_;
  const GlobalLocConfig& c = map.config();
  const double z = reading.range;
  const double sigma = map.effective_sigma(z);
  const double norm = 1.0 / (sigma * std::sqrt(2.0 * std::numbers::pi));
  const double inv2var = 0.5 / (sigma * sigma);
  const double bin = map.heading_bin();
  const int shift = bearing_shift(reading.bearing, bin, c.headings);
  const double rand_term = z < c.sensor.max_range ? c.z_rand / c.sensor.max_range : 0.0;
  const double max_term = z >= c.sensor.max_range ? c.z_max : 0.0;
  const double short_density = c.lambda_short * std::exp(-c.lambda_short * z);
  const core::Pose2 corner = map.pose_of(0, 0, 0);  // centre of pose cell (0, 0)
  const std::span<const std::uint32_t> candidates = map.candidates();
  const std::size_t n = candidates.size(), w = std::size_t(map.width());
  double total = 0.0;
  for (int k = 0; k < c.headings; ++k) {
    const int d = (k + shift) % c.headings;
    const double step = map.step_length(d);
    const std::span<const std::uint16_t> hits = map.first_hit_table(d);
    const double angle = k * bin + reading.bearing;
    const double ca = std::cos(angle), sa = std::sin(angle);
    const double* bel = belief_.data() + std::size_t(k) * n;
    double* next = next_.data() + std::size_t(k) * n;
    for (std::size_t candidate = 0; candidate < n; ++candidate) {
      const std::size_t i = candidates[candidate] % w, j = candidates[candidate] / w;
      double p = 0.0;
      if (method_ == GlobalMethod::likelihood_field) {
        const double x = corner.x + double(i) * c.pose_res, y = corner.y + double(j) * c.pose_res;
        const double dist = map.distance_to_occupied(x + z * ca, y + z * sa);
        p = c.z_hit * norm * std::exp(-dist * dist * inv2var) + rand_term;
      } else {
        const std::uint16_t h = hits[candidate];
        const double expected = h == LocalizationMap::kNoHit
                                    ? c.sensor.max_range
                                    : std::min(h * step, c.sensor.max_range);
        const double e = z - expected;
        const double hit = norm * std::exp(-e * e * inv2var);
        if (method_ == GlobalMethod::markov) {
          p = hit;
        } else {
          p = c.z_hit * hit + rand_term + max_term;
          if (z <= expected)
            p += c.z_short * short_density / (1.0 - std::exp(-c.lambda_short * expected));
        }
      }
      const double b = bel[candidate] * p;
      next[candidate] = b;
      total += b;
    }
  }
  if (!(total > 0.0) || !std::isfinite(total)) {
    ++dropped_;
    return false;
  }
  const double eta = 1.0 / total;
  for (double& b : next_) b *= eta;
  belief_.swap(next_);
  return true;
}

// ---------------------------------------------------------------------------------------------
// The estimate

namespace {

// The mean of the tied best candidates' poses (headings by circular mean); is_best takes an
// element of the candidate layout.
template <class IsBest>
GlobalEstimate mean_of_best(const LocalizationMap& map, IsBest&& is_best) {
  double sx = 0.0, sy = 0.0, sc = 0.0, ss = 0.0;
  std::size_t count = 0;
  for (std::size_t q = 0; q < map.candidate_cells(); ++q) {
    if (!is_best(q)) continue;
    const auto [i, j, k] = map.candidate_cell(q);
    const core::Pose2 p = map.pose_of(i, j, k);
    sx += p.x;
    sy += p.y;
    sc += std::cos(p.theta);
    ss += std::sin(p.theta);
    ++count;
  }
  GlobalEstimate e;
  e.ties = count;
  const auto dn = static_cast<double>(count);
  e.sensor = {sx / dn, sy / dn, std::atan2(ss, sc)};
  return e;
}

}  // namespace

GlobalEstimate localize_global(const LocalizationMap& map, std::span<const RangeReading> readings,
                               const core::Pose2& sensor_mount, GlobalMethod method,
                               PoseScores* scores) {
  if (method == GlobalMethod::pose_grid)
    return search_pose_grid(map, readings, readings, sensor_mount, PoseSearchOptions{}, scores)
        .estimate;
  const std::vector<RangeReading> used =
      detail::usable_readings(readings, map.config().sensor.max_range);
  MarkovLocalization markov(map, method);
  for (const RangeReading& r : used) markov.update(r);
  const std::span<const double> belief = markov.belief();
  const double best = *std::max_element(belief.begin(), belief.end());
  GlobalEstimate estimate = mean_of_best(map, [&](std::size_t q) { return belief[q] == best; });
  estimate.score = best;
  estimate.readings_dropped = markov.dropped();
  if (scores) *scores = {method, {}, detail::in_pose_layout(map, belief, 0.0)};
  estimate.readings_used = used.size();
  estimate.robot = detail::robot_of(estimate.sensor, sensor_mount);
  return estimate;
}

GlobalEstimate localize_scan(const LocalizationMap& map, const core::Scan& scan, int beams,
                             GlobalMethod method, PoseScores* scores) {
  const std::vector<RangeReading> readings =
      readings_of(scan, beams, map.config().sensor.max_range);
  return localize_global(map, readings, scan.sensor_mount, method, scores);
}

}  // namespace intgrid::localization
