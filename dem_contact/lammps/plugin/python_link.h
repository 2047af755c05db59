/* The Python interpreter the pair style reaches the package's kernels through: the running one (LAMMPS driven
   from Python) or one embedded in this process (lmp -in), found at run time, never linked. */
#ifndef DEM_CONTACT_PYTHON_LINK_H
#define DEM_CONTACT_PYTHON_LINK_H

#include <string>

namespace DemContact {
// Run the Python statements `code`; "" on success, else what went wrong (the traceback went to stderr).
std::string run_python(const std::string &code);
// a Python expression of the text s, whatever characters it has
std::string python_text(const std::string &s);
}    // namespace DemContact

#endif
