// SPDX-License-Identifier: BSD-3-Clause
// camfollower._core: the compiled half of the Python package.
#include "bindings.hpp"
#include "camfollower/solver/settings.hpp"
#include "camfollower/solver/shooting.hpp"

PYBIND11_MODULE(_core, m) {
    m.doc() = "camfollower compiled core (use the camfollower package, not this module directly)";
    m.attr("__version__") = CAMFOLLOWER_VERSION;             // from pyproject.toml, through CMake
    m.attr("MAX_POINTS") = camfollower::detail::max_points;  // largest point count of any sampled curve
    m.attr("MAX_PART_LENGTH") =
        camfollower::detail::max_part_length;  // m, largest length of a part (export's cutter radius)
    m.attr("MIN_CAMSHAFT_SPEED") = camfollower::detail::min_camshaft_speed;  // rad/s
    m.attr("MAX_CAMSHAFT_SPEED") = camfollower::detail::max_camshaft_speed;  // rad/s
    // DOFs from which linear_solver 'auto' runs the Newmark family on the sparse backend (which keeps
    // the trapezoidal velocity), and the largest state 2n shooting's dense monodromy takes.
    m.attr("SPARSE_BACKEND_THRESHOLD") = camfollower::sparse_backend_threshold;
    m.attr("SHOOTING_MAX_STATE_SIZE") = camfollower::ShootingOptions::max_state_size;
    camfollower::python::bind_motion(m);
    camfollower::python::bind_speed(m);
    camfollower::python::bind_parameters(m);
    camfollower::python::bind_settings(m);
    camfollower::python::bind_linkage(m);
    camfollower::python::bind_mechanism(m);
    camfollower::python::bind_line_contact(m);
    camfollower::python::bind_export(m);
    camfollower::python::bind_config(m);
    // An instance made by cls.__new__(cls) alone (its __init__ never ran) holds no C++ object; pybind11
    // would hand its first method raw memory (allocated through this hook, used for nothing else). Every
    // class of the module refuses instead.
    namespace py = pybind11;
    for (const auto& item : m.attr("__dict__").cast<py::dict>()) {
        if (!PyType_Check(item.second.ptr())) continue;
        if (py::detail::type_info* info = py::detail::get_type_info(reinterpret_cast<PyTypeObject*>(item.second.ptr())))
            info->operator_new = [](std::size_t) -> void* {
                throw py::value_error(
                    "this instance is uninitialized: its __init__ never ran (made by cls.__new__(cls) "
                    "alone); create it by calling the class");
            };
    }
}
