#include "pair_dem_contact.h"

#include "fix_dem_contact_history.h"
#include "python_link.h"
#ifdef DEM_CONTACT_AOT
#include "aot.h"
#endif

#include "atom.h"
#include "comm.h"
#include "compute.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

using namespace LAMMPS_NS;

namespace {
// the compiled step (pair_kernel.SIGNATURE): per-contact force on body 1, torques on both bodies, overlap
typedef int64_t (*StepFn)(int64_t n, int64_t *pairs, int64_t *hrow, double *H, int64_t h_rows, int64_t hs,
                          double *normals, double *overlaps, double *velocities, double *spins, double *wn,
                          int64_t turning, double *x, double *radius, double *rmass, int *type, int64_t nall,
                          const double *params, int64_t n_rows, const double *rowinfo, const double *type_size,
                          int64_t n_types, int64_t sized, double dt, double *out, double *forces, double *tforces,
                          double *torques, int64_t *prow, double *pc, int64_t *to, double *f, double *torque,
                          int64_t flags, double *virial);
// the flags of a step (pair_kernel.WRITE_OUT, SCATTER, VIRIAL)
const int64_t WRITE_OUT = 1, SCATTER = 2, VIRIAL = 4, ENERGY = 8;
// the law's outputs per contact (force, tangential force, twist and rolling torque: 3 each)
const int N_WORK = 9;
const int N_PARAMS = 43;    // laws.slots.N_PARAMS
// contact_terms.RI_...: columns of the table's per-row information (at 1 m/s)
const int RI_Q = 1, RI_DEEPEST = 4, RI_DEEP_ALPHA = 6, N_ROWINFO = 7;
const int ABI = 8;       // pair_kernel.ABI
const char *FIX_ID = "DEM_CONTACT_HISTORY";
// entry_row of a periodic twin's entry that is not evaluated (pair_dem_contact.h)
const int32_t TWIN = -2;
// the time step must give at least this many steps per elastic contact time of the stiffest pair
const double MIN_STEPS_PER_CONTACT = 10.0;
// tolerance on an atom's radius and mass against its type's (relative)
const double SIZE_TOL = 1e-9;

}    // namespace

PairDemContact::PairDemContact(LAMMPS *lmp) :
    Pair(lmp), evaluated_step(-1), vmax(0.0), rmax(0.0), slots(12), frame_spin(1), attached(false),
    warned_onset(false), sized(false), deep_checked(false), radii_change(false), reapplied(false), energy(0),
    row_size(0), fix(nullptr), cap(0), loaded_nlocal(0)
{
  single_enable = 0;
  restartinfo = 0;
  one_coeff = 1;
  finitecutflag = 1;
  no_virial_fdotr_compute = 1;
  centroidstressflag = CENTROID_NOTAVAIL;
  std::memset(&kernel, 0, sizeof(kernel));
}

PairDemContact::~PairDemContact()
{
  // (the arrays attach() keeps for this pair style stay with the Python process: a pair style made later at
  // the same address replaces them; no Python call here, which may run while the interpreter finalizes)
  if (fix && modify->get_fix_by_id(FIX_ID)) {
    fix->keeper = nullptr;
    modify->delete_fix(FIX_ID);
  }
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
  }
}

void PairDemContact::allocate()
{
  allocated = 1;
  int n = atom->ntypes;
  memory->create(setflag, n + 1, n + 1, "pair:setflag");
  memory->create(cutsq, n + 1, n + 1, "pair:cutsq");
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) setflag[i][j] = 0;
}

// pair_style dem/contact vmax V [slots N] [frame_spin yes|no] [rmax R] [energy yes|no]
void PairDemContact::settings(int narg, char **arg)
{
  vmax = 0.0;
  rmax = 0.0;
  energy = 0;
  for (int k = 0; k < narg; k += 2) {
    std::string key = arg[k];
    if (k + 1 >= narg) error->all(FLERR, "pair_style dem/contact: keyword {} needs a value", key);
    if (key == "vmax")
      vmax = utils::numeric(FLERR, arg[k + 1], false, lmp);
    else if (key == "slots")
      slots = utils::inumeric(FLERR, arg[k + 1], false, lmp);
    else if (key == "frame_spin")
      frame_spin = utils::logical(FLERR, arg[k + 1], false, lmp);
    else if (key == "rmax")
      rmax = utils::numeric(FLERR, arg[k + 1], false, lmp);
    else if (key == "energy")
      energy = utils::logical(FLERR, arg[k + 1], false, lmp);
    else
      error->all(FLERR, "pair_style dem/contact: unknown keyword {} (valid: vmax, slots, frame_spin, rmax, energy)",
                 key);
  }
  if (!(vmax > 0.0) || !std::isfinite(vmax))
    error->all(FLERR,
               "pair_style dem/contact needs vmax V: the largest normal impact speed of the run [m/s], finite and "
               "> 0 (the time step is checked against the contact time at that speed)");
  if (!(rmax >= 0.0) || !std::isfinite(rmax))
    error->all(FLERR, "pair_style dem/contact: rmax (the largest radius atoms reach in the run) must be finite and "
                      ">= 0 [m], got {}", rmax);
  if (slots < 1 || slots > 1000)
    error->all(FLERR, "pair_style dem/contact: slots (history rows per atom) must be in [1, 1000], got {}", slots);
}

void PairDemContact::attach_table(const char *path)
{
  attached = false;    // (until the table is read: a failed pair_coeff leaves no table)
  std::memset(&kernel, 0, sizeof(kernel));
  kernel.abi = ABI;
#ifdef DEM_CONTACT_AOT
  // (the step compiled ahead of time: no Python)
  std::string wrong = dem_contact_aot_attach(path, atom->ntypes, kernel, aot_table);
  if (!wrong.empty()) error->all(FLERR, "pair dem/contact: {}", wrong);
  attached = true;
  return;
#endif
  std::string code = "import dem_contact.lammps.pair_kernel as k\nk.attach(" + DemContact::python_text(path) + ", " +
      std::to_string(atom->ntypes) + ", " + std::to_string((uintptr_t) &kernel) + ")\n";
  std::string failed = DemContact::run_python(code);
  if (!failed.empty())
    error->one(FLERR, "pair dem/contact: dem_contact cannot be reached from this LAMMPS: {}", failed);
  if (kernel.error[0]) error->all(FLERR, "pair dem/contact: {}", kernel.error);
  attached = true;
}

// pair_coeff * * TABLE_FILE
void PairDemContact::coeff(int narg, char **arg)
{
  if (narg != 3 || strcmp(arg[0], "*") != 0 || strcmp(arg[1], "*") != 0)
    error->all(FLERR, "pair_coeff for dem/contact is: pair_coeff * * TABLE_FILE (one table for every pair of types)");
  if (!allocated) allocate();
  table_path = arg[2];
  if (comm->me == 0)
#ifdef DEM_CONTACT_AOT
    utils::logmesg(lmp, "pair dem/contact: reading {} (the step of its laws compiled ahead of time)\n", table_path);
#else
    utils::logmesg(lmp,
                   "pair dem/contact: reading {} and loading the compiled step of its laws (compiled at the first "
                   "run in this environment, up to a minute, then cached)\n",
                   table_path);
#endif
  attach_table(arg[2]);
  int n = atom->ntypes;
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) setflag[i][j] = 1;
  if (comm->me == 0) utils::logmesg(lmp, "pair dem/contact: {} from {}\n", kernel.laws, table_path);
  history_fix();
}

// the fix that keeps the contact rows in the atoms: made by pair_coeff (so that an input refers to its energy
// before the first run: f_DEM_CONTACT_HISTORY), or found (a second pair_coeff)
void PairDemContact::history_fix()
{
  row_size = (int) kernel.history_size + (energy ? N_EXTRA : 0);
  auto existing = modify->get_fix_by_id(FIX_ID);
  if (existing) {
    fix = dynamic_cast<FixDemContactHistory *>(existing);
    if (!fix || fix->slots != slots || fix->history_size != row_size)
      error->all(FLERR,
                 "pair dem/contact: the contact rows (fix {}) were made for other slots, energy or table laws: keep "
                 "them for the whole simulation, or give pair_style none first to start the contacts anew",
                 FIX_ID);
  } else {
    fix = dynamic_cast<FixDemContactHistory *>(
        modify->add_fix(fmt::format("{} all DEM/CONTACT/HISTORY {} {} {}", FIX_ID, slots, row_size, energy)));
  }
  fix->keeper = this;
}

void PairDemContact::init_style()
{
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR,
               "pair dem/contact needs atoms with radius, per-atom mass, spin and torque: use atom_style sphere");
  if (strcmp(update->unit_style, "si") != 0)
    error->all(FLERR, "pair dem/contact works in SI units: use units si (not {})", update->unit_style);
  if (!comm->ghost_velocity)
    error->all(FLERR, "pair dem/contact needs the velocities of ghost atoms: add comm_modify vel yes");
  if (!attached) error->all(FLERR, "pair dem/contact: no table file; give pair_coeff * * TABLE_FILE");

  // sizes that may change at any step, not only where LAMMPS rebuilds its lists: then a list of the types'
  // cutoffs (their largest radii, rmax, + skin), as a size list (the atoms' radii at the build + skin) would
  // leave out a pair that grew into contact between builds
  radii_change = !modify->get_fix_by_style("^adapt").empty();
  neighbor->add_request(this, (radii_change ? 0 : NeighConst::REQ_SIZE) | NeighConst::REQ_NEWTON_OFF);
  history_fix();

  // the per-contact output at the steps where a compute reads it
  readers = modify->get_compute_by_style("^dem/contact/local$");
  check_atoms();
  check_time_step();
}

// every atom has its type's density (and its type's radius, where the laws do not take other sizes)
void PairDemContact::check_atoms()
{
  int nlocal = atom->nlocal, ntypes = atom->ntypes;
  double *radius = atom->radius, *rmass = atom->rmass;
  int *type = atom->type;
  int bad = 0, bad_type = 0;
  double bad_r = 0.0, bad_m = 0.0;
  std::vector<double> local_max(ntypes + 1, 0.0);
  for (int i = 0; i < nlocal; i++) {
    int t = type[i] - 1;
    double r0 = kernel.type_size[2 * t], m0 = kernel.type_size[2 * t + 1];
    double rho = 3.0 * m0 / (4.0 * M_PI * r0 * r0 * r0);
    double m = rho * 4.0 / 3.0 * M_PI * radius[i] * radius[i] * radius[i];
    bool wrong_r = !kernel.size_free && std::fabs(radius[i] - r0) > SIZE_TOL * r0;
    if (wrong_r || !(std::fabs(rmass[i] - m) <= SIZE_TOL * m)) {
      if (!bad) {
        bad_type = t + 1;
        bad_r = radius[i];
        bad_m = rmass[i];
      }
      bad++;
    }
    local_max[t + 1] = std::max(local_max[t + 1], radius[i]);
  }
  int all_bad;
  MPI_Allreduce(&bad, &all_bad, 1, MPI_INT, MPI_SUM, world);
  if (bad)
    error->one(FLERR,
               "pair dem/contact: {} atoms here are not of their type's material and size (one of type {}: radius {} "
               "m, mass {} kg); type k is the table's sphere k: its density{}. Set the masses from the density "
               "(set type k density RHO) or write the table for these atoms",
               bad, bad_type, bad_r, bad_m,
               kernel.size_free ? "" : " and radius (the laws of this table take no other radius)");
  if (all_bad) error->all(FLERR, "pair dem/contact: atoms not of their type's material and size on another rank");
  type_rmax.assign(ntypes + 1, 0.0);
  MPI_Allreduce(local_max.data(), type_rmax.data(), ntypes + 1, MPI_DOUBLE, MPI_MAX, world);
  for (int t = 1; t <= ntypes; t++) {
    type_rmax[t] = std::max(type_rmax[t], std::max(kernel.type_size[2 * (t - 1)], rmax));
    // atoms a fix inserts (fix pour, fix deposit) reach the radius it reports
    // (extract's second argument: the atom type asked about, as pair granular asks)
    for (auto &f : modify->get_fix_list()) {
      int itype = t;
      auto r = (double *) f->extract("radius", itype);
      if (r) type_rmax[t] = std::max(type_rmax[t], *r);
    }
  }
}

// dt <= t_c / MIN_STEPS_PER_CONTACT for the stiffest pair of types at vmax, with the smallest atoms of each type
void PairDemContact::check_time_step()
{
  int ntypes = atom->ntypes, nlocal = atom->nlocal;
  std::vector<double> small(2 * ntypes, INFINITY), all(2 * ntypes);
  for (int i = 0; i < nlocal; i++) {
    int t = atom->type[i] - 1;
    small[2 * t] = std::min(small[2 * t], atom->radius[i]);
    small[2 * t + 1] = std::min(small[2 * t + 1], atom->rmass[i]);
  }
  MPI_Allreduce(small.data(), all.data(), 2 * ntypes, MPI_DOUBLE, MPI_MIN, world);
  double tc_min = INFINITY;
  int worst_a = 0, worst_b = 0;
  for (int a = 0; a < ntypes; a++)
    for (int b = a; b < ntypes; b++) {
      int row = (int) kernel.sphere_row[a * ntypes + b];
      double ra = std::min(all[2 * a], kernel.type_size[2 * a]), rb = std::min(all[2 * b], kernel.type_size[2 * b]);
      double ma = std::min(all[2 * a + 1], kernel.type_size[2 * a + 1]);
      double mb = std::min(all[2 * b + 1], kernel.type_size[2 * b + 1]);
      double rs = ra * rb / (ra + rb), ms = ma * mb / (ma + mb);
      double q_row = kernel.rowinfo[row * N_ROWINFO + RI_Q];
      double tc = kernel.tc_unit[row] * std::pow(vmax, -kernel.alpha[row]) * std::pow(ms * ms / rs / q_row, 0.2);
      if (tc < tc_min) {
        tc_min = tc;
        worst_a = a + 1;
        worst_b = b + 1;
      }
    }
  if (update->dt > tc_min / MIN_STEPS_PER_CONTACT)
    error->all(FLERR,
               "pair dem/contact: the time step {} s gives {:.3g} steps per contact time of types {} and {} at vmax = "
               "{} m/s ({:.4g} s), fewer than {}: use timestep {:.4g} or smaller",
               update->dt, tc_min / update->dt, worst_a, worst_b, vmax, tc_min, MIN_STEPS_PER_CONTACT,
               tc_min / MIN_STEPS_PER_CONTACT);
}

// contact time of atoms a and b at normal speed vn (the row's, scaled by m*^2 / R* as Hertz's: Johnson 1985,
// Contact Mechanics, eq. 11.24)
double PairDemContact::contact_time(int a, int b, double vn)
{
  int ta = atom->type[a] - 1, tb = atom->type[b] - 1;
  int row = (int) kernel.sphere_row[ta * kernel.n_types + tb];
  double *radius = atom->radius, *rmass = atom->rmass;
  double rs = radius[a] * radius[b] / (radius[a] + radius[b]);
  double ms = rmass[a] * rmass[b] / (rmass[a] + rmass[b]);
  double q_row = kernel.rowinfo[row * N_ROWINFO + RI_Q];
  return kernel.tc_unit[row] * std::pow(vn, -kernel.alpha[row]) * std::pow(ms * ms / rs / q_row, 0.2);
}

// a contact that began faster than vmax: an error where the time step does not resolve it, else a warning
void PairDemContact::check_onset(double vn, int a, int b)
{
  double steps = contact_time(a, b, vn) / update->dt;
  if (steps < MIN_STEPS_PER_CONTACT)
    error->one(FLERR,
               "pair dem/contact: atoms {} and {} began a contact at a normal speed of {:.4g} m/s, above vmax = {} "
               "m/s, which the time step resolves with {:.3g} steps per contact time, fewer than {}: give "
               "pair_style dem/contact the vmax that is reached, and a time step that resolves it",
               atom->tag[a], atom->tag[b], vn, vmax, steps, MIN_STEPS_PER_CONTACT);
  if (!warned_onset) {
    error->warning(FLERR,
                   "pair dem/contact: atoms {} and {} began a contact at a normal speed of {:.4g} m/s, above vmax = "
                   "{} m/s (resolved with {:.3g} steps per contact time): the checks assume vmax; give the vmax that "
                   "is reached",
                   atom->tag[a], atom->tag[b], vn, vmax, steps);
    warned_onset = true;
  }
}

// the overlap of a head-on impact at vmax (Johnson 1985, Contact Mechanics, eq. 11.23: (m*^2 / R*)^(1/5))
double PairDemContact::deepest(const double *info, double vmax, double rs, double ms)
{
  return info[RI_DEEPEST] * std::pow(vmax, info[RI_DEEP_ALPHA]) * std::pow(ms * ms / rs / info[RI_Q], 0.2);
}

void PairDemContact::tell_deep(LAMMPS *lmp, const std::string &who, int count, double worst, double vmax)
{
  int total = 0;
  double all_worst = 0.0;
  MPI_Allreduce(&count, &total, 1, MPI_INT, MPI_SUM, lmp->world);
  MPI_Allreduce(&worst, &all_worst, 1, MPI_DOUBLE, MPI_MAX, lmp->world);
  if (total && lmp->comm->me == 0)
    lmp->error->warning(FLERR,
                        "{}: {} contacts start with an overlap deeper than a head-on impact at vmax = {} m/s would "
                        "press them (up to {:.3g} times that overlap): their first contact force releases the energy "
                        "of the overlap; place the atoms apart, or give the vmax that reaches it",
                        who, total, vmax, all_worst);
}

// at the first set-up: a warning where contacts start deeper than a head-on impact at vmax would press them
// (their first force releases the energy of that overlap)
void PairDemContact::check_deep(int64_t n)
{
  const int nlocal = atom->nlocal;
  double *radius = atom->radius, *rmass = atom->rmass;
  int count = 0;
  double worst = 0.0;
  for (int64_t k = 0; k < n; k++) {
    const int a = (int) pairs[2 * k], b = (int) pairs[2 * k + 1];
    if (a >= nlocal) continue;    // (counted by the rank that owns atom a)
    const int row = (int) kernel.sphere_row[(atom->type[a] - 1) * kernel.n_types + atom->type[b] - 1];
    const double rs = radius[a] * radius[b] / (radius[a] + radius[b]);
    const double ms = rmass[a] * rmass[b] / (rmass[a] + rmass[b]);
    const double ratio = out[(size_t) N_OUT * k + OUT_DELTA] /
        deepest(kernel.rowinfo + (size_t) row * N_ROWINFO, vmax, rs, ms);
    if (ratio > 1.0) {
      count++;
      worst = std::max(worst, ratio);
    }
  }
  tell_deep(lmp, "pair dem/contact", count, worst, vmax);
}

// no atom larger than the radius its type's contacts are searched for (the neighbour cutoff), nor, where the
// laws take no other radius, of another radius than its type's
void PairDemContact::check_grown(int nlocal)
{
  double *radius = atom->radius;
  int *type = atom->type;
  for (int i = 0; i < nlocal; i++) {
    if (radius[i] > type_rmax[type[i]] * (1.0 + 1e-12))
      error->one(FLERR,
                 "pair dem/contact: atom {} (type {}) has grown to a radius of {} m, larger than the {} m its type's "
                 "contacts are searched for (the neighbour cutoff, set at the run's start): give pair_style "
                 "dem/contact rmax R with the largest radius the run reaches (fix adapt, fix pour)",
                 atom->tag[i], type[i], radius[i], type_rmax[type[i]]);
    const double r0 = kernel.type_size[2 * (type[i] - 1)];
    if (!kernel.size_free && std::fabs(radius[i] - r0) > SIZE_TOL * r0)
      error->one(FLERR,
                 "pair dem/contact: atom {} (type {}) has a radius of {} m during the run, its type's is {} m, and "
                 "the laws of this table take no other radius (a fix adapt?)",
                 atom->tag[i], type[i], radius[i], r0);
  }
}

double PairDemContact::init_one(int i, int j)
{
  if (!allocated || setflag[i][j] == 0)
    error->all(FLERR, "pair dem/contact: no table file; give pair_coeff * * TABLE_FILE");
  double cut = type_rmax[i] + type_rmax[j];
  return cut;
}

// the row of local atom i keyed `key` (-1: none)
int PairDemContact::row_of(int i, double key) const
{
  const double *k = fix->keys[i];
  for (int s = 0; s < slots; s++)
    if (k[s] == key) return s;
  return -1;
}

// a row of the pool for a contact of atoms i (local) and j (j_local: j, or the local atom a ghost j is the
// image of, or -1) that begins or is read from the atoms' rows: a free one, else a new one (the pool may move:
// rows are addressed by their index)
int32_t PairDemContact::take_row(int i, int j, int j_local)
{
  int32_t r;
  if (!free_rows.empty()) {
    r = free_rows.back();
    free_rows.pop_back();
  } else {
    if (pairing.size() >= (size_t) INT32_MAX)
      error->one(FLERR, "pair dem/contact: more than {} contacts on one rank: run on more ranks", INT32_MAX);
    r = (int32_t) pairing.size();
    pairing.emplace_back();
    if (live.size() < pairing.size() * row_size) live.resize(2 * pairing.size() * row_size + 64 * row_size);
  }
  std::memset(live.data() + (size_t) r * row_size, 0, sizeof(double) * row_size);
  pairing[r] = {i, j_local, atom->tag[i], atom->tag[j]};
  return r;
}

// the contact of pool row r ended at overlap delta_end (a gap, <= 0): the energy it dissipated given half to
// each of its local atoms (the rank of a partner that is a ghost here gives it the other half), the row freed
void PairDemContact::end_row(int32_t r, double delta_end)
{
  if (energy) {
    const double half = 0.5 * ended_work(live.data() + (size_t) r * row_size, row_size, delta_end);
    fix->dissipated[pairing[r].i] += half;
    if (pairing[r].j >= 0) fix->dissipated[pairing[r].j] += half;
  }
  pairing[r].ti = 0;
  free_rows.push_back(r);
}

// At a list build (a run's set-up, or a step where LAMMPS built its lists anew): the contacts of the atoms'
// rows (written by store_rows before the atoms moved, or read from a restart file) taken into the pool, by
// neighbour-list entry of a pair that touches now. A row that no such entry takes ended where its atoms moved
// apart (the energy it dissipated given to its atom, half, from the overlap now: the closest image of its
// partner, if here).
void PairDemContact::load_rows()
{
  // (rows a step wrote that no move asked for yet: the atoms are still where the pool's contacts were found)
  fix->refresh();
  const int nlocal = atom->nlocal;
  loaded_nlocal = nlocal;
  double **x = atom->x, *radius = atom->radius;
  double *special_lj = force->special_lj;
  const int inum = list->inum;
  int *ilist = list->ilist, *numneigh = list->numneigh, **firstneigh = list->firstneigh;
  tagint *tag = atom->tag;
  entry_start.resize(inum + 1);
  entry_start[0] = 0;
  for (int ii = 0; ii < inum; ii++) entry_start[ii + 1] = entry_start[ii] + numneigh[ilist[ii]];
  entry_row.assign(entry_start[inum], -1);
  find_twins(nlocal, nlocal + atom->nghost);
  pairing.clear();
  free_rows.clear();
  claimed.assign((size_t) nlocal * slots, 0);
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const int *jlist = firstneigh[i];
    for (int jj = 0; jj < numneigh[i]; jj++) {
      const int64_t e = entry_start[ii] + jj;
      if (entry_row[e] == TWIN) continue;
      if (special_lj[sbmask(jlist[jj])] == 0.0) continue;    // (excluded pairs: no contacts)
      const int j = jlist[jj] & NEIGHMASK;
      const int jl = j < nlocal ? j : entry_local[e];
      // only pairs that touch now continue a contact (a row of a pair apart: ended, below)
      const double dx = x[j][0] - x[i][0], dy = x[j][1] - x[i][1], dz = x[j][2] - x[i][2];
      const double rs = radius[i] + radius[j];
      if (dx * dx + dy * dy + dz * dz >= rs * rs) continue;
      // the contact's row: atom i's, else (i came from another rank, or had none) atom j's (or that of the
      // local atom it is the image of)
      int owner = i, s = row_of(i, (double) tag[j]);
      if (s < 0 && jl >= 0) {
        owner = jl;
        s = row_of(jl, (double) tag[i]);
      }
      if (s < 0) continue;
      if (claimed[(size_t) owner * slots + s])
        error->one(FLERR,
                   "pair dem/contact: atom {} touches two images of atom {} through a periodic boundary: the box is "
                   "narrower than two diameters along a periodic direction; make it wider",
                   tag[i], tag[j]);
      claimed[(size_t) owner * slots + s] = 1;
      // (both atoms here: the partner's copy is the same contact)
      const int other = owner == i ? jl : i;
      if (other >= 0) {
        const int t = row_of(other, (double) tag[owner]);
        if (t >= 0) claimed[(size_t) other * slots + t] = 1;
      }
      const int32_t r = take_row(i, j, jl);
      std::memcpy(live.data() + (size_t) r * row_size, fix->hist + ((size_t) owner * slots + s) * row_size,
                  sizeof(double) * row_size);
      entry_row[e] = r;
    }
  }
  // rows no entry took: ended. Every row is free now (the pool holds the contacts until store_rows)
  for (int i = 0; i < nlocal; i++) {
    double *k = fix->keys[i];
    for (int s = 0; s < slots; s++) {
      if (k[s] == 0.0) continue;
      if (energy && !claimed[(size_t) i * slots + s]) {
        const tagint partner = (tagint) k[s];
        double delta_end = 0.0;
        int j = atom->map_style != Atom::MAP_NONE ? atom->map(partner) : -1;
        if (j >= 0) {
          j = domain->closest_image(i, j);
          double **x = atom->x;
          const double dx = x[j][0] - x[i][0], dy = x[j][1] - x[i][1], dz = x[j][2] - x[i][2];
          delta_end = std::min(0.0, atom->radius[i] + atom->radius[j] - std::sqrt(dx * dx + dy * dy + dz * dz));
        }
        fix->dissipated[i] += 0.5 * ended_work(fix->hist + ((size_t) i * slots + s) * row_size, row_size, delta_end);
      }
      k[s] = 0.0;
    }
  }
}

// Periodic twins (pair_dem_contact.h): each entry (i, ghost j) whose ghost is the image of a local atom j0 whose
// own entries have the image of i. Of the two, the entry whose atom i has the higher id is not evaluated
// (entry_row TWIN); the other's entry_local is j0.
void PairDemContact::find_twins(int nlocal, int nall)
{
  const int inum = list->inum;
  entry_local.assign(entry_start[inum], -1);
  // (only along a periodic direction that this rank spans alone)
  bool spanned = false;
  for (int d = 0; d < 3; d++) spanned = spanned || (domain->periodicity[d] && comm->procgrid[d] == 1);
  if (!spanned) return;
  int *ilist = list->ilist, *numneigh = list->numneigh, **firstneigh = list->firstneigh;
  tagint *tag = atom->tag;
  // the local atom of each ghost's id, if any: by LAMMPS's atom map (which points at the local copy of an id), or
  // without one by the local atoms sorted by id
  std::vector<int> image_of(nall - nlocal, -1);
  std::vector<std::pair<tagint, int>> by_id;
  const bool mapped = atom->map_style != Atom::MAP_NONE;
  if (!mapped) {
    by_id.reserve(nlocal);
    for (int i = 0; i < nlocal; i++) by_id.emplace_back(tag[i], i);
    std::sort(by_id.begin(), by_id.end());
  }
  std::vector<char> listed(nlocal, 0);
  bool any = false;
  for (int g = nlocal; g < nall; g++) {
    int k = -1;
    if (mapped) {
      k = atom->map(tag[g]);
    } else {
      auto at = std::lower_bound(by_id.begin(), by_id.end(), std::make_pair(tag[g], -1));
      if (at != by_id.end() && at->first == tag[g]) k = at->second;
    }
    if (k >= 0 && k < nlocal) {
      image_of[g - nlocal] = k;
      any = true;
    }
  }
  if (!any) return;
  for (int ii = 0; ii < inum; ii++) listed[ilist[ii]] = 1;
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const int *jlist = firstneigh[i];
    for (int jj = 0; jj < numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      if (j < nlocal || image_of[j - nlocal] < 0 || tag[j] == tag[i]) continue;
      const int j0 = image_of[j - nlocal];
      if (!listed[j0]) continue;
      bool twin = false;
      const int *klist = firstneigh[j0];
      for (int kk = 0; kk < numneigh[j0] && !twin; kk++) {
        const int k = klist[kk] & NEIGHMASK;
        twin = k >= nlocal && image_of[k - nlocal] == i;
      }
      if (!twin) continue;
      const int64_t e = entry_start[ii] + jj;
      if (tag[i] < tag[j])
        entry_local[e] = j0;
      else
        entry_row[e] = TWIN;
    }
  }
}

// the pool's contacts written into the rows of their local atoms (both, where both are here), as the fix asks
// before atoms move (RowKeeper): the atoms are where the list was built
void PairDemContact::store_rows()
{
  fill.assign(atom->nmax, 0);
  // (the atoms of the pool's contacts: those here when it was loaded; atoms that came since keep their rows)
  for (int i = 0; i < loaded_nlocal && i < atom->nlocal; i++) std::memset(fix->keys[i], 0, sizeof(double) * slots);
  for (size_t r = 0; r < pairing.size(); r++) {
    const Pairing &w = pairing[r];
    if (w.ti == 0) continue;
    for (int side = 0; side < 2; side++) {
      const int i = side ? w.j : w.i;
      if (i < 0) continue;
      const tagint partner = side ? w.ti : w.tj;
      if (fill[i] >= slots)
        error->one(FLERR,
                   "pair dem/contact: atom {} has more than {} contacts at once: give pair_style dem/contact a "
                   "larger slots N (history rows per atom)",
                   side ? w.tj : w.ti, slots);
      const int s = fill[i]++;
      fix->keys[i][s] = (double) partner;
      std::memcpy(fix->hist + ((size_t) i * slots + s) * row_size, live.data() + r * row_size,
                  sizeof(double) * row_size);
    }
  }
}

// at a run's set-up: the forces of the last step again, where every atom has them from this step (the last
// of the run before, also when read from a restart file) and none changed since (then a run continued in
// pieces, or from a restart file, is the one run); false where any did, on any rank
bool PairDemContact::reapply_saved()
{
  int nlocal = atom->nlocal;
  int ok = 1;
  double **x = atom->x, **v = atom->v, **omega = atom->omega, *radius = atom->radius, *rmass = atom->rmass;
  const double step = (double) update->ntimestep;
  // positions up to a period of the box (LAMMPS wraps atoms into it at a run's set-up) and its rounding
  const int *periodic = domain->periodicity;
  const double *prd = domain->prd;
  typedef FixDemContactHistory F;
  for (int i = 0; ok && i < nlocal; i++) {
    const double *s = fix->saved[i];
    ok = s[F::SF_STEP] == step && s[F::SF_R] == radius[i] && s[F::SF_M] == rmass[i];
    for (int d = 0; ok && d < 3; d++) {
      double dx = x[i][d] - s[F::SF_X + d];
      if (periodic[d] && !domain->triclinic) dx -= prd[d] * std::round(dx / prd[d]);
      ok = std::fabs(dx) <= 1e-13 * (prd[d] + std::fabs(x[i][d])) && s[F::SF_V + d] == v[i][d] &&
          s[F::SF_W + d] == omega[i][d];
    }
  }
  int all;
  MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, world);
  return all != 0;
}

// the atoms with contact rows have the ids they had at the end of the last run: the rows are keyed by the
// partners' ids, which reset_atoms id (or a restart file of atoms renumbered otherwise) would give to others
void PairDemContact::check_ids(int nlocal)
{
  tagint *tag = atom->tag;
  typedef FixDemContactHistory F;
  tagint moved = 0;
  for (int i = 0; i < nlocal && !moved; i++) {
    const double id = fix->saved[i][F::SF_ID];
    if (id == 0.0 || id == (double) tag[i]) continue;
    for (int s = 0; s < slots; s++)
      if (fix->keys[i][s] != 0.0) {
        moved = tag[i];
        break;
      }
  }
  tagint any = 0;
  MPI_Allreduce(&moved, &any, 1, MPI_LMP_TAGINT, MPI_MAX, world);
  if (!any)
    for (int i = 0; i < nlocal; i++) fix->saved[i][F::SF_ID] = (double) tag[i];
  if (any)
    error->all(FLERR,
               "pair dem/contact: atom {} has contacts and had another id at the end of the last run: the contact "
               "histories are keyed by the partners' atom ids, which changed (reset_atoms id, delete_atoms ... "
               "compress yes, replicate?): renumber atoms before their first run only",
               any);
}

void PairDemContact::save_forces(int nlocal)
{
  double **x = atom->x, **v = atom->v, **omega = atom->omega;
  typedef FixDemContactHistory F;
  for (int i = 0; i < nlocal; i++) {
    double *s = fix->saved[i];
    for (int d = 0; d < 6; d++) s[d] = acc[6 * i + d];
    for (int d = 0; d < 3; d++) {
      s[F::SF_X + d] = x[i][d];
      s[F::SF_V + d] = v[i][d];
      s[F::SF_W + d] = omega[i][d];
    }
    s[F::SF_R] = atom->radius[i];
    s[F::SF_M] = atom->rmass[i];
    s[F::SF_STEP] = (double) update->ntimestep;
  }
}

bool PairDemContact::output_due() const
{
  for (auto c : readers)
    if (c->matchstep(update->ntimestep)) return true;
  return false;
}

// The entries of LAMMPS's half list whose pairs touch (tc[0, returned)), and those of contacts that ended, whose
// pairs are apart now (tc[q, entries), q set, in the list's reverse order): a lean pass, as most entries of a
// loose scene are apart (a function of its own, whose few values stay in registers)
__attribute__((noinline)) int64_t PairDemContact::find_touching(int inum, const int *ilist, const int *numneigh,
                                                                int *const *firstneigh, const int64_t *entry_start,
                                                                const int32_t *entry_row, double *const *x,
                                                                const double *radius, const double *special_lj,
                                                                Touch *tc, int64_t &q)
{
  int64_t m = 0;
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const int *jlist = firstneigh[i];
    const int jnum = numneigh[i];
    const int64_t e0 = entry_start[ii];
    const int32_t *at = entry_row + e0;
    const double xi = x[i][0], yi = x[i][1], zi = x[i][2], ri = radius[i];
    for (int jj = 0; jj < jnum; jj++) {
      const int32_t e = at[jj];
      if (e == TWIN) continue;    // (its twin entry evaluates the pair)
      int j = jlist[jj];
      if (j & ~NEIGHMASK) {
        if (special_lj[j >> SBBITS & 3] == 0.0) continue;    // excluded pairs (special_bonds lj 0), as pair granular
        j &= NEIGHMASK;
      }
      const double dx = x[j][0] - xi, dy = x[j][1] - yi, dz = x[j][2] - zi;
      const double rs = ri + radius[j], r2 = dx * dx + dy * dy + dz * dz;
      // (written whether the pair touches or not, kept where it does: no branch to mispredict)
      const int touch = r2 < rs * rs;
      tc[m] = {i, j, e0 + jj};
      m += touch;
      if ((e >= 0) & !touch) tc[--q] = {i, j, e0 + jj};
    }
  }
  return m;
}

void PairDemContact::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  const int hs = row_size;
  const bool setup = update->setupflag != 0;
  tagint *tag = atom->tag;
  double **x = atom->x, *radius = atom->radius;
  double **f = atom->f, **torque = atom->torque;
  double *special_lj = force->special_lj;
  const bool reapply = setup && reapply_saved();
  // (a set-up that reapplies the last step's forces keeps that step's recorded contacts, which a compute reads at
  // it)
  reapplied = reapply;

  if (setup) check_ids(nlocal);
  fix->setup_only = setup;
  // the contacts' histories by list entry, taken from the atoms' rows where LAMMPS built its lists (or a run
  // begins); the atoms' rows are stale from this step on (the fix asks store_rows for them)
  if (setup || neighbor->ago == 0) load_rows();
  fix->stale = true;

  tagint self_image = 0;
  double fastest = 0.0;
  int fastest_a = -1, fastest_b = -1;
  const int inum = list->inum;
  int *ilist = list->ilist, *numneigh = list->numneigh, **firstneigh = list->firstneigh;
  const int64_t entries = entry_start[inum];
  if (cap < entries + 1) {
    cap = entries + entries / 4 + 16;
    pairs.resize(2 * cap);
    to.resize(2 * cap);
    hrow.resize(cap);
    prow.resize(cap);
    inputs.resize(N_INPUTS * cap);
  }
  int64_t *pair_at = pairs.data(), *to_at = to.data(), *row_at = hrow.data(), *prow_at = prow.data();
  int32_t *entry_at = entry_row.data();
  // the law's inputs, blocks of cap contacts: normals, slip velocities and relative spins (3 each), overlaps,
  // spins of the contact frame about the normal
  double *normals = inputs.data(), *velocities = normals + 3 * cap, *spins = velocities + 3 * cap;
  double *overlaps = spins + 3 * cap, *wn = overlaps + cap;
  double **v = atom->v, **omega = atom->omega;
  const int *type = atom->type;
  const int64_t ntypes = kernel.n_types;
  const bool turning = kernel.turning != 0;
  // The pairs that touch, and the entries of contacts that ended
  if ((int64_t) touching.size() < entries + 1) touching.resize(entries + entries / 4 + 16);
  Touch *tc = touching.data();
  int64_t q = entries;
  const int64_t m = find_touching(inum, ilist, numneigh, firstneigh, entry_start.data(), entry_at, x, radius,
                                  special_lj, tc, q);
  // (contacts that ended, in the list's order: their energy accounted at the gap now)
  for (int64_t k = entries - 1; k >= q; k--) {
    const int i = tc[k].i, j = tc[k].j;
    const double dx = x[j][0] - x[i][0], dy = x[j][1] - x[i][1], dz = x[j][2] - x[i][2];
    end_row(entry_at[tc[k].e], radius[i] + radius[j] - std::sqrt(dx * dx + dy * dy + dz * dz));
    entry_at[tc[k].e] = -1;
  }
  int64_t n = 0;
  for (int64_t k = 0; k < m; k++) {
    const int i = tc[k].i, j = tc[k].j;
    int32_t &row = entry_at[tc[k].e];
    const int jl = j < nlocal ? j : entry_local[tc[k].e];    // (the local atom of j: itself, a twin's or -1)
    if (tag[i] == tag[j]) {
      self_image = tag[i];
      continue;
    }
    const int a = tag[i] < tag[j] ? i : j, b = tag[i] < tag[j] ? j : i;
    // (x_b - x_a, from the atoms in their canonical order: no branch on which of i, j is body 1)
    const double ex = x[b][0] - x[a][0], ey = x[b][1] - x[a][1], ez = x[b][2] - x[a][2];
    const double r2 = ex * ex + ey * ey + ez * ez;
    if (row < 0) {
      row = take_row(i, j, jl);
      // the normal speed a contact begins at (approach > 0)
      const double vn =
          ((v[a][0] - v[b][0]) * ex + (v[a][1] - v[b][1]) * ey + (v[a][2] - v[b][2]) * ez) / std::sqrt(r2);
      if (vn > fastest) {
        fastest = vn;
        fastest_a = a;
        fastest_b = b;
      }
    }
    pair_at[2 * n] = a;
    pair_at[2 * n + 1] = b;
    // (the local atoms that take the forces: a ghost's none, or for a periodic twin the atom it is the image of)
    to_at[2 * n] = a < nlocal ? a : jl;
    to_at[2 * n + 1] = b < nlocal ? b : jl;
    row_at[n] = row;
    prow_at[n] = kernel.sphere_row[(type[a] - 1) * ntypes + type[b] - 1];
    // The law's inputs, body 1 a: the unit normal from a to b, the overlap, the slip velocity with the full
    // radii v = v_a - v_b + (R_a w_a + R_b w_b) x n, the relative spin w_a - w_b, and the mean spin of the two
    // bodies about the normal (frame_spin no: 0)
    const double r = std::sqrt(r2), rinv = 1.0 / r;
    const double nx = ex * rinv, ny = ey * rinv, nz = ez * rinv;
    const double ra = radius[a], rb = radius[b];
    const double wx = ra * omega[a][0] + rb * omega[b][0], wy = ra * omega[a][1] + rb * omega[b][1],
                 wz = ra * omega[a][2] + rb * omega[b][2];
    double *nk = normals + 3 * n, *vk = velocities + 3 * n;
    nk[0] = nx;
    nk[1] = ny;
    nk[2] = nz;
    overlaps[n] = (ra + rb) - r;
    vk[0] = v[a][0] - v[b][0] + (wy * nz - wz * ny);
    vk[1] = v[a][1] - v[b][1] + (wz * nx - wx * nz);
    vk[2] = v[a][2] - v[b][2] + (wx * ny - wy * nx);
    if (turning)
      for (int d = 0; d < 3; d++) spins[3 * n + d] = omega[a][d] - omega[b][d];
    wn[n] = frame_spin ? 0.5 * ((omega[a][0] + omega[b][0]) * nx + (omega[a][1] + omega[b][1]) * ny +
                                (omega[a][2] + omega[b][2]) * nz)
                       : 0.0;
    n++;
  }
  if (self_image)
    error->one(FLERR,
               "pair dem/contact: atom {} touches itself through a periodic boundary: the box is narrower than two "
               "diameters along a periodic direction; make it wider",
               self_image);

  if (!setup && fastest > vmax) check_onset(fastest, fastest_a, fastest_b);

  out.resize((size_t) N_OUT * n + 1);
  double *H = live.data();
  int64_t h_rows = (int64_t) pairing.size();
  int64_t *rows = hrow.data();
  double dt = update->dt;
  if (setup) {
    // a set-up advances nothing: the law works on copies of the histories, with no time passing
    scratch.resize((size_t) n * hs + 1);
    scratch_rows.resize(n + 1);
    for (int64_t k = 0; k < n; k++) {
      std::memcpy(scratch.data() + k * hs, H + hrow[k] * hs, sizeof(double) * hs);
      scratch_rows[k] = k;
    }
    H = scratch.data();
    h_rows = n;
    rows = scratch_rows.data();
    dt = 0.0;
  }
  // per-contact parameter rows only where an atom here is not of its type's size (sizes change where LAMMPS
  // rebuilds its lists, at a run's set-up, or at any step under a fix adapt); no atom larger than the contact
  // search allows
  if (setup || neighbor->ago == 0 || radii_change) {
    check_grown(nlocal);
    sized = kernel.size_free && any_resized(nall);
  }
  if ((int64_t) work.size() < N_WORK * n + 1) work.resize(2 * N_WORK * n + 64);
  if (sized && (int64_t) pc.size() < (kernel.n_rows + n) * N_PARAMS) pc.resize((kernel.n_rows + 2 * n + 16) * N_PARAMS);
  // An ordinary step: the kernel adds the forces, torques and global virial to LAMMPS's. A run's set-up (whose
  // forces may be the saved ones), its last step (whose forces are saved), a per-atom virial or energy: the
  // per-contact output, added here. The contacts are recorded at a set-up (but one that reapplies the last
  // step's forces keeps that step's), a last step and where a compute dem/contact/local is invoked (the
  // per-contact output, and the forces added by the kernel).
  const bool last = !setup && update->ntimestep == update->laststep;
  const bool direct = !setup && !last && !vflag_atom && !eflag_atom && !cvflag_atom;
  const bool record = setup || last || output_due();
  int64_t flags = (direct ? SCATTER : WRITE_OUT) | (record ? WRITE_OUT : 0) | (direct && vflag_global ? VIRIAL : 0) |
      (energy ? ENERGY : 0);
  double vsum[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  auto step = (StepFn) kernel.step;
  double *in = inputs.data();
  int64_t bad = n ? step(n, pairs.data(), rows, H, h_rows, hs, in, in + 9 * cap, in + 3 * cap, in + 6 * cap,
                         in + 10 * cap, kernel.turning, x[0], radius, atom->rmass, atom->type, nall, kernel.params,
                         kernel.n_rows, kernel.rowinfo, kernel.type_size, kernel.n_types, sized, dt, out.data(),
                         work.data(), work.data() + 3 * n, work.data() + 6 * n, prow.data(),
                         sized ? pc.data() : const_cast<double *>(kernel.params), to.data(),
                         f[0], torque[0], flags, vsum)
                  : 0;
#ifdef DEM_CONTACT_AOT
  if (dem_contact_aot_raised) {
    dem_contact_aot_raised = 0;
    error->one(FLERR, "pair dem/contact: the step compiled ahead of time failed at step {} (told above); run the "
                      "same input with the plugin that reaches the package through Python for the message",
               update->ntimestep);
  }
#endif
  if (flags & VIRIAL)
    for (int d = 0; d < 6; d++) virial[d] += vsum[d];
  if (bad)
    error->one(FLERR,
               "pair dem/contact: {} contact forces are not finite at step {} (an overlap beyond the law's range, "
               "a time step too long for the contacts, or atoms placed inside each other)",
               bad, update->ntimestep);
  // the contacts of this step, recorded by their atoms' ids (a set-up that applies the forces it computed, a run's
  // last step, which a compute defined between runs reads, a step where a compute reads them)
  if (record && !reapply) {
    evaluated_step = update->ntimestep;
    rec_n = n;
    rec_ids.resize(3 * (size_t) n + 1);
    for (int64_t k = 0; k < n; k++) {
      const int64_t a = pairs[2 * k];
      rec_ids[3 * k] = tag[a];
      rec_ids[3 * k + 1] = tag[pairs[2 * k + 1]];
      rec_ids[3 * k + 2] = a < nlocal;
    }
    rec_out.assign(out.begin(), out.begin() + N_OUT * n);
  }
  if (setup && !deep_checked) {
    check_deep(n);
    deep_checked = true;
  }
  if (direct) return;
  acc.assign((size_t) 6 * nlocal + 1, 0.0);
  for (int64_t k = 0; k < n; k++) {
    const int a = (int) pairs[2 * k], b = (int) pairs[2 * k + 1];
    const int ta = (int) to[2 * k], tb = (int) to[2 * k + 1];
    const double *o = out.data() + N_OUT * k;
    if (ta >= 0) {
      double *c = acc.data() + 6 * ta;
      for (int d = 0; d < 3; d++) {
        c[d] += o[d];
        c[3 + d] += o[3 + d];
      }
    }
    if (tb >= 0) {
      double *c = acc.data() + 6 * tb;
      for (int d = 0; d < 3; d++) {
        c[d] -= o[d];
        c[3 + d] += o[6 + d];
      }
    }
    if (evflag)
      ev_tally_xyz(ta >= 0 ? ta : a, tb >= 0 ? tb : b, nlocal, 0, 0.0, 0.0, o[0], o[1], o[2], x[a][0] - x[b][0],
                   x[a][1] - x[b][1], x[a][2] - x[b][2]);
  }
  if (reapply) {
    for (int i = 0; i < nlocal; i++)
      for (int d = 0; d < 6; d++) acc[6 * i + d] = fix->saved[i][d];
  }
  for (int i = 0; i < nlocal; i++) {
    for (int d = 0; d < 3; d++) {
      f[i][d] += acc[6 * i + d];
      torque[i][d] += acc[6 * i + 3 + d];
    }
  }
  // (the forces a next run's set-up reapplies: at a run's last step)
  if (last) save_forces(nlocal);
}

// whether any of the nall atoms (local and ghost) has not its type's radius and mass (to 1e-12, as the kernel)
bool PairDemContact::any_resized(int nall)
{
  for (int i = 0; i < nall; i++) {
    int t = atom->type[i] - 1;
    double r0 = kernel.type_size[2 * t], m0 = kernel.type_size[2 * t + 1];
    if (std::fabs(atom->radius[i] - r0) > 1e-12 * r0 || std::fabs(atom->rmass[i] - m0) > 1e-12 * m0) return true;
  }
  return false;
}

double PairDemContact::memory_usage()
{
  return (double) (pairs.capacity() + to.capacity() + hrow.capacity()) * sizeof(int64_t) +
      (double) (entry_row.capacity() + free_rows.capacity()) * sizeof(int32_t) +
      (double) entry_local.capacity() * sizeof(int) + (double) touching.capacity() * sizeof(Touch) +
      (double) (inputs.capacity() + out.capacity() + scratch.capacity() + acc.capacity() + live.capacity() +
                rec_out.capacity()) * sizeof(double) +
      (double) pairing.capacity() * sizeof(Pairing) + (double) rec_ids.capacity() * sizeof(tagint);
}
