/* The pair step compiled ahead of time (dem_contact.lammps.aot; a plugin built with DEM_CONTACT_AOT): the
   package's compiled step of each tangential law family named at the build, linked into the plugin, so that
   pair_style dem/contact runs in an lmp with no Python. The build generates the tables below (the laws of the
   package version it was built from) and links numba's runtime (its memory functions) and aot_runtime.cpp
   (the error paths of the compiled code, which report instead of raising a Python exception). */
#ifndef DEM_CONTACT_AOT_H
#define DEM_CONTACT_AOT_H

#include <cstdint>
#include <string>
#include <vector>

struct DemContactAttach;

extern "C" {
// the steps of one tangential law family (the C entries of pair_kernel.step_function and
// wall_kernel.step_function)
struct DemContactAotStep {
  const char *law;
  void *step;
  void *wall_step;
};
extern const DemContactAotStep dem_contact_aot_steps[];
extern const int dem_contact_aot_n_steps;
// the package version the steps were compiled from (table files of it only)
extern const char *const dem_contact_aot_version;
// per law family (normal, tangential, twist, rolling): the law names in id order, separated by spaces
extern const char *const dem_contact_aot_laws[4];
// the parameter slots of the law ids of those families (laws.slots.P_NORMAL_LAW, ...), and the sizes of a
// parameter row and of a row's information (laws.slots.N_PARAMS, contact_terms.N_ROWINFO)
extern const int dem_contact_aot_law_slots[4];
extern const int dem_contact_aot_n_params;
extern const int dem_contact_aot_n_rowinfo;
// the history a parameter row needs (laws.table.vector_history_size): the laws per family, the first
// tangential slot by (normal, twist, rolling) law ids (flattened in that order), each tangential law's fixed
// slots and whether it has cells (2 slots each, params[row][P_NSPRING] of them)
extern const int dem_contact_aot_n_laws[4];
extern const int dem_contact_aot_tangential_base[];
extern const int dem_contact_aot_vector_slots[];
extern const int dem_contact_aot_cells[];
extern const int dem_contact_aot_p_nspring;
// the packed rows of a wall (walls.contract): ROW_SIZE, the columns KIND, KEY_BASE, NELEM, MOVES, VEL, OMEGA,
// CENTRE, CENTRE0, FIRST, DATA, the kind ids of a plane and a cylinder, the column of a table row's wall
// curvature (contact_terms.RI_CURV), the kind id of a mesh, the kind id of a payload row (PAYLOAD), a mesh's
// payload columns (walls.mesh.PAYLOAD_WIDTH) and where among them are its vertices now and at time 0, vertex
// ids, neighbours, orientation and history keys; the
// first line of a packed mesh file (mesh_file.MAGIC); the tolerance of a unit vector (walls.checks.UNIT_TOL), of
// a motion that keeps a plane's and a cylinder's surface (their SURFACE_TOL), and wall_kernel.ABI
enum { W_ROW_SIZE, W_KIND, W_KEY_BASE, W_NELEM, W_MOVES, W_VEL, W_OMEGA, W_CENTRE, W_CENTRE0, W_FIRST, W_DATA,
       W_PLANE, W_CYLINDER, W_RI_CURV, W_MESH, W_PAYLOAD, W_PAYLOAD_WIDTH, W_MESH_V, W_MESH_V0, W_MESH_IDS, W_MESH_NB, W_MESH_ORIENT,
       W_MESH_KEYS };
extern const int dem_contact_aot_wall_layout[];
extern const char *const dem_contact_aot_mesh_magic;
extern const double dem_contact_aot_unit_tol;
extern const double dem_contact_aot_surface_tol[2];
extern const int dem_contact_aot_wall_abi;
// an x86 feature of the machine the steps were compiled on that this one lacks (nullptr: none)
const char *dem_contact_aot_missing_feature();
// set where the compiled code took an error path (an exception in numba's terms); cleared by the caller
extern int dem_contact_aot_raised;
}

// The arrays of a table file read without Python (aot_attach fills them and points the attach structure at
// them)
struct DemContactAotTable {
  std::vector<double> params, rowinfo, type_size, tc_unit, alpha;
  std::vector<int64_t> sphere_row;
  std::vector<int64_t> wall_row;    // (types x n_mats: the row of each type against each wall material)
  int64_t n_mats = 0;
};

// The wall of a fix dem/contact/wall read without Python (aot_wall fills them and points the wall's attach
// structure at them)
struct DemContactAotWall {
  DemContactAotTable table;
  std::vector<double> walls;
};

struct DemContactWallAttach;

// Read the words of fix dem/contact/wall after its style (`words`) and the table file `path` for a box of
// `ntypes` atom types into `wall`, and fill `k` as wall_kernel.attach does (a plane, a cylinder, or a mesh from its packed mesh file; the
// step: the one compiled for the table's tangential law). Returns "" or what is wrong, with what to do.
std::string dem_contact_aot_wall_attach(const std::vector<std::string> &words, const std::string &path, int ntypes,
                                        DemContactWallAttach &k, DemContactAotWall &wall);

// Read the table file `path` for a box of `ntypes` atom types into `table` and fill `k` as
// pair_kernel.attach does (the step: the one compiled for the table's tangential law). Returns "" or what is
// wrong, with what to do.
std::string dem_contact_aot_attach(const std::string &path, int ntypes, DemContactAttach &k,
                                   DemContactAotTable &table);

#endif
