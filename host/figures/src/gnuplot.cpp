#include "intgrid/figures/gnuplot.hpp"

#include <stdexcept>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>

extern char** environ;

namespace intgrid::figures {

std::optional<int> run_program(const std::string& program, const std::vector<std::string>& args,
                               bool quiet) {
  std::vector<char*> argv;
  std::vector<std::string> all{program};
  all.insert(all.end(), args.begin(), args.end());
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (quiet) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  }
  pid_t pid = 0;
  const int error = posix_spawnp(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) return std::nullopt;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return std::nullopt;
  if (WIFEXITED(status)) {
    // 127: the shell's "command not found", which some exec wrappers report.
    if (WEXITSTATUS(status) == 127) return std::nullopt;
    return WEXITSTATUS(status);
  }
  return -1;
}

std::string gp_quoted(const std::string& text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string gp_terminal_line(bool cairo, int width, int height) {
  char text[160];
  if (cairo)
    std::snprintf(text, sizeof text, "set terminal pngcairo size %d,%d noenhanced font 'sans,11'\n",
                  width, height);
  else
    std::snprintf(text, sizeof text, "set terminal png size %d,%d noenhanced\n", width, height);
  return text;
}

GnuplotProbe probe_gnuplot(const std::string& program) {
  const std::optional<int> status = run_program(program, {"-e", "set terminal pngcairo"}, true);
  if (!status) return {};
  return {true, *status == 0};
}

bool draw_pngs(const std::string& gnuplot, const std::string& script,
               const std::filesystem::path& script_path,
               std::initializer_list<io::AtomicFile*> pngs) {
  io::AtomicFile file(script_path);
  file.stream() << script;
  file.stream().flush();
  if (!file.stream())
    throw std::runtime_error("cannot write the gnuplot script " + script_path.string());
  const std::optional<int> status = run_program(gnuplot, {file.temporary_path().string()}, false);
  if (!status) return false;
  if (*status != 0)
    throw std::runtime_error(gnuplot + " failed (exit status " + std::to_string(*status) +
                             ") making the plots; the CSVs are written");
  for (io::AtomicFile* png : pngs) {
    std::error_code error;
    if (std::filesystem::file_size(png->temporary_path(), error) == 0 || error)
      throw std::runtime_error(gnuplot + " wrote no " + png->target().string());
    png->commit();
  }
  return true;
}

void print_plots_skipped(const std::string& gnuplot) {
  std::printf("note: %s not found, plots skipped (install gnuplot-nox, or pass --gnuplot PATH)\n",
              gnuplot.c_str());
}

}  // namespace intgrid::figures
