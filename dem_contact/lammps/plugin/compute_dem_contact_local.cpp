#include "compute_dem_contact_local.h"

#include "fix_dem_contact_wall.h"
#include "pair_dem_contact.h"

#include "atom.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

using namespace LAMMPS_NS;

namespace {
const int N_COLUMNS = 17, N_WORK_COLUMNS = 2;
// a contact slides when |Ft| >= (1 - SLIDING_TOL) mu N (the column sliding of LammpsContacts.contacts())
const double SLIDING_TOL = 1e-9;
PairDemContact *our_pair(LAMMPS *lmp)
{
  return dynamic_cast<PairDemContact *>(lmp->force->pair_match("dem/contact", 1));
}
}    // namespace

ComputeDemContactLocal::ComputeDemContactLocal(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), nmax(0), rows(nullptr), work(false)
{
  if (narg > 4 || (narg == 4 && strcmp(arg[3], "work") != 0))
    error->all(FLERR, "compute dem/contact/local takes one keyword, work: compute ID all dem/contact/local [work]");
  work = narg == 4;
  local_flag = 1;
  vector_flag = 1;
  size_vector = 3;
  extvector = 0;
  vector = values;
  timeflag = 1;    // (the pair style and the wall fixes record the contacts at the steps LAMMPS invokes it at)
  size_local_cols = N_COLUMNS + (work ? N_WORK_COLUMNS : 0);
  size_local_rows = 0;
}

ComputeDemContactLocal::~ComputeDemContactLocal() { memory->destroy(rows); }

void ComputeDemContactLocal::init()
{
  PairDemContact *pair = our_pair(lmp);
  if (!pair) error->all(FLERR, "compute dem/contact/local needs pair_style dem/contact");
  if (work && !pair->energy_on())
    error->all(FLERR, "compute dem/contact/local work: the work of the contact forces is accounted with pair_style "
                      "dem/contact ... energy yes");
}

// the pair style and the wall fixes, checked to have the contacts of this step
std::vector<FixDemContactWall *> ComputeDemContactLocal::current(PairDemContact *&pair)
{
  pair = our_pair(lmp);
  if (!pair) error->all(FLERR, "compute dem/contact/local needs pair_style dem/contact");
  if (pair->evaluated_step != update->ntimestep)
    error->all(FLERR,
               "compute dem/contact/local: the pair style has no contacts of step {}: they are recorded at a run's "
               "set-up (but not the first after read_restart, which gives the atoms the forces saved in the file and "
               "computes none: run 1 first), its last step, and the steps a dump, thermo or fix invokes this compute "
               "at; read it at those steps (a variable or Python reading it at other steps of a run cannot)",
               update->ntimestep);
  // the pair style's contacts (a pair: reported by the rank that owned its atom id1 then), then each wall's
  std::vector<FixDemContactWall *> walls;
  for (auto f : modify->get_fix_by_style("^dem/contact/wall$")) {
    auto w = dynamic_cast<FixDemContactWall *>(f);
    if (w->evaluated_step != update->ntimestep)
      error->all(FLERR, "compute dem/contact/local: fix {} has no contacts of step {}: they are recorded at a run's "
                 "set-up (but not the first after read_restart: run 1 first), its last step, and the steps a dump, "
                 "thermo or fix invokes this compute at; read it at those steps", w->id, update->ntimestep);
    walls.push_back(w);
  }
  return walls;
}

// the global vector: the sphere contacts, the wall contacts and the largest overlap [m] over the ranks
void ComputeDemContactLocal::compute_vector()
{
  invoked_vector = update->ntimestep;
  PairDemContact *pair;
  const std::vector<FixDemContactWall *> walls = current(pair);
  double mine[2] = {0.0, 0.0}, all[2], deepest = 0.0;
  const tagint *ids = pair->contact_ids();
  for (int64_t k = 0; k < pair->contact_count(); k++)
    if (ids[3 * k + 2]) {
      mine[0] += 1.0;
      deepest = std::max(deepest, pair->contact_values()[PairDemContact::N_OUT * k + PairDemContact::OUT_DELTA]);
    }
  for (auto w : walls)
    for (int64_t k = 0; k < w->contact_count(); k++) {
      mine[1] += 1.0;
      deepest = std::max(deepest, w->contact_values()[PairDemContact::N_OUT * k + PairDemContact::OUT_DELTA]);
    }
  MPI_Allreduce(mine, all, 2, MPI_DOUBLE, MPI_SUM, world);
  vector[0] = all[0];
  vector[1] = all[1];
  MPI_Allreduce(&deepest, &vector[2], 1, MPI_DOUBLE, MPI_MAX, world);
}

void ComputeDemContactLocal::compute_local()
{
  invoked_local = update->ntimestep;
  PairDemContact *pair;
  const std::vector<FixDemContactWall *> walls = current(pair);
  const int64_t n = pair->contact_count();
  const tagint *ids = pair->contact_ids();
  int m = 0;
  for (int64_t k = 0; k < n; k++)
    if (ids[3 * k + 2]) m++;
  for (auto w : walls) m += (int) w->contact_count();
  if (m > nmax) {
    memory->destroy(rows);
    nmax = m;
    memory->create(rows, nmax, size_local_cols, "dem/contact/local:rows");
    array_local = rows;
  }
  size_local_rows = m;
  m = 0;
  for (int64_t k = 0; k < n; k++)
    if (ids[3 * k + 2])
      fill(rows[m++], ids[3 * k], ids[3 * k + 1], 0, pair->contact_values() + PairDemContact::N_OUT * k);
  for (size_t w = 0; w < walls.size(); w++) {
    const tagint *atoms = walls[w]->contact_ids();
    for (int64_t k = 0; k < walls[w]->contact_count(); k++)
      fill(rows[m++], atoms[k], 0, (int) w + 1, walls[w]->contact_values() + PairDemContact::N_OUT * k);
  }
}

// a row: ids, the force on atom id1 and its tangential part, the normal, the overlap, sliding, the wall, the torque
// of the twist and rolling laws on atom id1 (as the step gives it), the work of the normal and tangential forces
void ComputeDemContactLocal::fill(double *r, tagint id1, tagint id2, int wall, const double *o)
{
  r[0] = id1;
  r[1] = id2;
  for (int d = 0; d < 3; d++) {
    r[2 + d] = o[PairDemContact::OUT_F + d];
    r[5 + d] = o[PairDemContact::OUT_FT + d];
    r[8 + d] = o[PairDemContact::OUT_N + d];
  }
  r[11] = o[PairDemContact::OUT_DELTA];
  double N = 0.0, ft = 0.0;
  for (int d = 0; d < 3; d++) {
    N -= (r[2 + d] - r[5 + d]) * r[8 + d];
    ft += r[5 + d] * r[5 + d];
  }
  r[12] = (N > 0.0 && std::sqrt(ft) >= (1.0 - SLIDING_TOL) * o[PairDemContact::OUT_MU] * N) ? 1.0 : 0.0;
  r[13] = wall;
  for (int d = 0; d < 3; d++) r[14 + d] = o[PairDemContact::OUT_Q + d];
  if (work) {
    r[17] = o[PairDemContact::OUT_WORK_N];
    r[18] = o[PairDemContact::OUT_WORK_T];
  }
}

double ComputeDemContactLocal::memory_usage() { return (double) nmax * size_local_cols * sizeof(double); }
