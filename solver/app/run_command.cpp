#include <fmt/format.h>

#include <iostream>

#include "solver/app/commands.hpp"
#include "solver/core/error.hpp"
#include "solver/io/scene.hpp"
#include "solver/sim/run.hpp"

namespace pdmpm::app {

int run_command(const RunArgs& args) {
  try {
    const io::Scene scene = io::parse_scene(args.scene);
    sim::RunOptions opt;
    opt.out_dir = args.out.empty() ? std::filesystem::path("out") / scene.id : std::filesystem::path(args.out);
    opt.threads = args.threads;
    opt.progress = !args.quiet;
    opt.write_fields = !args.no_fields;
    const sim::RunResult r = sim::run_scene(scene, opt);
    const auto& s = r.summary;
    if (r.exit_code != 0) {
      std::cerr << "pdmpm: " << r.message << "\n";
      std::cerr << "pdmpm: outputs up to the failure are in " << opt.out_dir.string() << "\n";
      return r.exit_code;
    }
    if (!args.quiet) {
      const std::string rate = !s.contains("bond_updates_per_second")  // mpm, hybrid
          ? fmt::format("{:.3g} particle-steps/s", s["particle_steps_per_second"].get<double>())
          : fmt::format("{} bonds, {:.3g} bond updates/s", s["bonds"].get<long>(),
                        s["bond_updates_per_second"].get<double>());
      std::cerr << fmt::format("pdmpm: {} done: {} particles, {} steps of {:.4g} s in {:.3g} s ({}) → {}\n", scene.id,
                               s["particles"].get<long>(), s["steps"].get<long>(), s["dt"].get<double>(),
                               s["wall_time_s"].get<double>(), rate, opt.out_dir.string());
    }
    return 0;
  } catch (const InputError& e) {
    std::cerr << "pdmpm: error: " << e.what() << "\n";
    return 2;
  } catch (const RunError& e) {
    std::cerr << "pdmpm: run failed: " << e.what() << "\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "pdmpm: internal error: " << e.what() << "\n";
    return 4;
  }
}

}  // namespace pdmpm::app
