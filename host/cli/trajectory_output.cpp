#include "cli/trajectory_output.hpp"

#include <sys/resource.h>

#include <cmath>
#include <ostream>

#include "intgrid/io/atomic_file.hpp"
#include "intgrid/io/text_io.hpp"

namespace intgrid::cli {

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

std::size_t peak_memory_bytes() {
  struct rusage usage {};
  if (::getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<std::size_t>(usage.ru_maxrss) * 1024;
}

}  // namespace intgrid::cli
