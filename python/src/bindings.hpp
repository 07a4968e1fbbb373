// SPDX-License-Identifier: BSD-3-Clause
// Shared helpers for the binding files: one vectorizer used by every area.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <utility>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "camfollower/contact/contact_pair.hpp"  // Follower

namespace camfollower::python {

namespace py = pybind11;
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// Evaluate f(x) -> std::array<double, K> at every element of x; return a dict {name: array of
// x's shape} (plain floats when x is a scalar). The loop runs without the GIL.
template <std::size_t K, class F>
py::dict map_to_dict(const DoubleArray& x, const std::array<const char*, K>& names, F&& f) {
    const py::ssize_t n = x.size();
    std::array<py::array_t<double>, K> out;
    std::vector<py::ssize_t> shape(x.shape(), x.shape() + x.ndim());
    for (auto& a : out) a = py::array_t<double>(shape);
    std::array<double*, K> dst;
    for (std::size_t k = 0; k < K; ++k) dst[k] = out[k].mutable_data();
    const double* src = x.data();
    {
        py::gil_scoped_release release;
        for (py::ssize_t i = 0; i < n; ++i) {
            const std::array<double, K> v = f(src[i]);
            for (std::size_t k = 0; k < K; ++k) dst[k][i] = v[k];
        }
    }
    py::dict d;
    for (std::size_t k = 0; k < K; ++k) {
        if (x.ndim() == 0) d[names[k]] = py::float_(dst[k][0]);
        else d[names[k]] = out[k];
    }
    return d;
}

// A number given as a Python keyword or list entry: int, float or anything with __float__ (NumPy
// scalars), never a string or a bool. Raises TypeError naming the argument, instead of pybind11's
// "Unable to cast ... to C++ type '?'".
inline double number_argument(const std::string& name, const py::handle& value) {
    if (!py::isinstance<py::bool_>(value) && !py::isinstance<py::str>(value) && !py::isinstance<py::bytes>(value)) {
        const double x = PyFloat_AsDouble(value.ptr());
        if (!(x == -1.0 && PyErr_Occurred())) return x;
        PyErr_Clear();
    }
    std::string type = py::str(py::type::handle_of(value).attr("__name__"));
    throw py::type_error(name + " must be a number, got " + type);
}

// A follower object from Python as the C++ variant (mechanism.cpp): no pybind11 caster handles a
// variant of types without a default constructor.
Follower follower_from(const py::handle& f);

// A turn as given from Python: the ArmTurn enum or its name ("counter_clockwise"/"ccw", "clockwise"/"cw").
inline ArmTurn turn_argument(const py::object& turn) {
    if (py::isinstance<ArmTurn>(turn)) return turn.cast<ArmTurn>();
    if (py::isinstance<py::str>(turn)) return arm_turn_from(turn.cast<std::string>());
    throw py::type_error(detail::concat("turn must be an ArmTurn or one of 'counter_clockwise', 'clockwise', got ",
                                        std::string(py::str(py::type::of(turn).attr("__name__")))));
}

void bind_motion(py::module_& m);
void bind_linkage(py::module_& m);
void bind_speed(py::module_& m);
void bind_parameters(py::module_& m);
void bind_settings(py::module_& m);
void bind_mechanism(py::module_& m);
void bind_line_contact(py::module_& m);
void bind_export(py::module_& m);
void bind_config(py::module_& m);

}  // namespace camfollower::python
