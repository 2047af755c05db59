// The wall of fix dem/contact/wall read without Python, for the step compiled ahead of time: the words of a plane,
// a cylinder or a mesh as dem_contact.lammps.wall_kernel.parse reads them, packed as dem_contact.walls.table.pack
// packs them (the kinds' packed(): plane.PlaneWall, cylinder.CylinderWall; a mesh's triangles from a packed mesh
// file, dem_contact.lammps.mesh_file, as mesh.MeshWall.packed made them), with their checks and the same
// messages; the table's laws and arrays, its walls included, as aot_attach reads them.
#include "aot.h"
#include "fix_dem_contact_wall.h"
#include "pair_dem_contact.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {
const char *SYNTAX =
    "fix ID GROUP dem/contact/wall KIND ARGS [wall W] [velocity VX VY VZ] [angular_velocity WX WY WZ] "
    "[centre CX CY CZ] [slots N], KIND one of: plane PX PY PZ NX NY NZ; cylinder PX PY PZ AX AY AZ RC in|out "
    "[flat]; mesh FILE [scale S]";

typedef double V3[3];

// words[at, at + count) as numbers into out (as Python's float()); false where one is not
bool numbers(const std::vector<std::string> &words, size_t at, int count, double *out)
{
  if (at + count > words.size()) return false;
  for (int k = 0; k < count; k++) {
    const char *s = words[at + k].c_str();
    char *end = nullptr;
    out[k] = std::strtod(s, &end);
    if (end == s || *end != '\0') return false;
  }
  return true;
}

std::string got(const std::vector<std::string> &words, size_t at, int count)
{
  std::string text;
  for (size_t k = at; k < words.size() && k < at + count; k++) text += (text.empty() ? "" : " ") + words[k];
  return text.empty() ? "none" : text;
}

// x as Python's repr writes it (the fewest digits that read back as x; positional for exponents -4 ... 15)
std::string number_text(double x)
{
  if (!std::isfinite(x)) return std::isnan(x) ? "nan" : (x > 0 ? "inf" : "-inf");
  char b[64];
  int digits = 1;
  for (; digits < 17; digits++) {
    std::snprintf(b, sizeof(b), "%.*e", digits - 1, x);
    if (std::strtod(b, nullptr) == x) break;
  }
  std::snprintf(b, sizeof(b), "%.*e", digits - 1, x);
  const int exponent = x == 0.0 ? 0 : std::atoi(std::strchr(b, 'e') + 1);
  if (exponent < -4 || exponent >= 16) return b;
  std::snprintf(b, sizeof(b), "%.*f", std::max(digits - 1 - exponent, 1), x);
  return b;
}

double dot(const V3 a, const V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const V3 a) { return std::sqrt(dot(a, a)); }
void cross(const V3 a, const V3 b, V3 c)
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}
bool finite(const V3 a) { return std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]); }

#if !defined(__BYTE_ORDER__) || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "a packed mesh file holds little-endian numbers: this reader needs a little-endian machine"
#endif

// a whole number of at most 18 digits (as mesh_file's header), into out; false where text is not one
bool whole(const std::string &text, long long &out)
{
  if (text.empty() || text.size() > 18 || text.find_first_not_of("0123456789") != std::string::npos) return false;
  out = std::strtoll(text.c_str(), nullptr, 10);
  return true;
}

// The packed mesh file at path (mesh_file.py: its first line, the line of its version, interface, payload
// columns, triangles and keys, then the default centre and the payload rows as float64) into centre and payload
// (nt rows of the payload columns), checked as far as the wall kernels index with it: vertex ids, neighbours
// (-1 or a triangle), orientations (+-1), history keys (below the keys), the vertices now those at time 0.
// What is wrong with it (scaled: the fix gave a scale, which a packed mesh refuses), or ""
std::string read_mesh(const std::string &path, bool scaled, V3 centre, std::vector<double> &payload, int64_t &nt)
{
  const std::string again = ": write it again from its STL file with `dem-contact lammps-mesh`";
  FILE *f = std::fopen(path.c_str(), "rb");
  if (!f) return "the mesh file " + path + " cannot be read: " + std::strerror(errno);
  std::string data;
  char chunk[65536];
  for (size_t got; (got = std::fread(chunk, 1, sizeof(chunk), f)) > 0;) data.append(chunk, got);
  std::fclose(f);
  const std::string magic = dem_contact_aot_mesh_magic;
  if (data.compare(0, magic.size(), magic) != 0)
    return path + " is not a packed mesh file: the plugin compiled ahead of time reads a mesh from a packed mesh "
                  "file only; write one from the STL file (dem-contact lammps-mesh " + path + " --out FILE.mesh) and "
                  "name it";
  if (scaled)
    return "scale applies to an STL file: " + path + " is a packed mesh, whose coordinates were scaled when it was "
                                                     "written (dem-contact lammps-mesh --scale)";
  // the second line: version V abi A width W triangles NT keys K
  const size_t end = data.find('\n', magic.size());
  std::vector<std::string> head;
  if (end != std::string::npos) {
    const std::string line = data.substr(magic.size(), end - magic.size());
    for (size_t at = 0; at < line.size();) {
      const size_t stop = std::min(line.find(' ', at), line.size());
      head.push_back(line.substr(at, stop - at));    // (two spaces: an empty word, refused as mesh_file.read)
      at = stop + 1;
    }
  }
  long long abi = 0, width = 0, triangles = 0, keys = 0;
  if (head.size() != 10 || head[0] != "version" || head[2] != "abi" || head[4] != "width" ||
      head[6] != "triangles" || head[8] != "keys" || !whole(head[3], abi) || !whole(head[5], width) ||
      !whole(head[7], triangles) || !whole(head[9], keys))
    return "the packed mesh file " + path + " is corrupt (its second line)" + again;
  const int *L = dem_contact_aot_wall_layout;
  if (head[1] != dem_contact_aot_version || abi != dem_contact_aot_wall_abi || width != L[W_PAYLOAD_WIDTH])
    return "the packed mesh file " + path + " was written by dem_contact " + head[1] + " (wall interface " +
        std::to_string(abi) + "), this is " + dem_contact_aot_version + " (wall interface " +
        std::to_string(dem_contact_aot_wall_abi) + ")" + again;
  // (the size the header gives, compared without forming it: the triangle count is the file's to tell)
  const size_t body = data.size() - end - 1, row_bytes = sizeof(double) * (size_t) width;
  if (body < 3 * sizeof(double) || (body - 3 * sizeof(double)) % row_bytes != 0 ||
      (body - 3 * sizeof(double)) / row_bytes != (unsigned long long) triangles || triangles < 1)
    return "the packed mesh file " + path + " is corrupt (its size)" + again;
  nt = triangles;
  payload.resize((size_t) nt * width);
  std::memcpy(centre, data.data() + end + 1, sizeof(double) * 3);
  std::memcpy(payload.data(), data.data() + end + 1 + sizeof(double) * 3, sizeof(double) * payload.size());
  auto whole_in = [](double v, double lo, double hi) { return v >= lo && v < hi && v == std::floor(v); };
  bool ok = finite(centre);
  for (int64_t t = 0; ok && t < nt; t++) {
    const double *row = payload.data() + t * width;
    for (int c = 0; c < width; c++) ok = ok && std::isfinite(row[c]);
    for (int c = 0; c < 9; c++) ok = ok && row[L[W_MESH_V] + c] == row[L[W_MESH_V0] + c];
    for (int q = 0; q < 3; q++) {
      ok = ok && whole_in(row[L[W_MESH_IDS] + q], 0.0, 3.0 * (double) nt);
      ok = ok && (row[L[W_MESH_NB] + q] == -1.0 || whole_in(row[L[W_MESH_NB] + q], 0.0, (double) nt));
    }
    ok = ok && (row[L[W_MESH_ORIENT]] == 1.0 || row[L[W_MESH_ORIENT]] == -1.0);
    for (int q = 0; q < 2; q++) ok = ok && whole_in(row[L[W_MESH_KEYS] + q], 0.0, (double) keys);
  }
  if (!ok) return "the packed mesh file " + path + " is corrupt (its triangles)" + again;
  return "";
}
}    // namespace

std::string dem_contact_aot_wall_attach(const std::vector<std::string> &words, const std::string &path, int ntypes,
                                        DemContactWallAttach &k, DemContactAotWall &wall)
{
  if (k.abi != dem_contact_aot_wall_abi)
    return "the plugin was built for another version of dem_contact (wall interface " + std::to_string(k.abi) +
        ", its steps' is " + std::to_string(dem_contact_aot_wall_abi) +
        "): build it again with dem-contact lammps-plugin --ahead-of-time LAW";
  // the words (wall_kernel.parse)
  const std::string syntax = std::string(" (syntax: ") + SYNTAX + ")";
  if (words.empty() || (words[0] != "plane" && words[0] != "cylinder" && words[0] != "mesh"))
    return "unknown wall kind '" + (words.empty() ? std::string("(none)") : words[0]) + "'" + syntax;
  const std::string kind = words[0];
  size_t at = 1;
  V3 point = {0, 0, 0}, dir = {0, 0, 0};
  double rc = 0.0;
  bool inside = true, curved = true, scaled = false;
  double a[7] = {0, 0, 0, 0, 0, 0, 0};
  std::string mesh_path;
  if (kind == "mesh") {
    if (at >= words.size()) return "mesh needs an STL file" + syntax;
    mesh_path = words[at++];
    if (at < words.size() && words[at] == "scale") {
      if (!numbers(words, at + 1, 1, a)) return "scale needs 1 numbers, got " + got(words, at + 1, 1) + syntax;
      scaled = true;
      at += 2;
    }
  } else if (kind == "plane") {
    if (!numbers(words, at, 6, a)) return "plane needs 6 numbers, got " + got(words, at, 6) + syntax;
    at += 6;
  } else {
    if (!numbers(words, at, 7, a)) return "cylinder needs 7 numbers, got " + got(words, at, 7) + syntax;
    at += 7;
    const std::string side = at < words.size() ? words[at] : "";
    if (side != "in" && side != "out")
      return "cylinder needs its side after the radius, in or out, got " +
          (side.empty() ? std::string("None") : "'" + side + "'") + syntax;
    inside = side == "in";
    at++;
    if (at < words.size() && words[at] == "flat") {
      curved = false;
      at++;
    }
    rc = a[6];
  }
  if (kind != "mesh")
    for (int d = 0; d < 3; d++) {
      point[d] = a[d];
      dir[d] = a[3 + d];
    }
  V3 vel = {0, 0, 0}, omega = {0, 0, 0}, centre = {0, 0, 0};
  bool has_centre = false;
  int64_t slots = 0, mat = 0;
  while (at < words.size()) {
    const std::string key = words[at];
    if (key == "velocity" || key == "angular_velocity" || key == "centre") {
      double *out = key == "velocity" ? vel : key == "angular_velocity" ? omega : centre;
      if (!numbers(words, at + 1, 3, out)) return key + " needs 3 numbers, got " + got(words, at + 1, 3) + syntax;
      has_centre = has_centre || key == "centre";
      at += 4;
    } else if (key == "wall" || key == "slots") {
      const std::string text = at + 1 < words.size() ? words[at + 1] : "";
      char *end = nullptr;
      const long long value = std::strtoll(text.c_str(), &end, 10);
      if (text.empty() || *end != '\0')
        return key + " needs a whole number, got " + (text.empty() ? std::string("'none'") : "'" + text + "'");
      if (key == "wall")
        mat = value;
      else {
        if (value < 1 || value > 1000)
          return "slots (history rows per atom) must be in [1, 1000], got " + std::to_string(value);
        slots = value;
      }
      at += 2;
    } else
      return "unknown keyword '" + key + "'" + syntax;
  }
  // a mesh: its packed file (not an STL file, which the walls room reads in Python)
  std::vector<double> payload;
  int64_t nt = 0;
  V3 mesh_centre = {0, 0, 0};
  if (kind == "mesh") {
    std::string wrong = read_mesh(mesh_path, scaled, mesh_centre, payload, nt);
    if (!wrong.empty()) return wrong;
  }
  // the wall's checks (the kinds' packed(), walls.checks)
  const char *dir_name = kind == "plane" ? "normal" : "axis";
  if (!finite(point)) return "the wall's point must be 3 finite numbers";
  if (!finite(dir)) return std::string("the wall's ") + dir_name + " must be 3 finite numbers";
  if (kind != "mesh" && std::fabs(norm(dir) - 1.0) > dem_contact_aot_unit_tol)
    return std::string("the wall's ") + dir_name + " must be a unit vector (| |n| - 1 | <= " +
        number_text(dem_contact_aot_unit_tol) + "), |n| = " + number_text(norm(dir));
  if (kind == "cylinder" && !(std::isfinite(rc) && rc > 0.0))
    return "the wall's radius must be finite and > 0 [m], got " + number_text(rc);
  if (!finite(vel)) return "the wall's velocity must be 3 finite numbers";
  if (!finite(omega)) return "the wall's angular_velocity must be 3 finite numbers";
  if (has_centre && !finite(centre)) return "the wall's centre must be 3 finite numbers";
  if (!has_centre)
    for (int d = 0; d < 3; d++) centre[d] = kind == "mesh" ? mesh_centre[d] : point[d];
  V3 c1, c2;
  bool keeps;
  const double *tol = dem_contact_aot_surface_tol;
  if (kind == "mesh")
    keeps = norm(vel) == 0.0 && norm(omega) == 0.0;
  else if (kind == "plane") {
    cross(omega, dir, c2);
    keeps = std::fabs(dot(vel, dir)) <= tol[0] * norm(vel) && norm(c2) <= tol[0] * norm(omega);
  } else {
    V3 off = {centre[0] - point[0], centre[1] - point[1], centre[2] - point[2]}, c3;
    cross(vel, dir, c1);
    cross(omega, dir, c2);
    cross(off, dir, c3);
    keeps = norm(c1) <= tol[1] * norm(vel) && norm(c2) <= tol[1] * norm(omega) &&
        (norm(omega) == 0.0 || norm(c3) <= tol[1] * rc);
  }

  // the table (aot_attach's checks) and its walls
  DemContactAttach pair;
  std::memset(&pair, 0, sizeof(pair));
  std::string wrong = dem_contact_aot_attach(path, ntypes, pair, wall.table);
  if (!wrong.empty()) return wrong;
  const int64_t n_mats = wall.table.n_mats;
  const std::vector<int64_t> &wall_row = wall.table.wall_row;
  if (n_mats == 0)
    return "the table file " + path + " has no walls: write it with the walls' materials (`dem-contact "
           "lammps-table ... --wall E NU`, or pair_table(spheres, walls))";
  if (mat < 0 || mat >= n_mats)
    return "wall " + std::to_string(mat) + " is not a wall of the table file " + path + " (it has walls 0 ... " +
        std::to_string(n_mats - 1) + ")";
  const double want = kind != "cylinder" || !curved ? 0.0 : (inside ? -0.5 : 0.5) / rc;
  const int *L = dem_contact_aot_wall_layout;
  const double have = wall.table.rowinfo[wall_row[mat] * dem_contact_aot_n_rowinfo + L[W_RI_CURV]];
  if (have != want)
    return "the wall has curvature " + number_text(want) + " 1/m at its contacts, but its material (wall " +
        std::to_string(mat) + " of " + path + ") has curvature " + number_text(have) +
        ": write the table with that curvature for it (--wall E NU " + number_text(want) +
        "), or give the cylinder the word flat (R* = R1)";

  // the packed rows (walls.table.pack: one wall, then a mesh's payload rows; the kind's data as its packed()
  // returns it)
  wall.walls.assign((size_t) L[W_ROW_SIZE] * (1 + nt), 0.0);
  double *w = wall.walls.data();
  w[L[W_KIND]] = kind == "plane" ? L[W_PLANE] : kind == "cylinder" ? L[W_CYLINDER] : L[W_MESH];
  w[L[W_NELEM]] = kind == "mesh" ? (double) nt : 1.0;
  w[L[W_MOVES]] = keeps ? 0.0 : 1.0;
  for (int d = 0; d < 3; d++) {
    w[L[W_VEL] + d] = vel[d];
    w[L[W_OMEGA] + d] = omega[d];
    w[L[W_CENTRE] + d] = centre[d];
    w[L[W_CENTRE0] + d] = centre[d];
    // a plane's and a cylinder's point, direction now and at time 0
    if (kind != "mesh") {
      w[L[W_DATA] + d] = point[d];
      w[L[W_DATA] + 3 + d] = dir[d];
      w[L[W_DATA] + 6 + d] = point[d];
      w[L[W_DATA] + 9 + d] = dir[d];
    }
  }
  w[L[W_FIRST]] = kind == "mesh" ? 1.0 : -1.0;    // (the first payload row; KEY_BASE 0: the fix's one wall)
  if (kind == "mesh") {
    // (row data: the number of triangles; each payload row: PAYLOAD, then the triangle's columns)
    w[L[W_DATA]] = (double) nt;
    const int width = L[W_PAYLOAD_WIDTH];
    for (int64_t t = 0; t < nt; t++) {
      double *row = w + (1 + t) * L[W_ROW_SIZE];
      row[L[W_KIND]] = L[W_PAYLOAD];
      std::memcpy(row + 1, payload.data() + t * width, sizeof(double) * width);
    }
  }
  if (kind == "cylinder") {
    w[L[W_DATA] + 12] = rc;
    w[L[W_DATA] + 13] = inside ? 1.0 : -1.0;
    w[L[W_DATA] + 14] = want;
  }

  // the wall step of the table's tangential law (compiled beside its pair step)
  void *step = nullptr;
  for (int s = 0; s < dem_contact_aot_n_steps; s++)
    if (dem_contact_aot_steps[s].step == pair.step) step = dem_contact_aot_steps[s].wall_step;
  k.step = step;
  k.walls = w;
  k.wall_rows = 1 + nt;
  k.mat = mat;
  k.params = wall.table.params.data();
  k.n_rows = pair.n_rows;
  k.wall_row = wall_row.data();
  k.n_types = ntypes;
  k.n_mats = n_mats;
  k.rowinfo = wall.table.rowinfo.data();
  k.type_size = wall.table.type_size.data();
  k.size_free = pair.size_free;
  k.history_size = pair.history_size;
  // (a plane or a cylinder: one contact per atom; a mesh: one per patch it touches)
  k.slots = slots ? slots : kind == "mesh" ? 6 : 1;
  k.unbounded = kind == "mesh" ? 0 : 1;
  std::snprintf(k.describe, sizeof(k.describe), "%s (table wall %lld), %s",
                kind == "plane" ? "PlaneWall" : kind == "cylinder" ? "CylinderWall" : "MeshWall", (long long) mat,
                pair.laws);
  k.error[0] = 0;
  return "";
}
