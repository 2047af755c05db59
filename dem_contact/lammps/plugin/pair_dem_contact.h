/* pair_style dem/contact: dem_contact's contact laws for spheres (atom_style sphere, units si) in LAMMPS's own
   pair loop.

     pair_style dem/contact vmax V [slots N] [frame_spin yes|no] [rmax R] [energy yes|no]
     pair_coeff * * TABLE_FILE

   vmax: the largest normal impact speed [m/s] (the time step is checked against the contact time at it, and
   contacts that begin faster against theirs); slots: history rows per atom (default 12); frame_spin (default
   yes): pass the spin of the contact frame about the normal to the tangential law; no: keep the
   tangential history fixed in space, as LAMMPS's granular models; rmax: the largest radius atoms reach in the
   run [m] (default: each type's largest at the run's start, or the radius a fix inserts), where fix adapt grows
   them (the neighbour cutoff); energy (default no): account the work of each contact's forces (compute
   dem/contact/local work, the energy dissipated per atom: the history fix's per-atom vector and scalar).

   The table file (dem_contact.lammps.table_file.save) holds the parameter rows of every pair of atom types and
   their laws. This class walks LAMMPS's half neighbour list (newton off: a pair across two ranks is evaluated by
   both, in one canonical order, body 1 the lower atom id, from the same inputs, so both copies of its history
   stay equal and no history is communicated; a pair across a periodic boundary within one rank, listed twice,
   is evaluated once), keeps each contact's history by neighbour-list entry between list builds and in the
   per-atom rows of its fix (FixDemContactHistory) when atoms move, finds the touching pairs in a lean pass over
   the list (find_touching) and hands them to the package's compiled step once per step
   (dem_contact/lammps/pair_kernel.py), reached through Python (python_link.h). It adds the returned forces and
   torques to the local atoms and tallies the virial. */
#ifdef PAIR_CLASS
#else
#ifndef DEM_CONTACT_PAIR_H
#define DEM_CONTACT_PAIR_H

#include "fix_dem_contact_history.h"
#include "pair.h"
#ifdef DEM_CONTACT_AOT
#include "aot.h"
#endif

#include <cstddef>
#include <cstdint>
#include <new>
#include <string>
#include <vector>

// an allocator of memory that starts at a cache line (64 bytes): a pool whose rows are a whole number of lines
// then gives each row its own lines
template <class T> struct CacheLineAllocator {
  using value_type = T;
  CacheLineAllocator() = default;
  template <class U> CacheLineAllocator(const CacheLineAllocator<U> &) {}
  T *allocate(std::size_t n) { return static_cast<T *>(::operator new(n * sizeof(T), std::align_val_t(64))); }
  void deallocate(T *p, std::size_t) { ::operator delete(p, std::align_val_t(64)); }
  template <class U> bool operator==(const CacheLineAllocator<U> &) const { return true; }
  template <class U> bool operator!=(const CacheLineAllocator<U> &) const { return false; }
};

// what dem_contact.lammps.pair_kernel.attach writes (its class Attach, field for field)
struct DemContactAttach {
  int64_t abi;
  char error[2048];
  void *step;
  const double *params;
  int64_t n_rows;
  const int64_t *sphere_row;
  int64_t n_types;
  const double *rowinfo;
  const double *type_size;
  int64_t size_free;
  int64_t history_size;
  int64_t turning;    // the table has twist or rolling laws (the step takes the relative spins)
  const double *tc_unit;
  const double *alpha;
  char laws[512];
};

namespace LAMMPS_NS {

class PairDemContact : public Pair, public RowKeeper {
 public:
  // columns of the per-contact output of a step (dem_contact/lammps/pair_kernel.py, OUT_...)
  enum {
    OUT_F = 0,
    OUT_TA = 3,
    OUT_TB = 6,
    OUT_DELTA = 9,
    OUT_FT = 10,
    OUT_N = 13,
    OUT_MU = 16,
    OUT_WORK_N = 17,
    OUT_WORK_T = 18,
    OUT_Q = 19,
    N_OUT = 22
  };
  // the plugin's values after the law's history in a contact row (pair_kernel.X_..., N_EXTRA): X_WORK, the work
  // the contact's forces have done on it since it began, is the energy it dissipated when it ends
  enum { X_DELTA = 1, X_WORK = 2, N_EXTRA = 4 };
  // the work done on an ended contact of row h (hs values): its X_WORK, with the last part of the normal work, from
  // the last step's overlap and normal force (the law's V_N, slot 0) to the overlap now, delta_end (a gap, < 0),
  // and no force, by the trapezoid rule (pair_kernel.ended_work)
  static double ended_work(const double *h, int hs, double delta_end)
  {
    return h[hs - N_EXTRA + X_WORK] + 0.5 * h[0] * (delta_end - h[hs - N_EXTRA + X_DELTA]);
  }

  PairDemContact(class LAMMPS *);
  ~PairDemContact() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  double memory_usage() override;
  void store_rows() override;

  // the overlap of a head-on impact at vmax of a contact of the table's row information info (at 1 m/s) with
  // R* rs and m* ms: the row's, by the law's exponent of the speed and Hertz's scaling with m*^2 / R*
  static double deepest(const double *info, double vmax, double rs, double ms);
  // a warning (rank 0) of the contacts over the ranks, count here, that start deeper than that (worst: the
  // largest ratio here)
  static void tell_deep(class LAMMPS *lmp, const std::string &who, int count, double worst, double vmax);

  // the contacts of the last step recorded: a run's set-up (one that applied the forces it computed; one that
  // reapplied the last step's forces keeps that step's), its last step, and the steps LAMMPS invokes a compute
  // dem/contact/local at (output_due): its number (-1: none), the contacts' atoms (local indices, body 1 the lower
  // id; valid until atoms move between ranks or are sorted) and their rows of N_OUT values
  bigint evaluated_step;
  // whether a compute dem/contact/local is invoked at this step: one that a dump, thermo or fix invokes (LAMMPS
  // schedules its steps, Compute::matchstep)
  bool output_due() const;
  // whether this step is a set-up that gave the atoms the last step's forces again (which keeps that step's
  // contacts, the wall fixes' too)
  bool kept_last() const { return reapplied; }
  // the recorded contacts: their number, per contact the ids of its atoms (body 1 the lower) and whether this
  // rank owned atom id1 (3 values), and their rows of N_OUT values
  int64_t contact_count() const { return rec_n; }
  const tagint *contact_ids() const { return rec_ids.data(); }
  const double *contact_values() const { return rec_out.data(); }
  // what fix dem/contact/wall takes from the pair style: its table file, vmax and frame_spin
  const std::string &table_file() const { return table_path; }
  double speed_limit() const { return vmax; }
  int frame_spin_on() const { return frame_spin; }
  // whether the work of the contact forces is accounted (energy yes: N_EXTRA values more in each row)
  int energy_on() const { return energy; }

 private:
  double vmax, rmax;
  int slots, frame_spin;
  std::string table_path;
  DemContactAttach kernel;
#ifdef DEM_CONTACT_AOT
  DemContactAotTable aot_table;    // (the table file's arrays, read without Python)
#endif
  bool attached, warned_onset, sized, deep_checked, radii_change, reapplied;
  int energy, row_size;    // energy yes|no; the values of a contact row: the law's history (+ N_EXTRA)
  FixDemContactHistory *fix;
  std::vector<double> type_rmax;
  std::vector<class Compute *> readers;    // the computes dem/contact/local
  // Between list builds the contacts' histories live in a pool (live: rows of row_size values), one row per
  // contact, found by the neighbour-list entry of its pair (entry_row[entry_start[ii] + jj]: -1, none; TWIN:
  // an entry not evaluated, its pair's twin is); per pool row its atoms (i local, j local or -1 for a ghost of
  // another rank's atom) and their ids (ti = 0: a free row).
  // Periodic twins: a pair of local atom i and the ghost image of local atom j is in the (newton off) list
  // twice, as (i, image of j) and (j, image of i); it is evaluated once, by the entry whose atom i has the
  // lower id, and j takes its force there (entry_local[entry]: j; -1 elsewhere)
  struct Pairing {
    int i, j;
    tagint ti, tj;
  };
  std::vector<double, CacheLineAllocator<double>> live;
  std::vector<Pairing> pairing;
  std::vector<int64_t> entry_start;
  std::vector<int32_t> entry_row, free_rows;
  std::vector<int> entry_local;
  std::vector<char> claimed;
  std::vector<int> fill;
  // the step's contacts (room for cap): atoms, pool rows, parameter rows, and the law's inputs (N_INPUTS blocks)
  enum { N_INPUTS = 11 };
  std::vector<int64_t> pairs, hrow, scratch_rows, prow, to;
  struct Touch {    // a list entry whose pair touches, or whose contact ended: its atoms and the entry's index
    int i, j;
    int64_t e;
  };
  std::vector<Touch> touching;
  std::vector<double> inputs, out, scratch, acc, work, pc;
  // the contacts recorded at evaluated_step (kept through a set-up that reapplies the last step's forces)
  std::vector<tagint> rec_ids;
  std::vector<double> rec_out;
  int64_t rec_n = 0;
  int64_t cap;
  int loaded_nlocal;    // the local atoms when the pool was loaded (store_rows writes theirs)

  void allocate();
  void attach_table(const char *path);
  void check_atoms();
  void check_time_step();
  int row_of(int i, double key) const;
  int32_t take_row(int i, int j, int j_local);
  void find_twins(int nlocal, int nall);
  static int64_t find_touching(int inum, const int *ilist, const int *numneigh, int *const *firstneigh,
                               const int64_t *entry_start, const int32_t *entry_row, double *const *x,
                               const double *radius, const double *special_lj, Touch *tc, int64_t &q);
  void end_row(int32_t r, double delta_end);
  void load_rows();
  double contact_time(int a, int b, double vn);
  void check_onset(double vn, int a, int b);
  bool reapply_saved();
  void save_forces(int nlocal);
  void check_ids(int nlocal);
  bool any_resized(int nall);
  void history_fix();
  void check_deep(int64_t n);
  void check_grown(int nlocal);
};

}    // namespace LAMMPS_NS

#endif
#endif
