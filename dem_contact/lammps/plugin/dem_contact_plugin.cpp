// Registers pair_style dem/contact, fix dem/contact/wall, compute dem/contact/local and their history fix with
// LAMMPS (PLUGIN package: plugin load, or a *plugin.so on LAMMPS_PLUGIN_PATH).
#include "lammpsplugin.h"
#include "library.h"

#include "error.h"
#include "lammps.h"

#include "compute_dem_contact_local.h"
#include "fix_dem_contact_history.h"
#include "fix_dem_contact_wall.h"
#include "pair_dem_contact.h"

#ifndef DEM_CONTACT_LAMMPS_VERSION
#error "DEM_CONTACT_LAMMPS_VERSION (the LAMMPS version string the plugin is built for) must be defined"
#endif
#ifndef DEM_CONTACT_LAMMPS_VERSION_NUMBER
#error "DEM_CONTACT_LAMMPS_VERSION_NUMBER (as lammps_version(): 20250722) must be defined"
#endif

#include <string>

using namespace LAMMPS_NS;

static Pair *pair_creator(LAMMPS *lmp) { return new PairDemContact(lmp); }

static Compute *local_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new ComputeDemContactLocal(lmp, argc, argv);
}

static Fix *wall_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixDemContactWall(lmp, argc, argv);
}

static Fix *history_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixDemContactHistory(lmp, argc, argv);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  // LAMMPS loads a plugin of another version (with a warning only): its classes may not match this one's
  int version = lammps_version(lmp);
  if (version != DEM_CONTACT_LAMMPS_VERSION_NUMBER) {
    std::string text = "the dem_contact plugin was built for LAMMPS " DEM_CONTACT_LAMMPS_VERSION " (" +
        std::to_string(DEM_CONTACT_LAMMPS_VERSION_NUMBER) + "), this LAMMPS is " + std::to_string(version) +
        ": build it for this LAMMPS (dem-contact lammps-plugin --rebuild in its Python environment, or CMake "
        "against its headers)";
    ((LAMMPS *) lmp)->error->all(FLERR, text);    // (every rank loads the plugin)
    return;
  }
  lammpsplugin_t plugin;
  auto register_plugin = (lammpsplugin_regfunc) regfunc;
  plugin.version = DEM_CONTACT_LAMMPS_VERSION;
  plugin.author = "dem_contact";
  plugin.handle = handle;

  plugin.style = "pair";
  plugin.name = "dem/contact";
  plugin.info = "dem_contact's contact laws for spheres (Hertz, Thornton, Mindlin-Deresiewicz, MDR)";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &pair_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "compute";
  plugin.name = "dem/contact/local";
  plugin.info = "the contacts of pair_style dem/contact and fix dem/contact/wall at the step (for dump local)";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &local_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "dem/contact/wall";
  plugin.info = "a wall (plane, cylinder, STL mesh; rigid motion) with the laws of pair_style dem/contact";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &wall_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "DEM/CONTACT/HISTORY";
  plugin.info = "contact rows of pair_style dem/contact, moving with their atoms";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &history_creator;
  (*register_plugin)(&plugin, lmp);
}
