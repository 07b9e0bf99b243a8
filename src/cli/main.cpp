// holoray: command-line entry point. Each subcommand lives in its own file.
#include <CLI/CLI.hpp>

#include <cstdio>

#include "cli/animate_command.hpp"
#include "cli/compare_command.hpp"
#include "cli/devices_command.hpp"
#include "cli/completion.hpp"
#include "cli/interlace_command.hpp"
#include "cli/launch_check.hpp"
#include "cli/live_command.hpp"
#include "cli/preview_commands.hpp"
#include "cli/render_command.hpp"
#include "cli/subaperture_command.hpp"
#include "cli/web_command.hpp"
#include "cli/version.hpp"
#include "cluster/mpi_world.hpp"

int main(int argc, char** argv) {
  // Under mpirun: the MPI build takes over (launch_check.hpp says why two).
  holoray::cli::become_mpi_program_if_launched(argv);
  // Under mpirun (and built with MPI): this process's rank; else one of one.
  const holoray::cluster::World world(argc, argv);
  // Named, so that usage lines (and the man page made from them) say holoray.
  CLI::App app{"holoray: integral image (elemental image array) renderer", "holoray"};
  app.require_subcommand(1);
  app.set_version_flag("--version", holoray::cli::version_text);
  // Usage errors read as every other error; set before the subcommands,
  // which copy it.
  app.failure_message([](const CLI::App* a, const CLI::Error& e) {
    return "holoray: error: " + CLI::FailureMessage::simple(a, e);
  });
  holoray::cli::RenderCommandOptions render_opts;
  CLI::App* render = holoray::cli::add_render_command(app, render_opts);
  holoray::cli::SubapertureCommandOptions sub_opts;
  CLI::App* sub = holoray::cli::add_subaperture_command(app, sub_opts);
  holoray::cli::AnimateCommandOptions animate_opts;
  CLI::App* animate = holoray::cli::add_animate_command(app, animate_opts);
  holoray::cli::CompareCommandOptions compare_opts;
  CLI::App* compare = holoray::cli::add_compare_command(app, compare_opts);
  holoray::cli::SimulateCommandOptions simulate_opts;
  CLI::App* simulate = holoray::cli::add_simulate_command(app, simulate_opts);
  holoray::cli::InterlaceCommandOptions interlace_opts;
  CLI::App* interlace = holoray::cli::add_interlace_command(app, interlace_opts);
  holoray::cli::ViewsCommandOptions views_opts;
  CLI::App* views = holoray::cli::add_views_command(app, views_opts);
  holoray::cli::LiveCommandOptions live_opts;
  CLI::App* live = holoray::cli::add_live_command(app, live_opts);
  holoray::cli::WebCommandOptions web_opts;
  CLI::App* web = holoray::cli::add_web_command(app, web_opts);
  CLI::App* devices = holoray::cli::add_devices_command(app);
  holoray::cli::add_completion_option(app);
  app.footer(
      "\nExamples:\n"
      "  holoray render examples/primitives.nff -o eia.png\n"
      "  holoray animate examples/shots/swinging_box.toml -o frames/\n"
      "  holoray live examples/primitives.nff\n"
      "\nEach command's options: holoray COMMAND --help. The user guide: docs/guide/README.md");
  if (argc == 1) {  // a bare `holoray` shows what it does
    std::fputs(app.help().c_str(), stdout);
    return 0;
  }
  // CLI11 would only say that a subcommand is required.
  const auto known = [&](const std::string& name) {
    for (const CLI::App* c : app.get_subcommands([](CLI::App*) { return true; }))
      if (c->get_name() == name) return true;
    return false;
  };
  if (argc > 1 && argv[1][0] != '-' && !known(argv[1])) {
    std::fprintf(stderr, "holoray: error: unknown command '%s' (expected render, subaperture, animate, live, compare, simulate, views, interlace, web or devices)\n", argv[1]);
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version, --completion
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    if (world.rank() == 0) app.exit(e);  // once, not once per MPI rank
    return 2;  // usage errors: one status whatever CLI11's internal code
  }
  if ((render->parsed() || animate->parsed()) && !holoray::cluster::built_with_mpi()) {
    if (const std::string why = holoray::cli::mpi_launch_error(); !why.empty()) {
      std::fprintf(stderr, "holoray: error: %s\n", why.c_str());
      return 1;
    }
  }
  if (render->parsed()) return holoray::cli::run_render(render_opts, world);
  if (sub->parsed()) return holoray::cli::run_subaperture(sub_opts);
  if (animate->parsed()) return holoray::cli::run_animate(animate_opts, world);
  if (compare->parsed()) return holoray::cli::run_compare(compare_opts);
  if (simulate->parsed()) return holoray::cli::run_simulate(simulate_opts);
  if (views->parsed()) return holoray::cli::run_views(views_opts);
  if (interlace->parsed()) return holoray::cli::run_interlace(interlace_opts);
  if (live->parsed()) return holoray::cli::run_live(live_opts);
  if (web->parsed()) return holoray::cli::run_web(web_opts);
  if (devices->parsed()) return holoray::cli::run_devices();
  return 2;
}
