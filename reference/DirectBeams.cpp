#include "reference/DirectBeams.h"

#include "reference/WalkSampling.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace sss::reference {

double surface_offset_mm(const glm::dvec3& p) {
  const double m = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z), 1.0});
  return 64.0 * m * double(std::numeric_limits<float>::epsilon());
}

namespace {

struct Box {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()};
  glm::dvec3 hi{-std::numeric_limits<double>::infinity()};
  void add(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void add(const Box& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  bool contains(const glm::dvec3& p) const {
    return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z;
  }
  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
};

// A face of the medium as the beams see it (world mm, outward normal).
struct Face {
  glm::dvec3 c0, e1, e2, n;
  glm::dvec3 du, dv;  // u = dot(y - c0, du), v = dot(y - c0, dv): barycentrics of corners 1, 2
  std::uint32_t instance = 0, triangle = 0;
  // Directional lights: the refracted direction, cos θt and cos θi T(θi) / cos θt.
  glm::dvec3 d{0.0};
  double cos_t = 1.0, factor = 0.0;
};

// A stretch of a face's refracted beam, [t0, t1] along it, as a box.
struct Chunk {
  Box box;
  std::uint32_t face = 0;
};

// A uniform grid over chunk boxes for point-in-box queries: the cell of a point lists the
// chunks whose boxes overlap it (a BVH visited about 130 nodes per query on builtin:bunny,
// mostly branch misses; the grid looks up one cell). Cells are about two thirds of the
// median box; a box over more than 512 cells is kept aside and tested on every query, so a
// few large faces next to many small ones cannot blow the grid up.
class ChunkGrid {
 public:
  void build(const std::vector<Chunk>& chunks) {
    starts_.clear();
    entries_.clear();
    big_.clear();
    if (chunks.empty()) return;
    Box all;
    std::vector<double> sizes;
    sizes.reserve(chunks.size());
    for (const Chunk& c : chunks) {
      all.add(c.box);
      const glm::dvec3 e = c.box.hi - c.box.lo;
      sizes.push_back(std::max({e.x, e.y, e.z}));
    }
    std::nth_element(sizes.begin(), sizes.begin() + std::ptrdiff_t(sizes.size() / 2), sizes.end());
    const glm::dvec3 extent = glm::max(all.hi - all.lo, glm::dvec3(1e-9));
    double cell = std::max(sizes[sizes.size() / 2] / 1.5, 1e-9);
    // At most 2^22 cells.
    while ((extent.x / cell + 1.0) * (extent.y / cell + 1.0) * (extent.z / cell + 1.0) > double(1 << 22)) cell *= 1.25;
    origin_ = all.lo;
    inv_cell_ = 1.0 / cell;
    for (int a = 0; a < 3; ++a) dims_[a] = std::max(1, int(std::ceil(extent[a] * inv_cell_)));
    const std::size_t cells = std::size_t(dims_[0]) * std::size_t(dims_[1]) * std::size_t(dims_[2]);
    std::vector<std::uint32_t> count(cells + 1, 0);
    auto range = [&](const Box& b, std::array<int, 3>& lo, std::array<int, 3>& hi) {
      std::size_t n = 1;
      for (int a = 0; a < 3; ++a) {
        lo[std::size_t(a)] = cell_index(b.lo[a], a);
        hi[std::size_t(a)] = cell_index(b.hi[a], a);
        n *= std::size_t(hi[std::size_t(a)] - lo[std::size_t(a)] + 1);
      }
      return n;
    };
    std::array<int, 3> lo, hi;
    for (std::uint32_t k = 0; k < chunks.size(); ++k) {
      if (range(chunks[k].box, lo, hi) > 512) {
        big_.push_back(k);
        continue;
      }
      for (int z = lo[2]; z <= hi[2]; ++z)
        for (int y = lo[1]; y <= hi[1]; ++y)
          for (int x = lo[0]; x <= hi[0]; ++x) ++count[flat(x, y, z)];
    }
    starts_.assign(cells + 1, 0);
    for (std::size_t c = 0; c < cells; ++c) starts_[c + 1] = starts_[c] + count[c];
    entries_.resize(starts_[cells]);
    std::vector<std::uint32_t> fill(starts_.begin(), starts_.end() - 1);
    for (std::uint32_t k = 0; k < chunks.size(); ++k) {
      if (range(chunks[k].box, lo, hi) > 512) continue;
      for (int z = lo[2]; z <= hi[2]; ++z)
        for (int y = lo[1]; y <= hi[1]; ++y)
          for (int x = lo[0]; x <= hi[0]; ++x) entries_[fill[flat(x, y, z)]++] = entry(chunks[k], k);
    }
  }
  // Calls visit(k) for every chunk k whose box contains p.
  template <class Visit>
  void query(const std::vector<Chunk>& chunks, const glm::dvec3& p, Visit&& visit) const {
    for (std::uint32_t k : big_)
      if (chunks[k].box.contains(p)) visit(k);
    if (starts_.empty()) return;
    int c[3];
    for (int a = 0; a < 3; ++a) {
      const double f = (p[a] - origin_[a]) * inv_cell_;
      if (!(f >= 0.0) || f >= double(dims_[a]) + 1e-9) return;
      c[a] = std::min(int(f), dims_[a] - 1);
    }
    const std::size_t cell = flat(c[0], c[1], c[2]);
    for (std::uint32_t i = starts_[cell]; i < starts_[cell + 1]; ++i)
      if (entries_[i].contains(p)) visit(entries_[i].chunk);
  }

 private:
  int cell_index(double v, int a) const {
    return std::clamp(int(std::floor((v - origin_[a]) * inv_cell_)), 0, dims_[a] - 1);
  }
  std::size_t flat(int x, int y, int z) const {
    return (std::size_t(z) * std::size_t(dims_[1]) + std::size_t(y)) * std::size_t(dims_[0]) + std::size_t(x);
  }
  glm::dvec3 origin_{0.0};
  double inv_cell_ = 1.0;
  int dims_[3] = {1, 1, 1};
  // A cell's entries hold their chunk's box (in float, rounded outward) so that a query
  // scans contiguous memory.
  struct Entry {
    float lo[3], hi[3];
    std::uint32_t chunk;
    bool contains(const glm::dvec3& p) const {
      return p.x >= lo[0] && p.y >= lo[1] && p.z >= lo[2] && p.x <= hi[0] && p.y <= hi[1] && p.z <= hi[2];
    }
  };
  static Entry entry(const Chunk& c, std::uint32_t k) {
    Entry e;
    for (int a = 0; a < 3; ++a) {
      e.lo[a] = std::nextafter(float(c.box.lo[a]), -std::numeric_limits<float>::infinity());
      e.hi[a] = std::nextafter(float(c.box.hi[a]), std::numeric_limits<float>::infinity());
    }
    e.chunk = k;
    return e;
  }
  std::vector<std::uint32_t> starts_, big_;
  std::vector<Entry> entries_;
};

struct LightBeams {
  // Boxes are axis-aligned in a frame whose third axis is the light's direction of travel
  // (towards the medium's centre for point lights): refracted beams run roughly along it,
  // so their boxes stay narrow (about 8x fewer faces per query on builtin:bunny than in
  // world axes).
  glm::dmat3 frame{1.0};  // world -> frame
  std::uint32_t light = 0;
  scene::LightType type = scene::LightType::Directional;
  glm::dvec3 to_light{0.0};  // directional: unit, towards the light
  glm::dvec3 position{0.0};  // point / spot: world mm
  std::vector<Face> faces;
  std::vector<Chunk> chunks;
  ChunkGrid grid;
};

// A light's beams before any face: which light, where it is, and the frame the chunk
// boxes are aligned in (its direction of travel; towards the centre of `bounds` for
// point and spot lights).
LightBeams light_beams(const scene::Scene& s, std::uint32_t li, const Box& bounds) {
  const scene::Light& light = s.lights[li];
  LightBeams lb;
  lb.light = li;
  lb.type = light.type;
  glm::dvec3 axis;
  if (light.type == scene::LightType::Directional) {
    lb.to_light = -glm::normalize(glm::dvec3(light.direction()));
    axis = -lb.to_light;
  } else {
    lb.position = glm::dvec3(light.position()) * s.mm_per_unit;
    axis = 0.5 * (bounds.lo + bounds.hi) - lb.position;
    axis = glm::length(axis) > 0.0 ? glm::normalize(axis) : glm::dvec3(0.0, 0.0, 1.0);
  }
  glm::dvec3 t, b;
  walk::basis(axis, t, b);
  lb.frame = glm::transpose(glm::dmat3(t, b, axis));  // rows t, b, axis
  return lb;
}

// How a face's refracted beam runs: d0 the refracted direction at its first corner,
// theta a bound on the angle between refracted directions over the face, t_max how far
// it runs inside the medium's bounds.
struct BeamExtent {
  glm::dvec3 d0{0.0};
  double theta = 0.0;
  double t_max = 0.0;
};

// The beam a light sends into the medium through face f (corners `corner`): for a
// directional light, f's refracted direction, cosine and entry factor, and the longest
// corner distance to the bounds' exit; for a point or spot light, the refracted direction
// at the first corner and the spread of the incident directions over the corners. False
// where no light enters (the face turned away, total internal reflection).
bool refract_beam(const LightBeams& lb, scene::LightType type, double eta, const std::array<glm::dvec3, 3>& corner,
                  const Box& bounds, Face& f, BeamExtent& e) {
  if (type == scene::LightType::Directional) {
    const double cos_i = glm::dot(lb.to_light, f.n);
    if (!(cos_i > 0.0)) return false;
    if (!walk::refract(-lb.to_light, f.n, 1.0, eta, f.d)) return false;
    f.cos_t = -glm::dot(f.d, f.n);
    if (!(f.cos_t > 0.0)) return false;
    f.factor = cos_i * (1.0 - walk::fresnel(cos_i, 1.0, eta)) / f.cos_t;
    e.d0 = f.d;
    // The prism leaves the medium's box within the longest corner exit distance.
    e.t_max = 0.0;
    for (const glm::dvec3& c : corner) {
      double exit = std::numeric_limits<double>::infinity();
      for (int a = 0; a < 3; ++a) {
        if (f.d[a] > 0.0) exit = std::min(exit, (bounds.hi[a] - c[a]) / f.d[a]);
        if (f.d[a] < 0.0) exit = std::min(exit, (bounds.lo[a] - c[a]) / f.d[a]);
      }
      e.t_max = std::max(e.t_max, std::max(exit, 0.0));
    }
    return true;
  }
  if (!(glm::dot(lb.position - f.c0, f.n) > 0.0)) return false;  // the light is behind the face
  std::array<glm::dvec3, 3> in;
  for (int k = 0; k < 3; ++k) in[std::size_t(k)] = glm::normalize(corner[std::size_t(k)] - lb.position);
  if (!walk::refract(in[0], f.n, 1.0, eta, e.d0)) return false;
  for (int k = 1; k < 3; ++k)
    e.theta = std::max(e.theta, std::acos(std::clamp(glm::dot(in[0], in[std::size_t(k)]), -1.0, 1.0)));
  e.theta = e.theta * (1.0 + 1e-9) + 1e-12;
  return true;
}

// The face's beam cut into chunks about `length` long (a face diameter, at most 64 per
// face), each boxed in the light's frame and widened by the beam's spread and `grow`.
void add_chunks(LightBeams& lb, std::uint32_t face_index, const std::array<glm::dvec3, 3>& corner, double length,
                const BeamExtent& e, double grow) {
  const int count = std::max(1, int(std::ceil(e.t_max / length)));
  for (int k = 0; k < count; ++k) {
    Chunk c;
    c.face = face_index;
    const double t0 = e.t_max * k / count, t1 = e.t_max * (k + 1) / count;
    for (const glm::dvec3& p : corner) {
      c.box.add(lb.frame * (p + t0 * e.d0));
      c.box.add(lb.frame * (p + t1 * e.d0));
    }
    const double widen = t1 * e.theta + grow;
    c.box.lo -= widen;
    c.box.hi += widen;
    lb.chunks.push_back(c);
  }
}

double smoothstep01(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// The part of a light's output that leaves along the unit direction `travel` (spot cone),
// as the other renderers weigh it (Shading.cpp: GLSL smoothstep between the cones).
double spot_factor(const scene::Light& light, const glm::dvec3& travel) {
  if (light.type != scene::LightType::Spot) return 1.0;
  const double lo = std::cos(light.outer_cone), hi = std::cos(light.inner_cone);
  const double c = glm::dot(travel, glm::dvec3(light.direction()));
  return smoothstep01((c - lo) / std::max(hi - lo, 1e-9));
}

}  // namespace

struct DirectBeams::Impl {
  const scene::Scene* scene = nullptr;
  const RayScene* rays = nullptr;
  const MediumSurface* surface = nullptr;
  double eta = 1.0;
  std::vector<bool> member;  // instance -> part of this medium's surface
  std::vector<LightBeams> lights;

  glm::dvec3 outward_normal(std::uint32_t instance, std::uint32_t triangle) const {
    const scene::Mesh& mesh = scene->meshes[scene->instances[instance].mesh];
    const std::vector<glm::vec3>& w = rays->world_positions(instance);
    const glm::dvec3 p0 = w[mesh.indices[3 * triangle]], p1 = w[mesh.indices[3 * triangle + 1]],
                     p2 = w[mesh.indices[3 * triangle + 2]];
    const glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
    const double len = glm::length(n);
    if (!(len > 0.0)) return glm::dvec3(0.0);
    return n / len * double(surface->outward[instance][triangle]);
  }

  // Whether the light reaches the entry point y (world mm) on a face with outward normal n,
  // and the light's colour x intensity there (before any geometry factor).
  bool lit(const scene::Light& light, const glm::dvec3& y, const glm::dvec3& n, const glm::dvec3& to_light,
           double distance_mm) const {
    const double mm = scene->mm_per_unit;
    if (!light.reaches(glm::vec3(y / mm))) return false;
    const double off = surface_offset_mm(y);
    const double far = std::isfinite(distance_mm) ? distance_mm - 2.0 * off : std::numeric_limits<double>::infinity();
    if (!(far > 0.0)) return false;
    return !rays->occluded(glm::vec3(y + n * off), glm::vec3(to_light), 0.0f, float(far));
  }
  // Whether the straight segment x -> y stays inside the medium.
  bool inside(const glm::dvec3& x, const glm::dvec3& y, double t) const {
    const double off = surface_offset_mm(y);
    if (t <= off) return true;
    return !rays->occluded(glm::vec3(x), glm::vec3((y - x) / t), 0.0f, float(t - off));
  }

  void build(const scene::Scene& s);
  void gather_straight(const glm::dvec3& x, std::vector<DirectBeam>& out) const;
};

void DirectBeams::Impl::build(const scene::Scene& s) {
  // The medium's bounds: no beam point outside them is inside the medium.
  Box bounds;
  for (std::uint32_t i : surface->instances)
    for (const glm::vec3& p : rays->world_positions(i)) bounds.add(glm::dvec3(p));
  const double diag = glm::length(bounds.hi - bounds.lo);
  const double grow = 1e-6 * (diag + 1.0);
  bounds.lo -= grow;
  bounds.hi += grow;

  for (std::uint32_t li = 0; li < s.lights.size(); ++li) {
    const scene::Light& light = s.lights[li];
    const glm::dvec3 colour = glm::dvec3(light.color) * double(light.intensity);
    if (!(colour.x > 0.0 || colour.y > 0.0 || colour.z > 0.0)) continue;
    LightBeams lb = light_beams(s, li, bounds);
    for (std::uint32_t inst : surface->instances) {
      const scene::Mesh& mesh = s.meshes[s.instances[inst].mesh];
      const std::vector<glm::vec3>& w = rays->world_positions(inst);
      for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t) {
        Face f;
        f.instance = inst;
        f.triangle = t;
        f.c0 = w[mesh.indices[3 * t]];
        f.e1 = glm::dvec3(w[mesh.indices[3 * t + 1]]) - f.c0;
        f.e2 = glm::dvec3(w[mesh.indices[3 * t + 2]]) - f.c0;
        const glm::dvec3 N = glm::cross(f.e1, f.e2);
        const double n2 = glm::dot(N, N);
        if (!(n2 > 0.0)) continue;
        f.n = outward_normal(inst, t);
        f.du = glm::cross(f.e2, N) / n2;
        f.dv = glm::cross(N, f.e1) / n2;
        const std::array<glm::dvec3, 3> corner = {f.c0, f.c0 + f.e1, f.c0 + f.e2};
        const double diameter = std::max({glm::length(f.e1), glm::length(f.e2), glm::length(f.e2 - f.e1)});
        BeamExtent extent;
        extent.t_max = diag;
        if (!refract_beam(lb, light.type, eta, corner, bounds, f, extent) || !(extent.t_max > 0.0)) continue;
        const std::uint32_t face_index = std::uint32_t(lb.faces.size());
        lb.faces.push_back(f);
        add_chunks(lb, face_index, corner, std::max(diameter, extent.t_max / 64.0), extent, grow);
      }
    }
    lb.grid.build(lb.chunks);
    lights.push_back(std::move(lb));
  }
}

namespace {

// The refraction point of a point light at L on a face's plane (point c, outward unit
// normal n) for x below it: the minimum of |L - y| + eta |y - x| lies in the plane of
// incidence, at the root of f(s) = sin θi - eta sin θt, which rises monotonically along
// the line between the feet of L and x.
bool fermat_point(const glm::dvec3& L, const glm::dvec3& x, const glm::dvec3& c, const glm::dvec3& n, double eta,
                  glm::dvec3& y) {
  const double hl = glm::dot(L - c, n), hx = -glm::dot(x - c, n);
  if (!(hl > 0.0) || !(hx >= 0.0)) return false;
  const glm::dvec3 a = L - hl * n, b = x + hx * n;
  const double D = glm::length(b - a);
  const double scale = D + hl + hx;
  if (D <= 1e-14 * scale) {
    y = a;
    return true;
  }
  const glm::dvec3 e = (b - a) / D;
  auto f = [&](double s) {
    return s / std::sqrt(s * s + hl * hl) - eta * (D - s) / std::sqrt((D - s) * (D - s) + hx * hx);
  };
  double lo = 0.0, hi = D;
  double s = D * hl / (hl + hx + 1e-300);  // where the straight line crosses the plane
  for (int it = 0; it < 100; ++it) {
    const double fs = f(s);
    if (fs < 0.0) lo = s; else hi = s;
    const double q1 = s * s + hl * hl, q2 = (D - s) * (D - s) + hx * hx;
    const double df = hl * hl / (q1 * std::sqrt(q1)) + eta * hx * hx / (q2 * std::sqrt(q2));
    double next = s - fs / df;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - s) <= 1e-13 * scale || hi - lo <= 1e-13 * scale) {
      s = next;
      break;
    }
    s = next;
  }
  y = a + s * e;
  return true;
}

}  // namespace

void DirectBeams::Impl::gather_straight(const glm::dvec3& x, std::vector<DirectBeam>& out) const {
  const scene::Scene& s = *scene;
  for (std::uint32_t li = 0; li < s.lights.size(); ++li) {
    const scene::Light& light = s.lights[li];
    const glm::dvec3 colour = glm::dvec3(light.color) * double(light.intensity);
    glm::dvec3 l;
    double dist = std::numeric_limits<double>::infinity();
    if (light.type == scene::LightType::Directional) {
      l = -glm::normalize(glm::dvec3(light.direction()));
    } else {
      const glm::dvec3 d = glm::dvec3(light.position()) * s.mm_per_unit - x;
      dist = glm::length(d);
      if (!(dist > 0.0)) continue;
      l = d / dist;
    }
    const std::optional<Hit> hit = rays->intersect(glm::vec3(x), glm::vec3(l), 0.0f,
                                                   std::isfinite(dist) ? float(dist) : std::numeric_limits<float>::infinity());
    if (!hit || hit->instance >= member.size() || !member[hit->instance]) continue;
    const glm::dvec3 n = outward_normal(hit->instance, hit->triangle);
    if (!(glm::dot(n, l) > 0.0)) continue;  // not leaving the medium here
    const double t = hit->t;
    const glm::dvec3 y = x + t * l;
    if (!lit(light, y, n, l, dist - t)) continue;
    DirectBeam b;
    b.light = li;
    b.direction = -l;
    b.distance_mm = t;
    double e = spot_factor(light, -l);
    if (light.type != scene::LightType::Directional) {
      const double d_units = dist / s.mm_per_unit;
      e /= std::max(d_units * d_units, 1e-8);
    }
    b.irradiance = colour * e;
    b.instance = hit->instance;
    b.triangle = hit->triangle;
    b.barycentric = hit->barycentric;
    out.push_back(b);
  }
}

DirectBeams::DirectBeams(const scene::Scene& s, const RayScene& rays, const MediumSurface& surface, double eta)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.scene = &s;
  m.rays = &rays;
  m.surface = &surface;
  m.eta = eta;
  m.member.assign(s.instances.size(), false);
  for (std::uint32_t i : surface.instances) m.member[i] = true;
  if (eta != 1.0) m.build(s);
}

DirectBeams::~DirectBeams() = default;

std::size_t DirectBeams::chunk_count() const {
  std::size_t n = 0;
  for (const LightBeams& lb : impl_->lights) n += lb.chunks.size();
  return n;
}

void DirectBeams::gather(const glm::dvec3& x, std::vector<DirectBeam>& out) const {
  const Impl& m = *impl_;
  if (m.eta == 1.0) return m.gather_straight(x, out);
  const scene::Scene& s = *m.scene;
  for (const LightBeams& lb : m.lights) {
    const scene::Light& light = s.lights[lb.light];
    const glm::dvec3 colour = glm::dvec3(light.color) * double(light.intensity);
    // A face's chunks overlap at their ends: each face is solved once per query.
    thread_local std::vector<std::uint32_t> seen;
    seen.clear();
    lb.grid.query(lb.chunks, lb.frame * x, [&](std::uint32_t k) {
      const Chunk& c = lb.chunks[k];
      if (std::find(seen.begin(), seen.end(), c.face) != seen.end()) return;
      seen.push_back(c.face);
      const Face& f = lb.faces[c.face];
      glm::dvec3 y, d;
      double t, irradiance;
      glm::dvec3 to_light;
      double light_distance = std::numeric_limits<double>::infinity();
      if (lb.type == scene::LightType::Directional) {
        const double h = glm::dot(x - f.c0, f.n);
        t = -h / f.cos_t;
        if (!(t >= 0.0)) return;
        y = x - t * f.d;
        d = f.d;
        to_light = lb.to_light;
        irradiance = f.factor;
      } else {
        if (!fermat_point(lb.position, x, f.c0, f.n, m.eta, y)) return;
        t = glm::length(x - y);
        const glm::dvec3 toward = y - lb.position;
        const double rho = glm::length(toward);
        const glm::dvec3 i = toward / rho;
        const double cos_i = -glm::dot(i, f.n);
        if (!(cos_i > 0.0) || !walk::refract(i, f.n, 1.0, m.eta, d)) return;
        const double cos_t = -glm::dot(d, f.n);
        // The refracted ray tube: d(y) = i/eta + (cos_i/eta - cos_t) n over the face,
        // differentiated along two unit tangents.
        glm::dvec3 t1, t2;
        walk::basis(f.n, t1, t2);
        auto tube_edge = [&](const glm::dvec3& u) {
          const glm::dvec3 di = (u - i * glm::dot(i, u)) / rho;
          const double dcos_i = -glm::dot(di, f.n);
          const double dcos_t = cos_i * dcos_i / (m.eta * m.eta * cos_t);
          const glm::dvec3 dd = di / m.eta + (dcos_i / m.eta - dcos_t) * f.n;
          return u + t * dd;
        };
        const double area = std::abs(glm::dot(glm::cross(tube_edge(t1), tube_edge(t2)), d));
        if (!(area > 0.0)) return;
        const double rho_units = rho / s.mm_per_unit;
        irradiance = (1.0 - walk::fresnel(cos_i, 1.0, m.eta)) * cos_i * spot_factor(light, i) /
                     (std::max(rho_units * rho_units, 1e-8) * area);
        to_light = -i;
        light_distance = rho;
      }
      const double u = glm::dot(y - f.c0, f.du), v = glm::dot(y - f.c0, f.dv);
      if (u < 0.0 || v < 0.0 || u + v > 1.0) return;
      if (!(irradiance > 0.0)) return;
      if (!m.inside(x, y, t) || !m.lit(light, y, f.n, to_light, light_distance)) return;
      DirectBeam b;
      b.light = lb.light;
      b.direction = d;
      b.distance_mm = t;
      b.irradiance = colour * irradiance;
      b.instance = f.instance;
      b.triangle = f.triangle;
      b.barycentric = glm::vec2(float(u), float(v));
      out.push_back(b);
    });
  }
}

}  // namespace sss::reference
