#include "verification/support/lammps.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "solver/pd/constants.hpp"

namespace pdmpm::test::lammps {
namespace {

std::string g17(double v) { return fmt::format("{:.17g}", v); }

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream out(p);
  if (!out) throw std::runtime_error("lammps: cannot write " + p.string());
  out << text;
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

[[noreturn]] void unsupported(const std::string& what) {
  throw std::invalid_argument("lammps: the scene uses " + what + ", which the LAMMPS translation does not reproduce");
}

}  // namespace

std::string executable() {
  const char* env = std::getenv("PDMPM_LAMMPS");
  return env && *env ? env : "lmp";
}

bool available() {
  const std::string cmd = "command -v " + shell_quote(executable()) + " >/dev/null 2>&1";
  return std::system(cmd.c_str()) == 0;
}

Input make_input(const io::Scene& scene, const sim::PdSetup<3>& setup, const Options& o) {
  const auto& sys = setup.system;
  const auto& p = sys.particles;
  const Index n = p.n_real;
  if (scene.dimension != 3) unsupported("dimension " + std::to_string(scene.dimension) + " (LAMMPS' PERI is 3D)");
  if (p.n_ghost() > 0) unsupported("symmetry planes");
  if (sys.partial_volume != pd::PartialVolume::seed001) unsupported("partial_volume other than seed001");
  if (setup.precrack_cut > 0) unsupported("pre-cracks");
  if (setup.has_body_force) unsupported("a body force");
  if (!setup.boundaries.tractions.empty()) unsupported("traction boundaries");
  for (const auto& c : setup.boundaries.constraints)
    if (c.kind != bc::ConstraintKind::fixed) unsupported("a non-fixed kinematic boundary (" + c.name + ")");
  if (o.steps <= 0 || !(o.dt > 0.0)) throw std::invalid_argument("lammps: steps and dt must be positive");
  const double V = p.volume.empty() ? 0.0 : p.volume.front();
  for (double v : p.volume)
    if (v != V) unsupported("unequal particle volumes");

  std::string pair_style, pair_coeff;
  const double s00 = setup.damage ? setup.critical_stretch : 1.0e100;  // no breaking: an unreachable stretch
  if (scene.model == "pmb") {
    if (sys.influence != pd::Influence::constant) unsupported("PMB with a non-constant influence function");
    const double c = pd::pmb_micromodulus(pd::Influence::constant, sys.setting, sys.material, sys.delta, 1.0);
    pair_style = "peri/pmb";
    pair_coeff = fmt::format("{} {} {} 0.0", g17(c), g17(sys.delta), g17(s00));
  } else if (scene.model == "lps") {
    if (sys.influence != pd::Influence::inverse_distance) unsupported("LPS with an influence function other than 1/|ξ|");
    pair_style = "peri/lps";
    pair_coeff = fmt::format("{} {} {} {} 0.0", g17(sys.material.bulk()), g17(sys.material.shear()), g17(sys.delta), g17(s00));
  } else {
    unsupported("model " + scene.model);
  }

  // Atom type 1 is free; type 2 + k holds the particles of fixed boundary k.
  std::vector<int> type(static_cast<std::size_t>(n), 1);
  const auto& cons = setup.boundaries.constraints;
  for (std::size_t k = 0; k < cons.size(); ++k)
    for (Index i : cons[k].particles)
      if (type[i] == 1) type[i] = static_cast<int>(k) + 2;
  const int types = static_cast<int>(cons.size()) + 1;

  Vec<3> lo = Vec<3>::Constant(1e300), hi = Vec<3>::Constant(-1e300);
  for (Index i = 0; i < n; ++i) lo = lo.cwiseMin(p.x0[i]), hi = hi.cwiseMax(p.x0[i]);
  const double dx = sys.spacing();
  lo.array() -= dx, hi.array() += dx;

  std::ostringstream data;
  data << "# pdmpm scene " << scene.id << ": particles in pdmpm order (id = index + 1)\n\n"
       << n << " atoms\n" << types << " atom types\n\n";
  const char* axes[] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) data << g17(lo[a]) << ' ' << g17(hi[a]) << ' ' << axes[a] << "lo " << axes[a] << "hi\n";
  data << "\nAtoms # peri\n\n";
  for (Index i = 0; i < n; ++i)
    data << i + 1 << ' ' << type[i] << ' ' << g17(p.volume[i]) << ' ' << g17(sys.material.rho) << ' ' << g17(p.x0[i][0])
         << ' ' << g17(p.x0[i][1]) << ' ' << g17(p.x0[i][2]) << '\n';

  std::ostringstream in;
  in << "# pdmpm scene " << scene.id << " translated for LAMMPS' PERI package (verification/support/lammps.cpp)\n"
     << "units si\nboundary s s s\natom_style peri\natom_modify map array\n"
     << "lattice sc " << g17(dx) << "   # lc: partial-volume ramp and contact distance use it\n"
     << "read_data data.pdmpm\n"
     << "neighbor " << g17(dx) << " bin\nneigh_modify delay 0 every 1 check yes\n"
     << "pair_style " << pair_style << "\npair_coeff * * " << pair_coeff << "\n"
     << "velocity all set 0.0 0.0 0.0 sum no units box\n"
     << "fix integrate all nve\n";
  if (setup.indenter) {
    const auto& ind = *setup.indenter;
    // fix indent's K(R − r)² is a force density on PERI atoms (see lammps.hpp).
    const double K = ind.force_density ? ind.stiffness : ind.stiffness / V;
    for (int a = 0; a < 3; ++a)
      in << "variable ind_" << axes[a] << " equal \"" << g17(ind.center0[a]) << " + step*dt*(" << g17(ind.velocity[a]) << ")\"\n";
    in << "fix indenter all indent " << g17(K) << " sphere v_ind_x v_ind_y v_ind_z " << g17(ind.radius) << " units box\n";
  }
  for (std::size_t k = 0; k < cons.size(); ++k)
    in << "group held" << k << " type " << k + 2 << "\nfix hold" << k << " held" << k << " setforce 0.0 0.0 0.0   # "
       << cons[k].name << " (fixed)\n";
  const std::int64_t every = o.dump_every > 0 ? o.dump_every : o.steps;
  in << "compute damage all damage/atom\n"
     << "timestep " << g17(o.dt) << "\n"
     << "run 0 post no   # builds the bond families, so the real run starts with every s0 set (lammps.hpp)\n"
     << "thermo " << o.steps << "\n"
     << "dump fields all custom " << every << " dump.pdmpm id x y z vx vy vz c_damage\n"
     << "dump_modify fields sort id format float %.17g\n"
     << "run " << o.steps << "\n";
  return {in.str(), data.str()};
}

std::vector<Frame> read_dump(const std::filesystem::path& path, std::size_t particles) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("lammps: no dump at " + path.string());
  std::vector<Frame> frames;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("ITEM: TIMESTEP", 0) != 0) continue;
    Frame f;
    std::getline(in, line);
    f.step = std::stoll(line);
    std::getline(in, line);  // ITEM: NUMBER OF ATOMS
    std::getline(in, line);
    const std::size_t count = std::stoull(line);
    for (int k = 0; k < 4; ++k) std::getline(in, line);  // box bounds
    std::getline(in, line);  // ITEM: ATOMS id x y z ...
    std::istringstream head(line.substr(std::string("ITEM: ATOMS").size()));
    std::map<std::string, int> col;
    std::string name;
    for (int c = 0; head >> name; ++c) col[name] = c;
    for (const char* need : {"id", "x", "y", "z", "vx", "vy", "vz", "c_damage"})
      if (!col.count(need)) throw std::runtime_error(std::string("lammps: dump has no column ") + need);
    f.x.assign(particles, {0, 0, 0});
    f.v.assign(particles, {0, 0, 0});
    f.damage.assign(particles, 0.0);
    std::vector<double> row(col.size());
    for (std::size_t a = 0; a < count; ++a) {
      for (double& r : row) in >> r;
      const auto id = static_cast<std::size_t>(row[col["id"]]);
      if (id < 1 || id > particles) throw std::runtime_error("lammps: dump atom id out of range");
      const std::size_t i = id - 1;
      f.x[i] = {row[col["x"]], row[col["y"]], row[col["z"]]};
      f.v[i] = {row[col["vx"]], row[col["vy"]], row[col["vz"]]};
      f.damage[i] = row[col["c_damage"]];
    }
    std::getline(in, line);
    frames.push_back(std::move(f));
  }
  return frames;
}

Result run(const io::Scene& scene, const sim::PdSetup<3>& setup, const Options& o) {
  const Input input = make_input(scene, setup, o);
  std::filesystem::create_directories(o.work_dir);
  write_text(o.work_dir / "in.pdmpm", input.script);
  write_text(o.work_dir / "data.pdmpm", input.data);
  std::filesystem::remove(o.work_dir / "dump.pdmpm");
  const std::string cmd = "cd " + shell_quote(o.work_dir.string()) + " && OMP_NUM_THREADS=" + std::to_string(o.threads) +
                          " " + shell_quote(executable()) +
                          " -nocite -in in.pdmpm -log log.pdmpm -screen none > lmp.out 2>&1";
  const auto t0 = std::chrono::steady_clock::now();
  const int status = std::system(cmd.c_str());
  Result r;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.log = read_text(o.work_dir / "log.pdmpm");
  if (status != 0) {
    const std::string tail = r.log.size() > 2000 ? r.log.substr(r.log.size() - 2000) : r.log;
    throw std::runtime_error("lammps: `" + executable() + "` failed (status " + std::to_string(status) + ") in " +
                             o.work_dir.string() + "; log tail:\n" + tail + read_text(o.work_dir / "lmp.out"));
  }
  std::smatch m;
  // The last run's loop (the first is the `run 0` that builds the families).
  static const std::regex loop(R"(Loop time of ([0-9.eE+-]+) on)");
  for (std::sregex_iterator it(r.log.begin(), r.log.end(), loop), end; it != end; ++it) r.loop_seconds = std::stod((*it)[1]);
  if (std::regex_search(r.log, m, std::regex(R"(total # of bonds = ([0-9]+))"))) r.bonds = std::stoll(m[1]);
  if (std::regex_search(r.log, m, std::regex(R"(LAMMPS \(([^)]*)\))"))) r.version = m[1];
  r.sections = timing_breakdown(r.log);
  if (std::regex_search(r.log, m, std::regex(R"(memory allocation \(min/avg/max\) = [0-9.eE+-]+ \| [0-9.eE+-]+ \| ([0-9.eE+-]+) Mbytes)")))
    r.memory_mbytes = std::stod(m[1]);
  r.frames = read_dump(o.work_dir / "dump.pdmpm", static_cast<std::size_t>(setup.system.particles.n_real));
  return r;
}

std::map<std::string, double> timing_breakdown(const std::string& log) {
  // Rows like "Pair    | 1.9884     | 1.9884     | 1.9884     |   0.0 | 98.37"; "Other" has
  // only the average column filled. The last run's table wins.
  std::map<std::string, double> sections;
  static const std::regex row(R"((Pair|Bond|Kspace|Neigh|Comm|Output|Modify|Other)\s*\|\s*([0-9.eE+-]*)\s*\|\s*([0-9.eE+-]+))");
  std::istringstream in(log);
  std::string line;
  std::smatch m;
  while (std::getline(in, line))
    if (std::regex_search(line, m, row) && m.position(0) == 0) sections[m[1]] = std::stod(m[3]);
  return sections;
}

std::int64_t broken_sides_from_damage(const std::vector<double>& damage, const core::Families<3>& families) {
  double sides = 0.0;
  for (Index i = 0; i < families.n_owners(); ++i) sides += damage[i] * static_cast<double>(families.end(i) - families.begin(i));
  return std::llround(sides);
}

}  // namespace pdmpm::test::lammps
