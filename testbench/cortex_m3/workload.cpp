#include "testbench/cortex_m3/workload.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <iterator>
#include <span>
#include <vector>

#include "embedded_inputs.hpp"
#include "intgrid/core/ray_insertion.hpp"
#include "intgrid/core/resolution.hpp"
#include "intgrid/core/seps.hpp"
#include "intgrid/localization/global_localization.hpp"
#include "intgrid/slam/grid_slam_engine.hpp"
#include "intgrid/slam/probabilities.hpp"
#include "testbench/cortex_m3/workload_parameters.hpp"

using namespace intgrid::core;
using namespace intgrid::slam;
using namespace intgrid::localization;

namespace intgrid::embedded {
namespace {

constexpr int kTileSide = 64;
constexpr int kInsertionSide = 320;  // cells: 16 m, every ray of an 8 m range inside

// FNV-1a over the bytes of the values: what the host and the chip compare.
template <class T>
std::uint64_t digest(std::span<const T> values, std::uint64_t hash = 14695981039346656037ull) {
  for (const T& v : values) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    for (const unsigned char b : bytes) hash = (hash ^ b) * 1099511628211ull;
  }
  return hash;
}

// splitmix64: the fusion tiles' contents, identical on every machine.
std::uint64_t next_random(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

Scan scan_geometry() {
  Scan scan;
  scan.angle0 = inputs::kAngle0;
  scan.dangle = inputs::kDangle;
  scan.max_range = inputs::kMaxRange;
  scan.sensor_mount = {inputs::kMountX, inputs::kMountY, inputs::kMountTheta};
  scan.ranges.assign(inputs::kBeams, 0.0);
  return scan;
}

double odometry_reach() {
  return 1.0 + (std::abs(inputs::kOdometry[0]) + std::abs(inputs::kOdometry[1])) / 1000.0;
}

QuantizedScan slam_scan(std::size_t i) {
  QuantizedScan scan;
  scan.range_mm.assign(inputs::kRangesMm[i], inputs::kRangesMm[i] + inputs::kBeams);
  if (i == 1) {
    scan.odom_dx_mm = inputs::kOdometry[0];
    scan.odom_dy_mm = inputs::kOdometry[1];
    scan.odom_dtheta = inputs::kOdometry[2];
  }
  return scan;
}

// lambda 1 localizes the second scan; lambda 2 does not.
GridSlamConfig small_slam_config(int lambda) {
  GridSlamConfig c;
  c.schedule.lambda = lambda;
  c.schedule.xi = 2;  // the second scan is localized, not mapped
  c.window.cells = 5;
  c.window.headings = 5;
  c.beam.beams = 30;
  c.sensor.max_range = kMaxRangeMm / 1000.0;
  c.sensor.sigma = kSigma;
  c.map.margin = 1.0;
  return c;
}

ProbabilityGrid room_map() {
  ProbabilityGrid map({inputs::kMapWidth, inputs::kMapHeight, inputs::kMapResolution, 0.0, 0.0},
                      0.5);
  for (std::size_t i = 0; i < map.cells.size(); ++i)
    map.cells[i] = inputs::kMapOccupancy[i] / 255.0;
  return map;
}

GlobalLocConfig pose_grid_config() {
  GlobalLocConfig c;
  c.pose_res = 0.2;
  c.headings = 32;
  c.sensor.sigma = kSigma;
  c.sensor.max_range = kMaxRangeMm / 1000.0;
  c.refine_levels = 0;  // the workload times one reading's pass over the lattice, not a search
  return c;
}

// The reading of scan 0 nearest its middle bearing that the pose grid can use.
RangeReading middle_reading() {
  const Scan geometry = scan_geometry();
  for (std::size_t offset = 0; offset < inputs::kBeams; ++offset) {
    const std::size_t b = (inputs::kBeams / 2 + offset) % inputs::kBeams;
    const std::int32_t z = inputs::kRangesMm[0][b];
    if (z > 0 && z < kMaxRangeMm) return {z / 1000.0, geometry.bearing(b)};
  }
  return {1.0, 0.0};
}

NarrowIsmTable host_index_table() {
  return make_ism_table<std::int8_t>(
      kInsertionZStepMm, {std::begin(inputs::kIsmBegin), std::end(inputs::kIsmBegin)},
      {std::begin(inputs::kIsmIndices), std::end(inputs::kIsmIndices)});
}

}  // namespace

std::size_t input_bytes() {
  return sizeof inputs::kRangesMm + sizeof inputs::kOdometry + sizeof inputs::kMapOccupancy +
         sizeof inputs::kIsmBegin + sizeof inputs::kIsmIndices;
}

const char* name_of(Operation operation) {
  switch (operation) {
    case Operation::tile_fusion:
      return "tile_fusion";
    case Operation::scan_insertion:
      return "scan_insertion";
    case Operation::scan_rays:
      return "scan_rays";
    case Operation::pose_grid_update:
      return "pose_grid_update";
    case Operation::pose_grid_motion:
      return "pose_grid_motion";
    case Operation::pose_occupancy_reading:
      return "pose_occupancy_reading";
    case Operation::markov_reading:
      return "markov_reading";
  }
  return "unknown";
}

struct Workload::State {
  // Tile fusion.
  SepsCodec tile_codec{8, 0.05};
  std::vector<std::int8_t> tile_a, tile_b, tile_out;
  std::vector<double> tile_pa, tile_pb, tile_pout;
  // Scan insertion: the sensor at the centre of the grid, heading 0.
  std::vector<std::int32_t> sine = make_sine_table_q16();
  SepsCodec insertion_codec = embedded::insertion_codec();
  // The integer table is the host's, an input (embedded_inputs.hpp): tables are built in floating
  // point, and newlib's exp may round a last bit differently from the host's, which can move a
  // quantized index. The double one is built here.
  NarrowIsmTable index_table = host_index_table();
  IsmTable<double> probability_table;
  SlamSetup slam_setup;  // its bearings and mount serve the insertion too
  Grid<std::int8_t> index_grid;
  ProbabilityGrid probability_grid;
  std::uint64_t insertion_cells = 0;
  std::int64_t index_ray_sum = 0;  // scan_rays: what the table reads add up to
  double probability_ray_sum = 0.0;
  // Pose-grid update: the first scan mapped, the second measured, with and without localization.
  SlamSetup motion_setup;
  GridSlamEngine<IndexProbabilities> index_slam, index_motion;
  GridSlamEngine<DoubleProbabilities> double_slam, double_motion;
  QuantizedScan second_scan = slam_scan(1);
  // Pose occupancy grid.
  LocalizationMap localization_map;
  ReadingClaims claims;
  LogOddsClaims log_odds_claims;
  std::vector<std::int32_t> pog;
  std::vector<double> log_odds_pog;
  MarkovLocalization markov;
  RangeReading reading = middle_reading();

  State()
      : slam_setup(make_slam_setup(small_slam_config(1), scan_geometry(), odometry_reach())),
        motion_setup(make_slam_setup(small_slam_config(2), scan_geometry(), odometry_reach())),
        index_slam(slam_setup, make_probabilities<IndexProbabilities>(slam_setup)),
        index_motion(motion_setup, make_probabilities<IndexProbabilities>(motion_setup)),
        double_slam(slam_setup, make_probabilities<DoubleProbabilities>(slam_setup)),
        double_motion(motion_setup, make_probabilities<DoubleProbabilities>(motion_setup)),
        localization_map(room_map(), 0.65, 0.196, pose_grid_config()),
        markov(localization_map, GlobalMethod::markov) {
    std::uint64_t random = 2020;
    const int max = tile_codec.max_index();
    for (int i = 0; i < kTileSide * kTileSide; ++i) {
      const auto a = static_cast<int>(next_random(random) % (2 * max + 1)) - max;
      const auto b = static_cast<int>(next_random(random) % (2 * max + 1)) - max;
      tile_a.push_back(static_cast<std::int8_t>(a));
      tile_b.push_back(static_cast<std::int8_t>(b));
      tile_pa.push_back(tile_codec.probability(a));
      tile_pb.push_back(tile_codec.probability(b));
    }
    tile_out.assign(tile_a.size(), 0);
    tile_pout.assign(tile_a.size(), 0.5);

    probability_table =
        make_probability_ism_table(beam_model(), kInsertionCell, kInsertionZStepMm, kMaxRangeMm);
    const GridGeometry geometry{kInsertionSide, kInsertionSide, kInsertionCell, 0.0, 0.0};
    index_grid = Grid<std::int8_t>(geometry, 0);
    probability_grid = ProbabilityGrid(geometry, 0.5);
    for_each_ism_cell(insertion_rays(), index_table, 0, 0, slam_setup.sensor.mount_theta,
                      slam_setup.sensor.bearing, first_ranges(), kMaxRangeMm,
                      [&](int, int, std::int8_t) { ++insertion_cells; });

    for (auto* slam : {&index_slam, &index_motion}) slam->process(slam_scan(0));
    for (auto* slam : {&double_slam, &double_motion}) slam->process(slam_scan(0));

    claims = localization_map.claims(reading);
    log_odds_claims = localization_map.log_odds_claims(reading);
    pog.assign(localization_map.pose_cells(), 0);
    log_odds_pog.assign(localization_map.pose_cells(), 0.0);
  }

  IntegerRays insertion_rays() const { return {sine, kInsertionCellMm}; }
  std::span<const std::int32_t> first_ranges() const {
    return {inputs::kRangesMm[0], inputs::kBeams};
  }
  template <class T, class Sum>
  void sum_rays(const IsmTable<T>& table, Sum& sum) {
    for_each_ism_cell(insertion_rays(), table, 0, 0, slam_setup.sensor.mount_theta,
                      slam_setup.sensor.bearing, first_ranges(), kMaxRangeMm,
                      [&sum](int, int, T value) { sum += value; });
  }
  template <class T>
  void insert(Grid<T>& grid, const IsmTable<T>& table) {
    insert_scan_along_rays(grid, insertion_rays(), table, kInsertionSide / 2, kInsertionSide / 2, 0,
                           0, slam_setup.sensor.mount_theta, slam_setup.sensor.bearing,
                           first_ranges(), kMaxRangeMm, insertion_codec.max_index());
  }
};

Workload::Workload() : state_(std::make_unique<State>()) {}
Workload::~Workload() = default;

void Workload::run(Operation operation, bool integer) {
  State& s = *state_;
  switch (operation) {
    case Operation::tile_fusion:
      if (integer)
        fuse_indices<std::int8_t>(s.tile_a, s.tile_b, s.tile_out, s.tile_codec.max_index());
      else
        fuse_probabilities(s.tile_pa, s.tile_pb, s.tile_pout);
      break;
    case Operation::scan_insertion:
      if (integer)
        s.insert(s.index_grid, s.index_table);
      else
        s.insert(s.probability_grid, s.probability_table);
      break;
    case Operation::scan_rays:
      if (integer)
        s.sum_rays(s.index_table, s.index_ray_sum);
      else
        s.sum_rays(s.probability_table, s.probability_ray_sum);
      break;
    case Operation::pose_grid_update:
      if (integer)
        s.index_slam.process(s.second_scan);
      else
        s.double_slam.process(s.second_scan);
      break;
    case Operation::pose_grid_motion:
      if (integer)
        s.index_motion.process(s.second_scan);
      else
        s.double_motion.process(s.second_scan);
      break;
    case Operation::pose_occupancy_reading:
      if (integer)
        s.localization_map.add_reading_dense(s.claims, s.pog);
      else
        s.localization_map.add_reading_dense(s.log_odds_claims, s.log_odds_pog);
      break;
    case Operation::markov_reading:
      if (integer)
        s.localization_map.add_reading_dense(s.claims, s.pog);
      else
        s.markov.update(s.reading);
      break;
  }
}

namespace {
template <class Slam>
Result slam_result(const Slam& slam) {
  const SlamEstimate e = slam.estimate();
  const std::array<std::int64_t, 4> estimate{e.x_um, e.y_um, e.theta_q8, e.sigma_um};
  const auto& pi = slam.pose_grid();
  return {pi.size(), digest<std::int64_t>(estimate, digest<typename Slam::P>(pi))};
}
}  // namespace

Result Workload::result(Operation operation, bool integer) const {
  const State& s = *state_;
  switch (operation) {
    case Operation::tile_fusion:
      return {s.tile_out.size(),
              integer ? digest<std::int8_t>(s.tile_out) : digest<double>(s.tile_pout)};
    case Operation::scan_insertion:
      return {s.insertion_cells, integer ? digest<std::int8_t>(s.index_grid.cells)
                                         : digest<double>(s.probability_grid.cells)};
    case Operation::scan_rays:
      return {s.insertion_cells, integer ? digest<std::int64_t>({&s.index_ray_sum, 1})
                                         : digest<double>({&s.probability_ray_sum, 1})};
    case Operation::pose_grid_update:
      return integer ? slam_result(s.index_slam) : slam_result(s.double_slam);
    case Operation::pose_grid_motion:
      return integer ? slam_result(s.index_motion) : slam_result(s.double_motion);
    case Operation::pose_occupancy_reading:
      return {s.pog.size(), integer ? digest<std::int32_t>(s.pog) : digest<double>(s.log_odds_pog)};
    case Operation::markov_reading:
      return {s.pog.size(),
              integer ? digest<std::int32_t>(s.pog) : digest<double>(s.markov.belief())};
  }
  return {};
}

}  // namespace intgrid::embedded
