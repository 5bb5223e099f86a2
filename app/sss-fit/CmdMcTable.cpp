// sss-fit mc-table: regenerates the table behind model mc-table (profiles/McTable.h)
// from the project's Monte Carlo. The grid is the shipped one; the photon budget and the
// seed are options, and the same budget, seed and build give the same file bit for bit,
// whatever the thread count. The file is format version 2: with the once-scattered light
// stored apart (q per η and annulus), whose η = 1 total is checked here against its closed
// form (1 - ln 2)/2 (Chandrasekhar's first-order term; SingleScattering.h).
#include "CommandSupport.h"

#include "profiles/McTable.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <unistd.h>

namespace sss::app {

namespace {

// One table's walks, with progress on stderr: a bar on a terminal, else a line per 5%.
// `label` names the table, `part`/`parts` place it in a run of several.
profiles::McTableData generate_one(profiles::McTableOptions o, const McTableArgs& a,
                                   const std::string& label, std::size_t part, std::size_t parts) {
  if (a.photons) o.photons = a.photons;
  o.seed = a.seed;
  o.threads = a.threads;
  const auto start = std::chrono::steady_clock::now();
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  int last_logged = -1;
  o.progress = [&](double f) {
    if (tty) {
      progress_bar(label.c_str(), f);
      return;
    }
    // Not a terminal (CI logs, nohup): one line per 5%, with the time left.
    const int step = static_cast<int>(f * 20.0);
    if (step == last_logged) return;
    last_logged = step;
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "sss-fit mc-table: %s (%zu of %zu): %3.0f%% after %.0f s, about %.0f s left\n",
                 label.c_str(), part, parts, 100.0 * f, s, f > 0.0 ? s * (1.0 - f) / f : 0.0);
  };
  std::fprintf(stderr,
               "sss-fit mc-table: %s: %llu walks (seed %llu) for %zu eta x %zu albedo nodes, "
               "%zu annuli\n",
               label.c_str(), static_cast<unsigned long long>(o.photons),
               static_cast<unsigned long long>(o.seed), o.eta.size(), o.albedo.size(),
               o.r_edges.size() - 1);
  profiles::McTableData t = profiles::generate_mc_table(o);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double worst = 0.0;
  for (std::size_t i = 0; i < t.total.size(); ++i)
    if (t.total[i] > 0.0) worst = std::max(worst, t.total_se[i] / t.total[i]);
  std::printf("%s: %llu walks, %.1f s; largest relative standard error of a total reflectance "
              "%.2e\n",
              label.c_str(), static_cast<unsigned long long>(t.photons), seconds, worst);
  return t;
}

int check_photons(const profiles::McTableOptions& o, const McTableArgs& a) {
  const std::uint64_t photons = a.photons ? a.photons : o.photons;
  if (photons % o.chunk_photons != 0 || photons / o.chunk_photons < 2)
    return usage_error("--photons: must be a multiple of " + std::to_string(o.chunk_photons) +
                       " and at least " + std::to_string(2 * o.chunk_photons) + ", got " +
                       std::to_string(photons));
  return kExitOk;
}

}  // namespace

int run_mc_table(const McTableArgs& a) {
  if (a.anisotropic || a.g) {
    std::vector<double> gs = a.g ? std::vector<double>{*a.g} : profiles::shipped_mc_table_g_values();
    if (a.g && *a.g == 0.0)
      return usage_error("--g: 0 is the isotropic table (sss-fit mc-table without --g)");
    if (const int rc = check_photons(profiles::shipped_mc_table_g_options(gs[0]), a)) return rc;
    std::vector<profiles::McTableData> tables;
    for (std::size_t i = 0; i < gs.size(); ++i) {
      char label[64];
      std::snprintf(label, sizeof label, "layer g = %g", gs[i]);
      tables.push_back(generate_one(profiles::shipped_mc_table_g_options(gs[i]), a, label, i + 1,
                                    gs.size()));
    }
    const std::string bytes = a.g ? profiles::serialize_mc_table(tables[0])
                                  : profiles::serialize_mc_table_set(tables);
    // Parse what is about to be written: the file must load.
    if (a.g)
      profiles::parse_mc_table(bytes, a.out);
    else
      profiles::parse_mc_table_set(bytes, a.out);
    if (!write_output(a.out, bytes)) return kExitRuntime;
    std::printf("wrote %s: %zu bytes, %zu layer%s\n", a.out.c_str(), bytes.size(), tables.size(),
                tables.size() == 1 ? "" : "s");
    return kExitOk;
  }
  const profiles::McTableOptions o = profiles::shipped_mc_table_options();
  if (const int rc = check_photons(o, a)) return rc;
  const profiles::McTableData t = generate_one(o, a, "Monte Carlo table", 1, 1);
  const std::string bytes = profiles::serialize_mc_table(t);
  // Parse what is about to be written: the file must load.
  profiles::parse_mc_table(bytes, a.out);
  if (!write_output(a.out, bytes)) return kExitRuntime;
  std::printf("wrote %s: %zu bytes\n", a.out.c_str(), bytes.size());
  if (!t.eta.empty() && t.eta.front() == 1.0) {
    const double exact = (1.0 - std::log(2.0)) / 2.0;
    // The error is a batch mean over photons / chunk_photons batches: rough with few.
    std::printf("once-scattered total per unit albedo at eta 1: %.6f +- %.2g (closed form "
                "(1 - ln 2)/2 = %.6f, z %+.2f; error from %llu batches)\n",
                t.single_total[0], t.single_total_se[0], exact,
                (t.single_total[0] - exact) / t.single_total_se[0],
                static_cast<unsigned long long>(t.photons / t.chunk_photons));
  }
  return kExitOk;
}

}  // namespace sss::app
