#include "profiles/TabulatedProfile.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sss::profiles {

TabulatedProfile::Table TabulatedProfile::Table::build(std::vector<double> r_mm,
                                                       std::vector<double> v,
                                                       const char* what) {
  const std::string value_field = what;
  if (r_mm.size() != v.size())
    throw std::invalid_argument("r_mm: has " + std::to_string(r_mm.size()) + " radii but " +
                                value_field + " has " + std::to_string(v.size()) + " values");
  Table t;
  for (std::size_t i = 0; i < r_mm.size(); ++i) {
    if (!std::isfinite(r_mm[i]) || !(r_mm[i] > 0.0))
      throw std::invalid_argument("r_mm: radii must be finite and > 0 (node " +
                                  std::to_string(i) + ")");
    if (i > 0 && !(r_mm[i] > r_mm[i - 1]))
      throw std::invalid_argument("r_mm: radii must be strictly ascending (node " +
                                  std::to_string(i) + ")");
    if (!std::isfinite(v[i]) || v[i] < 0.0)
      throw std::invalid_argument(value_field + ": values must be finite and >= 0 (node " +
                                  std::to_string(i) + ")");
    if (v[i] == 0.0) continue;  // log-log interpolation cannot pass through 0
    t.log_r.push_back(std::log(r_mm[i]));
    t.log_v.push_back(std::log(v[i]));
  }
  const std::size_t n = t.log_r.size();
  if (n < 2)
    throw std::invalid_argument(value_field + ": needs at least two nodes with a value > 0");
  const double r_last = std::exp(t.log_r[n - 1]), r_prev = std::exp(t.log_r[n - 2]);
  const double k = (t.log_v[n - 2] - t.log_v[n - 1]) / (r_last - r_prev);
  t.tail_rate = k > 0.0 ? k : 1.0 / (r_last - r_prev);
  return t;
}

double TabulatedProfile::Table::eval(double r_mm) const {
  if (log_r.empty()) return 0.0;
  const double lr = std::log(std::max(r_mm, 0.0));  // -inf at r = 0: the constant part
  if (lr <= log_r.front()) return std::exp(log_v.front());
  if (lr >= log_r.back())
    return std::exp(log_v.back() - tail_rate * (r_mm - std::exp(log_r.back())));
  // log_r[i] <= lr < log_r[i + 1]
  const auto i = static_cast<std::size_t>(
      std::upper_bound(log_r.begin(), log_r.end(), lr) - log_r.begin() - 1);
  const double t = (lr - log_r[i]) / (log_r[i + 1] - log_r[i]);
  return std::exp(log_v[i] + t * (log_v[i + 1] - log_v[i]));
}

TabulatedProfile::TabulatedProfile(std::vector<double> r_mm, std::vector<double> R,
                                   double total, double total_transmittance)
    : reflectance_(Table::build(std::move(r_mm), std::move(R), "R")),
      total_(total),
      total_t_(total_transmittance) {
  if (!std::isfinite(total_)) throw std::invalid_argument("total: must be finite");
  if (!std::isfinite(total_t_))
    throw std::invalid_argument("total_transmittance: must be finite");
}

void TabulatedProfile::set_transmittance(std::vector<double> r_mm, std::vector<double> T) {
  transmittance_ = Table::build(std::move(r_mm), std::move(T), "T");
}

namespace {

// Nodes at the area-weighted bin centres, empty bins dropped.
void bin_nodes(const std::vector<double>& edges, const std::vector<double>& value,
               std::vector<double>& r, std::vector<double>& v) {
  for (std::size_t b = 0; b + 1 < edges.size() && b < value.size(); ++b) {
    if (!(value[b] > 0.0)) continue;
    r.push_back(std::sqrt(0.5 * (edges[b] * edges[b] + edges[b + 1] * edges[b + 1])));
    v.push_back(value[b]);
  }
}

}  // namespace

TabulatedProfile TabulatedProfile::from_monte_carlo(const MonteCarloResult& mc) {
  std::vector<double> r, v;
  bin_nodes(mc.bin_edges_mm, mc.reflectance.value, r, v);
  TabulatedProfile p(std::move(r), std::move(v), mc.reflectance.total, mc.transmittance.total);
  std::vector<double> rt, vt;
  bin_nodes(mc.bin_edges_mm, mc.transmittance.value, rt, vt);
  if (rt.size() >= 2) p.set_transmittance(std::move(rt), std::move(vt));
  return p;
}

double TabulatedProfile::support_radius() const { return std::exp(reflectance_.log_r.back()); }

double TabulatedProfile::inner_radius() const { return std::exp(reflectance_.log_r.front()); }

}  // namespace sss::profiles
