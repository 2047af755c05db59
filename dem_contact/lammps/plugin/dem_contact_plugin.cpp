// Registers pair_style dem/contact and its history fix with LAMMPS (PLUGIN package: plugin load, or a
// *plugin.so on LAMMPS_PLUGIN_PATH).
#include "lammpsplugin.h"

#include "fix_dem_contact_history.h"
#include "pair_dem_contact.h"

#ifndef DEM_CONTACT_LAMMPS_VERSION
#error "DEM_CONTACT_LAMMPS_VERSION (the LAMMPS version string the plugin is built for) must be defined"
#endif

using namespace LAMMPS_NS;

static Pair *pair_creator(LAMMPS *lmp) { return new PairDemContact(lmp); }

static Fix *history_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixDemContactHistory(lmp, argc, argv);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
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

  plugin.style = "fix";
  plugin.name = "DEM/CONTACT/HISTORY";
  plugin.info = "contact rows of pair_style dem/contact, moving with their atoms";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &history_creator;
  (*register_plugin)(&plugin, lmp);
}
