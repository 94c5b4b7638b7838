// python/arrays.h: the simulation's state and last step as NumPy arrays (copies), and NumPy input
// read back into the library's types.
#pragma once

#include "core/model.h"
#include "python/simulator.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <string>
#include <vector>

namespace frontier::render
{
struct Image;
}

namespace frontier::python
{

// The structured dtype of Simulator.contacts; called once when the module loads.
void registerArrayTypes();

pybind11::array_t<double> vec3Array(const core::Vec3& v);
// Three finite numbers from a sequence or array; throws pybind11::value_error naming `what`.
core::Vec3 vec3Of(const pybind11::object& value, const std::string& what);

std::vector<std::string> bodyNames(const Simulator& sim);
std::vector<std::string> jointNames(const Simulator& sim);
std::vector<std::string> coordinateNames(const Simulator& sim);
std::vector<std::string> actuatorNames(const Simulator& sim);
std::vector<std::string> actuatorKinds(const Simulator& sim);
pybind11::array_t<bool> staticMask(const Simulator& sim);
pybind11::array_t<double> masses(const Simulator& sim);

pybind11::array_t<double> positions(const Simulator& sim);         // (n, 3) m
pybind11::array_t<double> orientations(const Simulator& sim);      // (n, 4) w, x, y, z
pybind11::array_t<double> velocities(const Simulator& sim);        // (n, 3) m/s
pybind11::array_t<double> angularVelocities(const Simulator& sim); // (n, 3) rad/s
pybind11::array_t<double> jointPositions(const Simulator& sim);    // (k,) rad or m
pybind11::array_t<double> jointVelocities(const Simulator& sim);   // (k,) rad/s or m/s
pybind11::array contacts(const Simulator& sim);                    // structured, see module.cpp
pybind11::array_t<double> jointWrenches(const Simulator& sim);     // (j, 6) N, N m
pybind11::array_t<double> actuatorEfforts(const Simulator& sim);   // (a,) N m or N

pybind11::array_t<std::uint8_t> imageArray(const render::Image& image); // (h, w, 3)
// An (h, w, 3) or (h, w, 4) uint8 array as an RGBA image; throws pybind11::value_error.
render::Image imageOf(const pybind11::object& array);

} // namespace frontier::python
