// The native part of the Python package skinspec (python/skinspec/__init__.py re-exports it; docs/PYTHON.md).
#include "python/bindings.hpp"
#include "skinspec/version.hpp"
#include "spectral/input_error.hpp"

PYBIND11_MODULE(_skinspec, m) {
    namespace py = pybind11;
    m.doc() = "skinspec: spectral simulation of human skin appearance (native part)";
    m.attr("__version__") = std::string(skinspec::version);
    // Bad input: the same one-line messages as the command-line program, as a ValueError subclass.
    py::register_exception<skinspec::InputError>(m, "InputError", PyExc_ValueError);
    skinspec::python::bind_materials(m);
    skinspec::python::bind_spectra(m);
    skinspec::python::bind_color(m);
    skinspec::python::bind_fit(m);
    skinspec::python::bind_phase(m);
    skinspec::python::bind_bench(m);
    skinspec::python::bind_mcml(m);
    skinspec::python::bind_phase_study(m);
    skinspec::python::bind_profile_fit(m);
    skinspec::python::bind_swatch(m);
    skinspec::python::bind_exports(m);
    skinspec::python::bind_iad(m);
    skinspec::python::bind_image_fit(m);
}
