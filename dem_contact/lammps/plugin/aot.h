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
// a step of one tangential law family (pair_kernel.step_function's C entry)
struct DemContactAotStep {
  const char *law;
  void *step;
};
extern const DemContactAotStep dem_contact_aot_steps[];
extern const int dem_contact_aot_n_steps;
// the package version the steps were compiled from (table files of it only)
extern const char *const dem_contact_aot_version;
// per law family (normal, tangential, twist, rolling): the law names in id order, separated by spaces
extern const char *const dem_contact_aot_laws[4];
// the parameter slots of the law ids of those families (laws.slots.P_NORMAL_LAW, ...), and the sizes of a
// parameter row and of a row's information (laws.slots.N_PARAMS, kernels.N_ROWINFO)
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
};

// Read the table file `path` for a box of `ntypes` atom types into `table` and fill `k` as
// pair_kernel.attach does (the step: the one compiled for the table's tangential law). Returns "" or what is
// wrong, with what to do.
std::string dem_contact_aot_attach(const std::string &path, int ntypes, DemContactAttach &k,
                                   DemContactAotTable &table);

#endif
