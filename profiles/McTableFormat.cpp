// The mc-table file: serialize, parse (every field checked), and the copy compiled into
// the library (McTableEmbed.cpp). The layout is in profiles/data/README.md.
#include "profiles/McTable.h"

#include "profiles/Medium.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>

extern "C" {
// Defined by McTableEmbed.cpp (.incbin of profiles/data/mc_table.bin): the bytes, and
// their count computed by the assembler (no pointer subtraction across two objects).
extern const char sss_mc_table_begin[];
extern const unsigned long long sss_mc_table_size;
extern const char sss_mc_table_g_begin[];
extern const unsigned long long sss_mc_table_g_size;
}

namespace sss::profiles {

namespace {

static_assert(sizeof(std::size_t) >= 8, "table sizes are computed in size_t");
static_assert(std::endian::native == std::endian::little,
              "the mc-table file is little-endian; add byte swapping for this target");

constexpr char kMagic[8] = {'S', 'S', 'S', 'M', 'C', 'T', 'B', 'L'};
// 2: adds the once-scattered flux per unit albedo and the multiply-scattered errors
// (McTable.h). Version 1 files lack them and are refused: regenerate with sss-fit mc-table.
constexpr std::uint32_t kVersion = 2;
// 3: a table of Henyey-Greenstein walks (g != 0, issue 18 part 4): g after the roulette
// settings, and the once-scattered arrays per node (McTableData::g). Version 2 is still
// what a g = 0 table is written as, so the shipped isotropic table keeps its bytes.
constexpr std::uint32_t kVersionAnisotropic = 3;
constexpr char kSetMagic[8] = {'S', 'S', 'S', 'M', 'C', 'T', 'G', 'S'};
constexpr std::uint32_t kSetVersion = 1;

// FNV-1a, 64 bit (Fowler, Noll & Vo; offset basis and prime as published by the authors).
std::uint64_t fnv1a(std::string_view bytes) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

class Writer {
 public:
  template <class T>
  void put(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    s.append(b, sizeof(T));
  }
  void put_doubles(const std::vector<double>& v) {
    for (double x : v) put(x);
  }
  void put_floats(const std::vector<double>& v) {
    for (double x : v) put(static_cast<float>(x));
  }
  std::string s;
};

class Reader {
 public:
  Reader(std::string_view bytes, std::string_view name) : b_(bytes), name_(name) {}
  [[noreturn]] void fail(const std::string& field, const std::string& why) const {
    throw std::invalid_argument(std::string(name_) + ": " + field + ": " + why);
  }
  template <class T>
  T get(const char* field) {
    if (b_.size() - pos_ < sizeof(T))
      fail(field, "the file ends early (at byte " + std::to_string(pos_) + " of " +
                      std::to_string(b_.size()) + ")");
    T v;
    std::memcpy(&v, b_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  template <class T>
  std::vector<double> get_array(const char* field, std::size_t n) {
    if ((b_.size() - pos_) / sizeof(T) < n)
      fail(field, "the file ends early: " + std::to_string(n) + " values needed at byte " +
                      std::to_string(pos_) + " of " + std::to_string(b_.size()));
    std::vector<double> v(n);
    for (std::size_t i = 0; i < n; ++i) {
      T x;
      std::memcpy(&x, b_.data() + pos_ + i * sizeof(T), sizeof(T));
      if (!std::isfinite(x)) fail(field, "value " + std::to_string(i) + " is not finite");
      v[i] = static_cast<double>(x);
    }
    pos_ += n * sizeof(T);
    return v;
  }
  std::size_t pos() const { return pos_; }
  void skip(std::size_t n) { pos_ += n; }

 private:
  std::string_view b_;
  std::string_view name_;
  std::size_t pos_ = 0;
};

void check_axis(const Reader& r, const std::vector<double>& v, const char* field, double lo,
                double hi, bool lo_open, bool hi_open) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    const bool below = lo_open ? !(v[i] > lo) : !(v[i] >= lo);
    const bool above = hi_open ? !(v[i] < hi) : !(v[i] <= hi);
    if (below || above)
      r.fail(field, "value " + std::to_string(i) + " (" + message_number(v[i]) + ") outside " +
                        (lo_open ? "(" : "[") + message_number(lo) + ", " + message_number(hi) +
                        (hi_open ? ")" : "]"));
    if (i > 0 && !(v[i] > v[i - 1])) r.fail(field, "values must be strictly ascending");
  }
}

// A table or a set: checks the 8-byte magic and the trailing FNV-1a checksum, and returns
// everything but the checksum (a body that is short must not read the checksum as data).
std::string_view checked_body(std::string_view bytes, std::string_view name, const char (&magic)[8],
                              const char* not_magic) {
  const Reader whole(bytes, name);
  if (bytes.size() < sizeof(magic) || std::memcmp(bytes.data(), magic, sizeof(magic)) != 0)
    whole.fail("magic", not_magic);
  if (bytes.size() < 8 + sizeof(std::uint64_t)) whole.fail("checksum", "the file ends early");
  std::uint64_t stored;
  std::memcpy(&stored, bytes.data() + bytes.size() - 8, 8);
  if (stored != fnv1a(bytes.substr(0, bytes.size() - 8)))
    whole.fail("checksum", "the FNV-1a checksum of the contents does not match (file damaged)");
  return bytes.substr(0, bytes.size() - 8);
}

// The walk's parameters: photons, seed, chunks, roulette and (version 3) g.
void read_sampling(Reader& r, std::uint32_t version, McTableData& t) {
  t.photons = r.get<std::uint64_t>("photons");
  t.seed = r.get<std::uint64_t>("seed");
  t.chunk_photons = r.get<std::uint64_t>("chunk_photons");
  if (t.chunk_photons == 0) r.fail("chunk_photons", "must be > 0");
  if (t.photons % t.chunk_photons != 0 || t.photons / t.chunk_photons < 2)
    r.fail("photons", "must be a multiple of chunk_photons, at least two chunks");
  t.roulette_weight = r.get<double>("roulette_weight");
  t.roulette_survival = r.get<double>("roulette_survival");
  if (!(t.roulette_weight > 0.0 && t.roulette_weight < 1.0))
    r.fail("roulette_weight", "must lie in (0, 1)");
  if (!(t.roulette_survival > 0.0 && t.roulette_survival < 1.0))
    r.fail("roulette_survival", "must lie in (0, 1)");
  if (version == kVersionAnisotropic) {
    t.g = r.get<double>("g");
    if (!(t.g > -1.0 && t.g < 1.0) || t.g == 0.0)
      r.fail("g", "a version 3 table must have g in (-1, 1) and not 0, got " + message_number(t.g));
  }
}

// Totals in [0, 1] and no negative flux or standard error.
void check_values(Reader& r, const McTableData& t) {
  for (std::size_t i = 0; i < t.total.size(); ++i)
    if (!(t.total[i] >= 0.0 && t.total[i] <= 1.0) || !(t.total_se[i] >= 0.0))
      r.fail("total", "node " + std::to_string(i) + " is outside [0, 1] or has a negative error");
  for (std::size_t i = 0; i < t.single_total.size(); ++i)
    if (!(t.single_total[i] >= 0.0 && t.single_total[i] <= 1.0) || !(t.single_total_se[i] >= 0.0))
      r.fail("single_total", std::string(t.single_per_node() ? "node " : "eta ") +
                                 std::to_string(i) + " is outside [0, 1] or has a negative error");
  auto non_negative = [&](const std::vector<double>& v, const char* field) {
    for (std::size_t i = 0; i < v.size(); ++i)
      if (!(v[i] >= 0.0)) r.fail(field, "entry " + std::to_string(i) + " is negative");
  };
  non_negative(t.multiple_total_se, "multiple_total_se");
  non_negative(t.flux, "flux");
  non_negative(t.flux_se, "flux_se");
  non_negative(t.single_flux, "single_flux");
  non_negative(t.single_flux_se, "single_flux_se");
  non_negative(t.multiple_flux_se, "multiple_flux_se");
}

}  // namespace

std::string serialize_mc_table(const McTableData& t) {
  Writer w;
  w.s.append(kMagic, sizeof(kMagic));
  w.put<std::uint32_t>(t.single_per_node() ? kVersionAnisotropic : kVersion);
  w.put<std::uint32_t>(static_cast<std::uint32_t>(t.eta.size()));
  w.put<std::uint32_t>(static_cast<std::uint32_t>(t.albedo.size()));
  w.put<std::uint32_t>(static_cast<std::uint32_t>(t.r_edges.size()));
  w.put<std::uint64_t>(t.photons);
  w.put<std::uint64_t>(t.seed);
  w.put<std::uint64_t>(t.chunk_photons);
  w.put<double>(t.roulette_weight);
  w.put<double>(t.roulette_survival);
  if (t.single_per_node()) w.put<double>(t.g);
  w.put_doubles(t.eta);
  w.put_doubles(t.albedo);
  w.put_doubles(t.r_edges);
  w.put_doubles(t.total);
  w.put_doubles(t.total_se);
  w.put_doubles(t.single_total);
  w.put_doubles(t.single_total_se);
  w.put_doubles(t.multiple_total_se);
  // Annulus fluxes in single precision: a relative rounding of 6e-8, far below the
  // Monte Carlo noise of any entry (the smallest relative standard error is ~1e-4).
  w.put_floats(t.flux);
  w.put_floats(t.flux_se);
  w.put_floats(t.single_flux);
  w.put_floats(t.single_flux_se);
  w.put_floats(t.multiple_flux_se);
  w.put<std::uint64_t>(fnv1a(w.s));
  return std::move(w.s);
}

McTableData parse_mc_table(std::string_view bytes, std::string_view name) {
  const std::string_view body =
      checked_body(bytes, name, kMagic, "not an mc-table file (expected the 8 bytes SSSMCTBL)");
  Reader r(body, name);
  r.get<std::uint64_t>("magic");
  const auto version = r.get<std::uint32_t>("version");
  if (version != kVersion && version != kVersionAnisotropic)
    r.fail("version", "format " + std::to_string(version) + " is not supported (this build reads " +
                          std::to_string(kVersion) + " and " + std::to_string(kVersionAnisotropic) +
                          (version < kVersion ? "; 2 adds the once-scattered flux: regenerate "
                                                "the table with sss-fit mc-table)"
                                              : ")"));
  McTableData t;
  const std::size_t ne = r.get<std::uint32_t>("n_eta");
  const std::size_t na = r.get<std::uint32_t>("n_albedo");
  const std::size_t nedges = r.get<std::uint32_t>("n_edges");
  if (ne < 1 || ne > 1024) r.fail("n_eta", "must lie in [1, 1024], got " + std::to_string(ne));
  if (na < 2 || na > 4096) r.fail("n_albedo", "must lie in [2, 4096], got " + std::to_string(na));
  if (nedges < 3 || nedges > 4096)
    r.fail("n_edges", "must lie in [3, 4096], got " + std::to_string(nedges));
  read_sampling(r, version, t);
  t.eta = r.get_array<double>("eta", ne);
  t.albedo = r.get_array<double>("albedo", na);
  t.r_edges = r.get_array<double>("r_edges", nedges);
  check_axis(r, t.eta, "eta", kEtaMin, kEtaMax, false, false);
  check_axis(r, t.albedo, "albedo", 0.0, 1.0, true, true);
  if (t.r_edges.front() != 0.0) r.fail("r_edges", "the first edge must be 0");
  check_axis(r, {t.r_edges.begin() + 1, t.r_edges.end()}, "r_edges", 0.0, 1e15,
             true, false);
  const std::size_t nb = nedges - 1;
  t.total = r.get_array<double>("total", ne * na);
  t.total_se = r.get_array<double>("total_se", ne * na);
  // Once-scattered: per η (version 2) or per node (version 3).
  const std::size_t ns = t.single_per_node() ? ne * na : ne;
  t.single_total = r.get_array<double>("single_total", ns);
  t.single_total_se = r.get_array<double>("single_total_se", ns);
  t.multiple_total_se = r.get_array<double>("multiple_total_se", ne * na);
  t.flux = r.get_array<float>("flux", ne * na * nb);
  t.flux_se = r.get_array<float>("flux_se", ne * na * nb);
  t.single_flux = r.get_array<float>("single_flux", ns * nb);
  t.single_flux_se = r.get_array<float>("single_flux_se", ns * nb);
  t.multiple_flux_se = r.get_array<float>("multiple_flux_se", ne * na * nb);
  check_values(r, t);
  if (r.pos() != body.size())
    r.fail("size", std::to_string(body.size() - r.pos()) + " unexpected bytes before the checksum");
  return t;
}

double McTableData::multiple_flux(std::size_t e, std::size_t a, std::size_t b) const {
  if (single_per_node()) return std::max(0.0, flux[slot(e, a, b)] - single_flux[slot(e, a, b)]);
  return std::max(0.0, flux[slot(e, a, b)] - albedo[a] * single_flux[single_slot(e, b)]);
}

double McTableData::multiple_total(std::size_t e, std::size_t a) const {
  if (single_per_node()) return std::max(0.0, total[node(e, a)] - single_total[node(e, a)]);
  return std::max(0.0, total[node(e, a)] - albedo[a] * single_total[e]);
}

std::string serialize_mc_table_set(const std::vector<McTableData>& tables) {
  Writer w;
  w.s.append(kSetMagic, sizeof(kSetMagic));
  w.put<std::uint32_t>(kSetVersion);
  w.put<std::uint32_t>(static_cast<std::uint32_t>(tables.size()));
  for (const McTableData& t : tables) {
    const std::string one = serialize_mc_table(t);
    w.put<std::uint64_t>(one.size());
    w.s += one;
  }
  w.put<std::uint64_t>(fnv1a(w.s));
  return std::move(w.s);
}

std::vector<McTableData> parse_mc_table_set(std::string_view bytes, std::string_view name) {
  const std::string_view body = checked_body(
      bytes, name, kSetMagic, "not a set of mc-tables (expected the 8 bytes SSSMCTGS)");
  Reader r(body, name);
  r.get<std::uint64_t>("magic");
  const auto version = r.get<std::uint32_t>("version");
  if (version != kSetVersion)
    r.fail("version", "set format " + std::to_string(version) + " is not supported (this build "
                      "reads " + std::to_string(kSetVersion) + ")");
  const std::size_t count = r.get<std::uint32_t>("count");
  if (count < 1 || count > 64) r.fail("count", "must lie in [1, 64], got " + std::to_string(count));
  std::vector<McTableData> out;
  for (std::size_t i = 0; i < count; ++i) {
    const std::string field = "table " + std::to_string(i);
    const auto size = r.get<std::uint64_t>(field.c_str());
    if (size > body.size() - r.pos())
      r.fail(field, "its size (" + std::to_string(size) + " bytes) runs past the end of the file");
    out.push_back(parse_mc_table(body.substr(r.pos(), size),
                                 std::string(name) + " (" + field + ")"));
    r.skip(size);
    if (!out.back().single_per_node())
      r.fail(field, "must be a table of Henyey-Greenstein walks (format version 3, g != 0)");
    if (i > 0 && !(out.back().g > out[i - 1].g)) r.fail(field, "g must be strictly ascending");
  }
  if (r.pos() != body.size())
    r.fail("size", std::to_string(body.size() - r.pos()) + " unexpected bytes before the checksum");
  return out;
}

const std::vector<McTableData>& shipped_mc_table_layers() {
  static const std::vector<McTableData> layers = parse_mc_table_set(
      std::string_view(sss_mc_table_g_begin, static_cast<std::size_t>(sss_mc_table_g_size)),
      "profiles/data/mc_table_g.bin (compiled in)");
  return layers;
}

const McTableData& shipped_mc_table() {
  static const McTableData table = parse_mc_table(
      std::string_view(sss_mc_table_begin, static_cast<std::size_t>(sss_mc_table_size)),
      "profiles/data/mc_table.bin (compiled in)");
  return table;
}

}  // namespace sss::profiles
