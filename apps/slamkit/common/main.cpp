// slamkit: run, compare and reproduce 2D SLAM algorithms. `slamkit --help` lists the commands.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include <fmt/format.h>

#include "common/commands.hpp"
#include "common/progress.hpp"
#include "slamkit/core/numerical_error.hpp"
#include "slamkit/io/error.hpp"

namespace {

// Points a closed standard descriptor at /dev/null, so that no file the run opens takes its
// number (and receives the summary or the progress lines). Returns whether it was closed.
bool ReopenIfClosed(int fd, int flags) {
  if (fcntl(fd, F_GETFD) != -1 || errno != EBADF) return false;
  const int null_fd = open("/dev/null", flags);
  if (null_fd >= 0 && null_fd != fd) {
    dup2(null_fd, fd);
    close(null_fd);
  }
  return true;
}

// Thrown to stop a --dry-run between parsing and running.
struct DryRunDone {};

// Every subcommand, in the order `slamkit --help` lists them.
void RegisterCommands(CLI::App& app, int& exit_code) {
  slamkit::app::RegisterDemo(app, exit_code);
  slamkit::app::RegisterMonteCarlo(app, exit_code);
  slamkit::app::RegisterRun(app, exit_code);
  slamkit::app::RegisterGrid(app, exit_code);
  slamkit::app::RegisterGridSim(app, exit_code);
  slamkit::app::RegisterGridExplore(app, exit_code);
  slamkit::app::RegisterSuite(app, exit_code);
  slamkit::app::RegisterExplore(app, exit_code);
  slamkit::app::RegisterFeatures(app, exit_code);
  slamkit::app::RegisterStudy(app, exit_code);
  slamkit::app::RegisterCoop(app, exit_code);
  slamkit::app::RegisterMapDiff(app, exit_code);
  slamkit::app::RegisterPoseGraph(app, exit_code);
  slamkit::app::RegisterLocalize(app, exit_code);
  slamkit::app::RegisterMerge(app, exit_code);
  slamkit::app::RegisterReport(app, exit_code);
}

int Run(int argc, char** argv) {
  CLI::App app{"slamkit: 2D SLAM on simulated worlds and real robot logs"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("slamkit ") + SLAMKIT_VERSION);
  int exit_code = 0;
  bool dry_run = false;
  app.add_flag("--dry-run", dry_run,
               "parse the command and check the files it names, then stop: nothing runs, nothing "
               "is written (slamkit --dry-run grid --log ... --out DIR)");
  // Runs after every option is parsed and checked and before the command's own callback.
  app.parse_complete_callback([&dry_run] {
    if (dry_run) throw DryRunDone();
  });
  RegisterCommands(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const DryRunDone&) {
    std::printf("slamkit: dry run: the command line and the files it names check out; nothing "
                "was run\n");
    return 0;
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  } catch (const slamkit::InputError& e) {
    slamkit::app::PrintStderr("slamkit: error: {}\n", e.what());
    return 2;
  } catch (const slamkit::NumericalError& e) {
    // Raised before the outputs are written (the state is checked first), so --out is untouched.
    slamkit::app::PrintStderr("slamkit: error: numerical failure, nothing written: {}\n",
                              e.what());
    return 3;
  } catch (const std::exception& e) {
    slamkit::app::PrintStderr("slamkit: error: {}\n", e.what());
    return 1;
  }
  return exit_code;
}

}  // namespace

int main(int argc, char** argv) {
  ReopenIfClosed(STDIN_FILENO, O_RDONLY);
  const bool stdout_closed = ReopenIfClosed(STDOUT_FILENO, O_WRONLY);
  ReopenIfClosed(STDERR_FILENO, O_WRONLY);
  // A closed pipe on stdout or stderr is an EPIPE error to handle, not a silent death.
  std::signal(SIGPIPE, SIG_IGN);
  int exit_code = 1;
  try {
    exit_code = Run(argc, argv);
  } catch (...) {
    slamkit::app::WriteStderr("slamkit: error: unexpected exception\n");
    exit_code = 1;
  }
  // The summary is only in stdout's buffer until here: a lost summary is a failed run (the
  // output files already written stay).
  errno = 0;
  const bool flushed = std::fflush(stdout) == 0 && std::ferror(stdout) == 0;
  if (stdout_closed || !flushed) {
    const int error = stdout_closed ? EBADF : errno;
    slamkit::app::PrintStderr("slamkit: error: cannot write to stdout: {}\n",
                              error != 0 ? std::strerror(error) : "write error");
    if (exit_code == 0) exit_code = 1;
  }
  return exit_code;
}
