// The per-scan path of GridSlamEngine: included only by the files that instantiate it
// (grid_slam_engine_integer.cpp, grid_slam_engine_double.cpp). Integers only, apart from what the
// Probabilities type does; the integer instantiation is built without floating-point registers.
#pragma once

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "intgrid/core/failure.hpp"
#include "intgrid/slam/grid_slam_engine.hpp"
#include "intgrid/slam/probabilities.hpp"

namespace intgrid::slam {
namespace slam_detail {

using core::ray_detail::floor_div;

constexpr std::int64_t round_div(std::int64_t a, std::int64_t b) {
  return floor_div(2 * a + b, 2 * b);
}

using core::ray_detail::isqrt;

// The sum of n probabilities, pairwise: a running U_gamma sum stops growing once the total
// is some 45 times each term (Phi_plus is 0 past that gap), a pairwise one adds like terms.
template <class Pr>
typename Pr::P sum_pairwise(const Pr& pr, const typename Pr::P* p, std::size_t n) {
  if (n <= 4) {
    typename Pr::P total = pr.zero();
    for (std::size_t i = 0; i < n; ++i) total = pr.add(total, p[i]);
    return total;
  }
  return pr.add(sum_pairwise(pr, p, n / 2), sum_pairwise(pr, p + n / 2, n - n / 2));
}

}  // namespace slam_detail

template <class Pr>
std::size_t GridSlamEngine<Pr>::pose_index(int i, int j, int k) const {
  return (static_cast<std::size_t>(k) * static_cast<std::size_t>(n_) +
          static_cast<std::size_t>(j)) *
             static_cast<std::size_t>(n_) +
         static_cast<std::size_t>(i);
}

template <class Pr>
bool GridSlamEngine<Pr>::slice_is_empty(int k) const {
  const auto slice = pi_.begin() + static_cast<std::ptrdiff_t>(pose_index(0, 0, k));
  return std::all_of(slice, slice + n_ * n_, [&](P p) { return prob_.is_zero(p); });
}

template <class Pr>
SlamPose GridSlamEngine<Pr>::pose_of(std::size_t q) const {
  const std::size_t nn = static_cast<std::size_t>(n_) * static_cast<std::size_t>(n_);
  const auto i = static_cast<std::int64_t>(q % nn % static_cast<std::size_t>(n_));
  const auto j = static_cast<std::int64_t>(q % nn / static_cast<std::size_t>(n_));
  const auto k = static_cast<std::int64_t>(q / nn);
  const std::int64_t c = setup_.cell_mm;
  return {(ox_ + i) * c + fx_, (oy_ + j) * c + fy_, theta0_ + k * heading_unit()};
}

template <class Pr>
std::int64_t GridSlamEngine<Pr>::map_index(int cx, int cy) const {
  return std::int64_t{cy + setup_.origin_cell_y} * map_.geometry.width + cx + setup_.origin_cell_x;
}

template <class Pr>
void GridSlamEngine<Pr>::check_window_inside_map() const {
  // Every ray starts within the window plus the sensor mount and ends before max range.
  const std::int64_t mount =
      std::max(std::abs(setup_.sensor.mount_x_mm), std::abs(setup_.sensor.mount_y_mm));
  const std::int64_t reach =
      (setup_.max_range_mm + 3 * std::int64_t{setup_.sigma_mm} + 2 * mount) / setup_.cell_mm + 3;
  const std::int64_t x0 = ox_ + setup_.origin_cell_x - reach,
                     x1 = ox_ + n_ + setup_.origin_cell_x + reach;
  const std::int64_t y0 = oy_ + setup_.origin_cell_y - reach,
                     y1 = oy_ + n_ + setup_.origin_cell_y + reach;
  if (x0 < 0 || y0 < 0 || x1 >= map_.geometry.width || y1 >= map_.geometry.height)
    core::fail<std::runtime_error>(
        "SLAM: the pose window at cell (" + std::to_string(ox_ + n_ / 2) + ", " +
        std::to_string(oy_ + n_ / 2) + ") reached the edge of the map; raise the map margin");
}

template <class Pr>
void GridSlamEngine<Pr>::process(const QuantizedScan& scan) {
  if (scan.range_mm.size() != setup_.sensor.bearing.size())
    core::fail<std::invalid_argument>("SLAM: a scan has " + std::to_string(scan.range_mm.size()) +
                                      " ranges, the sensor " +
                                      std::to_string(setup_.sensor.bearing.size()));
  if (scans_ > 0) motion_update(scan);
  check_window_inside_map();
  const bool usable = std::any_of(scan.range_mm.begin(), scan.range_mm.end(),
                                  [&](std::int32_t r) { return r > 0 && r < setup_.max_range_mm; });
  if (!usable) {
    ++skipped_;
  } else {
    const GridSlamConfig& c = setup_.config;
    if (mappings_ > 0 && scans_ % static_cast<std::size_t>(c.schedule.lambda) == 0) {
      localize(scan);
      ++localizations_;
    }
    if (scans_ % static_cast<std::size_t>(c.schedule.xi) == 0) {
      map_scan(scan);
      ++mappings_;
    }
  }
  update_estimate();
  ++scans_;
}

template <class Pr>
void GridSlamEngine<Pr>::normalize() {
  const P total = slam_detail::sum_pairwise(prob_, pi_.data(), pi_.size());
  if (prob_.is_zero(total))
    core::fail<std::runtime_error>("SLAM: the pose grid lost all its probability");
  for (P& p : pi_) p = prob_.div(p, total);
}

// Pi'(x') = sum_x Pi(x) K(x' | x, u): for each source heading the displacement R(theta) u is
// applied to its (x, y) slice with a separable Gaussian, then spread over the target headings.
// The new window is centred on the predicted mean.
template <class Pr>
void GridSlamEngine<Pr>::motion_update(const QuantizedScan& scan) {
  using slam_detail::floor_div;
  using slam_detail::round_div;
  const std::int64_t dx = scan.odom_dx_mm, dy = scan.odom_dy_mm, dt = scan.odom_dtheta;
  const std::int64_t trans = slam_detail::isqrt(dx * dx + dy * dy);
  const std::int64_t rot = dt < 0 ? -dt : dt;
  const std::int64_t s_xy = std::max<std::int64_t>(
      1, setup_.motion_xy0_mm +
             ((setup_.motion_xy_per_mm_q16 * trans + setup_.motion_xy_per_unit_q16 * rot) >> 16));
  const std::int64_t s_t = std::max<std::int64_t>(
      1, setup_.motion_theta0 +
             ((setup_.motion_theta_per_mm_q16 * trans + setup_.motion_theta_per_unit_q16 * rot) >>
              16));
  const std::int64_t c = setup_.cell_mm;
  const std::int64_t unit = heading_unit();

  // The predicted mean, in mm and angle units, and the window centred on it.
  const auto mean_angle = static_cast<std::int32_t>(estimate_.theta_q8 >> 8);
  const auto [move_x, move_y] = rays().rotate(mean_angle, dx, dy);
  const std::int64_t x0 = round_div(estimate_.x_um, 1000) + move_x - (n_ / 2) * c;
  const std::int64_t y0 = round_div(estimate_.y_um, 1000) + move_y - (n_ / 2) * c;
  const std::int64_t theta0 = round_div(estimate_.theta_q8, 256) + dt - (nt_ / 2) * unit;
  const int nox = static_cast<int>(round_div(x0, c)), noy = static_cast<int>(round_div(y0, c));

  // A normalized kernel over index shifts m: error m * step + offset, within 3 sigma (and at
  // least the nearest shift); offset is the move of the origin less the odometry's. Only the
  // shifts that keep a window of `size` inside itself are kept (their storage is reserved once);
  // the total runs over all of them.
  const auto make_kernel = [&](std::vector<P>& k, std::int64_t offset, std::int64_t step,
                               std::int64_t sigma, std::int64_t size) {
    const std::int64_t reach = 3 * sigma + step;
    const std::int64_t lo = -floor_div(reach + offset, step);  // ceil((-reach - offset) / step)
    const std::int64_t hi = floor_div(reach - offset, step);
    const std::int64_t kept_lo = std::max(lo, 1 - size), kept_hi = std::min(hi, size - 1);
    k.clear();
    P total = prob_.zero();
    for (std::int64_t m = lo; m <= hi; ++m) {
      const std::int64_t e = m * step + offset;
      const P p = prob_.gaussian(e * e, sigma * sigma);
      if (m >= kept_lo && m <= kept_hi) k.push_back(p);
      total = prob_.add(total, p);
    }
    for (P& p : k) p = prob_.div(p, total);
    return kept_lo;
  };

  std::fill(next_.begin(), next_.end(), prob_.zero());
  const SlamPose origin = pose_of(0);  // the old window's
  const std::int64_t lo_t = make_kernel(kernel_t_, theta0 - origin.theta - dt, unit, s_t, nt_);
  const std::size_t nn = static_cast<std::size_t>(n_) * static_cast<std::size_t>(n_);
  for (int k = 0; k < nt_; ++k) {
    if (slice_is_empty(k)) continue;
    const P* slice = &pi_[pose_index(0, 0, k)];
    const auto [shift_x, shift_y] = rays().rotate(slice_angle(k), dx, dy);
    const std::int64_t lo_x = make_kernel(kernel_x_, x0 - origin.x_mm - shift_x, c, s_xy, n_);
    const std::int64_t lo_y = make_kernel(kernel_y_, y0 - origin.y_mm - shift_y, c, s_xy, n_);
    // Along x: row_[j][i'] = sum_i slice[j][i] K_x(i' - i).
    for (int j = 0; j < n_; ++j)
      for (int i2 = 0; i2 < n_; ++i2) {
        P sum = prob_.zero();
        for (std::size_t m = 0; m < kernel_x_.size(); ++m) {
          const std::int64_t i = i2 - (lo_x + static_cast<std::int64_t>(m));
          if (i < 0 || i >= n_) continue;
          sum = prob_.add(sum, prob_.mul(slice[j * n_ + i], kernel_x_[m]));
        }
        row_[static_cast<std::size_t>(j * n_ + i2)] = sum;
      }
    // Along y: plane_[j'][i'] = sum_j row_[j][i'] K_y(j' - j).
    for (int j2 = 0; j2 < n_; ++j2)
      for (int i2 = 0; i2 < n_; ++i2) {
        P sum = prob_.zero();
        for (std::size_t m = 0; m < kernel_y_.size(); ++m) {
          const std::int64_t j = j2 - (lo_y + static_cast<std::int64_t>(m));
          if (j < 0 || j >= n_) continue;
          sum =
              prob_.add(sum, prob_.mul(row_[static_cast<std::size_t>(j * n_ + i2)], kernel_y_[m]));
        }
        plane_[static_cast<std::size_t>(j2 * n_ + i2)] = sum;
      }
    // Over the headings.
    for (std::size_t m = 0; m < kernel_t_.size(); ++m) {
      const std::int64_t k2 = k + lo_t + static_cast<std::int64_t>(m);
      if (k2 < 0 || k2 >= nt_) continue;
      P* target = &next_[pose_index(0, 0, static_cast<int>(k2))];
      for (std::size_t q = 0; q < nn; ++q)
        target[q] = prob_.add(target[q], prob_.mul(plane_[q], kernel_t_[m]));
    }
  }
  std::swap(pi_, next_);
  ox_ = nox;
  oy_ = noy;
  fx_ = x0 - nox * c;
  fy_ = y0 - noy * c;
  theta0_ = theta0;
  normalize();
}

// Pi(x) <- Pi(x) prod_k p(z_k | x, M), p(z | x, M) = floor + sum_c p(z | d_c) P_M(o_c)
// prod_{c' before c} P_M(e_c'). The rays of each heading are walked once per scan; a pose
// then reads the map along them at its own cell.
template <class Pr>
void GridSlamEngine<Pr>::localize(const QuantizedScan& scan) {
  const GridSlamConfig& config = setup_.config;
  const std::size_t count = scan.range_mm.size();
  const std::size_t stride =
      std::max<std::size_t>(1, (count + static_cast<std::size_t>(config.beam.beams) - 1) /
                                   static_cast<std::size_t>(config.beam.beams));
  const std::int64_t sigma = setup_.sigma_mm, window = 3 * sigma;
  const std::int64_t width = map_.geometry.width;
  const core::IntegerRays rays = this->rays();
  ray_offsets_.clear();
  ray_likelihoods_.clear();
  scan_rays_.clear();
  for (int k = 0; k < nt_; ++k) {
    heading_rays_[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(scan_rays_.size());
    // A heading no pose holds needs no rays: once pruned, the poses lie within the motion
    // model's reach of the mean, a few bins of a wide window.
    if (slice_is_empty(k)) continue;
    const std::int32_t a = slice_angle(k);
    const auto [mx, my] = rays.rotate(a, setup_.sensor.mount_x_mm, setup_.sensor.mount_y_mm);
    for (std::size_t b = stride / 2; b < count; b += stride) {
      const std::int64_t z = scan.range_mm[b];
      if (z <= 0 || z >= setup_.max_range_mm) continue;
      Ray ray{static_cast<std::uint32_t>(ray_offsets_.size()), 0, 0, static_cast<std::int32_t>(z)};
      bool near = false;
      rays.walk(mx + fx_, my + fy_, a + setup_.sensor.mount_theta + setup_.sensor.bearing[b],
                z + window, [&](int cx, int cy, std::int64_t d) {
                  if (!near && d >= z - window) {
                    near = true;
                    ray.mid = static_cast<std::uint32_t>(ray_offsets_.size());
                  }
                  ray_offsets_.push_back(static_cast<std::int32_t>(cy * width + cx));
                  ray_likelihoods_.push_back(near ? prob_.gaussian((z - d) * (z - d), sigma * sigma)
                                                  : prob_.zero());
                });
      if (!near) ray.mid = static_cast<std::uint32_t>(ray_offsets_.size());
      ray.end = static_cast<std::uint32_t>(ray_offsets_.size());
      scan_rays_.push_back(ray);
    }
  }
  heading_rays_[static_cast<std::size_t>(nt_)] = static_cast<std::uint32_t>(scan_rays_.size());

  // A slice's poses above zero, in their bounding box, are scored together: a ray's empty
  // product is taken one ray cell at a time over the box's rows of P_M(e) (poses one cell apart
  // read neighbouring cells), each pose's factors in its own ray's order.
  const std::int8_t* cells = map_.cells.data();
  for (int k = 0; k < nt_; ++k) {
    int i0 = n_, i1 = -1, j0 = n_, j1 = -1;
    for (int j = 0; j < n_; ++j)
      for (int i = 0; i < n_; ++i)
        if (!prob_.is_zero(pi_[pose_index(i, j, k)])) {
          i0 = std::min(i0, i), i1 = std::max(i1, i);
          j0 = std::min(j0, j), j1 = std::max(j1, j);
        }
    if (i1 < 0) continue;
    const int box_w = i1 - i0 + 1, box_h = j1 - j0 + 1;
    const std::size_t box = static_cast<std::size_t>(box_w) * static_cast<std::size_t>(box_h);
    const std::int64_t corner = map_index(ox_ + i0, oy_ + j0);
    std::fill_n(joints_.begin(), box, typename Pr::Joint{});
    for (std::uint32_t r = heading_rays_[static_cast<std::size_t>(k)];
         r < heading_rays_[static_cast<std::size_t>(k) + 1]; ++r) {
      const Ray& ray = scan_rays_[r];
      std::fill_n(empty_products_.begin(), box, prob_.empty_product_start());
      for (std::uint32_t e = ray.begin; e < ray.mid; ++e) {
        const auto* cell_empty = cell_empty_.data() + corner + ray_offsets_[e];
        for (int j = 0; j < box_h; ++j) {
          Pr::multiply_empty(&empty_products_[static_cast<std::size_t>(j * box_w)],
                             cell_empty + std::int64_t{j} * width, box_w);
        }
      }
      for (int j = 0; j < box_h; ++j)
        for (int i = 0; i < box_w; ++i) {
          if (prob_.is_zero(pi_[pose_index(i0 + i, j0 + j, k)])) continue;
          const std::size_t q = static_cast<std::size_t>(j * box_w + i);
          const std::int8_t* base = cells + corner + std::int64_t{j} * width + i;
          P empty_before = prob_.empty_product(empty_products_[q]);
          P sum = prob_.zero();
          for (std::uint32_t e = ray.mid; e < ray.end; ++e) {
            const int n = base[ray_offsets_[e]];
            sum = prob_.add(
                sum, prob_.mul(prob_.mul(ray_likelihoods_[e], prob_.occupied(n)), empty_before));
            empty_before = prob_.mul(empty_before, prob_.empty(n));
          }
          prob_.multiply_into(joints_[q], prob_.add(sum, prob_.floor));
        }
    }
    for (int j = 0; j < box_h; ++j)
      for (int i = 0; i < box_w; ++i) {
        P& pose = pi_[pose_index(i0 + i, j0 + j, k)];
        if (prob_.is_zero(pose)) continue;
        pose = prob_.mul(pose, prob_.root_of(joints_[static_cast<std::size_t>(j * box_w + i)],
                                             config.beam.tempering));
      }
  }
  normalize();
  for (P& p : pi_)
    if (prob_.below_prune(p)) p = prob_.zero();
}

// The scan's indices seen from the window's offset in the SLAM-frame cell (cx, cy), heading
// `a`: for every usable
// reading, the precomputed narrow ISM laid along its ray; indices of one cell add up.
template <class Pr>
void GridSlamEngine<Pr>::add_pose_scan(int cx, int cy, std::int32_t a, const QuantizedScan& scan) {
  const core::IntegerRays rays = this->rays();
  const auto [mx, my] = rays.rotate(a, setup_.sensor.mount_x_mm, setup_.sensor.mount_y_mm);
  const std::int64_t base = map_index(cx, cy), width = map_.geometry.width;
  core::for_each_ism_cell(
      rays, setup_.ism, mx + fx_, my + fy_, a + setup_.sensor.mount_theta, setup_.sensor.bearing,
      scan.range_mm, setup_.max_range_mm, [&](int ix, int iy, std::int8_t n) {
        const auto cell = static_cast<std::size_t>(base + std::int64_t{iy} * width + ix);
        std::int16_t& sum = scan_image_[cell];
        if (sum == 0) touched_.push_back(static_cast<std::int32_t>(cell));
        sum = static_cast<std::int16_t>(
            std::clamp(sum + n, -setup_.max_seps_index, setup_.max_seps_index));
      });
}

// P(o_c | z, Pi) = sum_x Pi(x) ISM_x(c) over the poses above the cut-off (renormalized), cells
// a pose's scan does not reach counting 1/2 for it, fused into M. With one pose the sum is that
// pose's ISM.
template <class Pr>
void GridSlamEngine<Pr>::map_scan(const QuantizedScan& scan) {
  std::vector<std::pair<std::size_t, P>> poses;
  std::size_t mode = 0;
  for (std::size_t q = 0; q < pi_.size(); ++q) {
    if (prob_.more_probable(pi_[q], pi_[mode])) mode = q;
    if (!prob_.below_cutoff(pi_[q])) poses.emplace_back(q, pi_[q]);
  }
  if (poses.empty()) poses.emplace_back(mode, prob_.one());
  P total = prob_.zero();
  for (const auto& pose : poses) total = prob_.add(total, pose.second);
  const int max = setup_.max_seps_index;
  std::int8_t* cells = map_.cells.data();
  const auto fuse_into_map = [&](std::int32_t cell, int n) {
    cells[cell] = static_cast<std::int8_t>(std::clamp(cells[cell] + n, -max, max));
    cell_empty_[static_cast<std::size_t>(cell)] = prob_.empty_factor(cells[cell]);
  };
  const std::size_t nn = static_cast<std::size_t>(n_) * static_cast<std::size_t>(n_);
  for (const auto& [q, p] : poses) {
    const int k = static_cast<int>(q / nn), j = static_cast<int>(q % nn) / n_,
              i = static_cast<int>(q % nn) % n_;
    add_pose_scan(ox_ + i, oy_ + j, slice_angle(k), scan);
    const P w = prob_.div(p, total);
    for (const std::int32_t cell : touched_) {
      const int n = scan_image_[static_cast<std::size_t>(cell)];
      if (n == 0) continue;  // an index 0 says 1/2: the same as not reaching the cell
      scan_image_[static_cast<std::size_t>(cell)] = 0;
      if (poses.size() == 1) {
        fuse_into_map(cell, n);
        continue;
      }
      std::int32_t& slot = slot_[static_cast<std::size_t>(cell)];
      if (slot < 0) {
        slot = static_cast<std::int32_t>(mix_cells_.size());
        mix_cells_.push_back(cell);
        mix_occupied_.push_back(prob_.zero());
        mix_empty_.push_back(prob_.zero());
        mix_weight_.push_back(prob_.zero());
      }
      const auto s = static_cast<std::size_t>(slot);
      mix_occupied_[s] = prob_.add(mix_occupied_[s], prob_.mul(w, prob_.occupied(n)));
      mix_empty_[s] = prob_.add(mix_empty_[s], prob_.mul(w, prob_.empty(n)));
      mix_weight_[s] = prob_.add(mix_weight_[s], w);
    }
    touched_.clear();
  }
  for (std::size_t s = 0; s < mix_cells_.size(); ++s) {
    const P rest = prob_.mul(prob_.complement(mix_weight_[s]), prob_.half());
    fuse_into_map(mix_cells_[s],
                  prob_.seps_of(prob_.add(mix_occupied_[s], rest), prob_.add(mix_empty_[s], rest)));
    slot_[static_cast<std::size_t>(mix_cells_[s])] = -1;
  }
  mix_cells_.clear();
  mix_occupied_.clear();
  mix_empty_.clear();
  mix_weight_.clear();
}

// The mean of Pi and its positional standard deviation.
template <class Pr>
void GridSlamEngine<Pr>::update_estimate() {
  using W = typename Pr::Weight;
  // Weights relative to the most probable pose, which keeps U_gamma's weights in their table.
  P best = pi_[0];
  for (const P p : pi_)
    if (prob_.more_probable(p, best)) best = p;
  W s{}, sx{}, sy{}, st{}, sxx{}, syy{};
  for (int k = 0; k < nt_; ++k)
    for (int j = 0; j < n_; ++j)
      for (int i = 0; i < n_; ++i) {
        const W w = prob_.weight(prob_.div(pi_[pose_index(i, j, k)], best));
        s += w;
        sx += w * i;
        sy += w * j;
        st += w * k;
        sxx += w * i * i;
        syy += w * j * j;
      }
  const std::int64_t cell_um = std::int64_t{setup_.cell_mm} * 1000;
  const std::int64_t unit_q8 = std::int64_t{heading_unit()} * 256;
  const SlamPose origin = pose_of(0);
  const std::int64_t x0_um = origin.x_mm * 1000, y0_um = origin.y_mm * 1000;
  const std::int64_t theta0_q8 = origin.theta * 256;
  if constexpr (std::is_integral_v<W>) {
    if (s <= 0) core::fail<std::runtime_error>("SLAM: the pose grid has no weight");
    // Moments of large windows pass 2^63 once shifted: (m 2^16) / s is taken as
    // (m / s) 2^16 + ((m % s) 2^16) / s, the same quotient in 64 bits (32-bit chips have no
    // 128-bit integers).
    const auto mean_q16 = [&](W m) { return ((m / s) << 16) + ((m % s) << 16) / s; };
    const auto var_q16 = [&](W m2, W m) {
      const std::int64_t mean = mean_q16(m);
      return std::max<std::int64_t>(0, mean_q16(m2) - ((mean * mean) >> 16));
    };
    estimate_.x_um = x0_um + ((mean_q16(sx) * cell_um) >> 16);
    estimate_.y_um = y0_um + ((mean_q16(sy) * cell_um) >> 16);
    estimate_.theta_q8 = theta0_q8 + ((mean_q16(st) * unit_q8) >> 16);
    estimate_.sigma_um =
        (slam_detail::isqrt((var_q16(sxx, sx) + var_q16(syy, sy)) << 16) * cell_um) >> 16;
  } else {
    if (!(s > 0)) core::fail<std::runtime_error>("SLAM: the pose grid has no weight");
    const double mx = sx / s, my = sy / s, mt = st / s;
    const double var = std::max(0.0, sxx / s - mx * mx) + std::max(0.0, syy / s - my * my);
    estimate_.x_um = x0_um + std::llround(mx * static_cast<double>(cell_um));
    estimate_.y_um = y0_um + std::llround(my * static_cast<double>(cell_um));
    estimate_.theta_q8 = theta0_q8 + std::llround(mt * static_cast<double>(unit_q8));
    estimate_.sigma_um = std::llround(std::sqrt(var) * static_cast<double>(cell_um));
  }
}

}  // namespace intgrid::slam
