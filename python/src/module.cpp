// SPDX-License-Identifier: BSD-3-Clause
// camfollower._core: the compiled half of the Python package.
#include "bindings.hpp"

PYBIND11_MODULE(_core, m) {
    m.doc() = "camfollower compiled core (use the camfollower package, not this module directly)";
    m.attr("__version__") = CAMFOLLOWER_VERSION;  // from pyproject.toml, through CMake
    m.attr("MAX_POINTS") = camfollower::detail::max_points;  // largest point count of any sampled curve
    m.attr("MIN_CAMSHAFT_SPEED") = camfollower::detail::min_camshaft_speed;  // rad/s
    m.attr("MAX_CAMSHAFT_SPEED") = camfollower::detail::max_camshaft_speed;  // rad/s
    camfollower::python::bind_motion(m);
    camfollower::python::bind_geometry(m);
    camfollower::python::bind_model(m);
    camfollower::python::bind_solver(m);
    camfollower::python::bind_mechanism(m);
    camfollower::python::bind_line_contact(m);
    camfollower::python::bind_export(m);
    camfollower::python::bind_config(m);
}
