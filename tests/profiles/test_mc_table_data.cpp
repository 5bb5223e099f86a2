// The mc-table's data and generator (profiles/McTable.h): the file format and its
// refusals, the generator's options, determinism and bookkeeping, and the shipped table
// against exact transport (η = 1) and against the independent analog random walk of
// profiles/MonteCarlo.h run at test time. The lookup that interpolates the table
// (McTableProfile) has its own tests in test_mc_table_profile.cpp.
//
// Statistical tolerances come from the standard errors stored in the table (batch means)
// and those of the test-time run, so they tighten by themselves when the table is
// regenerated with more walks; the accuracy goals (0.5% at η = 1, 1% elsewhere)
// are asserted as fixed bounds next to them.
#include "profiles/HFunction.h"
#include "profiles/McTable.h"
#include "profiles/Medium.h"
#include "profiles/MonteCarlo.h"

#include "McTableTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numbers>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace sss::profiles {
namespace {

using test::annuli_covering;
using test::chi2_over_k_quantile;
using test::EdgeRange;
using test::z_family;
using test::z_one_sided;

constexpr double kEps = std::numeric_limits<double>::epsilon();

// ---------------------------------------------------------------------------------------
// Statistics helpers.

// ---------------------------------------------------------------------------------------
// The file format.

// FNV-1a 64 with the published offset basis and prime (Fowler, Noll & Vo), written here
// from the algorithm's definition, independently of McTableFormat.cpp: re-checksumming an
// edited file lets the test reach the check behind the checksum.
std::uint64_t fnv1a(std::string_view bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
  return h;
}

std::string rechecksum(std::string bytes) {
  const std::uint64_t h = fnv1a(std::string_view(bytes).substr(0, bytes.size() - 8));
  std::memcpy(bytes.data() + bytes.size() - 8, &h, 8);
  return bytes;
}

// A small table, fast to generate (~10 ms): two η (one with internal reflection), three
// albedos, four annuli.
McTableOptions small_options() {
  McTableOptions o;
  o.eta = {1.0, 1.4};
  o.albedo = {0.5, 0.9, 0.99};
  o.r_edges = {0.0, 0.1, 1.0, 4.0, 16.0};
  o.chunk_photons = 256;
  o.photons = 8 * 256;
  o.seed = 7;
  o.threads = 1;
  return o;
}

const McTableData& small_table() {
  static const McTableData t = generate_mc_table(small_options());
  return t;
}

// parse_mc_table must throw std::invalid_argument "NAME: FIELD: why".
void expect_parse_error(const std::string& bytes, const std::string& field,
                        const std::string& what, const std::string& phrase = "") {
  try {
    parse_mc_table(bytes, "edited.bin");
    ADD_FAILURE() << what << ": parsed without an error";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("edited.bin: " + field + ": ", 0), 0u) << what << ": " << m;
    if (!phrase.empty()) {
      EXPECT_NE(m.find(phrase), std::string::npos) << what << ": " << m;
    }
  }
}

TEST(McTableFormat, RoundTripIsExact) {
  const McTableData& t = small_table();
  const std::string bytes = serialize_mc_table(t);
  const McTableData p = parse_mc_table(bytes, "small");
  EXPECT_EQ(p.photons, t.photons);
  EXPECT_EQ(p.seed, t.seed);
  EXPECT_EQ(p.chunk_photons, t.chunk_photons);
  EXPECT_EQ(p.roulette_weight, t.roulette_weight);
  EXPECT_EQ(p.roulette_survival, t.roulette_survival);
  EXPECT_EQ(p.eta, t.eta);
  EXPECT_EQ(p.albedo, t.albedo);
  EXPECT_EQ(p.r_edges, t.r_edges);
  EXPECT_EQ(p.total, t.total);  // double in the file
  EXPECT_EQ(p.total_se, t.total_se);
  // Annulus fluxes are stored as float (documented): exactly the rounded values.
  ASSERT_EQ(p.flux.size(), t.flux.size());
  for (std::size_t i = 0; i < t.flux.size(); ++i) {
    EXPECT_EQ(p.flux[i], static_cast<double>(static_cast<float>(t.flux[i]))) << i;
    EXPECT_EQ(p.flux_se[i], static_cast<double>(static_cast<float>(t.flux_se[i]))) << i;
    EXPECT_EQ(p.multiple_flux_se[i], static_cast<double>(static_cast<float>(t.multiple_flux_se[i]))) << i;
  }
  // Version 2's once-scattered part: totals and the multiply-scattered total errors in
  // double, the annuli in float.
  EXPECT_EQ(p.single_total, t.single_total);
  EXPECT_EQ(p.single_total_se, t.single_total_se);
  EXPECT_EQ(p.multiple_total_se, t.multiple_total_se);
  ASSERT_EQ(p.single_flux.size(), t.eta.size() * t.bins());
  for (std::size_t i = 0; i < t.single_flux.size(); ++i) {
    EXPECT_EQ(p.single_flux[i], static_cast<double>(static_cast<float>(t.single_flux[i]))) << i;
    EXPECT_EQ(p.single_flux_se[i], static_cast<double>(static_cast<float>(t.single_flux_se[i]))) << i;
  }
  // A parsed table serializes to the very same bytes, and the trailer is FNV-1a 64 of
  // everything before it (as profiles/data/README.md documents).
  EXPECT_EQ(serialize_mc_table(p), bytes);
  std::uint64_t stored;
  std::memcpy(&stored, bytes.data() + bytes.size() - 8, 8);
  EXPECT_EQ(stored, fnv1a(std::string_view(bytes).substr(0, bytes.size() - 8)));
}

// Byte offsets of the documented layout (profiles/data/README.md).
constexpr std::size_t kVersionAt = 8, kNEtaAt = 12, kHeaderBytes = 64;

TEST(McTableFormat, ParseRefusesMalformedFilesNamingTheField) {
  const McTableData& t = small_table();
  const std::string good = serialize_mc_table(t);
  ASSERT_NO_THROW(parse_mc_table(good, "good.bin"));

  expect_parse_error("", "magic", "empty input");
  std::string s = good;
  s[0] = 'X';
  expect_parse_error(rechecksum(s), "magic", "wrong magic");
  expect_parse_error(good.substr(0, 6), "magic", "shorter than the magic");

  // One flipped bit anywhere behind the magic is caught by the checksum.
  for (std::size_t at : {kVersionAt, kHeaderBytes + 3, good.size() / 2, good.size() - 9}) {
    s = good;
    s[at] = static_cast<char>(s[at] ^ 0x10);
    expect_parse_error(s, "checksum", "flipped byte at " + std::to_string(at), "does not match");
  }
  // Truncated: first the checksum no longer matches; re-checksummed, the parser finds the
  // arrays end early (the last array, multiple_flux_se, is the one cut).
  expect_parse_error(good.substr(0, good.size() - 40), "checksum", "truncated");
  expect_parse_error(good.substr(0, 20), "checksum", "truncated in the header");
  s = good.substr(0, good.size() - 8 - 4 * 8);  // 8 floats of multiple_flux_se missing...
  s += std::string(8, '\0');                    // ...and a fresh checksum trailer
  expect_parse_error(rechecksum(s), "multiple_flux_se", "truncated, re-checksummed", "ends early");
  // Exactly two floats short: a parser that let the arrays run into the trailer would read
  // the checksum as multiple_flux_se and then find -8 bytes "before the checksum".
  s = good.substr(0, good.size() - 8 - 4 * 2) + std::string(8, '\0');
  expect_parse_error(rechecksum(s), "multiple_flux_se", "two floats short, re-checksummed", "ends early");
  s = good.substr(0, kHeaderBytes + 4);  // inside the η array
  s += std::string(8, '\0');
  expect_parse_error(rechecksum(s), "eta", "truncated inside eta, re-checksummed", "ends early");

  s = good;
  s[kVersionAt] = 4;
  expect_parse_error(rechecksum(s), "version", "wrong version", "4 is not supported");
  // Version 3 (an anisotropic layer) carries g after the roulette settings: a version 2
  // body relabelled 3 reads its first η as g (1: outside (-1, 1)).
  s = good;
  s[kVersionAt] = 3;
  expect_parse_error(rechecksum(s), "g", "version 3 without g", "must have g in (-1, 1)");
  // A version 1 file (no once-scattered part) is refused with what to do about it.
  s[kVersionAt] = 1;
  expect_parse_error(rechecksum(s), "version", "version 1", "1 is not supported");
  expect_parse_error(rechecksum(s), "version", "version 1", "regenerate the table with sss-fit mc-table");

  // Counts that promise more data than the file has are refused before anything is
  // allocated for them (n_eta 1024 × n_albedo 4096 × 4095 annuli would be 68 GB of floats).
  s = good;
  const std::uint32_t counts[3] = {1024, 4096, 4096};
  std::memcpy(s.data() + kNEtaAt, counts, sizeof(counts));
  expect_parse_error(rechecksum(s), "eta", "counts larger than the file", "ends early");
  s = good;
  const std::uint32_t zero = 0;
  std::memcpy(s.data() + kNEtaAt, &zero, 4);
  expect_parse_error(rechecksum(s), "n_eta", "no eta");

  // Values: edited in the table and serialized, so the checksum is right and the value
  // check is what fires.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  McTableData e = t;
  e.total[1] = nan;
  expect_parse_error(serialize_mc_table(e), "total", "NaN total", "not finite");
  e = t;
  e.flux_se[5] = nan;
  expect_parse_error(serialize_mc_table(e), "flux_se", "NaN flux_se", "not finite");
  e = t;
  e.albedo[2] = std::numeric_limits<double>::infinity();
  expect_parse_error(serialize_mc_table(e), "albedo", "infinite albedo", "not finite");
  e = t;
  std::swap(e.albedo[0], e.albedo[1]);
  expect_parse_error(serialize_mc_table(e), "albedo", "albedo not ascending", "ascending");
  e = t;
  e.eta[1] = e.eta[0];
  expect_parse_error(serialize_mc_table(e), "eta", "eta repeated", "ascending");
  e = t;
  e.eta[0] = 0.9;
  expect_parse_error(serialize_mc_table(e), "eta", "eta below 1", "outside");
  e = t;
  std::swap(e.r_edges[2], e.r_edges[3]);
  expect_parse_error(serialize_mc_table(e), "r_edges", "r_edges not ascending", "ascending");
  e = t;
  e.r_edges[0] = 0.01;
  expect_parse_error(serialize_mc_table(e), "r_edges", "r_edges not from 0", "first edge");
  e = t;
  e.albedo[2] = 1.0;
  expect_parse_error(serialize_mc_table(e), "albedo", "albedo 1", "outside");
  e = t;
  e.total[3] = 1.5;
  expect_parse_error(serialize_mc_table(e), "total", "total above 1", "outside [0, 1]");
  e = t;
  e.total[0] = -1e-3;
  expect_parse_error(serialize_mc_table(e), "total", "negative total", "outside [0, 1]");
  e = t;
  e.flux[2] = -1e-3;
  expect_parse_error(serialize_mc_table(e), "flux", "negative flux", "negative");
  e = t;
  e.single_total[1] = nan;
  expect_parse_error(serialize_mc_table(e), "single_total", "NaN single_total", "not finite");
  e = t;
  e.single_total[0] = 1.5;
  expect_parse_error(serialize_mc_table(e), "single_total", "single_total above 1", "outside [0, 1]");
  e = t;
  e.multiple_total_se[2] = -1e-3;
  expect_parse_error(serialize_mc_table(e), "multiple_total_se", "negative multiple_total_se", "negative");
  e = t;
  e.single_flux[3] = -1e-3;
  expect_parse_error(serialize_mc_table(e), "single_flux", "negative single_flux", "negative");
  e = t;
  e.single_flux_se[3] = nan;
  expect_parse_error(serialize_mc_table(e), "single_flux_se", "NaN single_flux_se", "not finite");
  e = t;
  e.multiple_flux_se[4] = -1e-3;
  expect_parse_error(serialize_mc_table(e), "multiple_flux_se", "negative multiple_flux_se", "negative");

  // Trailing bytes between the arrays and the checksum.
  s = good;
  s.insert(s.size() - 8, std::string(4, '\0'));
  expect_parse_error(rechecksum(s), "size", "4 trailing bytes", "4 unexpected bytes");
  // Bytes after the checksum make the checksum (the last 8 bytes) wrong.
  expect_parse_error(good + "x", "checksum", "a byte after the checksum");
}

TEST(McTableFormat, ShippedTableParsesWithTheDocumentedGrid) {
  const McTableData& t = shipped_mc_table();
  // Albedo axis: at least 48 nodes in [0.01, 0.9999], both ends exactly (the issue).
  ASSERT_GE(t.albedo.size(), 48u);
  EXPECT_EQ(t.albedo.front(), 0.01);
  EXPECT_EQ(t.albedo.back(), 0.9999);
  // Dense near 1: the generator spaces u = √(1 - α') evenly from 0.01 to √0.99, a step
  // of 0.0156, so u < √0.1 (α' > 0.9) holds for 20 nodes and u < 0.1 (α' > 0.99) for 6.
  auto above = [&](double x) {
    return std::count_if(t.albedo.begin(), t.albedo.end(), [x](double a) { return a > x; });
  };
  EXPECT_GE(above(0.9), 20);
  EXPECT_GE(above(0.99), 6);
  // η from exactly 1 to at least 1.6, inside the library's range.
  ASSERT_FALSE(t.eta.empty());
  EXPECT_EQ(t.eta.front(), 1.0);
  EXPECT_GE(t.eta.back(), 1.6);
  EXPECT_LE(t.eta.back(), kEtaMax);
  // r: 0, then log-spaced from 1e-3 to at least 64 mfp. Log-spaced: every ratio of
  // neighbouring edges (up to the last, which closes the grid) is the same to rounding of
  // 10^(k/16) (a few ε).
  ASSERT_GE(t.r_edges.size(), 4u);
  EXPECT_EQ(t.r_edges[0], 0.0);
  EXPECT_EQ(t.r_edges[1], 1e-3);
  EXPECT_GE(t.r_edges.back(), 64.0);
  const double q = t.r_edges[2] / t.r_edges[1];
  EXPECT_GT(q, 1.0);
  for (std::size_t i = 2; i + 2 < t.r_edges.size(); ++i)
    EXPECT_NEAR(t.r_edges[i + 1] / t.r_edges[i], q, 64 * kEps * q) << "edge " << i;
  // The budget is recorded and every node has a standard error.
  EXPECT_GT(t.photons, 0u);
  EXPECT_GT(t.chunk_photons, 0u);
  EXPECT_EQ(t.photons % t.chunk_photons, 0u);
  EXPECT_GE(t.photons / t.chunk_photons, 2u);
  // The grid is the one the regeneration command writes (shipped_mc_table_options).
  const McTableOptions o = shipped_mc_table_options();
  EXPECT_EQ(t.eta, o.eta);
  EXPECT_EQ(t.albedo, o.albedo);
  EXPECT_EQ(t.r_edges, o.r_edges);
  EXPECT_EQ(t.seed, o.seed);
  EXPECT_EQ(t.chunk_photons, o.chunk_photons);
  RecordProperty("shipped_photons", std::to_string(t.photons));
  std::printf("shipped mc-table: %zu eta x %zu albedo x %zu annuli, %llu walks, seed %llu\n",
              t.eta.size(), t.albedo.size(), t.bins(),
              static_cast<unsigned long long>(t.photons), static_cast<unsigned long long>(t.seed));
}

// ---------------------------------------------------------------------------------------
// The generator.

// generate_mc_table must throw std::invalid_argument "FIELD: why".
void expect_option_error(const McTableOptions& o, const std::string& field,
                         const std::string& what) {
  try {
    generate_mc_table(o);
    ADD_FAILURE() << what << ": no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind(field + ": ", 0), 0u) << what << ": " << e.what();
  }
}

TEST(McTableGenerator, RefusesBadOptionsNamingTheField) {
  const McTableOptions good = small_options();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  McTableOptions o = good;
  o.eta = {0.99, 1.4};
  expect_option_error(o, "eta", "eta below 1");
  o.eta = {1.0, 2.6};
  expect_option_error(o, "eta", "eta above 2.5");
  o.eta = {1.4, 1.3};
  expect_option_error(o, "eta", "eta descending");
  o.eta = {};
  expect_option_error(o, "eta", "no eta");
  o = good;
  o.albedo = {0.0, 0.5};
  expect_option_error(o, "albedo", "albedo 0");
  o.albedo = {0.5, 1.0};
  expect_option_error(o, "albedo", "albedo 1");
  o.albedo = {0.5, nan};
  expect_option_error(o, "albedo", "albedo NaN");
  o.albedo = {0.9, 0.9};
  expect_option_error(o, "albedo", "albedo repeated");
  o = good;
  o.r_edges = {0.1, 1.0, 2.0};
  expect_option_error(o, "r_edges", "r_edges not from 0");
  o.r_edges = {0.0, 1.0, 1.0};
  expect_option_error(o, "r_edges", "r_edges repeated");
  o.r_edges = {0.0};
  expect_option_error(o, "r_edges", "one edge");
  o = good;
  o.photons = o.chunk_photons * 3 + 1;
  expect_option_error(o, "photons", "photons not a multiple of chunk_photons");
  o.photons = o.chunk_photons;
  expect_option_error(o, "photons", "one chunk (no batch-means error)");
  o = good;
  o.chunk_photons = 0;
  expect_option_error(o, "chunk_photons", "chunk_photons 0");
  o = good;
  o.threads = -1;
  expect_option_error(o, "threads", "threads -1");
  o = good;
  o.roulette_survival = 1.0;
  expect_option_error(o, "roulette_survival", "roulette_survival 1");
}

TEST(McTableGenerator, SameBytesForAnyThreadCountAndOtherBytesForAnotherSeed) {
  McTableOptions o = small_options();
  o.threads = 1;
  const std::string one = serialize_mc_table(generate_mc_table(o));
  o.threads = 2;
  EXPECT_EQ(serialize_mc_table(generate_mc_table(o)), one);
  o.threads = 3;  // more threads than cores, chunks finishing out of order
  EXPECT_EQ(serialize_mc_table(generate_mc_table(o)), one);
  o.seed += 1;
  const McTableData other = generate_mc_table(o);
  EXPECT_NE(serialize_mc_table(other), one);
  EXPECT_NE(other.total, small_table().total);
}

// The once-scattered part (format version 2, McTable.h) on the small table:
//  - it is part of every node's flux: flux - α' q >= 0 per annulus and total - α' q_total
//    >= 0 (the n = 1 exits are added to the flux as escaped × α'^1, computed as
//    exp(ln α'), within a few ulps of α': tolerance 1e-12 relative);
//  - it does not depend on the albedo grid: a run with other albedos (same seed, η and
//    edges; the walks differ from the chunk's first on, as the roulette, set by the
//    largest albedo, draws numbers at other events) estimates the same q_total: within
//    4 combined SE (2 η; a false alarm 2 x 6.3e-5; the runs share their chunks' first
//    walks, a positive correlation that only narrows the difference);
//  - the multiply-scattered errors are batch-means standard deviations of the difference
//    of the two batch series, so Minkowski's inequality bounds them exactly:
//    |se(F) - α' se(Q)| <= se(F - α' Q) <= se(F) + α' se(Q) (1e-9 relative for rounding);
//  - at η = 1 a walk leaves at its first exit, so q's annuli add up to at most q_total.
TEST(McTableGenerator, OnceScatteredPartIsPartOfTheFluxAndIndependentOfTheAlbedos) {
  const McTableData& t = small_table();
  const std::size_t ne = t.eta.size(), na = t.albedo.size(), nb = t.bins();
  ASSERT_EQ(t.single_total.size(), ne);
  ASSERT_EQ(t.single_flux.size(), ne * nb);
  ASSERT_EQ(t.multiple_flux_se.size(), ne * na * nb);
  for (std::size_t e = 0; e < ne; ++e) {
    EXPECT_GT(t.single_total[e], 0.0);
    EXPECT_GT(t.single_total_se[e], 0.0);
    double annuli = 0.0;
    for (std::size_t b = 0; b < nb; ++b) annuli += t.single_flux[t.single_slot(e, b)];
    if (t.eta[e] == 1.0) {
      EXPECT_LE(annuli, t.single_total[e] * (1.0 + 1e-12));
    }
    for (std::size_t a = 0; a < na; ++a) {
      const double al = t.albedo[a];
      const std::size_t n = t.node(e, a);
      EXPECT_GE(t.total[n] - al * t.single_total[e], -1e-12 * t.total[n]) << e << " " << a;
      const double se_f = t.total_se[n], se_q = al * t.single_total_se[e];
      EXPECT_LE(t.multiple_total_se[n], (se_f + se_q) * (1.0 + 1e-9)) << e << " " << a;
      EXPECT_GE(t.multiple_total_se[n], std::fabs(se_f - se_q) * (1.0 - 1e-9)) << e << " " << a;
      for (std::size_t b = 0; b < nb; ++b) {
        const std::size_t k = t.slot(e, a, b), j = t.single_slot(e, b);
        EXPECT_GE(t.flux[k] - al * t.single_flux[j], -1e-12 * t.flux[k]) << e << " " << a << " " << b;
        const double f = t.flux_se[k], q = al * t.single_flux_se[j];
        EXPECT_LE(t.multiple_flux_se[k], (f + q) * (1.0 + 1e-9)) << e << " " << a << " " << b;
        EXPECT_GE(t.multiple_flux_se[k], std::fabs(f - q) * (1.0 - 1e-9)) << e << " " << a << " " << b;
      }
    }
  }
  McTableOptions o = small_options();
  o.albedo = {0.2, 0.7};
  const McTableData other = generate_mc_table(o);
  for (std::size_t e = 0; e < ne; ++e)
    EXPECT_NEAR(other.single_total[e], t.single_total[e],
                4.0 * std::hypot(other.single_total_se[e], t.single_total_se[e]))
        << "eta " << t.eta[e];
}

// At η = 1 (no internal reflection) a walk leaves once, with all its weight, and the
// same contribution goes to the node's total and, when it lands inside the last edge,
// to one annulus. So total = Σ annuli + (what left beyond the last edge, >= 0). The two
// sides add the same positive terms in different orders (per walk, per chunk, then over
// chunks): each is exact to (terms) ε relative, with terms <= photons + chunks + annuli;
// the tolerance is twice that plus 8 ε for the final divisions.
TEST(McTableGenerator, AtEtaOneTheAnnuliAddUpToTheTotal) {
  McTableOptions o = small_options();
  o.eta = {1.0};
  o.albedo = {0.1, 0.5, 0.9, 0.99, 0.9999};
  o.photons = 16 * 256;
  auto check = [&](const McTableData& t, bool covers_everything) {
    const double terms = static_cast<double>(o.photons + o.photons / o.chunk_photons + t.bins());
    for (std::size_t a = 0; a < t.albedo.size(); ++a) {
      double sum = 0.0;
      for (std::size_t b = 0; b < t.bins(); ++b) sum += t.flux[t.slot(0, a, b)];
      const double total = t.total[t.node(0, a)], tol = (2.0 * terms + 8.0) * kEps * total;
      EXPECT_GT(total, 0.0);
      EXPECT_LE(sum, total + tol) << "albedo " << t.albedo[a];
      if (covers_everything) {
        EXPECT_NEAR(sum, total, tol) << "albedo " << t.albedo[a];
      }
    }
  };
  // The small grid ends at 16 mfp: bright nodes lose some flux beyond it.
  const McTableData near = generate_mc_table(o);
  check(near, false);
  const std::size_t bright = near.albedo.size() - 1;
  double inside = 0.0;
  for (std::size_t b = 0; b < near.bins(); ++b) inside += near.flux[near.slot(0, bright, b)];
  EXPECT_LT(inside, near.total[near.node(0, bright)]);  // at α' = 0.9999 some leave beyond 16
  // Edges to 1e12 mfp: farther than any walk goes (each flight is < 37 mfp, the largest
  // -ln of a double in (0, 1]; 1e12 / 37 scattering events would need ~2.7e10 events,
  // while the roulette ends a walk after ~ln(20)/1e-4 = 3e4 events at α' = 0.9999 with
  // survival 0.1 per later event).
  o.r_edges = {0.0, 0.1, 1.0, 10.0, 1e3, 1e6, 1e12};
  check(generate_mc_table(o), true);
}

// ---------------------------------------------------------------------------------------
// The shipped table against exact transport: at η = 1 the total diffuse reflectance of an
// isotropic half-space under a normal beam is 1 - H(1)√(1 - α') (Chandrasekhar 1960),
// computed by HFunction.cpp independently of any random walk.

TEST(McTableShipped, IndexMatchedTotalsMatchTheHFunction) {
  const McTableData& t = shipped_mc_table();
  ASSERT_EQ(t.eta.front(), 1.0);
  // One check per node, all from one walk set (correlated): Bonferroni over the nodes at a
  // family-wise false-failure probability of 1e-4 gives z ≈ 4.8 for 64 nodes.
  const double z = z_family(1e-4, t.albedo.size());
  double worst_rel = 0.0, worst_z = 0.0;
  for (std::size_t a = 0; a < t.albedo.size(); ++a) {
    const double alpha = t.albedo[a];
    const double exact = exact_total_reflectance_index_matched(alpha);
    const double got = t.total[t.node(0, a)], se = t.total_se[t.node(0, a)];
    ASSERT_GT(se, 0.0) << alpha;
    const double rel = std::fabs(got / exact - 1.0);
    worst_rel = std::max(worst_rel, rel);
    worst_z = std::max(worst_z, std::fabs(got - exact) / se);
    // The goal: within 0.5% of the exact value.
    EXPECT_LT(rel, 0.005) << "alpha' " << alpha << ": table " << got << " +- " << se
                          << ", exact " << exact;
    // And consistent with its own standard error: no bias beyond the noise.
    EXPECT_NEAR(got, exact, z * se) << "alpha' " << alpha;
  }
  RecordProperty("worst_relative_error", std::to_string(worst_rel));
  RecordProperty("worst_z", std::to_string(worst_z));
  std::printf("eta = 1: worst |table/exact - 1| = %.3g%%, worst |z| = %.2f (bound %.2f)\n",
              100.0 * worst_rel, worst_z, z);
}

// ---------------------------------------------------------------------------------------
// The shipped table against the independent analog random walk (profiles/MonteCarlo.h:
// σs flights, continuous absorption weighting, HG sampling, per-photon errors), run at
// test time at table nodes. The two codes share only Fresnel's formula and the RNG
// class; the table's tricks (albedo scaling, Fresnel splitting over every η, roulette on
// the largest weight, batch-means errors) are absent from the analog walk.

// The index of the table's node nearest to x on an axis.
std::size_t nearest(const std::vector<double>& axis, double x) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < axis.size(); ++i)
    if (std::fabs(axis[i] - x) < std::fabs(axis[best] - x)) best = i;
  return best;
}

// One analog run at a table node, next to the table's values.
struct Comparison {
  double alpha = 0, eta = 0;
  double table = 0, table_se = 0;  // total diffuse reflectance
  double mc = 0, mc_se = 0;
  std::vector<double> z;    // per annulus: (table - analog) / combined SE
  std::vector<double> rel;  // per annulus: table / analog - 1
  double seconds = 0;
  std::uint64_t photons = 0;

  double se() const { return std::hypot(table_se, mc_se); }
  double rel_total() const { return table / mc - 1.0; }
  double z_total() const { return (table - mc) / se(); }
  double mean_z2() const {
    double sum = 0;
    for (double x : z) sum += x * x;
    return sum / static_cast<double>(z.size());
  }
  double rms_rel() const {
    double sum = 0;
    for (double x : rel) sum += x * x;
    return std::sqrt(sum / static_cast<double>(rel.size()));
  }
};

// The analog run of the medium with reduced albedo α' = σs'/σt' at σt' = 1 mm^-1 (so mm
// are mean free paths) and phase function HG(g): σs = α'/(1 - g), σa = 1 - α'. Binned on
// the table's own annuli over r in [0.25, 8] mfp.
Comparison compare_with_analog(std::size_t ai, std::size_t ei, double g, std::uint64_t photons,
                               std::uint64_t seed) {
  const McTableData& t = shipped_mc_table();
  Comparison c;
  c.alpha = t.albedo[ai];
  c.eta = t.eta[ei];
  c.photons = photons;
  const EdgeRange er = annuli_covering(t.r_edges, 0.25, 8.0);
  MonteCarloOptions o;
  o.photons = photons;
  o.seed = seed;
  o.threads = 1;  // ctest runs the cases side by side
  o.bin_edges_mm.assign(t.r_edges.begin() + static_cast<std::ptrdiff_t>(er.first),
                        t.r_edges.begin() + static_cast<std::ptrdiff_t>(er.last) + 1);
  // Roulette at 5% of the entry weight, as in the table's walks: unbiased for any setting
  // (MonteCarlo.RouletteIsUnbiased), and 1e-4 would spend most events on walks worth < 5%.
  o.roulette_weight = 0.05;
  const Coefficients m{1.0 - c.alpha, c.alpha / (1.0 - g), g, c.eta};
  const auto start = std::chrono::steady_clock::now();
  const MonteCarloResult r = run_monte_carlo(m, o);
  c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.truncated_photons, 0u);
  c.table = t.total[t.node(ei, ai)];
  c.table_se = t.total_se[t.node(ei, ai)];
  c.mc = r.reflectance.total;
  c.mc_se = r.reflectance.total_stderr;
  for (std::size_t b = er.first; b < er.last; ++b) {
    const double r0 = t.r_edges[b], r1 = t.r_edges[b + 1];
    const double area = std::numbers::pi * (r1 * r1 - r0 * r0);
    const double mc = r.reflectance.value[b - er.first] * area;
    const double mc_se = r.reflectance.stderr_[b - er.first] * area;
    const double tab = t.flux[t.slot(ei, ai, b)], tab_se = t.flux_se[t.slot(ei, ai, b)];
    c.z.push_back((tab - mc) / std::hypot(tab_se, mc_se));
    c.rel.push_back(tab / mc - 1.0);
  }
  return c;
}

struct AnalogNode {
  double alpha, eta;       // the table node nearest to these
  std::uint64_t photons;   // of the analog run
};

// Readable test names and values: "Albedo0p97Eta1p6" (gtest names allow [A-Za-z0-9_]).
std::string node_name(double alpha, double eta) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "Albedo%gEta%g", alpha, eta);
  std::string s = buf;
  std::replace(s.begin(), s.end(), '.', 'p');
  return s;
}
void PrintTo(const AnalogNode& n, std::ostream* os) {
  *os << "alpha' ~" << n.alpha << ", eta " << n.eta << ", " << n.photons << " photons";
}
struct NodeName {
  template <class Info>
  std::string operator()(const Info& info) const {
    return node_name(info.param.alpha, info.param.eta);
  }
};

// Nodes spanning the goal's α' ∈ [0.3, 0.999] and η from 1 to 2. Photons: chosen so that
// the analog run's relative standard error of the total is 0.1-0.16% (measured while
// writing this, the per-photon relative spread of the total is 4.1 at α' = 0.32, η = 1.4;
// 3.6 at 0.6 / 2.0; 1.1 at 0.9 / 1.3; 0.9 at 0.97 / 1.6; 0.6 at 0.99 / 1.4; 0.3 at
// 0.998 / 1.0), which with the shipped table's own (<= 0.16%) keeps the combined error
// below the 0.23% the 1% goal needs (see below). 8.5 s on one core for all six.
const AnalogNode kAnalogNodes[] = {
    {0.32, 1.4, 1u << 23}, {0.6, 2.0, 1u << 23},  {0.9, 1.3, 1u << 19},
    {0.97, 1.6, 1u << 19}, {0.99, 1.4, 1u << 18}, {0.998, 1.0, 1u << 16}};
constexpr std::size_t kAnalogChecks = std::size(kAnalogNodes);

class McTableVsAnalog : public ::testing::TestWithParam<AnalogNode> {};

TEST_P(McTableVsAnalog, TotalAndAnnuliAgree) {
  const AnalogNode n = GetParam();
  const McTableData& t = shipped_mc_table();
  const std::size_t ai = nearest(t.albedo, n.alpha), ei = nearest(t.eta, n.eta);
  ASSERT_NEAR(t.eta[ei], n.eta, 1e-12);
  ASSERT_GE(t.albedo[ai], 0.3);  // inside the goal's range
  ASSERT_LE(t.albedo[ai], 0.999);
  const Comparison c = compare_with_analog(ai, ei, 0.0, n.photons, 1000 + 100 * ai + ei);

  // Totals. Both are unbiased estimates of the same number, so their difference is
  // normal with the combined SE: a two-sided test, Bonferroni over the nodes at a
  // family-wise false-failure probability of 1e-4 (z ≈ 4.4 for six nodes).
  const double z = z_family(1e-4, kAnalogChecks);
  EXPECT_NEAR(c.table, c.mc, z * c.se()) << "alpha' " << c.alpha << " eta " << c.eta;
  // The goal, 1% of the Monte Carlo value. It can only be asserted where the
  // noise alone cannot break it at the same false-failure rate: combined SE <= 1%/z.
  EXPECT_LT(c.se(), 0.01 * c.mc / z) << "too few walks to test the 1% goal at alpha' "
                                     << c.alpha << " eta " << c.eta;
  EXPECT_LT(std::fabs(c.rel_total()), 0.01) << "alpha' " << c.alpha << " eta " << c.eta;

  // Annuli over [0.25, 8] mfp: the mean of z² over k annuli. For independent normal z it
  // is χ²_k / k (mean 1). The analog run's annuli are not independent at η > 1 (one
  // photon leaves through several annuli, Fresnel splitting), which widens the spread:
  // 200 pairs of independent analog runs at 25 annuli measured var(mean z²) = 0.078,
  // 0.080 and 0.097 at η = 1.0, 1.4 and 2.0, against 2/k = 0.080 for χ²_k/k. The bound
  // is therefore the quantile of χ²_k'/k' with k' = k / 1.5 (a variance 1.5 times
  // χ²_k/k's, margin over the measured 1.2), at the same family-wise 1e-4.
  const int k = static_cast<int>(c.z.size());
  const double bound = chi2_over_k_quantile(std::max(1, k * 2 / 3), 1e-4 / kAnalogChecks);
  EXPECT_LT(c.mean_z2(), bound) << "alpha' " << c.alpha << " eta " << c.eta;
  for (double x : c.z) EXPECT_TRUE(std::isfinite(x));

  RecordProperty("total_relative_error", std::to_string(c.rel_total()));
  RecordProperty("mean_z2", std::to_string(c.mean_z2()));
  std::printf(
      "alpha' %.6f eta %.2f: table %.6f +- %.2g, analog %.6f +- %.2g (%llu photons, %.2f s): "
      "%+.3f%% (z %+.2f, goal 1%%, combined SE %.3f%%); %d annuli mean z^2 %.2f (bound %.2f), "
      "RMS %.2f%%\n",
      c.alpha, c.eta, c.table, c.table_se, c.mc, c.mc_se,
      static_cast<unsigned long long>(c.photons), c.seconds, 100 * c.rel_total(), c.z_total(),
      100 * c.se() / c.mc, k, c.mean_z2(), bound, 100 * c.rms_rel());
}

INSTANTIATE_TEST_SUITE_P(Nodes, McTableVsAnalog, ::testing::ValuesIn(kAnalogNodes), NodeName());

// ---------------------------------------------------------------------------------------
// The similarity relation. The table is isotropic at the reduced albedo; a medium with
// g ≠ 0 is looked up at its reduced coefficients (σs' = σs(1 - g)). How good that is
// cannot be a property of the table: this measures it, against the analog walk with the
// real HG phase function at g = 0.8 and σt' = 1, and asserts only what was measured to
// hold with margin.
//
// Measured while writing this (2^22-walk table, analog runs at ~0.2% relative SE, the
// full table in the report, DISABLED_SimilarityStudy below): for α' in [0.9, 0.995] the
// table's total exceeds the anisotropic medium's by 0.7-0.96 (1 - α') at η = 1 (+7.8% at
// α' = 0.896, +1.6% at 0.982, +0.4% at 0.995) and by 0-0.6 (1 - α') at η = 1.4, and by far more
// for darker media (+23% at 0.71, +72% at 0.30, η = 1), where few scattering events
// cannot wash out the phase function. The bound asserted is 1.5 (1 - α') plus the
// statistical allowance z × combined SE. R(r) over [0.25, 8] mfp is off by 20-30% RMS at
// every albedo (isotropic scattering puts +40-70% more light out near the source and
// 10-20% less at 2-4 mfp): that is printed, not asserted.

using SimilarityNode = AnalogNode;
const SimilarityNode kSimilarityNodes[] = {
    {0.95, 1.4, 1u << 18}, {0.98, 1.0, 1u << 16}, {0.995, 1.4, 1u << 16}};

class McTableSimilarity : public ::testing::TestWithParam<SimilarityNode> {};

TEST_P(McTableSimilarity, AnisotropicTotalIsCloseToItsReducedNodeForBrightMedia) {
  const SimilarityNode n = GetParam();
  const McTableData& t = shipped_mc_table();
  const std::size_t ai = nearest(t.albedo, n.alpha), ei = nearest(t.eta, n.eta);
  const Comparison c = compare_with_analog(ai, ei, 0.8, n.photons, 2000 + 100 * ai + ei);
  const double z = z_family(1e-4, std::size(kSimilarityNodes));
  const double bound = 1.5 * (1.0 - c.alpha) + z * c.se() / c.mc;
  EXPECT_LT(std::fabs(c.rel_total()), bound) << "alpha' " << c.alpha << " eta " << c.eta;
  RecordProperty("total_relative_error", std::to_string(c.rel_total()));
  RecordProperty("profile_rms_relative_error", std::to_string(c.rms_rel()));
  std::printf("g = 0.8, alpha' %.5f, eta %.2f: table (isotropic, reduced) %.5f, analog HG "
              "%.5f +- %.5f (%llu photons, %.2f s): total %+.2f%% (bound %.2f%%), R(r) over "
              "[0.25, 8] mfp %.1f%% RMS\n",
              c.alpha, c.eta, c.table, c.mc, c.mc_se, static_cast<unsigned long long>(c.photons),
              c.seconds, 100 * c.rel_total(), 100 * bound, 100 * c.rms_rel());
}

INSTANTIATE_TEST_SUITE_P(Nodes, McTableSimilarity, ::testing::ValuesIn(kSimilarityNodes),
                         NodeName());

// The table of the report (README): total and R(r) errors of the similarity relation at
// g = 0.8 for several α', at η = 1 and 1.4, each analog run sized for a 0.2% relative
// SE of its total (a pilot of 4096 photons measures the spread). ~1 min on one core.
//   build/tests/test_profiles --gtest_also_run_disabled_tests
//     --gtest_filter='McTableStudy.DISABLED_SimilarityStudy'
TEST(McTableStudy, DISABLED_SimilarityStudy) {
  const McTableData& t = shipped_mc_table();
  std::printf("| η | α' | table (g = 0, reduced) | analog, HG g = 0.8 | total error | "
              "R(r) RMS error, 0.25-8 mfp | R(r) RMS error, 2-8 mfp |\n|---|---|---|---|---|---|---|\n");
  const EdgeRange er = annuli_covering(t.r_edges, 0.25, 8.0);
  for (double eta : {1.0, 1.4}) {
    for (double alpha : {0.3, 0.5, 0.7, 0.8, 0.9, 0.95, 0.98, 0.99, 0.995, 0.999, 0.9999}) {
      const std::size_t ai = nearest(t.albedo, alpha), ei = nearest(t.eta, eta);
      const Comparison pilot = compare_with_analog(ai, ei, 0.8, 4096, 77);
      const double n = 4096 * std::pow(pilot.mc_se / pilot.mc / 0.002, 2);
      const auto photons = std::clamp<std::uint64_t>(static_cast<std::uint64_t>(n), 4096, 1u << 23);
      const Comparison c = compare_with_analog(ai, ei, 0.8, photons, 78);
      double far = 0;
      std::size_t nfar = 0;
      for (std::size_t b = er.first; b < er.last; ++b)
        if (t.r_edges[b] >= 2.0) far += c.rel[b - er.first] * c.rel[b - er.first], ++nfar;
      std::printf("| %.2f | %.4f | %.4f | %.4f ± %.4f | %+.1f%% | %.0f%% | %.0f%% |\n", c.eta,
                  c.alpha, c.table, c.mc, c.mc_se, 100 * c.rel_total(), 100 * c.rms_rel(),
                  100 * std::sqrt(far / static_cast<double>(nfar)));
      std::fflush(stdout);
    }
  }
}

}  // namespace
}  // namespace sss::profiles
