/* Per-atom contact rows of pair_style dem/contact, which move with their atom: between ranks (exchange),
   through atom sorting, and into and out of restart files.

   Every atom has `slots` rows (an atom moving to another rank carries its filled rows only; a restart file
   has them all). Row s of atom i: its key keys[i][s] (the partner's atom id; 0: free) and the
   law's history hist[(i * slots + s) * history_size ...] (dem_contact's 3D history row). A contact of two
   atoms has a row in each where both are on the rank, equal (the pair style writes them; fix dem/contact/wall
   keeps one per wall contact). Per atom also the contact force and torque of the
   last step of a run, the state they were computed at and that step (saved[i][...]), which the next run's
   set-up reapplies when nothing has changed, also after a restart file (on any number of ranks), and the energy
   its ended contacts dissipated (dissipated[i], J: half of each contact with another atom, all of a wall
   contact; the work its forces did on the contact over its life), which this fix gives as its per-atom vector
   (dump custom: f_ID) and their sum over the atoms as its global scalar.

   Where a keeper holds the rows' newest values elsewhere while atoms keep their indices (the pair style keeps
   its contacts' histories by neighbour-list entry between list builds), the fix asks it to write them into the
   rows first (RowKeeper::store_rows) whenever they are needed: before atoms move between ranks or in memory
   (pre_exchange in a run, a minimization and a run's set-up; pack_exchange, copy_arrays: exchange, sorting,
   deletion), before a restart file is written, and at the end of a run. */
#ifndef DEM_CONTACT_FIX_HISTORY_H
#define DEM_CONTACT_FIX_HISTORY_H

#include "fix.h"

namespace LAMMPS_NS {

// what holds the newest values of a history fix's rows between moves of the atoms
class RowKeeper {
 public:
  // write them into the rows (atoms still at the indices they had since the keeper last read the rows)
  virtual void store_rows() = 0;

 protected:
  ~RowKeeper() = default;
};

class FixDemContactHistory : public Fix {
 public:
  // columns of saved: force (3), torque (3), then the state: x (3), v (3), omega (3), radius, rmass, and the
  // step they were saved at (-1: none); the atom's id at the end of the last run (0: none yet), which its
  // partners' keys name
  enum { SF_F = 0, SF_T = 3, SF_X = 6, SF_V = 9, SF_W = 12, SF_R = 15, SF_M = 16, SF_STEP = 17, SF_ID = 18,
         N_SAVED = 19 };

  FixDemContactHistory(class LAMMPS *, int, char **);
  ~FixDemContactHistory() override;
  int setmask() override;
  void setup_pre_exchange() override;
  void pre_exchange() override;
  void min_pre_exchange() override;
  void post_run() override;
  void end_of_step() override;
  double compute_scalar() override;

  double memory_usage() override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;

  int slots, history_size;
  double **keys;     // [nmax][slots]
  double *hist;      // [nmax * slots * history_size]
  double **saved;    // [nmax][N_SAVED]
  double *dissipated;    // [nmax]
  bool accounted;        // pair_style dem/contact ... energy yes
  RowKeeper *keeper;     // (null: the rows are the newest)
  bool stale;            // the keeper holds newer values than the rows
  bool setup_only;       // the pair style's last forces were a run's set-up's (none of a step since)
  // the rows made current (by the keeper, where they are stale)
  void refresh()
  {
    if (stale && keeper) {
      stale = false;
      keeper->store_rows();
    }
  }

 private:
  int per_atom() const { return slots * (1 + history_size) + N_SAVED + 1; }
  int pack_all(int, double *);
  void unpack_all(int, const double *);
};

}    // namespace LAMMPS_NS

#endif
