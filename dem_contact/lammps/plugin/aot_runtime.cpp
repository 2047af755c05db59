// What the steps compiled ahead of time call besides numba's memory functions (linked from numba's nrt.cpp)
// and libm: numba's ldexp, and the functions of its error paths (raising a Python exception), which here
// report the error instead: dem_contact_aot_raised is set and the pair style stops the run with a message.
// Hidden: where Python runs in the process too (fix dem/contact/wall), its functions are not replaced.
#include "aot.h"

#include <cmath>
#include <cstddef>
#include <cstdio>

#define HIDDEN __attribute__((visibility("hidden")))

extern "C" {
int dem_contact_aot_raised = 0;

HIDDEN double numba_ldexp(double x, int e) { return std::ldexp(x, e); }

// (an error path was taken: told once, and recorded for the pair style)
static void *raised(const char *what)
{
  if (!dem_contact_aot_raised)
    std::fprintf(stderr, "dem_contact: the step compiled ahead of time took an error path (%s)\n", what);
  dem_contact_aot_raised = 1;
  return nullptr;
}

HIDDEN void *PyExc_RuntimeError = nullptr;
HIDDEN void *PyExc_StopIteration = nullptr;
HIDDEN void *PyExc_SystemError = nullptr;
HIDDEN int numba_do_raise(void *) { return raised("numba_do_raise") ? 1 : 0; }
HIDDEN int numba_gil_ensure() { return 0; }
HIDDEN void numba_gil_release(int) {}
HIDDEN void *numba_unpickle(const char *, int, const char *) { return raised("numba_unpickle"); }
HIDDEN void *numba_runtime_build_excinfo_struct(void *, void *) { return raised("an exception"); }
HIDDEN void *PyBytes_FromStringAndSize(const char *, ptrdiff_t) { return raised("PyBytes_FromStringAndSize"); }
HIDDEN void PyErr_Clear() {}
HIDDEN void PyErr_SetNone(void *) { raised("PyErr_SetNone"); }
HIDDEN void PyErr_SetString(void *, const char *what) { raised(what); }
HIDDEN void PyErr_WriteUnraisable(void *) { raised("an exception in the step"); }
HIDDEN ptrdiff_t PyObject_Hash(void *) { return -1; }
HIDDEN void *PyTuple_Pack(ptrdiff_t, ...) { return raised("PyTuple_Pack"); }
HIDDEN void *PyUnicode_FromKindAndData(int, const void *, ptrdiff_t) { return raised("PyUnicode_FromKindAndData"); }
HIDDEN void *PyUnicode_FromString(const char *) { return raised("PyUnicode_FromString"); }
HIDDEN void Py_DecRef(void *) {}
}
