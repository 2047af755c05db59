// The wall of fix dem/contact/wall read without Python, for the step compiled ahead of time: the words of a plane
// or a cylinder as dem_contact.lammps.wall_kernel.parse reads them, packed as dem_contact.walls.table.pack packs
// them (the kinds' packed(): plane.PlaneWall, cylinder.CylinderWall), with their checks and the same messages;
// the table's laws and arrays, its walls included, as aot_attach reads them.
#include "aot.h"
#include "fix_dem_contact_wall.h"
#include "pair_dem_contact.h"

#include <algorithm>
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
  if (kind == "mesh")
    return "a mesh wall (its STL file read and packed by dem_contact's walls room) needs Python: this plugin has its "
           "steps compiled ahead of time, and runs planes and cylinders only; load the plugin that reaches "
           "dem_contact through Python (dem-contact lammps-plugin) for a mesh";
  size_t at = 1;
  V3 point = {0, 0, 0}, dir = {0, 0, 0};
  double rc = 0.0;
  bool inside = true, curved = true;
  double a[7];
  if (kind == "plane") {
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
  // the wall's checks (the kinds' packed(), walls.checks)
  const char *dir_name = kind == "plane" ? "normal" : "axis";
  if (!finite(point)) return "the wall's point must be 3 finite numbers";
  if (!finite(dir)) return std::string("the wall's ") + dir_name + " must be 3 finite numbers";
  if (std::fabs(norm(dir) - 1.0) > dem_contact_aot_unit_tol)
    return std::string("the wall's ") + dir_name + " must be a unit vector (| |n| - 1 | <= " +
        number_text(dem_contact_aot_unit_tol) + "), |n| = " + number_text(norm(dir));
  if (kind == "cylinder" && !(std::isfinite(rc) && rc > 0.0))
    return "the wall's radius must be finite and > 0 [m], got " + number_text(rc);
  if (!finite(vel)) return "the wall's velocity must be 3 finite numbers";
  if (!finite(omega)) return "the wall's angular_velocity must be 3 finite numbers";
  if (has_centre && !finite(centre)) return "the wall's centre must be 3 finite numbers";
  if (!has_centre)
    for (int d = 0; d < 3; d++) centre[d] = point[d];
  V3 c1, c2;
  bool keeps;
  const double *tol = dem_contact_aot_surface_tol;
  if (kind == "plane") {
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
  const double want = kind == "plane" || !curved ? 0.0 : (inside ? -0.5 : 0.5) / rc;
  const int *L = dem_contact_aot_wall_layout;
  const double have = wall.table.rowinfo[wall_row[mat] * dem_contact_aot_n_rowinfo + L[W_RI_CURV]];
  if (have != want)
    return "the wall has curvature " + number_text(want) + " 1/m at its contacts, but its material (wall " +
        std::to_string(mat) + " of " + path + ") has curvature " + number_text(have) +
        ": write the table with that curvature for it (--wall E NU " + number_text(want) +
        "), or give the cylinder the word flat (R* = R1)";

  // the packed row (walls.table.pack: one wall, no payload; the kind's data as its packed() returns it)
  wall.walls.assign(L[W_ROW_SIZE], 0.0);
  double *w = wall.walls.data();
  w[L[W_KIND]] = kind == "plane" ? L[W_PLANE] : L[W_CYLINDER];
  w[L[W_KEY_BASE]] = 0.0;
  w[L[W_NELEM]] = 1.0;
  w[L[W_MOVES]] = keeps ? 0.0 : 1.0;
  for (int d = 0; d < 3; d++) {
    w[L[W_VEL] + d] = vel[d];
    w[L[W_OMEGA] + d] = omega[d];
    w[L[W_CENTRE] + d] = centre[d];
    w[L[W_CENTRE0] + d] = centre[d];
    // point, direction now and at time 0
    w[L[W_DATA] + d] = point[d];
    w[L[W_DATA] + 3 + d] = dir[d];
    w[L[W_DATA] + 6 + d] = point[d];
    w[L[W_DATA] + 9 + d] = dir[d];
  }
  w[L[W_FIRST]] = -1.0;
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
  k.wall_rows = 1;
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
  k.slots = slots ? slots : 1;    // (a plane or a cylinder: one contact per atom)
  k.unbounded = 1;
  std::snprintf(k.describe, sizeof(k.describe), "%s (table wall %lld), %s",
                kind == "plane" ? "PlaneWall" : "CylinderWall", (long long) mat, pair.laws);
  k.error[0] = 0;
  return "";
}
