// The Monte Carlo profile table behind model `mc-table`: R(r) of a semi-infinite medium
// under a smooth dielectric boundary, lit by a normally incident pencil beam, computed by
// the project's own random walk once and shipped as data (profiles/data/mc_table.bin).
//
// Units: the table is in optical units, σt' = 1 (r in reduced mean free paths), with
// isotropic scattering at the reduced albedo α' = σs'/σt' (the similarity relation
// σs' = σs (1 - g): a medium with g ≠ 0 is looked up at its reduced coefficients). Any
// medium is then a lookup plus a scale: R_mm(r) = σt'² R_table(σt' r).
//
// What is stored, per (η, α') node: the flux fraction that leaves through each annulus
// [r_k, r_k+1) of the radial grid (the increments of the radial CDF C(r) = ∫0^r 2πr'R dr'),
// the total diffuse reflectance (all exits, also beyond the last edge), and the standard
// error of each. The CDF and not r·R(r) because a Monte Carlo tally measures exactly the
// flux through an annulus, with no binning bias: a point value of r·R(r) does not exist
// in the data and would have to be guessed from the bin averages, which biases it where
// R falls steeply. The lookup (McTableProfile) rebuilds a smooth R(r) whose integral over
// every annulus reproduces the tallied flux.
//
// Format version 2 also stores the once-scattered part (issue 18 part 2: the renderers
// add single scattering S(1) apart, in closed form, so a profile must be able to leave it
// out). In these units a walk enters straight down; an exit after exactly one scattering
// event carries α' (the one event's albedo factor) times its η-weight, and, a walk having
// reflected at the surface once, goes down again and cannot leave before it scatters
// again. So the once-scattered flux through annulus b at node (η, α') is exactly
// α' q(η, b), q not depending on α': the table stores q ("once-scattered flux per unit
// albedo") per η and annulus, and its total q_total(η), tallied in the same walks as
// everything else (exits with n = 1). `flux` and `total` keep every order, so the
// multiply-scattered part of the same walks is flux - α' q and total - α' q_total
// (exactly, up to the rounding of the stored values). Its standard error is not a
// function of the two errors (the parts are correlated, and the triangle bound
// se(flux) + α' se(q) is 25-2900x the actual error at α' = 0.01 over r <= 3 mfp and 29x
// in the disc r < 0.001 mfp even at α' = 0.9999, where the once-scattered light
// dominates the exits: judged by it, the shipped table's α' = 0.01 nodes would have 0-10
// annuli reliable for the apart lookup, where the stored error finds 54-58), so it is
// stored too, from the batch means of the difference itself.
//
// Generation (generate_mc_table) uses one set of random walks for every node of the
// table; McTableGenerator.cpp explains why that is unbiased and how the errors come out.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace sss::profiles {

// The real single-scattering albedo α = σs/σt of a medium with reduced albedo α' and
// Henyey-Greenstein g: σs' = σs(1 - g) and σt' = σa + σs' give α' = α(1 - g)/(1 - α g),
// so α = α'/(1 - g + g α'). Its reduced mean free path is 1/σt' = 1/(σt (1 - α g)).
inline double real_albedo(double albedo_reduced, double g) {
  return albedo_reduced / (1.0 - g + g * albedo_reduced);
}

struct McTableData {
  // The Henyey-Greenstein g of the walks (format version 3; 0 for version 2). With g != 0
  // the walks scatter with the real phase function (issue 18 part 4) instead of the
  // similarity medium's isotropic one; the axes are still η and the reduced albedo α',
  // r still in reduced mean free paths. The once-scattered light then no longer scales as
  // α' q of one q per η (the reduced radius of an exit depends on α), so single_total
  // and single_flux hold the once-scattered flux itself per node, laid out as total and
  // flux ([eta][albedo], [eta][albedo][bin]).
  double g = 0.0;
  bool single_per_node() const { return g != 0.0; }
  std::uint64_t photons = 0;        // random walks behind every node
  std::uint64_t seed = 0;
  std::uint64_t chunk_photons = 0;  // walks per batch: standard errors are batch-means
  double roulette_weight = 0.0;     // the run's variance-reduction settings, for the record
  double roulette_survival = 0.0;
  std::vector<double> eta;          // relative refractive index, ascending, >= 1
  std::vector<double> albedo;       // reduced albedo α', ascending, in (0, 1)
  std::vector<double> r_edges;      // annulus edges in mean free paths: 0, then ascending
  // [eta][albedo]: total diffuse reflectance and its standard error.
  std::vector<double> total, total_se;
  // [eta][albedo][bin], bin in [0, bins()): the flux fraction through annulus bin.
  std::vector<double> flux, flux_se;
  // Version 2: the once-scattered part per unit albedo (see above). [eta]: q_total and its
  // standard error; [eta][bin]: q through annulus bin and its standard error.
  std::vector<double> single_total, single_total_se;
  std::vector<double> single_flux, single_flux_se;
  // Version 2: the standard errors of the multiply-scattered parts total - α' q_total
  // ([eta][albedo]) and flux - α' q ([eta][albedo][bin]).
  std::vector<double> multiple_total_se, multiple_flux_se;

  std::size_t bins() const { return r_edges.empty() ? 0 : r_edges.size() - 1; }
  std::size_t node(std::size_t e, std::size_t a) const { return e * albedo.size() + a; }
  std::size_t slot(std::size_t e, std::size_t a, std::size_t b) const {
    return node(e, a) * bins() + b;
  }
  std::size_t single_slot(std::size_t e, std::size_t b) const { return e * bins() + b; }
  // The multiply-scattered parts at node (e, a): flux - α' q through annulus b and
  // total - α' q_total, clamped at 0 (they are >= 0 up to the rounding of the stored
  // values).
  double multiple_flux(std::size_t e, std::size_t a, std::size_t b) const;
  double multiple_total(std::size_t e, std::size_t a) const;
};

struct McTableOptions {
  std::vector<double> eta;
  std::vector<double> albedo;
  std::vector<double> r_edges;  // 0 first, then strictly ascending, in mean free paths
  std::uint64_t photons = 1u << 16;
  std::uint64_t seed = 1;
  std::uint64_t chunk_photons = 4096;  // photons must be a multiple of it (>= 2 chunks)
  int threads = 0;                     // 0: every hardware thread
  // Russian roulette on the walk's largest weight over every (η, α') node, relative to
  // the start: below roulette_weight it survives with probability roulette_survival.
  double roulette_weight = 0.05;
  double roulette_survival = 0.1;
  // Henyey-Greenstein g of the walks, in (-1, 1). 0: the isotropic walk of the shipped
  // table, in reduced units with albedo scaling over α'. Otherwise the walk runs in real
  // units (σt = 1) with HG scattering; node a's real albedo is real_albedo(α'_a, g) (one
  // walk still serves every node by albedo scaling: flights do not depend on α), and an
  // exit at real radius r lands in node a's annulus of r (1 - α_a g), its radius in
  // reduced mean free paths.
  double g = 0.0;
  // Called after each batch with the fraction done; calls never overlap.
  std::function<void(double)> progress;
};

// The grid and budget of the shipped table (the `sss-fit mc-table` defaults).
McTableOptions shipped_mc_table_options();
// The g nodes of the shipped anisotropic layers (profiles/data/mc_table_g.bin), ascending;
// the isotropic table is the node g = 0.
const std::vector<double>& shipped_mc_table_g_values();
// The grid and budget of the shipped layer at g (`sss-fit mc-table --anisotropic`): a
// coarser grid than the isotropic table's, to keep the shipped data small (profiles/data/
// README.md).
McTableOptions shipped_mc_table_g_options(double g);

// Runs the walks. Deterministic for a seed whatever `threads` is. Throws
// std::invalid_argument naming the field for a bad grid or budget.
McTableData generate_mc_table(const McTableOptions& opt);

// The file format (little-endian, documented in profiles/data/README.md).
std::string serialize_mc_table(const McTableData& t);
// Throws std::invalid_argument "NAME: FIELD: why" for anything malformed.
McTableData parse_mc_table(std::string_view bytes, std::string_view name);

// A set of tables (the anisotropic layers, profiles/data/mc_table_g.bin): each a table of
// Henyey-Greenstein walks, g ascending. Layout in profiles/data/README.md.
std::string serialize_mc_table_set(const std::vector<McTableData>& tables);
std::vector<McTableData> parse_mc_table_set(std::string_view bytes, std::string_view name);

// The table compiled into the library from profiles/data/mc_table.bin, parsed on first
// use (thread-safe).
const McTableData& shipped_mc_table();
// The anisotropic layers compiled in from profiles/data/mc_table_g.bin (g ascending,
// shipped_mc_table_g_values()), parsed on first use (thread-safe).
const std::vector<McTableData>& shipped_mc_table_layers();

}  // namespace sss::profiles
