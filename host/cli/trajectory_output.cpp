#include "cli/trajectory_output.hpp"

#include <sys/resource.h>

#include <cmath>
#include <ostream>

#include <algorithm>

#include "intgrid/io/atomic_file.hpp"
#include "intgrid/io/input_error.hpp"
#include "intgrid/io/relations_io.hpp"
#include "intgrid/io/text_io.hpp"

namespace intgrid::cli {

namespace {

// A summary of relation errors as metrics.json holds it.
nlohmann::json relation_json(const slam::RelationError& e) {
  return {{"matched", e.matched},
          {"unmatched", e.unmatched},
          {"off", e.off},
          {"off_fraction", e.matched > 0 ? double(e.off) / double(e.matched) : 0.0},
          {"trans_median", e.trans_median},
          {"rot_median_deg", e.rot_median_deg},
          {"trans_mean", e.trans_mean},
          {"trans_std", e.trans_std},
          {"rot_mean_deg", e.rot_mean_deg},
          {"rot_std_deg", e.rot_std_deg},
          {"trans_sq_mean", e.trans_sq_mean},
          {"trans_sq_std", e.trans_sq_std},
          {"rot_sq_mean", e.rot_sq_mean},
          {"rot_sq_std", e.rot_sq_std}};
}

// The worst stretches of a trajectory (at most 10), with their times also in seconds from the
// log's first scan (t0).
nlohmann::json stretches_json(std::span<const slam::RelationStretch> stretches, double t0) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t i = 0; i < std::min<std::size_t>(stretches.size(), 10); ++i) {
    const slam::RelationStretch& s = stretches[i];
    out.push_back({{"t1_first", s.t1_first},
                   {"t1_last", s.t1_last},
                   {"t2_min", s.t2_min},
                   {"t2_max", s.t2_max},
                   {"t1_from_start", {s.t1_first - t0, s.t1_last - t0}},
                   {"t2_from_start", {s.t2_min - t0, s.t2_max - t0}},
                   {"relations", s.relations},
                   {"off", s.off},
                   {"trans_max", s.trans_max},
                   {"rot_max_deg", s.rot_max_deg}});
  }
  return out;
}

}  // namespace

nlohmann::json error_json(const slam::TrajectoryError& e) {
  return {{"rmse_m", e.rmse},
          {"max_m", e.max},
          {"matched", e.matched},
          {"mean_heading_error_deg", e.mean_heading * 180.0 / M_PI}};
}

void write_trajectory(const std::filesystem::path& file, const std::vector<slam::TimedPose>& poses,
                      const std::string& what) {
  io::write_file_atomically(file, [&](std::ostream& out) {
    out << "# t x y theta (s, m, m, rad): " << what << "\n";
    for (const slam::TimedPose& p : poses)
      out << io::format_number(p.t) << ' ' << io::format_number(p.pose.x) << ' '
          << io::format_number(p.pose.y) << ' ' << io::format_number(p.pose.theta) << '\n';
  });
}

std::vector<core::Pose2> positions(const std::vector<slam::TimedPose>& poses) {
  std::vector<core::Pose2> out;
  for (const slam::TimedPose& p : poses) out.push_back(p.pose);
  return out;
}

std::string map_scale_caption(const core::GridGeometry& map, const std::string& frame) {
  return "Scale: one pixel is one " + io::format_number(map.resolution * 100.0) + " cm cell (" +
         io::format_number(1.0 / map.resolution) + " pixels a metre); north up, " + frame +
         " frame.";
}

std::size_t peak_memory_bytes() {
  struct rusage usage {};
  if (::getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<std::size_t>(usage.ru_maxrss) * 1024;
}

void write_relation_errors(const std::filesystem::path& file,
                           std::span<const slam::RelationResult> results,
                           std::span<const slam::RelationResult> odometry_results) {
  io::write_file_atomically(file, [&](std::ostream& out) {
    out << "t1,t2,trans_error_m,rot_error_deg,off,odometry_trans_error_m,odometry_rot_error_deg\n";
    const auto errors = [&out](const slam::RelationResult& r) {
      if (r.matched)
        out << io::format_number(r.trans_error) << ',' << io::format_number(r.rot_error_deg);
      else
        out << ',';
    };
    for (std::size_t i = 0; i < results.size(); ++i) {
      const slam::RelationResult& r = results[i];
      out << io::format_number(r.relation.t1) << ',' << io::format_number(r.relation.t2) << ',';
      errors(r);
      out << ',' << (r.off() ? 1 : 0) << ',';
      errors(odometry_results[i]);
      out << '\n';
    }
  });
}

std::vector<slam::TimedPose> by_time(std::vector<slam::TimedPose> poses) {
  std::stable_sort(poses.begin(), poses.end(),
                   [](const slam::TimedPose& a, const slam::TimedPose& b) { return a.t < b.t; });
  return poses;
}

RelationScoring read_relations_for(const std::filesystem::path& relations_file,
                                   const std::filesystem::path& log_file, const core::Log& log) {
  RelationScoring r;
  const std::vector<io::RelationRecord> records = io::read_relations(relations_file);
  r.relations = io::relations_of(records);
  r.odometry = slam::relation_errors(by_time(slam::scan_poses(log)), r.relations);
  if (slam::summarize_relations(r.odometry).matched == 0)
    throw io::InputError(
        relations_file, records.front().line, "t1",
        io::printed("none of its %zu relations matches a scan of the log %s within %g s (its "
                    "scans span %s to %s s)",
                    records.size(), log_file.string().c_str(), slam::kRelationTolerance,
                    io::format_number(log.scans.front().t).c_str(),
                    io::format_number(log.scans.back().t).c_str()));
  return r;
}

void add_relation_metrics(nlohmann::json& metrics, const std::filesystem::path& file,
                          const slam::RelationError& summary,
                          const slam::RelationError& odometry_summary,
                          std::span<const slam::RelationResult> results, double t0) {
  metrics["relations_file"] = file.string();
  metrics["relations"] = relation_json(summary);
  metrics["odometry_relations"] = relation_json(odometry_summary);
  metrics["relation_stretches"] = stretches_json(slam::worst_stretches(results), t0);
}

}  // namespace intgrid::cli
