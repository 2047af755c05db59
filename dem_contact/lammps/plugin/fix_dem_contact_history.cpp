#include "fix_dem_contact_history.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "memory.h"
#include "update.h"

#include <cstring>

using namespace LAMMPS_NS;

// fix ID all DEM/CONTACT/HISTORY slots row_size energy (made by pair_style dem/contact and fix dem/contact/wall)
FixDemContactHistory::FixDemContactHistory(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), keys(nullptr), hist(nullptr), saved(nullptr), dissipated(nullptr), keeper(nullptr),
    stale(false), setup_only(false)
{
  if (narg != 6)
    error->all(FLERR, "fix DEM/CONTACT/HISTORY is made by pair_style dem/contact and fix dem/contact/wall only");
  slots = utils::inumeric(FLERR, arg[3], false, lmp);
  history_size = utils::inumeric(FLERR, arg[4], false, lmp);
  const int energy = utils::inumeric(FLERR, arg[5], false, lmp);
  if (slots < 1 || history_size < 1) error->all(FLERR, "fix DEM/CONTACT/HISTORY: bad sizes");
  restart_peratom = 1;
  create_attribute = 1;
  // the energy dissipated, per atom and in all, where it is accounted (energy yes; the scalar says so when asked)
  accounted = energy != 0;
  peratom_flag = energy;
  size_peratom_cols = 0;
  peratom_freq = 1;
  scalar_flag = 1;
  extscalar = 1;
  global_freq = 1;
  maxexchange = 1 + per_atom();    // (pack_exchange: the count of filled rows, and at most every slot)
  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nmax; i++) set_arrays(i);
}

FixDemContactHistory::~FixDemContactHistory()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(keys);
  memory->sfree(hist);
  memory->destroy(saved);
  memory->destroy(dissipated);
}

int FixDemContactHistory::setmask()
{
  return FixConst::PRE_EXCHANGE | FixConst::MIN_PRE_EXCHANGE | FixConst::END_OF_STEP;
}

// the end of a step whose forces were a set-up's: rerun (a run's steps compute their own), whose snapshots of a
// dump come without the motion between them that the contact histories follow
void FixDemContactHistory::end_of_step()
{
  if (setup_only)
    error->all(FLERR,
               "pair dem/contact: rerun is refused: the snapshots of a dump carry no contact histories and the "
               "histories cannot follow the motion between them; compute what you need during the run (dump, "
               "compute dem/contact/local, fix ave/time)");
}

// a step where LAMMPS builds its lists anew (atoms may move), in a run, a minimization or a run's set-up: the
// rows made current
void FixDemContactHistory::setup_pre_exchange() { refresh(); }
void FixDemContactHistory::pre_exchange() { refresh(); }
void FixDemContactHistory::min_pre_exchange() { refresh(); }

// after a run: the state the forces saved at its last step belong to is that at the end of the step, the
// velocities and spins after its final integration (the pair style saw those of the half step)
void FixDemContactHistory::post_run()
{
  refresh();
  const double step = (double) update->ntimestep;
  double **v = atom->v, **omega = atom->omega;
  for (int i = 0; i < atom->nlocal; i++) {
    if (saved[i][SF_STEP] == step)
      for (int d = 0; d < 3; d++) {
        saved[i][SF_V + d] = v[i][d];
        saved[i][SF_W + d] = omega[i][d];
      }
    saved[i][SF_ID] = (double) atom->tag[i];
  }
}

// the energy the ended contacts of all atoms dissipated [J]
double FixDemContactHistory::compute_scalar()
{
  if (!accounted)
    error->all(FLERR,
               "fix {}: the energy the contacts dissipated is accounted with pair_style dem/contact ... energy yes",
               id);
  double mine = 0.0, all = 0.0;
  for (int i = 0; i < atom->nlocal; i++) mine += dissipated[i];
  MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_SUM, world);
  return all;
}

double FixDemContactHistory::memory_usage()
{
  return (double) atom->nmax * per_atom() * sizeof(double);
}

void FixDemContactHistory::grow_arrays(int nmax)
{
  memory->grow(keys, nmax, slots, "dem/contact:keys");
  hist = (double *) memory->srealloc(hist, sizeof(double) * nmax * slots * history_size, "dem/contact:hist");
  memory->grow(saved, nmax, (int) N_SAVED, "dem/contact:saved");
  memory->grow(dissipated, nmax, "dem/contact:dissipated");
  vector_atom = dissipated;
}

void FixDemContactHistory::copy_arrays(int i, int j, int /*delflag*/)
{
  refresh();
  std::memcpy(keys[j], keys[i], sizeof(double) * slots);
  std::memcpy(hist + (size_t) j * slots * history_size, hist + (size_t) i * slots * history_size,
              sizeof(double) * slots * history_size);
  std::memcpy(saved[j], saved[i], sizeof(double) * N_SAVED);
  dissipated[j] = dissipated[i];
}

void FixDemContactHistory::set_arrays(int i)
{
  std::memset(keys[i], 0, sizeof(double) * slots);
  std::memset(hist + (size_t) i * slots * history_size, 0, sizeof(double) * slots * history_size);
  std::memset(saved[i], 0, sizeof(double) * N_SAVED);
  saved[i][SF_STEP] = -1.0;
  dissipated[i] = 0.0;
}

// an atom leaving for another rank: its filled contact rows only (their count, then each one's key and values),
// its saved state and the energy it was given
int FixDemContactHistory::pack_exchange(int i, double *buf)
{
  refresh();
  int m = 1, filled = 0;
  for (int s = 0; s < slots; s++) {
    if (keys[i][s] == 0.0) continue;
    buf[m++] = keys[i][s];
    std::memcpy(buf + m, hist + ((size_t) i * slots + s) * history_size, sizeof(double) * history_size);
    m += history_size;
    filled++;
  }
  buf[0] = filled;
  std::memcpy(buf + m, saved[i], sizeof(double) * N_SAVED);
  m += N_SAVED;
  buf[m++] = dissipated[i];
  return m;
}

int FixDemContactHistory::unpack_exchange(int i, double *buf)
{
  const int filled = (int) buf[0];
  int m = 1;
  std::memset(keys[i], 0, sizeof(double) * slots);
  for (int s = 0; s < filled; s++) {
    keys[i][s] = buf[m++];
    std::memcpy(hist + ((size_t) i * slots + s) * history_size, buf + m, sizeof(double) * history_size);
    m += history_size;
  }
  std::memcpy(saved[i], buf + m, sizeof(double) * N_SAVED);
  m += N_SAVED;
  dissipated[i] = buf[m++];
  return m;
}

// every slot of an atom (a restart file's layout): keys, rows, the saved state, the energy it was given
int FixDemContactHistory::pack_all(int i, double *buf)
{
  int m = 0;
  for (int s = 0; s < slots; s++) buf[m++] = keys[i][s];
  const double *h = hist + (size_t) i * slots * history_size;
  for (int q = 0; q < slots * history_size; q++) buf[m++] = h[q];
  for (int q = 0; q < N_SAVED; q++) buf[m++] = saved[i][q];
  buf[m++] = dissipated[i];
  return m;
}

void FixDemContactHistory::unpack_all(int i, const double *buf)
{
  int m = 0;
  for (int s = 0; s < slots; s++) keys[i][s] = buf[m++];
  double *h = hist + (size_t) i * slots * history_size;
  for (int q = 0; q < slots * history_size; q++) h[q] = buf[m++];
  for (int q = 0; q < N_SAVED; q++) saved[i][q] = buf[m++];
  dissipated[i] = buf[m++];
}

// restart data of an atom: its count, slots, history_size, then every slot (pack_all), with the id the atom had
// at the last run's set-up or end (SF_ID: atoms renumbered since are refused at the next run, after the file too)
int FixDemContactHistory::pack_restart(int i, double *buf)
{
  refresh();
  buf[1] = slots;
  buf[2] = history_size;
  int m = 3 + pack_all(i, buf + 3);
  buf[0] = m;
  return m;
}

void FixDemContactHistory::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  if ((int) extra[nlocal][m] != 3 + per_atom() && (int) extra[nlocal][m + 1] == slots &&
      (int) extra[nlocal][m + 2] == history_size)
    error->one(FLERR,
               "dem/contact: the restart file's contact rows ({}) are of another version of dem_contact's plugin "
               "({} values per atom, this one's {}): continue the run with the version that wrote it",
               id, (int) extra[nlocal][m], 3 + per_atom());
  if ((int) extra[nlocal][m + 1] != slots || (int) extra[nlocal][m + 2] != history_size)
    error->one(FLERR,
               "dem/contact: the restart file's contact rows ({}) have {} slots of {} values, this run's {} of {}: "
               "give pair_style dem/contact (or fix dem/contact/wall) the slots of the run that wrote it and the "
               "same table file",
               id, (int) extra[nlocal][m + 1], (int) extra[nlocal][m + 2], slots, history_size);
  unpack_all(nlocal, &extra[nlocal][m + 3]);
}

int FixDemContactHistory::size_restart(int /*nlocal*/) { return 3 + per_atom(); }

int FixDemContactHistory::maxsize_restart() { return 3 + per_atom(); }
