/* compute ID all dem/contact/local: the contacts of pair_style dem/contact and of every fix dem/contact/wall at
   the step, one row each (each contact once over the ranks: a pair by the rank that owned its atom of lower id, a
   wall contact by the rank of its atom), for dump local:

     compute ID all dem/contact/local [work]

     id1 id2 fx fy fz ftx fty ftz nx ny nz overlap sliding wall tx ty tz [work_n work_t]

   A pair: id1 < id2 (atom ids), wall 0. A wall contact: id1 the atom, id2 0, wall k for the k-th fix
   dem/contact/wall (from 1, in the order the fixes were defined). (fx, fy, fz) the contact force on atom id1 [N]
   (body 2 takes the opposite), (ftx, fty, ftz) its tangential part [N], (nx, ny, nz) the unit normal from id1 to
   body 2, overlap [m]; sliding: 1 where |ft| >= (1 - 1e-9) mu N with N > 0 (the laws cap |ft| at mu N, to
   rounding), else 0. The normal force N, positive when pushing apart, is -(f - ft) . n. (tx, ty, tz): the torque
   of the twist and rolling laws on atom id1 [N m] (zero without them; the moment of ft is not in it). With work (and pair_style
   dem/contact ... energy yes), work_n, work_t: the work
   the normal and the tangential force have done on the contact since it began [J] (trapezoid sums of N d(delta)
   and Ft . d(slip)): what it absorbed, stored elastically while it lasts; when it ends, their sum is the energy
   it dissipated, added to its atoms' (the per-atom vector of the history fixes, FixDemContactHistory).

   Its global vector (c_ID[1], c_ID[2], c_ID[3]): the sphere contacts and the wall contacts at the step, summed over
   the ranks, and the largest overlap of them [m]. */
#ifdef COMPUTE_CLASS
#else
#ifndef DEM_CONTACT_COMPUTE_LOCAL_H
#define DEM_CONTACT_COMPUTE_LOCAL_H

#include "compute.h"

#include <vector>

namespace LAMMPS_NS {

class ComputeDemContactLocal : public Compute {
 public:
  ComputeDemContactLocal(class LAMMPS *, int, char **);
  ~ComputeDemContactLocal() override;
  void init() override;
  void compute_local() override;
  void compute_vector() override;
  double memory_usage() override;

 private:
  int nmax;
  double **rows;
  double values[3];
  bool work;
  std::vector<class FixDemContactWall *> current(class PairDemContact *&pair);
  void fill(double *row, tagint id1, tagint id2, int wall, const double *values);
};

}    // namespace LAMMPS_NS

#endif
#endif
