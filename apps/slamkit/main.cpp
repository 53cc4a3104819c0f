// slamkit: run, compare and reproduce 2D SLAM algorithms. `slamkit --help` lists the commands.
#include <cstdio>
#include <exception>

#include <fmt/format.h>

#include "commands.hpp"
#include "slamkit/io/error.hpp"

int main(int argc, char** argv) {
  CLI::App app{"slamkit: 2D SLAM on simulated worlds and real robot logs"};
  app.require_subcommand(1);
  int exit_code = 0;
  slamkit::app::RegisterDemo(app, exit_code);
  slamkit::app::RegisterMonteCarlo(app, exit_code);
  slamkit::app::RegisterRun(app, exit_code);
  slamkit::app::RegisterGrid(app, exit_code);
  slamkit::app::RegisterGridSim(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  } catch (const slamkit::InputError& e) {
    fmt::print(stderr, "slamkit: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "slamkit: error: {}\n", e.what());
    return 1;
  }
  return exit_code;
}
