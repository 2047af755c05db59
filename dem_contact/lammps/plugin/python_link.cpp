#include "python_link.h"

#include <cstdio>
#include <cwchar>
#include <dlfcn.h>

#ifndef DEM_CONTACT_LIBPYTHON
#error "DEM_CONTACT_LIBPYTHON (the path of the libpython the package runs on) must be defined"
#endif
#ifndef DEM_CONTACT_PYTHON
#error "DEM_CONTACT_PYTHON (the python executable of the package's environment) must be defined"
#endif

namespace {
typedef int (*IntFn)();
typedef void (*InitExFn)(int);
typedef int (*GilEnsureFn)();
typedef void (*GilReleaseFn)(int);
typedef int (*RunFn)(const char *);
typedef wchar_t *(*DecodeFn)(const char *, size_t *);
typedef void (*SetNameFn)(const wchar_t *);

void *symbol(const char *name) { return dlsym(RTLD_DEFAULT, name); }
}    // namespace

std::string DemContact::run_python(const std::string &code)
{
  if (!symbol("Py_IsInitialized")) {
    // no Python in this process (lmp -in): load the library of the package's Python, with global symbols
    // (numpy's and numba's extension modules resolve theirs against it)
    if (!dlopen(DEM_CONTACT_LIBPYTHON, RTLD_NOW | RTLD_GLOBAL))
      return std::string("cannot load ") + DEM_CONTACT_LIBPYTHON + " (" + dlerror() +
          "): build the plugin again with the Python environment dem_contact is installed in "
          "(dem-contact lammps-plugin --rebuild)";
  }
  auto is_initialized = (IntFn) symbol("Py_IsInitialized");
  auto run = (RunFn) symbol("PyRun_SimpleString");
  auto ensure = (GilEnsureFn) symbol("PyGILState_Ensure");
  auto release = (GilReleaseFn) symbol("PyGILState_Release");
  if (!is_initialized || !run || !ensure || !release) return "the Python library lacks its C API";
  if (!is_initialized()) {
    // an interpreter of the package's environment: its python executable as the program name finds the
    // environment (pyvenv.cfg) and its site-packages
    auto decode = (DecodeFn) symbol("Py_DecodeLocale");
    auto set_name = (SetNameFn) symbol("Py_SetProgramName");
    auto init = (InitExFn) symbol("Py_InitializeEx");
    if (!decode || !set_name || !init) return "the Python library lacks its embedding API";
    static wchar_t *name = decode(DEM_CONTACT_PYTHON, nullptr);
    set_name(name);
    init(0);    // (0: LAMMPS and MPI keep their signal handlers)
    int gil = ensure();
    run("import sys\nsys.argv = ['lmp']\n");
    release(gil);
  }
  int gil = ensure();
  int rc = run(code.c_str());
  release(gil);
  if (rc != 0) return "the Python statements failed (traceback above): " + code;
  return "";
}

std::string DemContact::python_text(const std::string &s)
{
  std::string hex;
  char b[3];
  for (unsigned char c : s) {
    std::snprintf(b, sizeof(b), "%02x", c);
    hex += b;
  }
  return "bytes.fromhex('" + hex + "').decode()";
}
