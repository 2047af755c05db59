// The table file read without Python, for the step compiled ahead of time (dem_contact.lammps.table_file.load
// and pair_kernel.attach, in C++: the same checks of format, version and laws, the same arrays).
#include "aot.h"
#include "pair_dem_contact.h"

#include "json.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

using LAMMPS_NS::json;

extern "C" void NRT_MemSys_init(void);    // (numba's runtime, linked in)

namespace {
const char *FORMAT = "dem_contact pair table";
const char *FAMILIES[4] = {"normal", "tangential", "twist", "rolling"};

std::vector<std::string> words(const char *text)
{
  std::istringstream in(text);
  std::vector<std::string> out;
  std::string w;
  while (in >> w) out.push_back(w);
  return out;
}

int index_of(const std::vector<std::string> &names, const std::string &name)
{
  for (size_t k = 0; k < names.size(); k++)
    if (names[k] == name) return (int) k;
  return -1;
}

// doc[name] as numbers, rows x cols (cols 0: a list), into out; false where it is not
template <typename T> bool numbers(const json &doc, const char *name, size_t rows, size_t cols, std::vector<T> &out)
{
  if (!doc.contains(name)) return false;
  const json &a = doc[name];
  if (!a.is_array() || a.size() != rows) return false;
  out.clear();
  for (const json &row : a) {
    if (cols == 0) {
      if (!row.is_number()) return false;
      out.push_back(row.get<T>());
      continue;
    }
    if (!row.is_array() || row.size() != cols) return false;
    for (const json &v : row) {
      if (!v.is_number()) return false;
      out.push_back(v.get<T>());
    }
  }
  return true;
}
}    // namespace

std::string dem_contact_aot_attach(const std::string &path, int ntypes, DemContactAttach &k,
                                   DemContactAotTable &t)
{
  static bool runtime = false;
  if (!runtime) {
    NRT_MemSys_init();
    runtime = true;
  }
  const std::string again = ": write it again with dem_contact.lammps.table_file.save";
  std::ifstream in(path);
  if (!in)
    return "the table file " + path + " does not exist: write it with dem_contact.lammps.table_file.save (or "
        "`dem-contact lammps-table`)";
  json doc;
  try {
    doc = json::parse(in);
  } catch (std::exception &e) {
    return "the table file " + path + " cannot be read as JSON (" + e.what() + ")" + again;
  }
  if (!doc.is_object() || !doc.contains("format") || doc["format"] != FORMAT)
    return path + " is not a dem_contact pair table (its 'format' is not '" + FORMAT + "')";
  const std::string version = doc.contains("version") && doc["version"].is_string() ? doc["version"] : "?";
  if (version != dem_contact_aot_version)
    return "the table file " + path + " was written by dem_contact " + version + "; this plugin's step was " +
        "compiled ahead of time from " + dem_contact_aot_version + ": write the table with that version, or " +
        "build the plugin with this one (dem-contact lammps-plugin --ahead-of-time LAW)";
  const char *missing = dem_contact_aot_missing_feature();
  if (missing)
    return std::string("this plugin's step was compiled ahead of time on a machine with the CPU feature ") +
        missing + ", which this one lacks: build it on this machine (dem-contact lammps-plugin --ahead-of-time LAW)";
  if (!doc.contains("laws") || !doc["laws"].is_array()) return "the table file " + path + " is corrupt (no 'laws' list)";
  const json &laws = doc["laws"];
  const size_t n_rows = laws.size();
  const int np = dem_contact_aot_n_params, ni = dem_contact_aot_n_rowinfo;
  if (!numbers(doc, "params", n_rows, np, t.params))
    return "the table file " + path + " is corrupt (its 'params' is missing, not numbers or not " +
        std::to_string(n_rows) + " x " + std::to_string(np) + ")" + again;
  // the law ids of the rows: those of this version's names
  for (size_t r = 0; r < n_rows; r++) {
    for (int f = 0; f < 4; f++) {
      const json &names = laws[r];
      const bool none = !names.is_object() || !names.contains(FAMILIES[f]) || names[FAMILIES[f]].is_null();
      double id = 0.0;
      if (!none) {
        if (!names[FAMILIES[f]].is_string()) return "the table file " + path + " is corrupt (a law name)" + again;
        const std::string name = names[FAMILIES[f]];
        const int k_id = index_of(words(dem_contact_aot_laws[f]), name);
        if (k_id < 0)
          return "the table file " + path + " needs the " + FAMILIES[f] + " law '" + name + "' (row " +
              std::to_string(r) + "), which dem_contact " + dem_contact_aot_version + " lacks";
        id = 1.0 + k_id;
      }
      t.params[r * np + dem_contact_aot_law_slots[f]] = id;
    }
  }
  const size_t nt = doc.contains("radius") && doc["radius"].is_array() ? doc["radius"].size() : 0;
  if ((int) nt != ntypes)
    return "the table file " + path + " is for " + std::to_string(nt) + " atom types, the LAMMPS box has " +
        std::to_string(ntypes) + ": write it for the box's types (PairTable.save)";
  std::vector<double> radius, mass;
  if (!numbers(doc, "sphere_row", nt, nt, t.sphere_row) || !numbers(doc, "radius", nt, 0, radius) ||
      !numbers(doc, "mass", nt, 0, mass) || !numbers(doc, "rowinfo", n_rows, ni, t.rowinfo) ||
      !numbers(doc, "tc_unit", n_rows, 0, t.tc_unit) || !numbers(doc, "alpha", n_rows, 0, t.alpha) ||
      !doc.contains("history_size") || !doc["history_size"].is_number_integer() || !doc.contains("tangential") ||
      !doc["tangential"].is_string() || !doc.contains("normal") || !doc["normal"].is_string())
    return "the table file " + path + " is corrupt (an array of the wrong shape, or a value missing)" + again;
  for (int64_t row : t.sphere_row)
    if (row < 0 || row >= (int64_t) n_rows) return "the table file " + path + " is corrupt (a sphere row)" + again;
  // the rows of the types against the walls' materials (none: a table without walls)
  const json *walls = doc.contains("wall_row") ? &doc["wall_row"] : nullptr;
  t.n_mats = walls && walls->is_array() && walls->size() == nt && nt > 0 && (*walls)[0].is_array()
      ? (int64_t) (*walls)[0].size() : 0;
  if (!walls || !walls->is_array() || walls->size() != nt ||
      (t.n_mats > 0 && !numbers(doc, "wall_row", nt, t.n_mats, t.wall_row)))
    return "the table file " + path + " is corrupt (its 'wall_row')" + again;
  if (t.n_mats == 0) t.wall_row.clear();
  for (int64_t row : t.wall_row)
    if (row < 0 || row >= (int64_t) n_rows) return "the table file " + path + " is corrupt (a wall row)" + again;
  t.type_size.clear();
  for (size_t k_t = 0; k_t < nt; k_t++) {
    t.type_size.push_back(radius[k_t]);
    t.type_size.push_back(mass[k_t]);
  }
  const std::string tangential = doc["tangential"];
  void *step = nullptr;
  std::string compiled;
  for (int s = 0; s < dem_contact_aot_n_steps; s++) {
    if (tangential == dem_contact_aot_steps[s].law) step = dem_contact_aot_steps[s].step;
    compiled += std::string(s ? ", " : "") + dem_contact_aot_steps[s].law;
  }
  if (!step)
    return "the table file " + path + " has the tangential law " + tangential + "; this plugin's step was " +
        "compiled ahead of time for " + compiled + ": build it for " + tangential +
        " (dem-contact lammps-plugin --ahead-of-time " + tangential + ")";
  // every row of the table's normal and tangential laws, and the history rows long enough for its laws (the
  // step writes where the laws' slots are: PairTable's checks)
  const std::vector<std::string> normals = words(dem_contact_aot_laws[0]), tangentials = words(dem_contact_aot_laws[1]);
  const int nid = index_of(normals, doc["normal"].get<std::string>()), tid = index_of(tangentials, tangential);
  if (nid < 0 || tid < 0) return "the table file " + path + " is corrupt (its laws are not this version's)" + again;
  const int *n_laws = dem_contact_aot_n_laws;
  int64_t need = 0;
  for (size_t r = 0; r < n_rows; r++) {
    const double *p = t.params.data() + r * np;
    if (p[dem_contact_aot_law_slots[0]] != nid + 1.0 || p[dem_contact_aot_law_slots[1]] != tid + 1.0)
      return "the table file " + path + " is corrupt (row " + std::to_string(r) + " is not of its laws " +
          doc["normal"].get<std::string>() + " + " + tangential + ")" + again;
    const int q = std::max(0, (int) p[dem_contact_aot_law_slots[2]] - 1), rl = std::max(0, (int) p[dem_contact_aot_law_slots[3]] - 1);
    const double cells = p[dem_contact_aot_p_nspring];
    if (q >= n_laws[2] || rl >= n_laws[3] ||
        (dem_contact_aot_cells[tid] && !(cells >= 2.0 && cells <= 1e6 && cells == (int64_t) cells)))
      return "the table file " + path + " is corrupt (row " + std::to_string(r) + ": its twist or rolling law, or "
          "its MDR cell count)" + again;
    const int64_t row_need = dem_contact_aot_tangential_base[(nid * n_laws[2] + q) * n_laws[3] + rl] +
        dem_contact_aot_vector_slots[tid] + (dem_contact_aot_cells[tid] ? 2 * (int64_t) cells : 0);
    need = std::max(need, row_need);
  }
  if (doc["history_size"].get<int64_t>() < need)
    return "the table file " + path + " is corrupt (history_size " + std::to_string(doc["history_size"].get<int64_t>()) +
        ", its laws need " + std::to_string(need) + ")" + again;
  bool turning = false;
  for (size_t r = 0; r < n_rows; r++)
    turning = turning || t.params[r * np + dem_contact_aot_law_slots[2]] > 1.0 ||
        t.params[r * np + dem_contact_aot_law_slots[3]] > 1.0;
  k.step = step;
  k.params = t.params.data();
  k.n_rows = (int64_t) n_rows;
  k.sphere_row = t.sphere_row.data();
  k.n_types = (int64_t) nt;
  k.rowinfo = t.rowinfo.data();
  k.type_size = t.type_size.data();
  k.size_free = doc.contains("size_free") && doc["size_free"].is_boolean() && doc["size_free"].get<bool>();
  k.history_size = doc["history_size"].get<int64_t>();
  k.turning = turning;
  k.tc_unit = t.tc_unit.data();
  k.alpha = t.alpha.data();
  std::snprintf(k.laws, sizeof(k.laws), "%s + %s", doc["normal"].get<std::string>().c_str(), tangential.c_str());
  k.error[0] = 0;
  return "";
}
