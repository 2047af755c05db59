/* The registration record LAMMPS's PLUGIN package reads from a plugin's lammpsplugin_init() (LAMMPS manual,
   "Writing plugins"): the LAMMPS version the plugin is built for, the style kind and name, and its factory. */
#ifndef DEM_CONTACT_LAMMPSPLUGIN_H
#define DEM_CONTACT_LAMMPSPLUGIN_H

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
void lammpsplugin_init(void *, void *, void *);
}

#endif
