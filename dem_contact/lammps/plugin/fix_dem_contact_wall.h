/* fix dem/contact/wall: a wall of dem_contact's walls room (a plane, a cylinder or an STL mesh, with a rigid
   motion) touching the atoms of a group, with the contact laws of pair_style dem/contact's table file.

     fix ID GROUP dem/contact/wall KIND ARGS [wall W] [velocity VX VY VZ] [angular_velocity WX WY WZ]
         [centre CX CY CZ] [slots N]

   KIND ARGS: plane PX PY PZ NX NY NZ | cylinder PX PY PZ AX AY AZ RC in|out [flat] | mesh FILE [scale S]
   (dem_contact/lammps/wall_kernel.py reads them; with the steps compiled ahead of time, aot_wall.cpp reads a
   plane's or a cylinder's). W: the wall's material, the W-th wall of the table file
   (default 0). Define pair_style dem/contact and its pair_coeff first: the fix takes its table, vmax and
   frame_spin.

   The fix keeps each atom's wall contact rows in the per-atom rows of its own history fix
   (FixDemContactHistory, which moves them with the atoms), and hands the local atoms to the package's compiled
   wall step once per step (post_force). Its global vector (7): the wall's force [N] and torque about its centre
   [N m] from the atoms, and the power it gives them [W], summed over the ranks. */
#ifdef FIX_CLASS
#else
#ifndef DEM_CONTACT_FIX_WALL_H
#define DEM_CONTACT_FIX_WALL_H

#include "fix.h"

#ifdef DEM_CONTACT_AOT
#include "aot.h"
#endif

#include <cstdint>
#include <string>
#include <vector>

// what dem_contact.lammps.wall_kernel.attach writes (its class WallAttach, field for field)
struct DemContactWallAttach {
  int64_t abi;
  char error[2048];
  void *step;
  double *walls;
  int64_t wall_rows;
  int64_t mat;
  const double *params;
  int64_t n_rows;
  const int64_t *wall_row;
  int64_t n_types;
  int64_t n_mats;
  const double *rowinfo;
  const double *type_size;
  int64_t size_free;
  int64_t history_size;
  int64_t slots;
  int64_t unbounded;
  char describe[512];
};

namespace LAMMPS_NS {

class FixDemContactHistory;
class PairDemContact;

class FixDemContactWall : public Fix {
 public:
  FixDemContactWall(class LAMMPS *, int, char **);
  ~FixDemContactWall() override;
  int setmask() override;
  void post_constructor() override;
  void init() override;
  void setup(int) override;
  void post_force(int) override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  // the wall's contacts recorded where a compute dem/contact/local reads them (the steps of the pair style's
  // PairDemContact::evaluated_step): the step (-1: none), their number, the ids of their atoms and their rows of
  // PairDemContact::N_OUT values
  bigint evaluated_step;
  int64_t contact_count() const { return rec_n; }
  const tagint *contact_ids() const { return rec_ids.data(); }
  const double *contact_values() const { return rec_out.data(); }

 private:
  DemContactWallAttach kernel;
#ifdef DEM_CONTACT_AOT
  DemContactAotWall aot_wall;    // (the wall and the table's arrays, read without Python)
#endif
  std::string words, table_path, history_id;
  FixDemContactHistory *history;
  PairDemContact *pair;
  double report[14], load_all[7];    // (wall_kernel.N_REPORT)
  bool load_summed, warned_onset, deep_checked;
  int64_t n_out;
  int energy;      // pair_style dem/contact ... energy yes when the fix was defined
  int row_size;    // the values of a contact row: the law's history (+ N_EXTRA with pair_style ... energy yes)
  std::vector<double> out;
  std::vector<int64_t> out_atoms;
  // (the last step's contacts, kept through a set-up that reapplies its forces)
  // the contacts recorded at evaluated_step: their atoms' ids and rows (kept through a set-up that reapplies the
  // last step's forces)
  std::vector<tagint> rec_ids;
  std::vector<double> rec_out;
  int64_t rec_n = 0;
  // the wall's clock: LAMMPS's time plus offset (0 when the fix is defined); the clock at the last step evaluated
  // (has_clock)
  double clock_offset, clock_last;
  int has_clock;

  void attach();
  double now() const;
  void evaluate(bool setup);
  void check_time_step();
  void check_deep();
};

}    // namespace LAMMPS_NS

#endif
#endif
