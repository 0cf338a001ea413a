// The thetad command line. Subcommands are added as their features land.
#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
  CLI::App app{"thetad: theta-D, SDRE and LQR control of the X-Cell miniature helicopter"};
  app.require_subcommand(1);
  CLI11_PARSE(app, argc, argv);
  return 0;
}
