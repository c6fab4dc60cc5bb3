// The SCM solver (docs/soil.md). Per step and wheel: (1) intersect the wheel cylinder with the
// grid nodes around it (vertical lines through the nodes, lower root of the cylinder equation);
// (2) per contact node the elastic trial stress capped by the Bekker pressure, viscous damping,
// and the Mohr-Coulomb / Janosi-Hanamoto shear; (3) sum forces and moments. EndStep moves the
// soil displaced plastically this step to the rim of each wheel's contact patch and smooths
// slopes steeper than the erosion angle.
#include "vb/soil/scm_soil.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>

#include "vb/engine/error.h"
#include "vb/soil/belt_row.h"
#include "vb/soil/wheel_bottom.h"
#include "vb/soil/pow_lower_bound.h"

namespace vb::soil {

namespace {

constexpr int kTileBits = 4;
constexpr int kTileSize = 1 << kTileBits;   // 16 x 16 nodes per tile
constexpr int kTileMask = kTileSize - 1;
// Stability of the stiff elastic soil spring at the step: the wheel's total contact stiffness
// K is limited so that K dt^2 / m <= kStiffnessLimit (semi-implicit Euler is stable below 4;
// 1 leaves room for the suspension and for load transfer). At the HMMWV wheel and 5 ms this
// caps Ke near 6.7e7 Pa/m over 0.06 m^2: the elastic part of the sinkage becomes ~1 mm instead
// of ~0.4 mm, the plastic (Bekker) part is unchanged.
constexpr double kStiffnessLimit = 1.0;
// Shear displacement beyond which the soil is taken as fully sheared (1 - e^-5 = 99.3 %).
constexpr double kShearCapInK = 5.0;
// Erosion moves below this height (m) no longer put a node back on the work list: the slope is
// settled to 0.01 mm.
constexpr double kErosionSettled_m = 1e-5;
// Smallest cosine between the wheel-surface normal and the vertical used to turn a grid cell's
// horizontal area into the wheel-surface area above it (78 degrees: the deepest snow rut).
constexpr double kMinCos = 0.2;
// Slack (m) of the belt scan's quick rejects against the rounding of an interpolated belt
// height (~1e-13 m): a reject needs the belt this much above the bound.
constexpr double kScanMargin_m = 1e-7;
// The 4-neighbour offsets, in the order every pass visits them.
constexpr int kDi[4] = {1, -1, 0, 0}, kDj[4] = {0, 0, 1, -1};
// A belt block's other nodes (+i, +j, +i+j; belt_node_stride 2): grid offsets and the pointer
// offsets inside the block's tile.
constexpr int kMi[3] = {1, 0, 1}, kMj[3] = {0, 1, 1};
constexpr int kMateOffset[3] = {1, kTileSize, kTileSize + 1};

struct Node {
  double base_m = 0.0;        // initial terrain level
  double level0_m = 0.0;      // undisturbed level: base plus deposits minus erosion
  double plastic_m = 0.0;     // plastic sinkage along the terrain normal
  double sink_m = 0.0;        // plastic_m / cos_slope, kept with it (the level's drop below
                              // level0: Level() without a division, bit for bit the same)
  Vec3 shear_m = Vec3::Zero();// Janosi shear displacement (world vector, in the contact plane)
  float cos_slope = 1.0f;     // z of the undeformed terrain normal
  int8_t slot = -1;           // soil slot (SoilSlot), -1: rigid or outside the world
  uint8_t local = 0;          // index in its tile: row * kTileSize + column (TileOf)
  uint8_t links = 0xff;       // where its 4-neighbours are, 2 bits per direction e (kDi, kDj;
                              // bits 2e, 2e + 1): kInTile, kAdjacentTile or kOutside (0: all
                              // four in its tile)
  int32_t contact_step = -2;  // last step with wheel contact
  int32_t queue_stamp = -1;   // scratch stamp (rim and erosion work list membership)
};

static_assert(sizeof(Node) == 72, "the local index and links live in the padding after slot");

// Node::links, per direction: the neighbour is in the node's tile (pointer offset kInTileStep),
// in the adjacent tile that way (Tile::adj; kCrossStep from the node's local index), or outside
// the world.
constexpr unsigned kInTile = 0, kAdjacentTile = 1, kOutside = 2;
constexpr int kInTileStep[4] = {1, -1, kTileSize, -kTileSize};
constexpr int kCrossStep[4] = {-kTileMask, kTileMask, -kTileMask * kTileSize, kTileMask * kTileSize};

// Advances a contact node's Janosi shear displacement by one step of the surface's slip: restarted
// when the node (or its block) was not in contact the step before, moved by the velocity's part
// tangent to the surface normal nw, kept in the tangent plane and capped at jmax (where the
// mobilised share is tabulated). Returns its length. The one shear law of wheels and belts.
[[gnu::always_inline]] inline double AdvanceShear(bool restart, const Vec3& v, const Vec3& nw,
                                                  double dt, double jmax, Vec3* shear) {
  if (restart) shear->setZero();
  const double vn = v.dot(nw);
  const Vec3 vt = v - vn * nw;
  *shear += vt * dt;
  *shear -= shear->dot(nw) * nw;
  double j_len = shear->norm();
  if (j_len > jmax) {
    *shear *= jmax / j_len;
    j_len = jmax;
  }
  return j_len;
}

struct Tile {
  Node nodes[kTileSize * kTileSize];
  // Per tile row: an upper bound on the level of its deformable nodes (the highest level0 any
  // of them has had; levels only sink below level0: a plastic sinkage is never negative but by
  // rounding, ~1e-17 m, far inside kScanMargin_m). -1e300: no deformable node in the row.
  double row_top_m[kTileSize];
  // The allocated tiles beside this one in the directions +i, -i, +j, -j (kDi, kDj), nullptr
  // where none is (not allocated, or outside the world). Kept by Allocate; rebuilt by Restore
  // (a snapshot's copies hold the pointers of the soil they were taken from).
  Tile* adj[4] = {nullptr, nullptr, nullptr, nullptr};
};

static_assert(std::is_standard_layout_v<Tile> && offsetof(Tile, nodes) == 0,
              "TileOf: a tile's address is its first node's");

// The tile holding node n: its nodes array starts n->local nodes before n (no look-up through
// the tile list).
inline Tile* TileOf(Node* n) { return reinterpret_cast<Tile*>(n - n->local); }

// The node's current level: level0 - plastic / cos_slope (sink_m holds the quotient).
double Level(const Node& n) { return n.level0_m - n.sink_m; }

// z >= Level(n).
bool AboveLevel(const Node& n, double z) { return z >= Level(n); }

// Sets a node's plastic sinkage and the cached sink_m = plastic / cos_slope with it.
void SetPlastic(Node& n, double plastic) {
  n.plastic_m = plastic;
  n.sink_m = plastic / n.cos_slope;
}

// static_cast<int>(std::ceil(x)) and (std::floor(x)) for x within the range of int: the
// conversion truncates towards zero, the comparison (exact: an int is a double) adds the step.
int CeilToInt(double x) {
  const int t = static_cast<int>(x);
  return t + (t < x ? 1 : 0);
}
int FloorToInt(double x) {
  const int t = static_cast<int>(x);
  return t - (t > x ? 1 : 0);
}

// Bottom of a flat belt segment from a to b (across it: half width hw along lat, which may be
// tilted by the track's roll) on vertical lines: the segment's terms once (Init), then At per
// line.
struct BeltBottom {
  double ax = 0.0, ay = 0.0, az = 0.0, dz = 0.0, sx = 0.0, sy = 0.0, len2 = 0.0;
  double lx = 0.0, ly = 0.0, latz = 0.0, lat_h = 1.0, hw = 0.0;
  bool valid = false;   // the segment's horizontal projection is not a point
  void Init(const Vec3& a, const Vec3& b, const Vec3& lat, double half_w) {
    ax = a.x();
    ay = a.y();
    az = a.z();
    dz = b.z() - a.z();
    sx = b.x() - a.x();
    sy = b.y() - a.y();
    len2 = sx * sx + sy * sy;
    valid = !(len2 < 1e-12);
    if (!valid) return;
    const double inv_len = 1.0 / std::sqrt(len2);
    lx = -sy * inv_len;     // horizontal, across the segment
    ly = sx * inv_len;
    if (lx * lat.x() + ly * lat.y() < 0.0) {
      lx = -lx;
      ly = -ly;
    }
    latz = lat.z();
    lat_h = std::sqrt(std::max(1e-6, 1.0 - lat.z() * lat.z()));
    hw = half_w;
  }
  // The belt's bottom z on the vertical line through (x, y); false if the line misses it.
  // t: position along the segment's horizontal projection (0 at a, 1 at b), l: across it.
  bool At(double x, double y, double* z, double* t, double* l) const {
    if (!valid) return false;
    const double ux = x - ax, uy = y - ay;
    *t = (ux * sx + uy * sy) / len2;
    *l = ux * lx + uy * ly;
    if (std::abs(*l) > hw) return false;
    *z = az + *t * dz + *l * latz / lat_h;
    return true;
  }
};

}  // namespace

struct ScmSoil::Impl {
  const terrain::Terrain& terrain;
  double dx = 0.0;
  int i_min = 0, j_min = 0, i_max = 0, j_max = 0;
  int tiles_x = 0, tiles_y = 0;
  std::vector<int32_t> tile_index;           // tiles_x * tiles_y, -1: not allocated
  std::vector<std::unique_ptr<Tile>> tiles;  // in allocation order
  std::array<SoilParams, 3> soils;
  std::array<double, 3> tan_friction{};  // tan of each soil's friction angle (per node otherwise)
  std::array<PowLowerBound, 3> pow_bound;  // z^bekker_n from below, per soil
  // The Bekker yield test: sigma > kb z^n with soil `slot`'s exponent n; on yield *p_bekker is
  // kb * std::pow(z, n). Skips pow where the table bound already shows sigma below it.
  bool Yields(size_t slot, double kb, double z, double sigma, double* p_bekker) const {
    if (kb >= 0.0 && sigma <= kb * pow_bound[slot](z)) return false;
    *p_bekker = kb * std::pow(z, soils[slot].bekker_n);
    return sigma > *p_bekker;
  }
  // Janosi-Hanamoto: the share 1 - e^(-j/K) of the shear strength mobilised at shear
  // displacement j of soil `slot` (K its janosi_shear_m). The displacement is clamped at
  // shear_cap_m = kShearCapInK K, where the nodes of a spinning wheel or track sit: there the
  // value comes from the table, computed by the same expression (bit-identical, without exp).
  std::array<double, 3> shear_cap_m{};
  std::array<double, 3> capped_mobilised{};
  double Mobilised(size_t slot, double j) const {
    if (j == shear_cap_m[slot]) return capped_mobilised[slot];
    return 1.0 - std::exp(-j / soils[slot].janosi_shear_m);
  }
  // A contact node's normal stress at sinkage z (along the terrain normal): the elastic trial
  // (stiffness ke on z minus its plastic sinkage) up to Bekker's pressure kb z^n of its soil; on
  // yield Bekker's, and the plastic sinkage follows. *flow: the soil volume that move displaces
  // per unit horizontal area (0 without yield). The one pressure law of wheels and belts.
  double Press(Node& n, double z, double ke, double kb, double* flow) const {
    double sigma = ke * (z - n.plastic_m);
    double p_bekker = 0.0;
    *flow = 0.0;
    if (Yields(static_cast<size_t>(n.slot), kb, z, sigma, &p_bekker)) {
      sigma = p_bekker;
      const double plastic = z - p_bekker / ke;
      *flow = (plastic - n.plastic_m) / static_cast<double>(n.cos_slope);
      SetPlastic(n, plastic);
    }
    return sigma;
  }
  // A contact node's force on the surface: its stress sigma on the surface area it carries
  // (along the surface normal nw), the damping stress on its cell (cell x cover) along the
  // terrain normal, and the Mohr-Coulomb strength of the total stress (damping included, Chrono's
  // order, reference §2.3) mobilised by its shear displacement of length j_len.
  Vec3 NodeForce(const Node& n, double sigma, double sigma_damp, double area, double cell,
                 double cover, const Vec3& nw, const Vec3& terrain_normal, double j_len) const {
    Vec3 f = sigma * area * nw + sigma_damp * cell * cover * terrain_normal;
    if (j_len > 0.0) {
      const auto slot = static_cast<size_t>(n.slot);
      const double tau_max = soils[slot].cohesion_pa + (sigma + sigma_damp) * tan_friction[slot];
      const double tau = tau_max * Mobilised(slot, j_len);
      f -= (tau * area / j_len) * n.shear_m;
    }
    return f;
  }
  int32_t step = 0;
  ScmStats stats;
  double max_raise_m = 0.0;   // highest level0 - base of any node so far (scan bound)
  // Raises (dh > 0) or lowers a node's undisturbed level. Lowering cannot raise a maximum (every
  // node's level0 - base is <= max_raise_m and its level0 <= its tile row's top, and
  // level0 + dh <= level0 for dh <= 0 in floating point), so only a raise updates them.
  void Raise(Node* n, double dh) {
    n->level0_m += dh;
    if (dh > 0.0) {
      max_raise_m = std::max(max_raise_m, n->level0_m - n->base_m);
      double& top = TileOf(n)->row_top_m[n->local >> kTileBits];
      top = std::max(top, n->level0_m);
    }
  }

  // This step's contacts, wheel by wheel (ranges into `contacts`).
  struct Contact {
    int i, j;
    double flow_m;   // plastic sinkage increment (vertical) this step
    Node* node;      // the node at (i, j) (tiles never move while they exist)
  };
  struct Patch {
    size_t begin, end;
    Vec3 center, axis;   // the wheel that made it (a belt segment: its ends, axis = across)
    double radius, half_width;
    bool belt = false;
    Vec3 belt_end = Vec3::Zero();
  };
  std::vector<Contact> contacts;
  std::vector<Patch> patches;
  // Scratch of one wheel query.
  struct Hit {
    Node* node;
    int i, j;
    Vec3 p;          // hit point on the wheel surface
    double lat, lon; // position along the axis / along the rolling direction
    double cover;    // share of the cell under the tread (edge columns: < 1)
  };
  std::vector<Hit> hits;
  // WheelContact's hits: a buffer written by index (sized before the scan for the most it can
  // keep, so the scan's loop holds no call), the count in WheelContact's locals.
  std::vector<Hit> wheel_hits;
  // Erosion work lists: nodes to check in this pass / next pass, with their ring distance from
  // the rim they started at; `pending` carries nodes still changing at the end of a step over.
  struct Work {
    int i, j, ring;
    Node* node;   // the node at (i, j) (tiles never move while they exist; Restore looks
                  // pending's up again in the restored tiles)
  };
  std::vector<Work> pending;
  size_t n_rim = 0;   // this step's rim: active_buf[0, n_rim) (see active_buf)
  int32_t queue_stamp = 0;
  // The erosion passes' work lists (this pass's, the next pass's): buffers written by index
  // (sized before a pass for the most it can add), their lengths in Erode's locals. EndStep
  // writes the rim straight into active_buf, the first pass's list, its nodes stamped with the
  // first pass's queue stamp (queue_stamp + 1): membership of the rim and of that list at once.
  std::vector<Work> active_buf, next_buf;

  explicit Impl(const terrain::Terrain& t) : terrain(t) {}

  // Grid row j's part of a node look-up, for scans that visit several nodes of one row.
  struct GridRow {
    bool inside = false;    // j within the world
    int lj = 0;             // j - j_min
    size_t tile_base = 0;   // tile_index of the row's first tile (if inside)
  };
  GridRow Row(int j) const {
    GridRow r;
    r.inside = j >= j_min && j <= j_max;
    r.lj = j - j_min;
    r.tile_base = r.inside ? static_cast<size_t>(r.lj >> kTileBits) * tiles_x : 0;
    return r;
  }
  // The node at (i, r's j), its tile allocated first if `allocate`; nullptr outside the world
  // (or in a tile not allocated). *tile: the node's tile.
  Node* AtInRow(const GridRow& r, int i, bool allocate, Tile** tile) {
    if (i < i_min || i > i_max || !r.inside) return nullptr;
    const int li = i - i_min;
    const size_t t = r.tile_base + static_cast<size_t>(li >> kTileBits);
    int32_t idx = tile_index[t];
    if (idx < 0) {
      if (!allocate) return nullptr;
      idx = Allocate(li >> kTileBits, r.lj >> kTileBits);
      tile_index[t] = idx;
    }
    *tile = tiles[static_cast<size_t>(idx)].get();
    return &(*tile)->nodes[(r.lj & kTileMask) * kTileSize + (li & kTileMask)];
  }
  Node* At(int i, int j, bool allocate) {
    Tile* tile = nullptr;
    return AtInRow(Row(j), i, allocate, &tile);
  }

  // The 4-neighbours of node n at (i, j) in the order +i, -i, +j, -j (kDi, kDj), the same
  // nodes as At(i + kDi[e], j + kDj[e], allocate) and looked up (allocated) in that order: inside
  // n's tile by pointer offset (the hot path of the rim and erosion passes), else through At.
  void Neighbours(Node* n, int i, int j, bool allocate, Node* nb[4]) {
    const int li = (i - i_min) & kTileMask, lj = (j - j_min) & kTileMask;
    nb[0] = li != kTileMask && i < i_max ? n + 1 : At(i + 1, j, allocate);
    nb[1] = li != 0 ? n - 1 : At(i - 1, j, allocate);
    nb[2] = lj != kTileMask && j < j_max ? n + kTileSize : At(i, j + 1, allocate);
    nb[3] = lj != 0 ? n - kTileSize : At(i, j - 1, allocate);
  }

  // Whether z is at or above the soil top of every tile row of grid rows j_lo..j_hi over the
  // tiles holding columns i_lo..i_hi, all of them inside the world and allocated (false else).
  bool AboveSoilTops(int i_lo, int i_hi, int j_lo, int j_hi, double z) const {
    if (i_lo < i_min || i_hi > i_max || j_lo < j_min || j_hi > j_max) return false;
    const int tx0 = (i_lo - i_min) >> kTileBits, tx1 = (i_hi - i_min) >> kTileBits;
    for (int j = j_lo; j <= j_hi; ++j) {
      const int lj = j - j_min;
      const size_t row = static_cast<size_t>(lj >> kTileBits) * tiles_x;
      for (int tx = tx0; tx <= tx1; ++tx) {
        const int32_t idx = tile_index[row + static_cast<size_t>(tx)];
        if (idx < 0 || !(z >= tiles[static_cast<size_t>(idx)]->row_top_m[lj & kTileMask])) {
          return false;
        }
      }
    }
    return true;
  }

  // Not inline: once per tile, and the look-ups that call it (AtInRow, At) stay small enough to
  // be inlined into the scans.
  __attribute__((noinline)) int32_t Allocate(int tx, int ty) {
    auto tile = std::make_unique<Tile>();
    for (int b = 0; b < kTileSize; ++b) {
      tile->row_top_m[b] = -1e300;
      for (int a = 0; a < kTileSize; ++a) {
        Node& n = tile->nodes[b * kTileSize + a];
        n.local = static_cast<uint8_t>(b * kTileSize + a);
        const int i = i_min + tx * kTileSize + a, j = j_min + ty * kTileSize + b;
        if (i > i_max || j > j_max) continue;  // beyond the world edge: stays rigid (links 0xff)
        // Peek's cases: +i in the tile if a < kTileMask and i < i_max, in the next tile if
        // a == kTileMask and i < i_max, else outside; -i in the tile if a > 0, else the tile
        // before (none at the world's first column); the same along j.
        const unsigned pi = i < i_max ? (a != kTileMask ? kInTile : kAdjacentTile) : kOutside;
        const unsigned mi = a != 0 ? kInTile : kAdjacentTile;
        const unsigned pj = j < j_max ? (b != kTileMask ? kInTile : kAdjacentTile) : kOutside;
        const unsigned mj = b != 0 ? kInTile : kAdjacentTile;
        n.links = static_cast<uint8_t>(pi | mi << 2 | pj << 4 | mj << 6);
        const terrain::SurfacePoint sp = terrain.Query(i * dx, j * dx);
        n.base_m = n.level0_m = sp.height_m;
        n.cos_slope = static_cast<float>(std::max(0.05, sp.normal_W.z()));
        n.slot = static_cast<int8_t>(SoilSlot(sp.surface));
        if (n.slot >= 0) tile->row_top_m[b] = std::max(tile->row_top_m[b], n.level0_m);
      }
    }
    Link(tile.get(), tx, ty);
    tiles.push_back(std::move(tile));
    ++stats.tiles;
    return static_cast<int32_t>(tiles.size() - 1);
  }

  // Tile (tx, ty) and its allocated neighbours point at each other (Tile::adj).
  void Link(Tile* tile, int tx, int ty) {
    const int ntx[4] = {tx + 1, tx - 1, tx, tx}, nty[4] = {ty, ty, ty + 1, ty - 1};
    for (int e = 0; e < 4; ++e) {
      tile->adj[e] = nullptr;
      if (ntx[e] < 0 || ntx[e] >= tiles_x || nty[e] < 0 || nty[e] >= tiles_y) continue;
      const int32_t idx = tile_index[static_cast<size_t>(nty[e]) * tiles_x + ntx[e]];
      if (idx < 0) continue;
      Tile* other = tiles[static_cast<size_t>(idx)].get();
      tile->adj[e] = other;
      other->adj[e ^ 1] = tile;   // the opposite direction: +i <-> -i, +j <-> -j
    }
  }

  double LevelAt(int i, int j) {
    const Node* n = At(i, j, false);
    return n != nullptr ? Level(*n) : terrain.Height(i * dx, j * dx);
  }

  void Erode(const BulldozingParams& bp);
  // TrackContact with the belt pressing every kStride-th node each way (1 or 2). At 2 the
  // pressed node stands for its 2 x 2 block (+i, +j, +i+j: the same tile): the block's other
  // nodes under the belt at or below its level follow it (contacts, bearing through its stress
  // on the block's cell); one standing above it (soil bulldozing or erosion put there, fresh soil
  // ahead of the rut) is pressed by its own law and bears on its own cell in place of the
  // pressed node's stress there, so deposits under the belt bear as on the full grid. The block
  // shares one slip velocity, Janosi shear displacement (on the pressed node) and force split.
  template <int kStride>
  TrackSoilOutput Track(const SoilConfig& config, const TrackSoilInput& tr, double dt);
  std::vector<char> hit_rep_in;   // belt_node_stride 2: the pressed node itself in contact
  void DepositOnRim(const Patch& patch, size_t begin, size_t end, double volume);
  // What one erosion pass's node visits share (Erode's locals, written back around ErodeVisit).
  struct ErodePass {
    double threshold;
    int32_t cur_step, stamp;
    int propagations;
    double max_raise;
    Work* out;      // the next pass's work list
    size_t n_out;
  };
  void ErodeVisit(const Work& w, ErodePass& s);
  // The rim nodes of contact ct in the order +i, -i, +j, -j (deformable, not in contact this
  // step, not yet on the rim: not stamped rim_stamp), written from rim[n_rim] on; their tiles
  // allocated if missing. Returns the new count.
  __attribute__((noinline)) size_t RimOf(const Contact& ct, int32_t step, int32_t rim_stamp,
                                         Work* rim, size_t n_rim) {
    Node* nbs[4];
    Neighbours(ct.node, ct.i, ct.j, true, nbs);
    for (int e = 0; e < 4; ++e) {
      Node* nb = nbs[e];
      if (nb == nullptr || nb->slot < 0 || nb->contact_step == step ||
          nb->queue_stamp == rim_stamp) {
        continue;
      }
      nb->queue_stamp = rim_stamp;
      rim[n_rim++] = {ct.i + kDi[e], ct.j + kDj[e], 0, nb};
    }
    return n_rim;
  }
  // The node at (i, j) if it exists (inside the world, its tile allocated), else nullptr: At's
  // look-up without allocation, inline (no call in the erosion's fast path).
  Node* Peek(int i, int j) const {
    if (i < i_min || i > i_max || j < j_min || j > j_max) return nullptr;
    const int li = i - i_min, lj = j - j_min;
    const size_t t = static_cast<size_t>(lj >> kTileBits) * tiles_x +
                     static_cast<size_t>(li >> kTileBits);
    const int32_t idx = tile_index[t];
    if (idx < 0) return nullptr;
    return &tiles[static_cast<size_t>(idx)]->nodes[(lj & kTileMask) * kTileSize + (li & kTileMask)];
  }
  // The 4-neighbours of node n, in Neighbours' order (+i, -i, +j, -j: kDi, kDj), for the rim and
  // erosion loops: the nodes Peek finds (inside the world, their tile allocated), from n's links
  // without a look-up: in n's tile by pointer offset (nearly always all four), across a tile
  // border through the adjacent tile's pointer. No call on the way, so the callers' doubles stay
  // in registers. False if one of them does not exist (outside the world, or its tile not
  // allocated): the caller then takes its own path, which may allocate.
  [[gnu::always_inline]] static bool FourNeighbours(Node* n, Node* nb[4]) {
    const unsigned links = n->links;
    if (links == 0) {
      nb[0] = n + 1;
      nb[1] = n - 1;
      nb[2] = n + kTileSize;
      nb[3] = n - kTileSize;
      return true;
    }
    const Tile* tile = TileOf(n);
    bool all = true;
    for (int e = 0; e < 4; ++e) {
      const unsigned where = (links >> (2 * e)) & 3u;
      Node* p = nullptr;
      if (where == kInTile) {
        p = n + kInTileStep[e];
      } else if (where == kAdjacentTile && tile->adj[e] != nullptr) {
        p = &tile->adj[e]->nodes[n->local + kCrossStep[e]];
      }
      nb[e] = p;
      all = all && p != nullptr;
    }
    return all;
  }
  std::vector<double> room;
  std::vector<char> full_scratch;
  std::vector<size_t> under_tread;   // DepositOnRim's scratch
};

ScmSoil::ScmSoil(const terrain::Terrain& terrain, const SoilConfig& config)
    : config_(config), impl_(std::make_unique<Impl>(terrain)) {
  if (!(config_.grid_spacing_m > 0.0)) {
    throw InputError(config_.source, 0, "grid.spacing_m", "must be > 0");
  }
  if (config_.belt_node_stride != 1 && config_.belt_node_stride != 2) {
    throw InputError(config_.source, 0, "belt_node_stride", "must be 1 or 2");
  }
  if (!(config_.default_wheel_mass_kg > 0.0) || !(config_.default_wheel_spin_inertia_kgm2 > 0.0)) {
    throw InputError(config_.source, 0, "stabilisation", "default wheel mass and inertia must be > 0");
  }
  for (terrain::SurfaceClass c : terrain.patches().classes) {
    if (terrain::IsDeformable(c) && config_.For(c) == nullptr) {
      throw InputError(config_.source, 0, std::string(terrain::SurfaceClassName(c)),
                       "the task has " + std::string(terrain::SurfaceClassName(c)) +
                           " patches but the soil file does not describe that class");
    }
  }
  Impl& m = *impl_;
  for (size_t k = 0; k < 3; ++k) {
    if (config_.classes[k]) {
      m.soils[k] = *config_.classes[k];
      // As Chrono: the elastic stiffness is never below the frictional modulus.
      m.soils[k].elastic_stiffness_papm =
          std::max(m.soils[k].elastic_stiffness_papm, m.soils[k].bekker_kphi);
      m.tan_friction[k] = std::tan(m.soils[k].friction_angle_rad);
      m.pow_bound[k].Init(m.soils[k].bekker_n);
      m.shear_cap_m[k] = kShearCapInK * m.soils[k].janosi_shear_m;
      m.capped_mobilised[k] = 1.0 - std::exp(-m.shear_cap_m[k] / m.soils[k].janosi_shear_m);
    }
  }
  m.dx = config_.grid_spacing_m;
  const double hx = terrain.size_x_m() / 2.0, hy = terrain.size_y_m() / 2.0;
  m.i_min = static_cast<int>(std::ceil(-hx / m.dx - 1e-9));
  m.i_max = static_cast<int>(std::floor(hx / m.dx + 1e-9));
  m.j_min = static_cast<int>(std::ceil(-hy / m.dx - 1e-9));
  m.j_max = static_cast<int>(std::floor(hy / m.dx + 1e-9));
  m.tiles_x = (m.i_max - m.i_min) / kTileSize + 1;
  m.tiles_y = (m.j_max - m.j_min) / kTileSize + 1;
  m.tile_index.assign(static_cast<size_t>(m.tiles_x) * m.tiles_y, -1);
}

ScmSoil::~ScmSoil() = default;

WheelSoilOutput ScmSoil::WheelContact(const WheelSoilInput& wheel, double dt) {
  Impl& m = *impl_;
  ++m.stats.wheel_queries;
  WheelSoilOutput out;
  const Vec3& c = wheel.center_W;
  const terrain::SurfacePoint under = m.terrain.Query(c.x(), c.y());
  const double r = wheel.radius_m, half_w = 0.5 * wheel.width_m;
  const Vec3 a = wheel.axis_W.normalized();
  const bool centre_on_soil = terrain::IsDeformable(under.surface);
  // A wheel whose centre is over rigid ground may still have part of its tread over a soil patch
  // (a seam): the soil answers for its own nodes wherever the centre is, the vehicle's rigid tire
  // for the rigid patches (tire_contact.h, GroundScope::kRigidOnly).
  if (!centre_on_soil &&
      m.terrain.MixAround(c.x(), c.y(), r + half_w + 0.5 * m.dx + r * std::abs(a.z())) ==
          terrain::GroundMix::kRigid) {
    return out;  // rigid ground only: the vehicle's tire
  }
  out.on_soil = true;
  out.surface = under.surface;
  Vec3 fwd = a.cross(Vec3::UnitZ());
  if (fwd.norm() < 0.1) return out;  // wheel lying on its side: no rolling contact model
  fwd.normalize();
  // How deep the wheel can reach into the soil around it: the soil is nowhere higher than the
  // terrain under the centre, plus its slope over the wheel's reach, plus the highest deposit
  // so far. That bounds the contact length and so the nodes to scan.
  const double nz = std::max(0.05, under.normal_W.z());
  const double reach = r + half_w;
  const double soil_top = under.height_m + reach * std::sqrt(1.0 - nz * nz) / nz +
                          m.max_raise_m + 0.5 * m.dx;
  const double lowest = c.z() - r * std::sqrt(1.0 - a.z() * a.z()) - half_w * std::abs(a.z());
  const double depth = soil_top - lowest;
  if (depth <= 0.0) return out;  // above the soil
  const double half_len = depth >= r ? r : std::sqrt(depth * (2.0 * r - depth));
  const Vec3 lat_h = Vec3::UnitZ().cross(fwd);
  const double half_lat = half_w + 0.5 * m.dx + r * std::abs(a.z());
  const double ex = std::abs(fwd.x()) * half_len + std::abs(lat_h.x()) * half_lat;
  const double ey = std::abs(fwd.y()) * half_len + std::abs(lat_h.y()) * half_lat;
  const int i_lo = static_cast<int>(std::ceil((c.x() - ex) / m.dx));
  const int i_hi = static_cast<int>(std::floor((c.x() + ex) / m.dx));
  const int j_lo = static_cast<int>(std::ceil((c.y() - ey) / m.dx));
  const int j_hi = static_cast<int>(std::floor((c.y() + ey) / m.dx));

  // (1) Geometry: the lowest point of the cylinder above each node, kept if below the soil.
  const double hw_ext = half_w + 0.5 * m.dx;
  // Nodes the cylinder clears are rejected without the intersection (wheel_bottom.h).
  const WheelHeightBound bound(c, a, r, hw_ext);
  const double lon_step = m.dx * fwd.x();
  const double lat_reach = hw_ext + std::abs(a.z()) * std::sqrt(r * r + hw_ext * hw_ext) + 1e-6;
  // The scan keeps at most one hit per node of the box [i_lo, i_hi] x [j_lo, j_hi].
  if (i_hi >= i_lo && j_hi >= j_lo) {
    const size_t box = static_cast<size_t>(i_hi - i_lo + 1) * static_cast<size_t>(j_hi - j_lo + 1);
    if (m.wheel_hits.size() < box) m.wheel_hits.resize(box);
  }
  Impl::Hit* const hits = m.wheel_hits.data();
  size_t n_hits = 0;
  // Kept hits go to `hits` in scan order, which is also the order of the sums over them: the
  // contact rectangle's bounds (for the patch width) and the stiffness and damping totals (for
  // the stabilisation) are taken as each hit is kept, term by term as a loop over the hits
  // would.
  const double cell = m.dx * m.dx;
  double lat_lo = 1e300, lat_hi = -1e300, lon_lo = 1e300, lon_hi = -1e300;
  double k_total = 0.0, c_total = 0.0;
  auto keep = [&](const Impl::Hit& h) {
    hits[n_hits++] = h;
    lat_lo = std::min(lat_lo, h.lat);
    lat_hi = std::max(lat_hi, h.lat);
    lon_lo = std::min(lon_lo, h.lon);
    lon_hi = std::max(lon_hi, h.lon);
    const SoilParams& s = m.soils[static_cast<size_t>(h.node->slot)];
    k_total += s.elastic_stiffness_papm * cell * h.cover;
    c_total += s.damping_paspm * cell * h.cover;
  };
  for (int j = j_lo; j <= j_hi; ++j) {
    // The row tile by tile: one look-up per tile (the first node in it under the tread, as the
    // node-by-node look-up allocated it), the others by pointer offset.
    // Only the row's nodes within the tread's lateral reach: a point of the cylinder with
    // |lat| <= hw_ext is within sqrt(r^2 + hw_ext^2) of the centre, so its horizontal axial
    // offset ua = lat - t a_z is at most lat_reach (plus 1e-6 m and a node each side for
    // rounding): the nodes left out are ones WheelBottomAt rejects.
    int row_lo = i_lo, row_hi = i_hi;
    if (std::abs(a.x()) > 1e-6) {
      const double uy = j * m.dx - c.y();
      double x0 = c.x() + (-lat_reach - uy * a.y()) / a.x();
      double x1 = c.x() + (lat_reach - uy * a.y()) / a.x();
      if (x0 > x1) std::swap(x0, x1);
      row_lo = std::max(row_lo, FloorToInt(x0 / m.dx) - 1);
      row_hi = std::min(row_hi, CeilToInt(x1 / m.dx) + 1);
    }
    // The row's ends whose horizontal axial offset ua exceeds lat_reach are nodes WheelBottomAt
    // rejects (above), before any look-up: left out. ua is monotonic along the row (each
    // operation of it is), so the nodes left are those with |ua| <= lat_reach.
    {
      const double uy = j * m.dx - c.y();
      while (row_lo <= row_hi &&
             std::abs((row_lo * m.dx - c.x()) * a.x() + uy * a.y()) > lat_reach) {
        ++row_lo;
      }
      while (row_hi >= row_lo &&
             std::abs((row_hi * m.dx - c.x()) * a.x() + uy * a.y()) > lat_reach) {
        --row_hi;
      }
    }
    const Impl::GridRow row = m.Row(j);
    const double lon_row = (j * m.dx - c.y()) * fwd.y() - c.x() * fwd.x();  // lon at i = 0
    int i = row_lo;
    while (i <= row_hi) {
      const int chunk_end =
          std::min(row_hi, m.i_min + (((i - m.i_min) >> kTileBits) + 1) * kTileSize - 1);
      Node* base = nullptr;
      int base_i = 0;
      bool looked_up = false;
      // Node i of this row: kept if the tread over it is below its level. Nodes whose cell
      // (+-dx/2 across) overlaps the tread are pressed, each carrying the share of its cell the
      // tread covers, so the effective width is the wheel's (sum of covers x dx = width)
      // wherever the wheel stands between grid columns. A node just beyond the tread edge takes
      // the cylinder's height there (the tread edge, extended by < dx/2). `n` is nullptr until
      // the first node under the tread looks its tile up (allocating it).
      auto consider = [&](int i, Node* n) {
        double hit_z = 0.0, lat = 0.0;
        if (!WheelBottomAt(c, a, r, hw_ext, i * m.dx, j * m.dx, &hit_z, &lat)) return;
        const double cover = std::min(1.0, (half_w - std::abs(lat)) / m.dx + 0.5);
        if (!(cover > 0.0)) return;
        if (!looked_up) {
          base = m.At(i, j, true);
          base_i = i;
          looked_up = true;
        }
        if (base == nullptr) return;    // outside the world
        if (n == nullptr) n = base + (i - base_i);  // beyond i_max: a rigid node (slot -1)
        if (n->slot < 0) return;
        if (AboveLevel(*n, hit_z)) return;
        const double ux = i * m.dx - c.x(), uy = j * m.dx - c.y();
        keep({n, i, j, Vec3(i * m.dx, j * m.dx, hit_z), lat, ux * fwd.x() + uy * fwd.y(), cover});
      };
      // consider() for a node of an allocated tile (n its deformable node): the same tests
      // without the look-up, so the loop over such nodes holds no call.
      auto consider_in_tile = [&](int i, Node* n) {
        double hit_z = 0.0, lat = 0.0;
        if (!WheelBottomAt(c, a, r, hw_ext, i * m.dx, j * m.dx, &hit_z, &lat)) return;
        const double cover = std::min(1.0, (half_w - std::abs(lat)) / m.dx + 0.5);
        if (!(cover > 0.0)) return;
        if (AboveLevel(*n, hit_z)) return;
        const double ux = i * m.dx - c.x(), uy = j * m.dx - c.y();
        keep({n, i, j, Vec3(i * m.dx, j * m.dx, hit_z), lat, ux * fwd.x() + uy * fwd.y(), cover});
      };
      // In an allocated tile (nothing to allocate) a node is first tested against the bound on
      // the cylinder's height over it (lon walked along the row), and only the nodes it leaves
      // are intersected.
      int32_t idx = -1;
      if (row.inside && i >= m.i_min && i <= m.i_max) {
        idx = m.tile_index[row.tile_base + static_cast<size_t>((i - m.i_min) >> kTileBits)];
      }
      if (idx >= 0) {
        Node* nd = &m.tiles[static_cast<size_t>(idx)]
                        ->nodes[(row.lj & kTileMask) * kTileSize + ((i - m.i_min) & kTileMask)];
        base = nd;
        base_i = i;
        looked_up = true;
        double lon = lon_row + i * lon_step;
        for (; i <= chunk_end; ++i, ++nd, lon += lon_step) {
          if (nd->slot < 0) continue;   // rigid (or beyond i_max): never kept
          if (bound.Clears(Level(*nd), lon)) continue;
          consider_in_tile(i, nd);
        }
      } else {
        for (; i <= chunk_end; ++i) consider(i, nullptr);
      }
      i = chunk_end + 1;
    }
  }
  if (n_hits == 0) return out;

  // Patch width for the Bekker law: the smaller side of the contact rectangle (Bekker's b),
  // never wider than the wheel. (Chrono uses 2A/L of the patch's convex hull, about half that.)
  // (lat_lo, lat_hi, lon_lo, lon_hi: taken in the scan, keep)
  const double b = std::max(
      m.dx, std::min({lat_hi - lat_lo + m.dx, 2.0 * half_w, lon_hi - lon_lo + m.dx}));

  // Stabilisation: effective stiffness and damping scales for this wheel and step.
  const double mass = wheel.mass_kg > 0.0 ? wheel.mass_kg : config_.default_wheel_mass_kg;
  // (k_total, c_total: summed in the scan, keep)
  const double k_scale = std::min(1.0, kStiffnessLimit * mass / (k_total * dt * dt));
  const double c_scale = 1.0 / (1.0 + c_total * dt / mass);  // implicit-Euler damper

  // (2) + (3) Node stresses, forces, moments. kb: each soil's Bekker modulus kc / b + kphi.
  double kb[3];
  for (size_t k = 0; k < 3; ++k) kb[k] = m.soils[k].bekker_kc / b + m.soils[k].bekker_kphi;
  Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
  double sinkage = 0.0;
  const size_t begin = m.contacts.size();
  // The contacts written by index (no call in the loop).
  m.contacts.resize(begin + n_hits);
  Impl::Contact* const contacts = m.contacts.data() + begin;
  const int32_t prev_step = m.step - 1;
  for (size_t k = 0; k < n_hits; ++k) {
    const Impl::Hit& h = hits[k];
    Node& n = *h.node;
    const SoilParams& s = m.soils[static_cast<size_t>(n.slot)];
    const double ca = n.cos_slope;
    const double z = ca * (n.level0_m - h.p.z());  // sinkage along the terrain normal
    double flow = 0.0;
    const double sigma = m.Press(n, z, s.elastic_stiffness_papm * k_scale, kb[n.slot], &flow);
    // Wheel surface normal at the hit point (towards the axis) and the point's velocity.
    const Vec3 w = h.p - c;
    Vec3 nw = -(w - w.dot(a) * a);
    nw /= nw.norm();
    const Vec3 v = wheel.velocity_W + wheel.angular_velocity_W.cross(w);
    // The horizontal cell under the node carries the wheel surface of area cell / cos.
    const double area = cell * h.cover / std::max(kMinCos, nw.z());
    // Viscous damping resists the soil's compression, i.e. motion along the terrain normal
    // (Chrono: sigma += -R Vn with Vn along the undeformed normal, reference §2.3), on the cell
    // the node stands for. Along the wheel's radial normal it would act on the front arc as a
    // drag proportional to the travel speed (~1 kN per HMMWV wheel in snow at 4 m/s) that a
    // rolling wheel does not feel from the soil's compression rate. Never pulls the wheel down:
    // at most cancels the elastic-plastic pressure (as the clamp of the total stress at 0 did).
    const double vn_terrain = v.dot(under.normal_W);
    const double sigma_damp = std::max(-sigma, -s.damping_paspm * c_scale * vn_terrain);
    // Shear: the shear displacement restarts when a node enters contact afresh.
    const double j_len = AdvanceShear(n.contact_step < prev_step, v, nw, dt,
                                      m.shear_cap_m[static_cast<size_t>(n.slot)], &n.shear_m);
    const Vec3 f =
        m.NodeForce(n, sigma, sigma_damp, area, cell, h.cover, nw, under.normal_W, j_len);
    force += f;
    torque += w.cross(f);
    n.contact_step = m.step;
    const double node_sinkage = ca * (n.base_m - h.p.z());
    if (!centre_on_soil && (k == 0 || node_sinkage > sinkage)) {
      out.surface = m.terrain.SurfaceAt(h.p.x(), h.p.y());  // the soil's class, not the centre's
    }
    sinkage = std::max(sinkage, node_sinkage);
    contacts[k] = {h.i, h.j, flow, h.node};
  }
  m.patches.push_back({begin, m.contacts.size(), c, a, r, half_w});
  m.stats.contact_nodes += static_cast<long>(n_hits);

  out.force_W = force;
  out.torque_W = torque;
  out.normal_force_n = std::max(0.0, force.dot(under.normal_W));
  out.sinkage_m = sinkage;
  return out;
}

// Spreads `volume` (a height summed over cells) evenly over the rim nodes rim[begin, end), but no
// rim node is raised into the wheel above it (as Chrono caps the raise at the node's hit level):
// water-filling, nodes under the tread take at most up to the tread, the rest share the
// remainder. Only if every rim node is under the tread and full is the cap ignored (volume is
// conserved first).
void ScmSoil::Impl::DepositOnRim(const Patch& patch, size_t begin, size_t end, double volume) {
  const size_t n = end - begin;
  if (n == 0) {
    stats.lost_volume_m3 += volume * dx * dx;
    return;
  }
  room.assign(n, 1e300);
  // The rim nodes under the tread (room < 1e300), in rim order: the only ones the water-filling
  // can cap while a share is <= 1e300 (always: a share is a part of the displaced volume).
  if (under_tread.size() < n) under_tread.resize(n);
  size_t n_under = 0;
  // A wheel's tread (|lat| <= half width) lies within lat_reach of the centre's vertical plane
  // across the axle (as in WheelContact's rows): a rim node further out is not under it.
  const Vec3& ca = patch.center;
  const Vec3& ax = patch.axis;
  const double lat_reach =
      patch.half_width +
      std::abs(ax.z()) * std::sqrt(patch.radius * patch.radius + patch.half_width * patch.half_width) +
      1e-6;
  BeltBottom belt;
  if (patch.belt) belt.Init(patch.center, patch.belt_end, patch.axis, patch.half_width);
  for (size_t k = 0; k < n; ++k) {
    const Work& w = active_buf[begin + k];
    if (!patch.belt &&
        std::abs((w.i * dx - ca.x()) * ax.x() + (w.j * dx - ca.y()) * ax.y()) > lat_reach) {
      continue;
    }
    double z = 0.0, lat = 0.0, t = 0.0;
    const bool under = patch.belt ? belt.At(w.i * dx, w.j * dx, &z, &t, &lat) && t >= 0.0 &&
                                        t <= 1.0
                                  : WheelBottomAt(patch.center, patch.axis, patch.radius,
                                                  patch.half_width, w.i * dx, w.j * dx, &z, &lat);
    if (under) {
      room[k] = std::max(0.0, z - Level(*w.node));
      under_tread[n_under++] = k;
    }
  }
  double remaining = volume;
  size_t open = n;
  std::vector<char>& full = full_scratch;
  full.assign(n, 0);
  while (open > 0 && remaining > 0.0) {
    const double share = remaining / static_cast<double>(open);
    bool capped = false;
    // Every rim node with room < share, in rim order, takes its room: with share <= 1e300 the
    // others (room 1e300) never do, so only the nodes under the tread are looked at.
    auto cap = [&](size_t k) {
      if (full[k] || room[k] >= share) return;
      Raise(active_buf[begin + k].node, room[k]);
      remaining -= room[k];
      full[k] = 1;
      --open;
      capped = true;
    };
    if (share <= 1e300) {
      for (size_t u = 0; u < n_under; ++u) cap(under_tread[u]);
    } else {
      for (size_t k = 0; k < n; ++k) cap(k);
    }
    if (capped) continue;
    for (size_t k = 0; k < n; ++k) {
      if (full[k]) continue;
      Raise(active_buf[begin + k].node, share);
    }
    remaining = 0.0;
  }
  if (remaining > 0.0) {  // all rim nodes under the tread and full: raise them anyway
    const double share = remaining / static_cast<double>(n);
    for (size_t k = 0; k < n; ++k) Raise(active_buf[begin + k].node, share);
  }
}

TrackSoilOutput ScmSoil::TrackContact(const TrackSoilInput& tr, double dt) {
  // The belt's node stride as a compile-time constant: the default (every node) scans exactly as
  // before the coarse grid existed, with no per-node cost of it.
  return config_.belt_node_stride == 2 ? impl_->Track<2>(config_, tr, dt)
                                       : impl_->Track<1>(config_, tr, dt);
}

template <int kStride>
TrackSoilOutput ScmSoil::Impl::Track(const SoilConfig& config, const TrackSoilInput& tr,
                                     double dt) {
  Impl& m = *this;
  TrackSoilOutput out;
  for (Vec3& f : out.point_force_W) f.setZero();
  const int n = std::clamp(tr.n_points, 0, kMaxTrackPoints);
  const double half_w = 0.5 * tr.width_m;
  const Vec3 lat = tr.lateral_W.normalized();
  double total_len = 0.0;
  for (int k = 0; k + 1 < n; ++k) total_len += (tr.points_W[k + 1] - tr.points_W[k]).norm();
  if (!(total_len > 0.0)) return out;
  const double mass = tr.mass_kg > 0.0 ? tr.mass_kg : config.default_wheel_mass_kg;
  // The belt's grid: every stride-th node each way, counted from the world's first node (so that
  // a block of stride x stride nodes never straddles a tile: kTileSize is even), is pressed and
  // stands for the block's cell, cell_w wide.
  constexpr int stride = kStride;
  const double cell_w = stride * m.dx;
  const double cell = cell_w * cell_w;
  auto align_up = [](int v, int base) {   // the first pressed index >= v
    if (stride == 1) return v;
    const int r = (v - base) % stride;
    return r == 0 ? v : v + (r > 0 ? stride - r : -r);
  };
  for (int k = 0; k + 1 < n; ++k) {
    const Vec3& a = tr.points_W[k];
    const Vec3& b = tr.points_W[k + 1];
    const Vec3 mid = 0.5 * (a + b);
    const terrain::SurfacePoint under = m.terrain.Query(mid.x(), mid.y());
    out.segment_surface[k] = under.surface;
    if (!terrain::IsDeformable(under.surface)) continue;
    out.segment_on_soil[k] = true;
    ++m.stats.wheel_queries;
    const double seg_len = (b - a).norm();
    if (seg_len < 1e-9) continue;
    const Vec3 s_dir = (b - a) / seg_len;
    Vec3 nw = lat.cross(s_dir);  // belt surface normal, towards the vehicle
    if (nw.z() < 0.0) nw = -nw;
    const double nz = std::max(0.05, under.normal_W.z());
    const double reach = 0.5 * seg_len + half_w;
    const double soil_top = under.height_m + reach * std::sqrt(1.0 - nz * nz) / nz +
                            m.max_raise_m + 0.5 * m.dx;
    if (std::min(a.z(), b.z()) - half_w * std::abs(lat.z()) >= soil_top) continue;
    const double ext = half_w + cell_w;
    const int i_lo = static_cast<int>(std::ceil((std::min(a.x(), b.x()) - ext) / m.dx));
    const int i_hi = static_cast<int>(std::floor((std::max(a.x(), b.x()) + ext) / m.dx));
    const int j_lo = static_cast<int>(std::ceil((std::min(a.y(), b.y()) - ext) / m.dx));
    const int j_hi = static_cast<int>(std::floor((std::max(a.y(), b.y()) + ext) / m.dx));
    // The last segment owns its end point; every other segment stops just before it, so a node
    // belongs to one segment only.
    const double t_end = k + 2 == n ? 1.0 : 1.0 - 1e-12;
    // Scan only the segment's footprint: per grid row, the x interval where the node is within
    // the belt's half width (+ dx/2) across and within the part of the segment that can reach
    // below the soil top (the sprocket and idler segments rise out of the soil).
    const double sx = b.x() - a.x(), sy = b.y() - a.y();
    const double len2 = sx * sx + sy * sy;
    if (len2 < 1e-12) continue;
    const double inv_len = 1.0 / std::sqrt(len2);
    double lx = -sy * inv_len, ly = sx * inv_len;
    if (lx * lat.x() + ly * lat.y() < 0.0) {
      lx = -lx;
      ly = -ly;
    }
    const double lat_h = std::sqrt(std::max(1e-6, 1.0 - lat.z() * lat.z()));
    const double top = soil_top + ext * std::abs(lat.z()) / lat_h;
    double t_lo = 0.0, t_hi = t_end;
    const double dz = b.z() - a.z();
    if (dz > 1e-12) t_hi = std::min(t_hi, (top - a.z()) / dz);
    if (dz < -1e-12) t_lo = std::max(t_lo, (top - a.z()) / dz);
    if (t_lo > t_hi) continue;
    const double hw_scan = half_w + 0.5 * cell_w;
    // x - a.x within [lo, hi] where c0 + c1 (x - a.x) lies in [v_lo, v_hi]
    auto clip = [](double c0, double c1, double v_lo, double v_hi, double* lo, double* hi) {
      if (std::abs(c1) < 1e-12) {
        if (c0 < v_lo || c0 > v_hi) *lo = 1.0, *hi = -1.0;
        return;
      }
      double x0 = (v_lo - c0) / c1, x1 = (v_hi - c0) / c1;
      if (x0 > x1) std::swap(x0, x1);
      *lo = std::max(*lo, x0);
      *hi = std::min(*hi, x1);
    };
    // The covered-node test along a row (belt_row.h); locals: no reloads after push_back.
    BeltRow row;
    row.dx = m.dx;
    row.cell_w = cell_w;
    row.ax = a.x();
    row.sx = sx;
    row.len2 = len2;
    row.lx = lx;
    row.half_w = half_w;
    row.hw_scan = hw_scan;
    row.t_end = t_end;
    const double tilt = lat.z() / lat_h;
    // The whole segment at once, exact as the chunk reject below: the belt's lowest point over
    // the band it scans (t in [0, 1], |l| <= hw_scan) is above every soil top of the tile rows
    // in its box, and every tile there exists (the scan would allocate none).
    if (m.AboveSoilTops(i_lo, i_hi, j_lo, j_hi,
                        std::min(a.z(), b.z()) - hw_scan * std::abs(tilt) - kScanMargin_m)) {
      continue;
    }
    const double dx = m.dx, ax = a.x(), az = a.z();
    const int i_min = m.i_min;
    // The quick rejects below bound the belt's height along a row by its linear form
    // z_row + (x - ax) z_slope (z_row: the height at x = ax), which differs from the per-node
    // height (t, l, then az + t dz + l tilt) by rounding only (~1e-13 m): kScanMargin_m covers
    // it, so no node they skip could be a contact.
    const double z_slope = sx / len2 * dz + lx * tilt;
    const double zy_slope = sy / len2 * dz + ly * tilt;   // the belt height's slope along y
    // A block's other nodes q (kMi, kMj) relative to the pressed one: across the belt
    // (ml = l + ml_i[q] + ml_j[q]) and in the belt's height (mz = z + mz_i[q] + mz_j[q]), the
    // terms of those sums once per segment.
    double ml_i[3], ml_j[3], mz_i[3], mz_j[3];
    for (int q = 0; q < 3; ++q) {
      ml_i[q] = kMi[q] * lx * dx;
      ml_j[q] = kMj[q] * ly * dx;
      mz_i[q] = kMi[q] * dx * z_slope;
      mz_j[q] = kMj[q] * dx * zy_slope;
    }
    m.hits.clear();
    m.hit_rep_in.clear();
    for (int j = align_up(j_lo, m.j_min); j <= j_hi; j += stride) {
      const double uy = j * m.dx - a.y();
      double lo = -1e300, hi = 1e300;
      clip(uy * sy / len2, sx / len2, t_lo, t_hi, &lo, &hi);
      clip(uy * ly, lx, -hw_scan, hw_scan, &lo, &hi);
      if (lo > hi) continue;
      const int i0 =
          align_up(std::max(i_lo, CeilToInt((a.x() + lo) / m.dx - 1e-9)), i_min);
      const int i1 = std::min(i_hi, FloorToInt((a.x() + hi) / m.dx + 1e-9));
      if (i0 > i1) continue;
      // BeltBottom::At inlined along the row (t, l and the height are linear in x)
      row.t_row = uy * sy / len2;
      row.l_row = uy * ly;
      const double z_row = az + row.t_row * dz + row.l_row * tilt;
      const Impl::GridRow grid_row = m.Row(j);
      // The row tile by tile: one look-up per tile (the first node in it that the belt covers),
      // the others by pointer offset.
      int i = i0;
      while (i <= i1) {
        const int chunk_end =
            std::min(i1, i_min + (((i - i_min) >> kTileBits) + 1) * kTileSize - 1);
        // The first node in this tile that the belt covers: the one tile look-up (which
        // allocates the tile), the other nodes by pointer offset.
        Node* base = nullptr;
        Tile* tile = nullptr;
        for (; i <= chunk_end; i += stride) {
          double t = 0.0, l = 0.0, cover = 0.0;
          if (!row.Covers(i, &t, &l, &cover)) continue;
          base = m.AtInRow(grid_row, i, true, &tile);
          break;
        }
        if (i > chunk_end) continue;   // the belt covers no node of this chunk
        const int base_i = i;
        if (base == nullptr) {         // outside the world
          i = chunk_end + 1;
          continue;
        }
        // Quick rejects, exact: the belt height is linear along the row, so its lowest node
        // over the chunk is an end; above the tile row's soil top the whole chunk is skipped,
        // and a node with the belt above its undisturbed level (never below its level) without
        // the full test.
        const double z0 = z_row + (base_i * dx - ax) * z_slope;
        const double z1 = z_row + (chunk_end * dx - ax) * z_slope;
        if constexpr (stride == 1) {
          if (std::min(z0, z1) - kScanMargin_m >= tile->row_top_m[grid_row.lj & kTileMask]) {
            i = chunk_end + 1;
            continue;
          }
        } else {
          // the block's other nodes (+i, +j: the next row of the same tile) may carry deposits
          const double z_lo = std::min(std::min(z0, z1 + dx * z_slope),
                                       std::min(z0, z1 + dx * z_slope) + dx * zy_slope);
          const int lj = grid_row.lj & kTileMask;
          if (z_lo - kScanMargin_m >= std::max(tile->row_top_m[lj], tile->row_top_m[lj + 1])) {
            i = chunk_end + 1;
            continue;
          }
        }
        const double z_step = stride * dx * z_slope;
        double z_quick = z0 - kScanMargin_m;   // at node i
        for (; i <= chunk_end; i += stride, z_quick += z_step) {
          Node* node = base + (i - base_i);  // beyond i_max: a rigid node (slot -1), skipped
          if constexpr (stride == 1) {
            if (node->slot < 0) continue;
            if (node->plastic_m >= 0.0 && z_quick >= node->level0_m) continue;
          } else {
            if (node->slot < 0) continue;
            // the whole block at once: the belt above every node's undisturbed level
            const Node& n1 = node[1];
            const Node& n2 = node[kTileSize];
            const Node& n3 = node[kTileSize + 1];
            const double zb = z_quick + std::min(0.0, dx * z_slope) + std::min(0.0, dx * zy_slope);
            const double top = std::max(std::max(node->level0_m, n1.level0_m),
                                        std::max(n2.level0_m, n3.level0_m));
            const bool plastic_ok = (node->plastic_m >= 0.0) & (n1.plastic_m >= 0.0) &
                                    (n2.plastic_m >= 0.0) & (n3.plastic_m >= 0.0);
            if (plastic_ok && zb >= top) continue;
          }
          double t = 0.0, l = 0.0, cover = 0.0;
          if (!row.Covers(i, &t, &l, &cover)) continue;
          const double hit_z = az + t * dz + l * tilt;
          if constexpr (stride == 1) {
            if (AboveLevel(*node, hit_z)) continue;
          } else {
            // the pressed node above its soil: the block still bears where one of its other
            // nodes under the belt (a deposit) reaches the belt
            const bool rep_in = !AboveLevel(*node, hit_z);
            if (!rep_in) {
              bool any = false;
              for (int q = 0; q < 3 && !any; ++q) {
                const Node& mt = node[kMateOffset[q]];
                const double ml = l + ml_i[q] + ml_j[q];
                if (mt.slot < 0 || !(std::abs(ml) < half_w + 0.5 * dx)) continue;
                const double mz = hit_z + mz_i[q] + mz_j[q];
                any = !AboveLevel(mt, mz);
              }
              if (!any) continue;
            }
            m.hit_rep_in.push_back(rep_in ? 1 : 0);
          }
          m.hits.push_back({node, i, j, Vec3(i * dx, j * dx, hit_z), l, t, cover});
        }
      }
    }
    if (m.hits.empty()) continue;
    double lat_lo = 1e300, lat_hi = -1e300;
    for (const Impl::Hit& h : m.hits) {
      lat_lo = std::min(lat_lo, h.lat);
      lat_hi = std::max(lat_hi, h.lat);
    }
    const double bb = std::max(cell_w, std::min(lat_hi - lat_lo + cell_w, 2.0 * half_w));
    const double seg_mass = mass * seg_len / total_len;
    double k_total = 0.0, c_total = 0.0;
    for (const Impl::Hit& h : m.hits) {
      const SoilParams& sp = m.soils[static_cast<size_t>(h.node->slot)];
      k_total += sp.elastic_stiffness_papm * cell * h.cover;
      c_total += sp.damping_paspm * cell * h.cover;
    }
    const double k_scale = std::min(1.0, kStiffnessLimit * seg_mass / (k_total * dt * dt));
    const double c_scale = 1.0 / (1.0 + c_total * dt / seg_mass);
    double kb[3];   // each soil's Bekker modulus kc / b + kphi
    for (size_t q = 0; q < 3; ++q) kb[q] = m.soils[q].bekker_kc / bb + m.soils[q].bekker_kphi;
    const size_t begin = m.contacts.size();
    if constexpr (stride == 1) {
      for (const Impl::Hit& h : m.hits) {
        Node& nd = *h.node;
        const SoilParams& sp = m.soils[static_cast<size_t>(nd.slot)];
        const double ca = nd.cos_slope;
        const double z = ca * (nd.level0_m - h.p.z());
        double flow = 0.0;
        const double sigma =
            m.Press(nd, z, sp.elastic_stiffness_papm * k_scale, kb[nd.slot], &flow);
        const double t = h.lon;
        const Vec3 v = (1.0 - t) * tr.velocities_W[k] + t * tr.velocities_W[k + 1];
        const double area = cell * h.cover / std::max(kMinCos, nw.z());
        const double vn_terrain = v.dot(under.normal_W);
        const double sigma_damp = std::max(-sigma, -sp.damping_paspm * c_scale * vn_terrain);
        const double j_len = AdvanceShear(nd.contact_step < m.step - 1, v, nw, dt,
                                          m.shear_cap_m[static_cast<size_t>(nd.slot)], &nd.shear_m);
        const Vec3 f =
            m.NodeForce(nd, sigma, sigma_damp, area, cell, h.cover, nw, under.normal_W, j_len);
        out.point_force_W[k] += (1.0 - t) * f;
        out.point_force_W[k + 1] += t * f;
        nd.contact_step = m.step;
        const double sink = ca * (nd.base_m - h.p.z());
        out.point_sinkage_m[k] = std::max(out.point_sinkage_m[k], sink);
        out.point_sinkage_m[k + 1] = std::max(out.point_sinkage_m[k + 1], sink);
        m.contacts.push_back({h.i, h.j, flow, h.node});
      }
    } else {
      for (size_t hk = 0; hk < m.hits.size(); ++hk) {
        const Impl::Hit& h = m.hits[hk];
        Node& nd = *h.node;
        const bool rep_in = m.hit_rep_in[hk] != 0;
        const auto slot = static_cast<size_t>(nd.slot);
        const SoilParams& sp = m.soils[slot];
        const double ca = nd.cos_slope;
        // the block's shear history restarts when none of its nodes was in contact last step
        const int32_t last =
            std::max(std::max(nd.contact_step, (&nd)[1].contact_step),
                     std::max((&nd)[kTileSize].contact_step, (&nd)[kTileSize + 1].contact_step));
        double sigma = 0.0, flow = 0.0;
        if (rep_in) {
          const double z = ca * (nd.level0_m - h.p.z());
          sigma = m.Press(nd, z, sp.elastic_stiffness_papm * k_scale, kb[slot], &flow);
        }
        const double t = h.lon;
        const Vec3 v = (1.0 - t) * tr.velocities_W[k] + t * tr.velocities_W[k + 1];
        const double area = cell * h.cover / std::max(kMinCos, nw.z());
        const double vn_terrain = v.dot(under.normal_W);
        const double sigma_damp =
            rep_in ? std::max(-sigma, -sp.damping_paspm * c_scale * vn_terrain) : 0.0;
        const double tan_phi = m.tan_friction[slot];
        // Normal force (along nw) and shear strength of the block: the pressed node's stress on
        // the block's cell; a node of the block standing above the pressed node's level (soil
        // bulldozing or erosion put there, or fresh soil ahead of the rut) is pressed by its own
        // law and bears on its own cell instead of the pressed node's stress there.
        double sigma_area = sigma * area;
        double tau_area =
            rep_in ? (sp.cohesion_pa + (sigma + sigma_damp) * tan_phi) * area : 0.0;
        const double level_rep = Level(nd);
        for (int q = 0; q < 3; ++q) {
          Node& mt = (&nd)[kMateOffset[q]];
          const double ml = h.lat + ml_i[q] + ml_j[q];
          if (mt.slot < 0 || !(std::abs(ml) < half_w + 0.5 * dx)) continue;
          const double target = level_rep + (mt.base_m - nd.base_m);
          const double mz = h.p.z() + mz_i[q] + mz_j[q];
          if (rep_in && !(Level(mt) > target)) {   // at or below the pressed node: follows it
            mt.contact_step = m.step;
            m.contacts.push_back({h.i + kMi[q], h.j + kMj[q], 0.0, &mt});
            continue;
          }
          if (AboveLevel(mt, mz)) continue;   // the belt does not reach it
          const auto mslot = static_cast<size_t>(mt.slot);
          const SoilParams& msp = m.soils[mslot];
          const double mca = mt.cos_slope;
          const double mzs = mca * (mt.level0_m - mz);
          double mflow = 0.0;
          const double msigma =
              m.Press(mt, mzs, msp.elastic_stiffness_papm * k_scale, kb[mslot], &mflow);
          const double mcover = std::min(1.0, (half_w - std::abs(ml)) / dx + 0.5);
          const double marea = dx * dx * mcover / std::max(kMinCos, nw.z());
          sigma_area += (msigma - sigma) * marea;
          tau_area += ((rep_in ? 0.0 : msp.cohesion_pa) +
                       (msigma - sigma) * m.tan_friction[mslot]) * marea;
          mt.contact_step = m.step;
          const double msink = mca * (mt.base_m - mz);
          out.point_sinkage_m[k] = std::max(out.point_sinkage_m[k], msink);
          out.point_sinkage_m[k + 1] = std::max(out.point_sinkage_m[k + 1], msink);
          m.contacts.push_back({h.i + kMi[q], h.j + kMj[q], mflow, &mt});
        }
        const double j_len =
            AdvanceShear(last < m.step - 1, v, nw, dt, m.shear_cap_m[slot], &nd.shear_m);
        Vec3 f = sigma_area * nw + sigma_damp * cell * h.cover * under.normal_W;
        if (j_len > 0.0 && tau_area > 0.0) {
          f -= (tau_area * m.Mobilised(slot, j_len) / j_len) * nd.shear_m;
        }
        out.point_force_W[k] += (1.0 - t) * f;
        out.point_force_W[k + 1] += t * f;
        if (rep_in) {
          nd.contact_step = m.step;
          const double sink = ca * (nd.base_m - h.p.z());
          out.point_sinkage_m[k] = std::max(out.point_sinkage_m[k], sink);
          out.point_sinkage_m[k + 1] = std::max(out.point_sinkage_m[k + 1], sink);
          m.contacts.push_back({h.i, h.j, flow, h.node});
        }
      }
    }
    Impl::Patch patch{begin, m.contacts.size(), a, lat, 0.0, half_w};
    patch.belt = true;
    patch.belt_end = b;
    m.patches.push_back(patch);
    m.stats.contact_nodes += static_cast<long>(m.hits.size());
  }
  return out;
}

void ScmSoil::EndStep(double /*dt*/) {
  Impl& m = *impl_;
  const BulldozingParams& bp = config_.bulldozing;
  if (bp.enabled) {
    // at most four rim nodes per contact: the rim written by index, no call on the way, into
    // the erosion's first work list (active_buf), each node stamped with the first pass's stamp
    if (m.active_buf.size() < 4 * m.contacts.size()) m.active_buf.resize(4 * m.contacts.size());
    Impl::Work* const rim = m.active_buf.data();
    const int32_t rim_stamp = m.queue_stamp + 1;
    size_t n_rim = 0;
    const int32_t step = m.step;   // a local: the node writes below cannot change it
    for (const Impl::Patch& patch : m.patches) {
      // Rim: untouched deformable 4-neighbours of this patch's contact nodes, in contact order.
      double volume = 0.0;  // displaced height summed over nodes (all cells have equal area)
      const size_t rim_begin = n_rim;
      const Impl::Contact* const contacts = m.contacts.data();
      for (size_t k = patch.begin; k < patch.end; ++k) {
        const Impl::Contact& ct = contacts[k];
        volume += ct.flow_m;
        Node* const n = ct.node;
        const int ci = ct.i, cj = ct.j;
        // if a neighbour does not exist (outside the world or its tile not allocated), RimOf,
        // which allocates the missing tiles in Neighbours' order (not inline: the loop has no
        // call on the way)
        Node* nb[4];
        if (!m.FourNeighbours(n, nb)) {
          n_rim = m.RimOf(ct, step, rim_stamp, rim, n_rim);
          continue;
        }
        auto add = [&](int e, Node* nb) {
          if (nb->slot < 0 || nb->contact_step == step || nb->queue_stamp == rim_stamp) return;
          nb->queue_stamp = rim_stamp;
          rim[n_rim++] = {ci + kDi[e], cj + kDj[e], 0, nb};
        };
        add(0, nb[0]);
        add(1, nb[1]);
        add(2, nb[2]);
        add(3, nb[3]);
      }
      if (volume > 0.0) m.DepositOnRim(patch, rim_begin, n_rim, bp.flow_factor * volume);
    }
    m.n_rim = n_rim;
    m.Erode(bp);
  }
  m.contacts.clear();
  m.patches.clear();
  ++m.step;
  ++m.stats.steps;
}

// Slopes steeper than the erosion angle between a node and a 4-neighbour flow downhill: half the
// excess height over 4 neighbours per pass, exactly conserving (what leaves one node arrives at
// the other). Nodes under a wheel neither give nor take. Chrono scans the rim dilated
// `erosion_propagations` times on every pass; here a work list starts at the rim (and at the
// nodes still moving at the end of the last step) and follows the flow: every node that gave or
// took soil is checked again in the next pass, up to `erosion_propagations` rings from where
// it started. Same domain bound and settings, but only nodes that can change are visited.
void ScmSoil::Impl::Erode(const BulldozingParams& bp) {
  ErodePass s;
  s.threshold = dx * std::tan(bp.erosion_angle_rad);
  // Locals for what the node writes below cannot change (the compiler cannot know that).
  s.cur_step = step;
  s.propagations = bp.erosion_propagations;
  // The first pass's list: the rim, then the nodes carried over (their node pointers hold between
  // steps: tiles never move, and Restore looks them up again), each once.
  // The rim is active_buf[0, n_rim) already, its nodes stamped queue_stamp + 1 by EndStep.
  ++queue_stamp;
  if (active_buf.size() < n_rim + pending.size()) active_buf.resize(n_rim + pending.size());
  size_t n_active = n_rim;
  auto first = [this, &n_active](const Work& w) {
    if (w.node->queue_stamp == queue_stamp) return;
    w.node->queue_stamp = queue_stamp;
    active_buf[n_active++] = w;
  };
  for (const Work& w : pending) first(w);
  pending.clear();
  // A local for the maximum raise: the node writes below (doubles and int32 stamps) could change
  // the member as far as the compiler knows, which would reload and store it at every raise.
  s.max_raise = max_raise_m;   // written back after the passes (max is exact in any order)
  for (int pass = 0; pass < bp.erosion_iterations && n_active > 0; ++pass) {
    const int32_t stamp = s.stamp = ++queue_stamp;
    // a visit adds at most its node and its four neighbours, each once per pass
    if (next_buf.size() < 5 * n_active) next_buf.resize(5 * n_active);
    Work* const out = next_buf.data();
    size_t n_out = 0;
    stats.eroded_node_visits += static_cast<long>(n_active);
    // The visits with all four neighbours existing (nearly all) here, with no call on the way
    // (so that the doubles stay in registers); the others through ErodeVisit, which can read
    // the terrain and allocate a tile. Both make the same moves in the same order.
    const double threshold = s.threshold;
    const int32_t cur_step = s.cur_step;
    const int propagations = s.propagations;
    double max_raise = s.max_raise;
    const Work* const work = active_buf.data();
    for (size_t k = 0; k < n_active; ++k) {
      const Work& w = work[k];
      Node* const n = w.node;
      if (n->slot < 0 || n->contact_step == cur_step) continue;
      // w's grid position and ring read where they are used (the work lists' entries are
      // only needed to queue a node, which few edges do)
      Node* nb[4];
      if (!FourNeighbours(n, nb)) {
        s.max_raise = max_raise;
        s.out = out;
        s.n_out = n_out;
        ErodeVisit(w, s);
        max_raise = s.max_raise;
        n_out = s.n_out;
        continue;
      }
      // n's level0 and sinkage in registers: n's own writes below are these, and no neighbour
      // is n. level_n = Level(*n) throughout.
      double level0_n = n->level0_m;
      const double sink_n = n->sink_m;
      double level_n = level0_n - sink_n;
      bool n_queued = n->queue_stamp == stamp;
      // One move between n and neighbour nb (direction e): the arithmetic and order of
      // ErodeVisit's.
      auto edge = [&](int e, Node* nb) {
        const double dy = level_n - (nb->level0_m - nb->sink_m);
        if (std::abs(dy) <= threshold) return;
        if (nb->slot < 0 || nb->contact_step == cur_step) return;
        const double q = 0.5 * (std::abs(dy) - threshold) / 4.0;
        Node* up;
        if (dy > 0.0) {
          level0_n += -q;
          n->level0_m = level0_n;
          nb->level0_m += q;
          up = nb;
        } else {
          level0_n += q;
          n->level0_m = level0_n;
          nb->level0_m += -q;
          up = n;
        }
        const double up_level0 = up->level0_m;
        max_raise = std::max(max_raise, up_level0 - up->base_m);
        double& top = TileOf(up)->row_top_m[up->local >> kTileBits];
        top = std::max(top, up_level0);
        level_n = level0_n - sink_n;
        if (q > kErosionSettled_m) {
          if (!n_queued) {
            n_queued = true;
            n->queue_stamp = stamp;
            out[n_out++] = {w.i, w.j, w.ring, n};
          }
          if (w.ring < propagations && nb->queue_stamp != stamp) {
            nb->queue_stamp = stamp;
            out[n_out++] = {w.i + kDi[e], w.j + kDj[e], w.ring + 1, nb};
          }
        }
      };
      edge(0, nb[0]);
      edge(1, nb[1]);
      edge(2, nb[2]);
      edge(3, nb[3]);
    }
    s.max_raise = max_raise;
    active_buf.swap(next_buf);
    n_active = n_out;
  }
  max_raise_m = s.max_raise;
  pending.assign(active_buf.data(), active_buf.data() + n_active);  // still moving: next step
}

// One erosion visit of node w (any neighbours: outside the world, in a tile not allocated): the
// general form of Erode's fast path, same moves in the same order. A neighbour that does not
// exist has the terrain's level; if soil flows to or from it, its tile is allocated.
__attribute__((noinline)) void ScmSoil::Impl::ErodeVisit(const Work& w, ErodePass& s) {
  Node* n = w.node;
  const int32_t stamp = s.stamp;
  auto enqueue = [&s, stamp](Node* nd, int i, int j, int ring) {
    if (nd->queue_stamp == stamp) return;
    nd->queue_stamp = stamp;
    s.out[s.n_out++] = {i, j, ring, nd};
  };
  auto raise_up = [this, &s](Node* nd, double dh) {
    nd->level0_m += dh;
    s.max_raise = std::max(s.max_raise, nd->level0_m - nd->base_m);
    double& top = TileOf(nd)->row_top_m[nd->local >> kTileBits];
    top = std::max(top, nd->level0_m);
  };
  double level_n = Level(*n);
  // one look-up for the neighbour's level and, if it moves, the node itself (its tile is
  // allocated only then: most neighbours are within the threshold). The four neighbours lie
  // in four different tiles when outside n's, so allocating one leaves the others' nullptr
  // true.
  const int wi = w.i, wj = w.j;
  Node* nbs[4];
  Neighbours(n, wi, wj, false, nbs);
  for (int e = 0; e < 4; ++e) {
    Node* nb = nbs[e];
    const double level_nb = nb != nullptr
                                ? Level(*nb)
                                : terrain.Height((wi + kDi[e]) * dx, (wj + kDj[e]) * dx);
    const double dy = level_n - level_nb;
    if (std::abs(dy) <= s.threshold) continue;
    const int ni = wi + kDi[e], nj = wj + kDj[e];
    if (nb == nullptr) nb = At(ni, nj, true);
    if (nb == nullptr || nb->slot < 0 || nb->contact_step == s.cur_step) continue;
    const double q = 0.5 * (std::abs(dy) - s.threshold) / 4.0;
    // from the higher node to the lower one: Raise(n, -moved), Raise(nb, moved)
    if (dy > 0.0) {
      n->level0_m += -q;
      raise_up(nb, q);
    } else {
      raise_up(n, q);
      nb->level0_m += -q;
    }
    level_n = Level(*n);
    if (q > kErosionSettled_m) {
      enqueue(n, wi, wj, w.ring);
      if (w.ring < s.propagations) enqueue(nb, ni, nj, w.ring + 1);
    }
  }
}

double ScmSoil::SurfaceHeight(double x_m, double y_m) const {
  const int i = static_cast<int>(std::lround(x_m / impl_->dx));
  const int j = static_cast<int>(std::lround(y_m / impl_->dx));
  return impl_->LevelAt(i, j);
}

double ScmSoil::VolumeChange_m3() const {
  double sum = 0.0;
  for (const auto& tile : impl_->tiles) {
    for (const Node& n : tile->nodes) {
      if (n.slot >= 0) sum += Level(n) - n.base_m;
    }
  }
  return sum * impl_->dx * impl_->dx;
}

double ScmSoil::CompactedVolume_m3() const {
  double sum = 0.0;
  for (const auto& tile : impl_->tiles) {
    for (const Node& n : tile->nodes) {
      if (n.slot >= 0) sum += n.sink_m;
    }
  }
  return sum * impl_->dx * impl_->dx;
}

const ScmStats& ScmSoil::stats() const {
  impl_->stats.memory_bytes = impl_->tiles.size() * sizeof(Tile) +
                              impl_->tile_index.size() * sizeof(int32_t);
  return impl_->stats;
}

bool ScmSoil::NeighbourLinksMatchLookUps() const {
  const Impl& m = *impl_;
  for (int ty = 0; ty < m.tiles_y; ++ty) {
    for (int tx = 0; tx < m.tiles_x; ++tx) {
      const int32_t idx = m.tile_index[static_cast<size_t>(ty) * m.tiles_x + tx];
      if (idx < 0) continue;
      Tile& tile = *m.tiles[static_cast<size_t>(idx)];
      for (int b = 0; b < kTileSize; ++b) {
        for (int a = 0; a < kTileSize; ++a) {
          const int i = m.i_min + tx * kTileSize + a, j = m.j_min + ty * kTileSize + b;
          if (i > m.i_max || j > m.j_max) continue;
          Node* nb[4];
          const bool all = Impl::FourNeighbours(&tile.nodes[b * kTileSize + a], nb);
          bool all_looked_up = true;
          for (int e = 0; e < 4; ++e) {
            const Node* looked_up = m.Peek(i + kDi[e], j + kDj[e]);
            if (nb[e] != looked_up) return false;
            all_looked_up = all_looked_up && looked_up != nullptr;
          }
          if (all != all_looked_up) return false;
        }
      }
    }
  }
  return true;
}

// Snapshot: everything that carries from one step to the next. The per-step scratch (this step's
// contacts, patches, hits, the rim list) is empty between steps.
struct SoilSnapshot::Data {
  std::vector<Tile> tiles;        // allocation order
  std::vector<int32_t> tile_index;
  int32_t step = 0;
  ScmStats stats;
  double max_raise_m = 0.0;
  std::vector<ScmSoil::Impl::Work> pending;
  int32_t queue_stamp = 0;
};

SoilSnapshot::SoilSnapshot() = default;
SoilSnapshot::~SoilSnapshot() = default;
SoilSnapshot::SoilSnapshot(const SoilSnapshot& other)
    : data_(other.data_ ? std::make_unique<Data>(*other.data_) : nullptr) {}
SoilSnapshot& SoilSnapshot::operator=(const SoilSnapshot& other) {
  if (this != &other) data_ = other.data_ ? std::make_unique<Data>(*other.data_) : nullptr;
  return *this;
}

SoilSnapshot ScmSoil::Snapshot() const {
  const Impl& m = *impl_;
  SoilSnapshot snapshot;
  snapshot.data_ = std::make_unique<SoilSnapshot::Data>();
  SoilSnapshot::Data& d = *snapshot.data_;
  d.tiles.reserve(m.tiles.size());
  for (const auto& tile : m.tiles) d.tiles.push_back(*tile);
  d.tile_index = m.tile_index;
  d.step = m.step;
  d.stats = m.stats;
  d.max_raise_m = m.max_raise_m;
  d.pending = m.pending;
  d.queue_stamp = m.queue_stamp;
  return snapshot;
}

void ScmSoil::Restore(const SoilSnapshot& snapshot) {
  VB_DEMAND(snapshot.data_ != nullptr);
  const SoilSnapshot::Data& d = *snapshot.data_;
  Impl& m = *impl_;
  VB_DEMAND(d.tile_index.size() == m.tile_index.size());
  if (m.tiles.size() > d.tiles.size()) m.tiles.resize(d.tiles.size());
  for (size_t i = 0; i < d.tiles.size(); ++i) {
    if (i < m.tiles.size()) {
      *m.tiles[i] = d.tiles[i];
    } else {
      m.tiles.push_back(std::make_unique<Tile>(d.tiles[i]));
    }
  }
  m.tile_index = d.tile_index;
  // the tiles' neighbour pointers into this soil's tiles (the copies hold the snapshot's)
  for (int ty = 0; ty < m.tiles_y; ++ty) {
    for (int tx = 0; tx < m.tiles_x; ++tx) {
      const int32_t idx = m.tile_index[static_cast<size_t>(ty) * m.tiles_x + tx];
      if (idx >= 0) m.Link(m.tiles[static_cast<size_t>(idx)].get(), tx, ty);
    }
  }
  m.step = d.step;
  m.stats = d.stats;
  m.max_raise_m = d.max_raise_m;
  // the carried-over work's nodes in this soil's tiles (Erode uses the pointers)
  m.pending.clear();
  for (const ScmSoil::Impl::Work& w : d.pending) {
    Impl::Work r = w;
    r.node = m.At(w.i, w.j, false);
    if (r.node != nullptr) m.pending.push_back(r);
  }
  m.queue_stamp = d.queue_stamp;
  m.contacts.clear();
  m.patches.clear();
  m.hits.clear();
}

}  // namespace vb::soil
