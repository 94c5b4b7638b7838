// python/arrays.cpp: NumPy copies of the state and of the last step.
#include "python/arrays.h"

#include "core/joints/coordinates.h"
#include "render/renderer.h"
#include "run/actuator_efforts.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace py = pybind11;

namespace frontier::python
{

namespace
{
// One row of Simulator.contacts.
struct ContactRow
{
    std::int32_t body_a;
    std::int32_t body_b;
    double point[3];  // m
    double normal[3]; // unit, a towards b
    double depth;     // m
    double force[3];  // N on b
};

// An (n, 3) array of one vector of every body's state.
py::array_t<double> bodyVectors(const Simulator& sim, core::Vec3 core::BodyState::*member)
{
    const std::vector<core::BodyState>& bodies = sim.state().bodies;
    py::array_t<double> out({static_cast<py::ssize_t>(bodies.size()), py::ssize_t{3}});
    auto a = out.mutable_unchecked<2>();
    for (std::size_t i = 0; i < bodies.size(); ++i)
    {
        const core::Vec3& v = bodies[i].*member;
        const auto r = static_cast<py::ssize_t>(i);
        a(r, 0) = v.x();
        a(r, 1) = v.y();
        a(r, 2) = v.z();
    }
    return out;
}

// An (n,) array of one property of every body of the model.
template <typename T, typename F> py::array_t<T> perBody(const Simulator& sim, F value)
{
    const std::vector<core::Body>& bodies = sim.model().bodies;
    py::array_t<T> out(static_cast<py::ssize_t>(bodies.size()));
    auto a = out.template mutable_unchecked<1>();
    for (std::size_t i = 0; i < bodies.size(); ++i)
    {
        a(static_cast<py::ssize_t>(i)) = value(bodies[i]);
    }
    return out;
}

template <typename F> py::array_t<double> perCoordinate(const Simulator& sim, F value)
{
    const std::vector<Coordinate>& coordinates = sim.coordinates();
    py::array_t<double> out(static_cast<py::ssize_t>(coordinates.size()));
    auto a = out.mutable_unchecked<1>();
    for (std::size_t k = 0; k < coordinates.size(); ++k)
    {
        a(static_cast<py::ssize_t>(k)) = value(coordinates[k]);
    }
    return out;
}
} // namespace

void registerArrayTypes()
{
    PYBIND11_NUMPY_DTYPE(ContactRow, body_a, body_b, point, normal, depth, force);
}

py::array_t<double> vec3Array(const core::Vec3& v)
{
    py::array_t<double> out(3);
    auto a = out.mutable_unchecked<1>();
    for (int k = 0; k < 3; ++k)
    {
        a(k) = v[k];
    }
    return out;
}

core::Vec3 vec3Of(const py::object& value, const std::string& what)
{
    const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
    if (!array || array.ndim() != 1 || array.shape(0) != 3)
    {
        throw py::value_error(what + ": expected three numbers");
    }
    const core::Vec3 v(array.at(0), array.at(1), array.at(2));
    if (!v.allFinite())
    {
        throw py::value_error(what + ": expected three finite numbers");
    }
    return v;
}

std::vector<std::string> bodyNames(const Simulator& sim)
{
    std::vector<std::string> names;
    for (const core::Body& body : sim.model().bodies)
    {
        names.push_back(body.name);
    }
    return names;
}

std::vector<std::string> jointNames(const Simulator& sim)
{
    std::vector<std::string> names;
    for (const core::Joint& joint : sim.model().joints)
    {
        names.push_back(joint.name);
    }
    return names;
}

std::vector<std::string> coordinateNames(const Simulator& sim)
{
    std::vector<std::string> names;
    for (const Coordinate& c : sim.coordinates())
    {
        names.push_back(c.name);
    }
    return names;
}

std::vector<std::string> actuatorNames(const Simulator& sim)
{
    std::vector<std::string> names;
    for (std::size_t a = 0; a < sim.model().actuators.size(); ++a)
    {
        names.push_back(sim.actuatorName(a));
    }
    return names;
}

std::vector<std::string> actuatorKinds(const Simulator& sim)
{
    std::vector<std::string> kinds;
    for (const core::Actuator& a : sim.model().actuators)
    {
        kinds.emplace_back(core::actuatorTypeName(a.kind));
    }
    return kinds;
}

py::array_t<bool> staticMask(const Simulator& sim)
{
    return perBody<bool>(sim, [](const core::Body& body) { return body.isStatic; });
}

py::array_t<double> masses(const Simulator& sim)
{
    return perBody<double>(sim, [](const core::Body& body) { return body.mass; });
}

py::array_t<double> positions(const Simulator& sim)
{
    return bodyVectors(sim, &core::BodyState::position_W);
}

py::array_t<double> velocities(const Simulator& sim)
{
    return bodyVectors(sim, &core::BodyState::velocity_W);
}

py::array_t<double> angularVelocities(const Simulator& sim)
{
    return bodyVectors(sim, &core::BodyState::angularVelocity_W);
}

py::array_t<double> orientations(const Simulator& sim)
{
    const std::vector<core::BodyState>& bodies = sim.state().bodies;
    py::array_t<double> out({static_cast<py::ssize_t>(bodies.size()), py::ssize_t{4}});
    auto a = out.mutable_unchecked<2>();
    for (std::size_t i = 0; i < bodies.size(); ++i)
    {
        const core::Quat& q = bodies[i].orientation_WB;
        const auto r = static_cast<py::ssize_t>(i);
        a(r, 0) = q.w();
        a(r, 1) = q.x();
        a(r, 2) = q.y();
        a(r, 3) = q.z();
    }
    return out;
}

py::array_t<double> jointPositions(const Simulator& sim)
{
    return perCoordinate(sim, [&](const Coordinate& c)
                         { return core::fileCoordinate(sim.model(), sim.state(), c.joint, c.coordinate); });
}

py::array_t<double> jointVelocities(const Simulator& sim)
{
    return perCoordinate(
        sim, [&](const Coordinate& c)
        { return core::jointCoordinateVelocity(sim.model(), sim.state(), c.joint, c.coordinate); });
}

py::array contacts(const Simulator& sim)
{
    std::vector<core::ContactImpulse> impulses;
    if (sim.hasLastStep())
    {
        sim.simulator().contactImpulses(impulses);
    }
    py::array_t<ContactRow> out(static_cast<py::ssize_t>(impulses.size()));
    auto a = out.mutable_unchecked<1>();
    const double dt = sim.model().simulation.dt;
    for (std::size_t k = 0; k < impulses.size(); ++k)
    {
        const core::ContactImpulse& c = impulses[k];
        ContactRow& row = a(static_cast<py::ssize_t>(k));
        row.body_a = c.contact.bodyA;
        row.body_b = c.contact.bodyB;
        row.depth = c.contact.depth;
        for (int i = 0; i < 3; ++i)
        {
            row.point[i] = c.contact.point_W[i];
            row.normal[i] = c.contact.normal_W[i];
            row.force[i] = c.impulse_W[i] / dt;
        }
    }
    return out;
}

py::array_t<double> jointWrenches(const Simulator& sim)
{
    const std::size_t joints = sim.model().joints.size();
    py::array_t<double> out({static_cast<py::ssize_t>(joints), py::ssize_t{6}});
    auto a = out.mutable_unchecked<2>();
    std::vector<core::Vec6> impulses(joints, core::Vec6::Zero());
    if (sim.hasLastStep())
    {
        sim.simulator().jointChildImpulses(sim.state(), impulses);
    }
    const double dt = sim.model().simulation.dt;
    for (std::size_t j = 0; j < joints; ++j)
    {
        for (int i = 0; i < 6; ++i)
        {
            a(static_cast<py::ssize_t>(j), i) = impulses[j][i] / dt;
        }
    }
    return out;
}

py::array_t<double> actuatorEfforts(const Simulator& sim)
{
    const std::size_t count = sim.model().actuators.size();
    py::array_t<double> out(static_cast<py::ssize_t>(count));
    auto a = out.mutable_unchecked<1>();
    std::vector<run::CoordinateEffort> efforts;
    if (sim.hasLastStep())
    {
        run::lastActuatorEfforts(sim.model(), sim.simulator(), efforts);
    }
    for (std::size_t k = 0; k < count; ++k)
    {
        a(static_cast<py::ssize_t>(k)) = k < efforts.size() ? efforts[k].effort : 0.0;
    }
    return out;
}

py::array_t<std::uint8_t> imageArray(const render::Image& image)
{
    py::array_t<std::uint8_t> out(
        {static_cast<py::ssize_t>(image.height), static_cast<py::ssize_t>(image.width), py::ssize_t{3}});
    std::uint8_t* rgb = out.mutable_data();
    const std::size_t pixels = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
    for (std::size_t p = 0; p < pixels; ++p)
    {
        std::memcpy(rgb + 3 * p, image.rgba.data() + 4 * p, 3);
    }
    return out;
}

render::Image imageOf(const py::object& array)
{
    if (!py::isinstance<py::array>(array) ||
        !py::array(array.cast<py::array>()).dtype().is(py::dtype::of<std::uint8_t>()))
    {
        throw py::value_error("an image: expected an (height, width, 3) or (height, width, 4) uint8 array "
                              "(convert others with .astype(numpy.uint8) after scaling to 0..255)");
    }
    const auto pixels = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(array);
    if (!pixels || pixels.ndim() != 3 || (pixels.shape(2) != 3 && pixels.shape(2) != 4) ||
        pixels.shape(0) < 1 || pixels.shape(1) < 1)
    {
        throw py::value_error("an image: expected an (height, width, 3) or (height, width, 4) uint8 array");
    }
    render::Image image;
    image.height = static_cast<int>(pixels.shape(0));
    image.width = static_cast<int>(pixels.shape(1));
    const auto channels = static_cast<std::size_t>(pixels.shape(2));
    const std::size_t count = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
    image.rgba.assign(4 * count, 255);
    const std::uint8_t* in = pixels.data();
    for (std::size_t p = 0; p < count; ++p)
    {
        std::memcpy(image.rgba.data() + 4 * p, in + channels * p, channels);
    }
    return image;
}

} // namespace frontier::python
