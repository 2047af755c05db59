#include "fix_dem_contact_wall.h"

#include "fix_dem_contact_history.h"
#include "pair_dem_contact.h"
#include "python_link.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "modify.h"
#include "update.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {
// the compiled wall step (wall_kernel.SIGNATURE)
typedef int64_t (*WallStepFn)(int64_t nlocal, double *x, double *v, double *omega, double *radius, double *rmass,
                              int *type, int *mask, int64_t groupbit, double *walls, int64_t wall_rows, double t,
                              int64_t mat, const double *params, int64_t n_rows, const int64_t *wall_row,
                              int64_t n_types, int64_t n_mats, const double *rowinfo, const double *type_size,
                              int64_t size_free, double *keys, double *H, int64_t slots, int64_t hs, double *saved,
                              double *dissipated, double dt, int64_t flags, double step_no, const double *box,
                              double *f, double *torque,
                              double *report, double *out, int64_t *out_atoms, int64_t out_cap);
// wall_kernel: ABI, the flags of a step, the report's columns, the box facts
const int ABI = 6;
const int64_t ADVANCE = 1, SAVE = 2, REAPPLY = 4, FRAME_SPIN = 8, ENERGY = 16;
enum { R_LOAD = 0, R_CONTACTS = 7, R_BAD = 8, R_OVERFLOW = 9, R_BEHIND = 10, R_FAST_V = 11, R_FAST_STEPS = 12,
       R_FAST_ATOM = 13, N_REPORT = 14 };
// contact_terms.RI_...: columns of the table's per-row information
const int RI_Q = 1, RI_TC = 2, RI_ALPHA = 3, RI_CURV = 5, N_ROWINFO = 7;
// as pair dem/contact: the fewest time steps per contact time
const double MIN_STEPS_PER_CONTACT = 10.0;

}    // namespace

FixDemContactWall::FixDemContactWall(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), evaluated_step(-1), history(nullptr), pair(nullptr), load_summed(false),
    warned_onset(false), deep_checked(false), n_out(0), clock_offset(0.0), clock_last(0.0),
    has_clock(0)
{
  for (int k = 3; k < narg; k++) words += (k > 3 ? "\n" : "") + std::string(arg[k]);
  vector_flag = 1;
  size_vector = 7;
  global_freq = 1;
  extvector = 1;
  restart_global = 1;
  dynamic_group_allow = 1;
  std::memset(report, 0, sizeof(report));
  std::memset(load_all, 0, sizeof(load_all));
  attach();
  // the wall's clock starts now: the pose given is the wall's when the fix is defined (as fix wall/gran's motions)
  clock_offset = -now();
  energy = pair->energy_on();
  row_size = (int) kernel.history_size + (energy ? PairDemContact::N_EXTRA : 0);
  history_id = std::string("DEM_CONTACT_WALL_") + id;
}

FixDemContactWall::~FixDemContactWall()
{
  if (history && modify->get_fix_by_id(history_id)) modify->delete_fix(history_id);
}

int FixDemContactWall::setmask() { return POST_FORCE; }

// the wall and the table of the pair style, read by dem_contact (wall_kernel.attach)
void FixDemContactWall::attach()
{
  pair = dynamic_cast<PairDemContact *>(force->pair_match("dem/contact", 1, 0));
  if (!pair || pair->table_file().empty())
    error->all(FLERR,
               "fix dem/contact/wall needs pair_style dem/contact and its pair_coeff * * TABLE_FILE before it (the "
               "wall's laws are the table's)");
  table_path = pair->table_file();
  std::memset(&kernel, 0, sizeof(kernel));
  kernel.abi = ABI;
#ifdef DEM_CONTACT_AOT
  // (the step compiled ahead of time: no Python)
  std::string wrong = dem_contact_aot_wall_attach(utils::split_lines(words), table_path, atom->ntypes, kernel, aot_wall);
  if (!wrong.empty()) error->all(FLERR, "fix {} dem/contact/wall: {}", id, wrong);
  if (comm->me == 0) utils::logmesg(lmp, "fix {} dem/contact/wall: {} (its step compiled ahead of time)\n", id,
                                    kernel.describe);
  return;
#endif
  std::string code = "import dem_contact.lammps.wall_kernel as k\nk.attach(" + DemContact::python_text(words) + ", " +
      DemContact::python_text(table_path) + ", " + std::to_string(atom->ntypes) + ", " +
      std::to_string((uintptr_t) &kernel) +
      ")\n";
  std::string failed = DemContact::run_python(code);
  if (!failed.empty())
    error->one(FLERR, "fix dem/contact/wall: dem_contact cannot be reached from this LAMMPS: {}", failed);
  if (kernel.error[0]) error->all(FLERR, "fix {} dem/contact/wall: {}", id, kernel.error);
  if (comm->me == 0) utils::logmesg(lmp, "fix {} dem/contact/wall: {}\n", id, kernel.describe);
}

// the contact rows of the wall's contacts, moving with the atoms (and read back from a restart file)
void FixDemContactWall::post_constructor()
{
  history = dynamic_cast<FixDemContactHistory *>(modify->add_fix(
      fmt::format("{} all DEM/CONTACT/HISTORY {} {} {}", history_id, kernel.slots, row_size, energy)));
}

void FixDemContactWall::init()
{
  auto p = dynamic_cast<PairDemContact *>(force->pair_match("dem/contact", 1, 0));
  if (!p)
    error->all(FLERR, "fix {} dem/contact/wall needs pair_style dem/contact (its table file gives the wall's laws)",
               id);
  if (p != pair || p->table_file() != table_path)
    error->all(FLERR,
               "fix {} dem/contact/wall: pair_style dem/contact was defined again, or read another table file, after "
               "the fix: define the fix again (unfix, fix) after the pair style",
               id);
  if (p->energy_on() != energy)
    error->all(FLERR,
               "fix {} dem/contact/wall was defined with pair_style dem/contact ... energy {}: define the fix again "
               "(unfix, fix) after changing energy",
               id, energy ? "yes" : "no");
  history = dynamic_cast<FixDemContactHistory *>(modify->get_fix_by_id(history_id));
  if (!history || history->slots != kernel.slots || history->history_size != row_size)
    error->all(FLERR, "fix {} dem/contact/wall: its contact rows (fix {}) are missing or of other sizes", id,
               history_id);
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "fix dem/contact/wall needs atoms with radius, per-atom mass, spin and torque: use "
                      "atom_style sphere");
  check_time_step();
}

// dt <= t_c / MIN_STEPS_PER_CONTACT for the wall's stiffest row at vmax, with the smallest atoms of each type
void FixDemContactWall::check_time_step()
{
  int ntypes = atom->ntypes, nlocal = atom->nlocal;
  std::vector<double> small(2 * ntypes, INFINITY), all(2 * ntypes);
  for (int i = 0; i < nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    int t = atom->type[i] - 1;
    small[2 * t] = std::min(small[2 * t], atom->radius[i]);
    small[2 * t + 1] = std::min(small[2 * t + 1], atom->rmass[i]);
  }
  MPI_Allreduce(small.data(), all.data(), 2 * ntypes, MPI_DOUBLE, MPI_MIN, world);
  const double vmax = pair->speed_limit();
  double tc_min = INFINITY;
  int worst = 0;
  for (int t = 0; t < ntypes; t++) {
    int row = (int) kernel.wall_row[t * kernel.n_mats + kernel.mat];
    const double *info = kernel.rowinfo + (size_t) row * N_ROWINFO;
    double r = std::min(all[2 * t], kernel.type_size[2 * t]), m = std::min(all[2 * t + 1], kernel.type_size[2 * t + 1]);
    double rs = info[RI_CURV] == 0.0 ? r : 1.0 / (1.0 / r + info[RI_CURV]);
    double tc = info[RI_TC] * std::pow(vmax, -info[RI_ALPHA]) * std::pow(m * m / rs / info[RI_Q], 0.2);
    if (tc < tc_min) {
      tc_min = tc;
      worst = t + 1;
    }
  }
  if (update->dt > tc_min / MIN_STEPS_PER_CONTACT)
    error->all(FLERR,
               "fix {} dem/contact/wall: the time step {} s gives {:.3g} steps per contact time of type {} with the "
               "wall at vmax = {} m/s ({:.4g} s), fewer than {}: use timestep {:.4g} or smaller",
               id, update->dt, tc_min / update->dt, worst, vmax, tc_min, MIN_STEPS_PER_CONTACT,
               tc_min / MIN_STEPS_PER_CONTACT);
}

// the wall's clock [s]: LAMMPS's time (thermo time) plus the offset that starts it when the fix is defined and
// keeps it going on across a reset_timestep
double FixDemContactWall::now() const
{
  return update->atime + (double) (update->ntimestep - update->atimestep) * update->dt + clock_offset;
}

void FixDemContactWall::setup(int /*vflag*/)
{
  // the wall goes on from where the last step left it, whatever LAMMPS's time was set to between the runs
  if (has_clock) clock_offset += clock_last - now();
  evaluate(true);
}

void FixDemContactWall::post_force(int /*vflag*/) { evaluate(false); }

void FixDemContactWall::evaluate(bool setup)
{
  const int nlocal = atom->nlocal;
  const double t = now();
  load_summed = false;
  std::memset(report, 0, sizeof(report));
  if (!setup) {
    clock_last = t;
    has_clock = 1;
  }
  n_out = 0;
  // A run's set-up advances nothing (the law works on copies of the histories, with no time passing) and
  // reapplies the forces saved at the last step of the run before to the atoms whose state is unchanged; the
  // last step of a run saves them.
  int64_t flags = setup ? REAPPLY : ADVANCE | (update->ntimestep == update->laststep ? SAVE : 0);
  if (pair->frame_spin_on()) flags |= FRAME_SPIN;
  if (energy) flags |= ENERGY;
  double box[7];
  for (int d = 0; d < 3; d++) {
    box[d] = domain->prd[d];
    box[3 + d] = domain->periodicity[d] && !domain->triclinic ? 1.0 : 0.0;
  }
  box[6] = pair->speed_limit();
  // (every contact has one of the atoms' rows; recorded at a set-up, where the contacts' overlaps are checked, a
  // run's last step, which a compute defined between runs reads, and the steps a compute reads them)
  const bool last = !setup && update->ntimestep == update->laststep;
  const bool record = setup || last || pair->output_due();
  const int64_t cap = record ? (int64_t) nlocal * kernel.slots : 0;
  if ((int64_t) out_atoms.size() < cap + 1) {
    out.resize((size_t) PairDemContact::N_OUT * (cap + 1));
    out_atoms.resize(cap + 1);
  }
  auto step = (WallStepFn) kernel.step;
  const int64_t m = nlocal == 0 ? 0
      : step(nlocal, atom->x[0], atom->v[0], atom->omega[0], atom->radius, atom->rmass, atom->type, atom->mask,
             groupbit, kernel.walls, kernel.wall_rows, t, kernel.mat, kernel.params, kernel.n_rows, kernel.wall_row,
             kernel.n_types, kernel.n_mats, kernel.rowinfo, kernel.type_size, kernel.size_free, history->keys[0],
             history->hist, kernel.slots, row_size, history->saved[0], history->dissipated,
             setup ? 0.0 : update->dt, flags,
             (double) update->ntimestep, box, atom->f[0], atom->torque[0], report, out.data(), out_atoms.data(), cap);
  static_assert(sizeof(report) / sizeof(report[0]) == N_REPORT, "report: wall_kernel.N_REPORT values");
  n_out = std::min(m, cap);
  if (setup && !deep_checked) {
    check_deep();
    deep_checked = true;
  }
  // the contacts of this step, recorded by their atoms' ids; a set-up where the pair style gave the atoms the last
  // step's forces again keeps that step's, as the pair style does
  tagint *tag = atom->tag;
  if (record && !(setup && pair->kept_last())) {
    evaluated_step = update->ntimestep;
    rec_n = n_out;
    rec_ids.resize(n_out + 1);
    for (int64_t k = 0; k < n_out; k++) rec_ids[k] = tag[out_atoms[k]];
    rec_out.assign(out.begin(), out.begin() + PairDemContact::N_OUT * n_out);
  }
  if (report[R_BEHIND] > 0)
    error->one(FLERR,
               "fix {} dem/contact/wall: the centre of atom {} is behind the wall at step {} (placed there, or it "
               "passed through: a time step too long for its speed)",
               id, tag[(int) report[R_BEHIND] - 1], update->ntimestep);
  if (report[R_OVERFLOW] > 0)
    error->one(FLERR,
               "fix {} dem/contact/wall: atom {} touches the wall at more than {} places at once: give the fix a "
               "larger slots N (history rows per atom)",
               id, tag[(int) report[R_OVERFLOW] - 1], kernel.slots);
  if (report[R_BAD] > 0)
    error->one(FLERR,
               "fix {} dem/contact/wall: the wall's forces on {} atoms are not finite at step {} (an overlap beyond "
               "the law's range, a time step too long for the contacts, or atoms placed inside the wall)",
               id, (int) report[R_BAD], update->ntimestep);
  if (report[R_FAST_ATOM] > 0) {
    const double vn = report[R_FAST_V], steps = report[R_FAST_STEPS];
    const tagint a = tag[(int) report[R_FAST_ATOM] - 1];
    if (steps < MIN_STEPS_PER_CONTACT)
      error->one(FLERR,
                 "fix {} dem/contact/wall: atom {} began a contact with the wall at a normal speed of {:.4g} m/s, "
                 "above vmax = {} m/s, which the time step resolves with {:.3g} steps per contact time, fewer than "
                 "{}: give pair_style dem/contact the vmax that is reached, and a time step that resolves it",
                 id, a, vn, pair->speed_limit(), steps, MIN_STEPS_PER_CONTACT);
    if (!warned_onset) {
      error->warning(FLERR,
                     "fix {} dem/contact/wall: atom {} began a contact with the wall at a normal speed of {:.4g} "
                     "m/s, above vmax = {} m/s (resolved with {:.3g} steps per contact time): the checks assume "
                     "vmax; give the vmax that is reached",
                     id, a, vn, pair->speed_limit(), steps);
      warned_onset = true;
    }
  }
}

// at the first set-up: a warning where contacts start deeper than a head-on impact at vmax would press them (as
// pair dem/contact's)
void FixDemContactWall::check_deep()
{
  const double vmax = pair->speed_limit();
  int count = 0;
  double worst = 0.0;
  for (int64_t k = 0; k < n_out; k++) {
    const int i = (int) out_atoms[k];
    const int row = (int) kernel.wall_row[(atom->type[i] - 1) * kernel.n_mats + kernel.mat];
    const double *info = kernel.rowinfo + (size_t) row * N_ROWINFO;
    const double r = atom->radius[i];
    const double rs = info[RI_CURV] == 0.0 ? r : 1.0 / (1.0 / r + info[RI_CURV]);
    const double ratio = out[(size_t) PairDemContact::N_OUT * k + PairDemContact::OUT_DELTA] /
        PairDemContact::deepest(info, vmax, rs, atom->rmass[i]);
    if (ratio > 1.0) {
      count++;
      worst = std::max(worst, ratio);
    }
  }
  PairDemContact::tell_deep(lmp, fmt::format("fix {} dem/contact/wall", id), count, worst, vmax);
}

// the wall's load summed over the ranks: force (3) [N], torque about its centre (3) [N m], power given to the
// atoms [W]
double FixDemContactWall::compute_vector(int n)
{
  if (!load_summed) {
    MPI_Allreduce(report + R_LOAD, load_all, 7, MPI_DOUBLE, MPI_SUM, world);
    load_summed = true;
  }
  return load_all[n];
}

void FixDemContactWall::write_restart(FILE *fp)
{
  if (comm->me == 0) {
    double buf[4] = {3.0, clock_offset, clock_last, (double) has_clock};
    int size = 3 * sizeof(double);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(buf + 1, sizeof(double), 3, fp);
  }
}

void FixDemContactWall::restart(char *buf)
{
  auto b = (double *) buf;
  clock_offset = b[0];
  clock_last = b[1];
  has_clock = (int) b[2];
}
