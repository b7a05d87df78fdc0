#include "verification/support/strip_gauge.hpp"

#include <algorithm>

namespace pdmpm::test {

io::Scene as_mpm_j2(io::Scene s) {
  s.method = io::Method::mpm;
  s.model = "mpm";
  io::MpmSpec m;  // GIMP, MUSL, cell 2Δx: the defaults, Noorian et al.'s choices
  m.constitutive = mpm::MaterialModel::j2;
  s.mpm = m;
  s.damage = false;
  return s;
}

std::vector<GaugeReading> gauge_history(const GateRun& run, double x_lo, double x_hi, double y_lo, double y_hi) {
  const auto fields = run.fields();
  std::vector<GaugeReading> out;
  for (const auto& frame : fields.frames()) {
    const auto pos = fields.read(frame, "position");
    const auto u = fields.read(frame, "displacement");
    const auto stress = fields.read(frame, "stress");  // xx, yy, zz, xy, yz, xz
    double n = 0, sx = 0, su = 0, sxx = 0, sxu = 0, s = 0;
    for (std::size_t i = 0; 3 * i < pos.size(); ++i) {
      const double x0 = pos[3 * i] - u[3 * i], y0 = pos[3 * i + 1] - u[3 * i + 1];
      if (x0 < x_lo || x0 > x_hi || y0 < y_lo || y0 > y_hi) continue;
      n += 1, sx += x0, su += u[3 * i], sxx += x0 * x0, sxu += x0 * u[3 * i], s += stress[6 * i];
    }
    out.push_back({(n * sxu - sx * su) / (n * sxx - sx * sx), s / n});
  }
  return out;
}

double interpolate(const std::vector<double>& x, const std::vector<double>& y, double xq) {
  const auto it = std::lower_bound(x.begin(), x.end(), xq);
  if (it == x.begin()) return y.front();
  if (it == x.end()) return y.back();
  const std::size_t k = static_cast<std::size_t>(it - x.begin());
  return y[k - 1] + (y[k] - y[k - 1]) * (xq - x[k - 1]) / (x[k] - x[k - 1]);
}

}  // namespace pdmpm::test
